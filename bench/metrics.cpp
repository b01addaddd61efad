#include "bench/metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace deepgi::bench {

namespace {

void checkSameSize(const FloatImage& a, const FloatImage& b) {
    if (a.width != b.width || a.height != b.height || a.channels < 3 || b.channels < 3)
        throw std::invalid_argument("metric: images differ in size or have fewer than 3 channels (" +
                                    std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
                                    std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}

template <class F>
double meanOverRgb(const FloatImage& a, const FloatImage& b, F f) {
    checkSameSize(a, b);
    const size_t n = size_t(a.width) * a.height;
    if (n == 0) return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) sum += f(double(a.pixels[i * a.channels + c]), double(b.pixels[i * b.channels + c]));
    return sum / double(n * 3);
}

}  // namespace

double relativeMse(const FloatImage& a, const FloatImage& ref, double eps) {
    return meanOverRgb(a, ref, [eps](double x, double r) { return (x - r) * (x - r) / (r * r + eps); });
}

double meanRelativeError(const FloatImage& a, const FloatImage& ref, double eps) {
    return meanOverRgb(a, ref, [eps](double x, double r) { return std::abs(x - r) / (std::abs(r) + eps); });
}

std::vector<float> displayLuminance(const FloatImage& img) {
    const size_t n = size_t(img.width) * img.height;
    std::vector<float> y(n);
    for (size_t i = 0; i < n; ++i) {
        float v[3];
        for (int c = 0; c < 3; ++c) v[c] = linearToSrgb(std::clamp(img.pixels[i * img.channels + c], 0.0f, 1.0f));
        y[i] = 0.2126f * v[0] + 0.7152f * v[1] + 0.0722f * v[2];
    }
    return y;
}

double ssim(const std::vector<float>& a, const std::vector<float>& b, int w, int h) {
    if (a.size() != size_t(w) * h || b.size() != a.size()) throw std::invalid_argument("ssim: size mismatch");
    if (w <= 0 || h <= 0) return 1.0;
    const double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
    const int R = 3;
    double total = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
            int n = 0;
            for (int dy = -R; dy <= R; ++dy)
                for (int dx = -R; dx <= R; ++dx) {
                    const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
                    const double va = a[size_t(yy) * w + xx], vb = b[size_t(yy) * w + xx];
                    sa += va;
                    sb += vb;
                    saa += va * va;
                    sbb += vb * vb;
                    sab += va * vb;
                    ++n;
                }
            const double ma = sa / n, mb = sb / n;
            const double va = std::max(0.0, saa / n - ma * ma), vb = std::max(0.0, sbb / n - mb * mb);
            const double cov = sab / n - ma * mb;
            total += ((2 * ma * mb + C1) * (2 * cov + C2)) / ((ma * ma + mb * mb + C1) * (va + vb + C2));
        }
    return total / (double(w) * h);
}

double ssimDisplay(const FloatImage& a, const FloatImage& ref) {
    checkSameSize(a, ref);
    return ssim(displayLuminance(a), displayLuminance(ref), a.width, a.height);
}

FloatImage subtract(const FloatImage& a, const FloatImage& b) {
    checkSameSize(a, b);
    FloatImage d{a.width, a.height, 3, {}};
    d.pixels.resize(size_t(a.width) * a.height * 3);
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i)
        for (int c = 0; c < 3; ++c) d.pixels[i * 3 + c] = a.pixels[i * a.channels + c] - b.pixels[i * b.channels + c];
    return d;
}

FloatImage rgb(const FloatImage& img) {
    FloatImage d{img.width, img.height, 3, {}};
    d.pixels.resize(size_t(img.width) * img.height * 3);
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i)
        for (int c = 0; c < 3; ++c) d.pixels[i * 3 + c] = img.channels > c ? img.pixels[i * img.channels + c] : 0.0f;
    return d;
}

FloatImage channelRange(const FloatImage& img, int first, int count) {
    if (first < 0 || count < 1 || first + count > img.channels)
        throw std::invalid_argument("channelRange: channels " + std::to_string(first) + ".." + std::to_string(first + count - 1) +
                                    " of a " + std::to_string(img.channels) + "-channel image");
    FloatImage d{img.width, img.height, count, std::vector<float>(size_t(img.width) * img.height * count)};
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i)
        for (int c = 0; c < count; ++c) d.pixels[i * count + c] = img.pixels[i * img.channels + first + c];
    return d;
}

FloatImage stackRgb(const std::vector<const FloatImage*>& parts) {
    if (parts.empty()) return {};
    for (const FloatImage* p : parts) checkSameSize(*p, *parts[0]);
    const int n = int(parts.size()) * 3;
    FloatImage d{parts[0]->width, parts[0]->height, n, std::vector<float>(size_t(parts[0]->width) * parts[0]->height * n)};
    for (size_t i = 0; i < size_t(d.width) * d.height; ++i)
        for (size_t k = 0; k < parts.size(); ++k)
            for (int c = 0; c < 3; ++c) d.pixels[i * n + k * 3 + c] = parts[k]->pixels[i * parts[k]->channels + c];
    return d;
}

double relativeChange(const FloatImage& a, const FloatImage& b) {
    checkSameSize(a, b);
    double diff = 0.0, mag = 0.0;
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i)
        for (int c = 0; c < 3; ++c) {
            diff += std::abs(double(a.pixels[i * a.channels + c]) - b.pixels[i * b.channels + c]);
            mag += std::abs(double(b.pixels[i * b.channels + c]));
        }
    return mag > 0.0 ? diff / mag : 0.0;
}

std::vector<int> paretoFront(const std::vector<Point2>& p) {
    std::vector<int> idx(p.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](int a, int b) { return p[a].x != p[b].x ? p[a].x < p[b].x : p[a].y < p[b].y; });
    std::vector<int> front;
    double bestY = INFINITY;
    for (int i : idx) {
        if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y)) continue;
        if (p[i].y < bestY) {
            front.push_back(i);
            bestY = p[i].y;
        }
    }
    return front;
}

}  // namespace deepgi::bench
