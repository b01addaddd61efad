#pragma once
// Drawing for the bench's plots and image grids, on OpenImageIO ImageBufs (3-channel float, values 0..1 in
// display space) with ImageBufAlgo: text (DejaVu Sans, package fonts-dejavu-core), lines, boxes, colour maps.
#include "renderer/core/image_io.h"

#include <OpenImageIO/imagebuf.h>

#include <array>
#include <string>

namespace deepgi::bench::draw {

using Colour = std::array<float, 3>;  // display RGB in [0, 1]

// A w x h canvas filled with `background`.
OIIO::ImageBuf canvas(int width, int height, Colour background = {1.0f, 1.0f, 1.0f});
// Text with its top-left corner near (x, y), `size` pixels high. Throws std::runtime_error when no font is found.
void text(OIIO::ImageBuf& dst, int x, int y, const std::string& s, Colour c = {0, 0, 0}, int size = 12);
int textWidth(const std::string& s, int size = 12);
void line(OIIO::ImageBuf& dst, int x0, int y0, int x1, int y1, Colour c);
void box(OIIO::ImageBuf& dst, int x0, int y0, int x1, int y1, Colour c, bool fill = false);  // inclusive corners
// Copies src with its top-left corner at (x, y).
void paste(OIIO::ImageBuf& dst, int x, int y, const OIIO::ImageBuf& src);
// A linear RGB image shown as sRGB after multiplying by `scale` (clamped to [0, 1]).
OIIO::ImageBuf display(const FloatImage& linear, float scale = 1.0f);
// A single-channel image (values in [0, 1], clamped) through the "inferno" colour map: black 0, yellow 1.
OIIO::ImageBuf heat(const std::vector<float>& values, int width, int height);
// Writes an 8-bit PNG; throws std::runtime_error naming the file on failure.
void savePng(const OIIO::ImageBuf& img, const std::string& path);

}  // namespace deepgi::bench::draw
