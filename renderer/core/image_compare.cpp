#include "renderer/core/image_compare.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace deepgi {


std::vector<float> luminance(const FloatImage& img) {
    const size_t n = size_t(img.width) * img.height;
    std::vector<float> l(n);
    for (size_t i = 0; i < n; ++i) {
        const float* p = &img.pixels[i * img.channels];
        l[i] = img.channels >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
    }
    return l;
}

namespace {

void checkSizes(const FloatImage& a, const FloatImage& b) {
    if (a.width != b.width || a.height != b.height || a.width <= 0 || a.height <= 0)
        throw std::invalid_argument("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                    " and " + std::to_string(b.width) + "x" + std::to_string(b.height));
}

double meanFinite(const std::vector<float>& v) {
    double s = 0.0;
    size_t n = 0;
    for (float x : v) if (std::isfinite(x)) { s += x; ++n; }
    return n ? s / double(n) : 0.0;
}

}  // namespace

std::string ImageFigures::line() const {
    if (!valid) return "no figures";
    char buf[256];
    std::snprintf(buf, sizeof(buf), "rel L1 (4x4) %.2f%%  ratio of means %.4f  relMSE %.4g  max |dL| %.4g at (%d, %d)",
                  blockRelL1 * 100.0, ratioOfMeans, relMse, maxAbs, maxX, maxY);
    return buf;
}

ImageFigures compareImages(const FloatImage& test, const FloatImage& ref, const std::vector<uint8_t>& mask) {
    checkSizes(test, ref);
    const int w = test.width, h = test.height;
    if (!mask.empty() && mask.size() != size_t(w) * h) throw std::invalid_argument("mask size does not match the images");
    const std::vector<float> lt = luminance(test), lr = luminance(ref);
    auto counts = [&](size_t i) { return (mask.empty() || mask[i]) && std::isfinite(lt[i]) && std::isfinite(lr[i]); };
    ImageFigures f;
    double sumT = 0.0, sumR = 0.0, sumAbs = 0.0;
    for (size_t i = 0; i < lt.size(); ++i) {
        if (!counts(i)) continue;
        sumT += lt[i];
        sumR += lr[i];
        const double d = std::abs(double(lt[i]) - lr[i]);
        sumAbs += d;
        if (d > f.maxAbs || f.pixels == 0) { f.maxAbs = d; f.maxX = int(i % size_t(w)); f.maxY = int(i / size_t(w)); }
        ++f.pixels;
    }
    if (f.pixels == 0) return f;
    f.meanTest = sumT / double(f.pixels);
    f.meanRef = sumR / double(f.pixels);
    const double eps = std::max(0.01 * std::abs(f.meanRef), 1e-30);
    double mse = 0.0;
    for (size_t i = 0; i < lt.size(); ++i)
        if (counts(i)) {
            const double d = double(lt[i]) - lr[i];
            mse += d * d / (double(lr[i]) * lr[i] + eps * eps);
        }
    f.relMse = mse / double(f.pixels);
    f.relL1 = sumR > 0.0 ? sumAbs / sumR : 0.0;
    f.ratioOfMeans = sumR > 0.0 ? sumT / sumR : 0.0;
    double blockAbs = 0.0, blockRef = 0.0;
    for (int by = 0; by + 4 <= h; by += 4)
        for (int bx = 0; bx + 4 <= w; bx += 4) {
            double bt = 0.0, br = 0.0;
            bool whole = true;
            for (int y = by; y < by + 4 && whole; ++y)
                for (int x = bx; x < bx + 4; ++x) {
                    const size_t i = size_t(y) * w + x;
                    if (!counts(i)) { whole = false; break; }
                    bt += lt[i];
                    br += lr[i];
                }
            if (!whole) continue;
            blockAbs += std::abs(bt - br) / 16.0;
            blockRef += br / 16.0;
        }
    f.blockRelL1 = blockRef > 0.0 ? blockAbs / blockRef : 0.0;
    f.valid = true;
    return f;
}

FloatImage absDifference(const FloatImage& a, const FloatImage& b) {
    checkSizes(a, b);
    FloatImage d{a.width, a.height, 3, std::vector<float>(size_t(a.width) * a.height * 3)};
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i)
        for (int c = 0; c < 3; ++c) {
            const float va = a.pixels[i * a.channels + std::min(c, a.channels - 1)];
            const float vb = b.pixels[i * b.channels + std::min(c, b.channels - 1)];
            d.pixels[i * 3 + c] = std::abs(va - vb);
        }
    return d;
}

FloatImage relativeError(const FloatImage& test, const FloatImage& ref) {
    checkSizes(test, ref);
    const std::vector<float> lt = luminance(test), lr = luminance(ref);
    const float eps = float(std::max(0.01 * std::abs(meanFinite(lr)), 1e-30));
    FloatImage e{test.width, test.height, 1, std::vector<float>(lt.size())};
    for (size_t i = 0; i < lt.size(); ++i) e.pixels[i] = std::abs(lt[i] - lr[i]) / (std::abs(lr[i]) + eps);
    return e;
}

std::vector<std::array<float, 3>> heatPalette(int n) {
    n = std::max(n, 2);
    OIIO::ImageBuf ramp(OIIO::ImageSpec(n, 1, 1, OIIO::TypeDesc::FLOAT));
    for (int x = 0; x < n; ++x) {
        const float v = float(x) / float(n - 1);
        ramp.setpixel(x, 0, &v, 1);
    }
    OIIO::ImageBuf rgb = OIIO::ImageBufAlgo::color_map(ramp, 0, "inferno");
    std::vector<std::array<float, 3>> out(static_cast<size_t>(n));
    // OIIO's maps are linear values: encode them, so that the colours on screen and in PNGs are inferno's own.
    for (int x = 0; x < n; ++x) {
        rgb.getpixel(x, 0, out[size_t(x)].data(), 3);
        for (float& v : out[size_t(x)]) v = linearToSrgb(v);
    }
    return out;
}

