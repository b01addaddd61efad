#include "bench/gi_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace deepgi::bench {

namespace {

void requireRgbSameSize(const FloatImage& a, const FloatImage& b) {
    if (a.width != b.width || a.height != b.height || a.channels < 3 || b.channels < 3)
        throw std::invalid_argument("GI figure: images differ in size or have fewer than 3 channels (" +
                                    std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
                                    std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}

double sum(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

LumaImage luminance(const FloatImage& img) {
    if (img.channels < 3) throw std::invalid_argument("luminance: image has fewer than 3 channels");
    LumaImage l{img.width, img.height, std::vector<double>(size_t(img.width) * img.height)};
    for (size_t i = 0; i < l.v.size(); ++i) {
        const float* p = &img.pixels[i * img.channels];
        l.v[i] = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    }
    return l;
}

LumaImage blockMeans(const LumaImage& l, int block) {
    if (block < 1) throw std::invalid_argument("blockMeans: block size must be at least 1");
    const int bw = (l.width + block - 1) / block, bh = (l.height + block - 1) / block;
    LumaImage out{bw, bh, std::vector<double>(size_t(bw) * bh, 0.0)};
    std::vector<int> count(out.v.size(), 0);
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            const size_t b = size_t(y / block) * bw + x / block;
            out.v[b] += l.v[size_t(y) * l.width + x];
            ++count[b];
        }
    for (size_t i = 0; i < out.v.size(); ++i) out.v[i] /= double(count[i]);
    return out;
}

double relativeL1(const FloatImage& test, const FloatImage& ref, int block) {
    requireRgbSameSize(test, ref);
    const LumaImage t = blockMeans(luminance(test), block), r = blockMeans(luminance(ref), block);
    double diff = 0.0, mag = 0.0;
    for (size_t i = 0; i < r.v.size(); ++i) {
        diff += std::abs(t.v[i] - r.v[i]);
        mag += r.v[i];
    }
    return mag > 0.0 ? diff / mag : kNaN;
}

double ratioOfMeans(const FloatImage& test, const FloatImage& ref) {
    requireRgbSameSize(test, ref);
    const double r = sum(luminance(ref).v);
    return r > 0.0 ? sum(luminance(test).v) / r : kNaN;
}

Leak leak(const FloatImage& img) {
    const LumaImage l = luminance(img);
    Leak k;
    if (l.v.empty()) return k;
    k.max = -std::numeric_limits<double>::infinity();
    for (double x : l.v) k.max = std::isfinite(x) ? std::max(k.max, x) : std::numeric_limits<double>::infinity();
    k.mean = sum(l.v) / double(l.v.size());
    return k;
}

Deviation deviationFromConstant(const FloatImage& img, double exact) {
    if (!(exact > 0.0)) throw std::invalid_argument("deviationFromConstant: the exact value must be positive");
    const LumaImage l = luminance(img);
    Deviation d;
    if (l.v.empty()) return d;
    double s = 0.0, sl = 0.0;
    for (double x : l.v) {
        const double e = std::abs(x / exact - 1.0);
        d.maxRel = std::max(d.maxRel, std::isfinite(e) ? e : std::numeric_limits<double>::infinity());
        s += e;
        sl += x;
    }
    d.meanRel = s / double(l.v.size());
    d.ratio = sl / double(l.v.size()) / exact;
    return d;
}

double noiseFloor(const FloatImage& quarterA, const FloatImage& quarterB, int block) {
    return relativeL1(quarterA, quarterB, block) / std::sqrt(5.0);
}

FloatImage constantImage(int width, int height, float value) {
    return FloatImage{width, height, 3, std::vector<float>(size_t(width) * height * 3, value)};
}

}  // namespace deepgi::bench
