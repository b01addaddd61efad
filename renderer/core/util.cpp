#include "renderer/core/util.h"

#include <algorithm>
#include <ctime>
#include <stdexcept>

namespace deepgi {

std::pair<int, int> parseImageSize(const std::string& text, bool allowZero) {
    const auto fail = [&](const std::string& why) {
        return std::runtime_error("invalid size '" + text + "': " + why + " (expected WxH, e.g. 320x180)");
    };
    const size_t x = text.find_first_of("xX");
    if (x == std::string::npos) throw fail("no 'x' between width and height");
    const int lowest = allowZero ? 0 : 1;
    const auto parseSide = [&](const std::string& part, const char* what) {
        if (part.empty()) throw fail(std::string("missing ") + what);
        if (part.size() > 6 || part.find_first_not_of("0123456789") != std::string::npos)
            throw fail(std::string(what) + " '" + part + "' is not a " + (allowZero ? "non-negative" : "positive") + " integer");
        const int v = std::stoi(part);
        if (v < lowest || v > 65536) throw fail(std::string(what) + " must be between " + std::to_string(lowest) + " and 65536");
        return v;
    };
    return {parseSide(text.substr(0, x), "width"), parseSide(text.substr(x + 1), "height")};
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

uint64_t fnv1a(uint64_t h, const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

double threadCpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

}  // namespace deepgi