FloatImage heatMap(const FloatImage& one, float scaleMax) {
    const std::vector<std::array<float, 3>> pal = heatPalette(256);
    FloatImage out{one.width, one.height, 3, std::vector<float>(size_t(one.width) * one.height * 3)};
    const float s = scaleMax > 0.0f ? scaleMax : 1.0f;
    for (size_t i = 0; i < size_t(one.width) * one.height; ++i) {
        const float v = one.pixels[i * one.channels];
        const float t = std::isfinite(v) ? std::clamp(v / s, 0.0f, 1.0f) : 1.0f;
        const auto& c = pal[size_t(std::lround(t * 255.0f))];
        for (int k = 0; k < 3; ++k) out.pixels[i * 3 + k] = c[size_t(k)];
    }
    return out;
}

void writeHeatMapPng(const std::string& path, const FloatImage& one, float scaleMax, const std::string& title) {
    const FloatImage heat = heatMap(one, scaleMax);
    const int w = std::max(heat.width, 260), legendH = 46, h = heat.height + legendH;
    OIIO::ImageBuf canvas(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT));
    const float bg[3] = {0.1f, 0.1f, 0.11f};
    OIIO::ImageBufAlgo::fill(canvas, bg);
    OIIO::ImageBuf img(OIIO::ImageSpec(heat.width, heat.height, 3, OIIO::TypeDesc::FLOAT), (void*)heat.pixels.data());
    OIIO::ImageBufAlgo::paste(canvas, 0, 0, 0, 0, img);
    // Legend: the colour bar, ticks at 0, 1/4, 1/2, 3/4 and 1 of the scale, labelled in percent.
    const int barX0 = 10, barX1 = w - 10, barY0 = heat.height + 6, barY1 = heat.height + 18;
    const std::vector<std::array<float, 3>> pal = heatPalette(256);
    for (int x = barX0; x < barX1; ++x) {
        const auto& c = pal[size_t(std::lround(255.0 * (x - barX0) / std::max(barX1 - barX0 - 1, 1)))];
        OIIO::ImageBufAlgo::fill(canvas, c.data(), OIIO::ROI(x, x + 1, barY0, barY1));
    }
    const std::string font = std::filesystem::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")
                                 ? "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
                                 : "";
    const float white[3] = {0.9f, 0.9f, 0.9f};
    for (int k = 0; k <= 4; ++k) {
        const int x = barX0 + (barX1 - barX0 - 1) * k / 4;
        OIIO::ImageBufAlgo::render_line(canvas, x, barY1, x, barY1 + 4, white);
        char label[32];
        std::snprintf(label, sizeof(label), "%s%g%%", k == 4 ? ">=" : "", double(scaleMax) * 100.0 * k / 4.0);
        const auto align = k == 0 ? OIIO::ImageBufAlgo::TextAlignX::Left
                         : k == 4 ? OIIO::ImageBufAlgo::TextAlignX::Right : OIIO::ImageBufAlgo::TextAlignX::Center;
        OIIO::ImageBufAlgo::render_text(canvas, x, barY1 + 16, label, 11, font, white, align);
    }
    OIIO::ImageBufAlgo::render_text(canvas, w / 2, h - 2, title, 11, font, white, OIIO::ImageBufAlgo::TextAlignX::Center);
    std::vector<unsigned char> px(size_t(w) * h * 3);
    std::vector<float> f(px.size());
    canvas.get_pixels(OIIO::ROI(0, w, 0, h, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, f.data());
    for (size_t i = 0; i < f.size(); ++i) px[i] = (unsigned char)std::lround(std::clamp(f[i], 0.0f, 1.0f) * 255.0f);
    writePng8(path, w, h, 3, px);
}

FloatImage downsampleBox(const FloatImage& img, int w, int h) {
    if (w <= 0 || h <= 0 || img.width <= 0 || img.height <= 0) throw std::invalid_argument("downsampleBox: empty size");
    if (w == img.width && h == img.height) return img;
    FloatImage out{w, h, img.channels, std::vector<float>(size_t(w) * h * img.channels, 0.0f)};
    const double sx = double(img.width) / w, sy = double(img.height) / h;
    for (int y = 0; y < h; ++y) {
        const double y0 = y * sy, y1 = (y + 1) * sy;
        for (int x = 0; x < w; ++x) {
            const double x0 = x * sx, x1 = (x + 1) * sx;
            double wsum = 0.0;
            std::vector<double> acc(size_t(img.channels), 0.0);
            for (int iy = int(y0); iy < std::min(int(std::ceil(y1)), img.height); ++iy) {
                const double wy = std::min(y1, iy + 1.0) - std::max(y0, double(iy));
                for (int ix = int(x0); ix < std::min(int(std::ceil(x1)), img.width); ++ix) {
                    const double wgt = wy * (std::min(x1, ix + 1.0) - std::max(x0, double(ix)));
                    if (wgt <= 0.0) continue;
                    for (int c = 0; c < img.channels; ++c) acc[size_t(c)] += wgt * img.at(ix, iy, c);
                    wsum += wgt;
                }
            }
            for (int c = 0; c < img.channels; ++c) out.at(x, y, c) = float(wsum > 0.0 ? acc[size_t(c)] / wsum : 0.0);
        }
    }
    return out;
}

}  // namespace deepgi
