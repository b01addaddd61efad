#include "bench/draw.h"

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepgi::bench::draw {

namespace {
// Found by OIIO in /usr/share/fonts (fonts-dejavu-core, see tools/install-deps.sh).
const char* kFont = "DejaVuSans";
}  // namespace

OIIO::ImageBuf canvas(int width, int height, Colour background) {
    OIIO::ImageBuf b(OIIO::ImageSpec(std::max(width, 1), std::max(height, 1), 3, OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::fill(b, background);
    return b;
}

void text(OIIO::ImageBuf& dst, int x, int y, const std::string& s, Colour c, int size) {
    if (s.empty()) return;
    if (!OIIO::ImageBufAlgo::render_text(dst, x, y + size, s, size, kFont, c, OIIO::ImageBufAlgo::TextAlignX::Left,
                                         OIIO::ImageBufAlgo::TextAlignY::Baseline))
        throw std::runtime_error("bench: cannot draw text with font " + std::string(kFont) + " (install fonts-dejavu-core): " +
                                 dst.geterror());
}

int textWidth(const std::string& s, int size) {
    const OIIO::ROI r = OIIO::ImageBufAlgo::text_size(s, size, kFont);
    return r.defined() ? r.width() : int(s.size()) * size / 2;
}

void line(OIIO::ImageBuf& dst, int x0, int y0, int x1, int y1, Colour c) {
    OIIO::ImageBufAlgo::render_line(dst, x0, y0, x1, y1, c, true);
}

void box(OIIO::ImageBuf& dst, int x0, int y0, int x1, int y1, Colour c, bool fill) {
    OIIO::ImageBufAlgo::render_box(dst, x0, y0, x1, y1, c, fill);
}

void paste(OIIO::ImageBuf& dst, int x, int y, const OIIO::ImageBuf& src) {
    OIIO::ImageBufAlgo::paste(dst, x, y, 0, 0, src);
}

OIIO::ImageBuf display(const FloatImage& linear, float scale) {
    OIIO::ImageBuf b(OIIO::ImageSpec(linear.width, linear.height, 3, OIIO::TypeDesc::FLOAT));
    std::vector<float> px(size_t(linear.width) * linear.height * 3);
    for (size_t i = 0; i < size_t(linear.width) * linear.height; ++i)
        for (int c = 0; c < 3; ++c) px[i * 3 + c] = linearToSrgb(std::clamp(linear.pixels[i * linear.channels + c] * scale, 0.0f, 1.0f));
    b.set_pixels(b.roi(), OIIO::TypeDesc::FLOAT, px.data());
    return b;
}

OIIO::ImageBuf heat(const std::vector<float>& values, int width, int height) {
    OIIO::ImageBuf v(OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::FLOAT));
    std::vector<float> px(values.size());
    for (size_t i = 0; i < px.size(); ++i) px[i] = std::isfinite(values[i]) ? std::clamp(values[i], 0.0f, 1.0f) : 1.0f;
    v.set_pixels(v.roi(), OIIO::TypeDesc::FLOAT, px.data());
    return OIIO::ImageBufAlgo::color_map(v, 0, "inferno");
}

void savePng(const OIIO::ImageBuf& img, const std::string& path) {
    if (!img.write(path, OIIO::TypeDesc::UINT8)) throw std::runtime_error("bench: cannot write " + path + ": " + img.geterror());
}

}  // namespace deepgi::bench::draw
