#pragma once
// Float and 8-bit image files through OpenImageIO. Rows are stored top-down in memory.
#include <string>
#include <vector>

namespace deepgi {

struct FloatImage {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;  // width*height*channels, row 0 = top
    float& at(int x, int y, int c) { return pixels[(size_t(y) * width + x) * channels + c]; }
    float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
};

// Throws std::runtime_error naming the file on failure.
void writeExr(const std::string& path, const FloatImage& img);
FloatImage readImage(const std::string& path);  // any format OIIO reads, as float (8-bit PNG -> [0,1], sRGB not decoded)
void writePng8(const std::string& path, int width, int height, int channels, const std::vector<unsigned char>& px);

// Display transforms shared by the CLI and the reference: exposure, then sRGB encoding of clamped values.
float linearToSrgb(float v);
float srgbToLinear(float v);
std::vector<unsigned char> toSrgb8(const FloatImage& img, float exposureEV = 0.0f);

}  // namespace deepgi
