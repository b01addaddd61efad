#include "renderer/core/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepgi {

void writeExr(const std::string& path, const FloatImage& img) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": cannot create image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(img.width, img.height, img.channels, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, img.pixels.data()) || !out->close())
        throw std::runtime_error(path + ": cannot write EXR: " + out->geterror());
}

FloatImage readImage(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error(path + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    FloatImage img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    img.pixels.resize(size_t(img.width) * img.height * img.channels);
    if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
        throw std::runtime_error(path + ": cannot decode image: " + in->geterror());
    in->close();
    return img;
}

void writePng8(const std::string& path, int width, int height, int channels, const std::vector<unsigned char>& px) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": cannot create image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, px.data()) || !out->close())
        throw std::runtime_error(path + ": cannot write PNG: " + out->geterror());
}

float linearToSrgb(float v) {
    v = std::min(std::max(v, 0.0f), 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

std::vector<unsigned char> toSrgb8(const FloatImage& img, float exposureEV) {
    const float scale = std::exp2(exposureEV);
    const int outC = std::min(img.channels, 3);
    std::vector<unsigned char> px(size_t(img.width) * img.height * outC);
    for (size_t i = 0, n = size_t(img.width) * img.height; i < n; ++i)
        for (int c = 0; c < outC; ++c) {
            float v = img.pixels[i * img.channels + c] * scale;
            if (!std::isfinite(v)) v = 0.0f;
            px[i * outC + c] = (unsigned char)std::lround(linearToSrgb(v) * 255.0f);
        }
    return px;
}

}  // namespace deepgi
