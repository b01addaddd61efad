#pragma once
// Comparing two linear images the way docs/gi-accuracy.md defines it: Rec.709 luminance, relative L1 on 4x4 block
// means, ratio of means; plus relative MSE and the largest difference. Shared by `deepgi compare`, the viewer's
// inspector and its "Path trace this view" figures. Also the error images and the false-colour scale they use.
#include "renderer/core/image_io.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace deepgi {

// Rec.709 luminance (0.2126 R + 0.7152 G + 0.0722 B) of linear RGB; a 1- or 2-channel image reads its first channel.
std::vector<float> luminance(const FloatImage& img);

struct ImageFigures {
    bool valid = false;
    size_t pixels = 0;          // compared (mask and non-finite values excluded)
    double relMse = 0.0;        // mean of (Lt - Lr)^2 / (Lr^2 + eps^2), eps = 1% of the mean reference luminance
    double relL1 = 0.0;         // sum |Lt - Lr| / sum Lr, per pixel
    double blockRelL1 = 0.0;    // the same on 4x4 block means of both images (gi-accuracy.md's "relative L1")
    double ratioOfMeans = 0.0;  // mean Lt / mean Lr
    double maxAbs = 0.0;        // max |Lt - Lr|
    int maxX = 0, maxY = 0;     // where (row 0 = top)
    double meanTest = 0.0, meanRef = 0.0;
    // "rel L1 (4x4) 3.1%  ratio of means 0.982  relMSE 0.0123  max |dL| 0.5 at (x, y)" for a figures line.
    std::string line() const;
};

// Figures of `test` against `ref` (same size; throws std::invalid_argument naming both sizes otherwise). Texels
// where mask is 0 (mask: width*height, may be empty = all) or either image is not finite are left out; a 4x4 block
// counts only if all its texels count. Blocks are whole: the last width%4 columns and height%4 rows are left out
// of the block figure.
ImageFigures compareImages(const FloatImage& test, const FloatImage& ref, const std::vector<uint8_t>& mask = {});

// |a - b| per channel (first three), and the relative luminance error |Lt - Lr| / (Lr + eps) as one channel with
// eps = 1% of the mean reference luminance (so that black reference pixels do not blow up).
FloatImage absDifference(const FloatImage& a, const FloatImage& b);
FloatImage relativeError(const FloatImage& test, const FloatImage& ref);

// The false-colour scale of error views (OpenImageIO's "inferno"): n display (sRGB-encoded) colours from 0 to 1.
std::vector<std::array<float, 3>> heatPalette(int n = 256);
// Maps a one-channel image through the palette, 0 .. scaleMax (values above are the last colour): display RGB 0..1.
FloatImage heatMap(const FloatImage& oneChannel, float scaleMax);
// Writes the heat map as a PNG with a legend strip below it (colour bar and its labelled ticks, drawn with
// OpenImageIO), titled `title`. Throws std::runtime_error naming the file.
void writeHeatMapPng(const std::string& path, const FloatImage& oneChannel, float scaleMax, const std::string& title);

// Box-filtered resize to w x h (area average with fractional coverage): for comparing a frame with a smaller
// reference of the same view.
FloatImage downsampleBox(const FloatImage& img, int w, int h);

}  // namespace deepgi
