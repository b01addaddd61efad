#pragma once
// The GI accuracy figures of ../shared/docs/gi-accuracy.md, on linear RGB FloatImages (first three channels):
// Rec.709 luminance, relative L1 over 4x4 block means, ratio of means, leak, furnace deviation, noise floor.
#include "renderer/core/image_io.h"

#include <vector>

namespace deepgi::bench {

// A single-channel image of doubles, row 0 at the top.
struct LumaImage {
    int width = 0, height = 0;
    std::vector<double> v;
};

// L = 0.2126 R + 0.7152 G + 0.0722 B per pixel.
LumaImage luminance(const FloatImage& img);
// Means over block x block tiles; a partial tile at the right or bottom edge is the mean of the pixels it has.
LumaImage blockMeans(const LumaImage& l, int block = 4);
// sum |L_test - L_ref| / sum L_ref over block means of luminance. NaN when sum L_ref is not positive (no
// reference light: the figure is undefined). Throws std::invalid_argument on a size mismatch.
double relativeL1(const FloatImage& test, const FloatImage& ref, int block = 4);
// mean L_test / mean L_ref (NaN when mean L_ref is not positive).
double ratioOfMeans(const FloatImage& test, const FloatImage& ref);

// Mean and maximum luminance of an image whose true radiance is exactly 0 (the whole image).
struct Leak {
    double mean = 0.0, max = 0.0;
};
Leak leak(const FloatImage& img);

// Deviation of the luminance from an exact constant value, per pixel over the whole image (borders included).
struct Deviation {
    double maxRel = 0.0;   // max |L / exact - 1|
    double meanRel = 0.0;  // mean |L / exact - 1|
    double ratio = 0.0;    // mean L / exact
};
Deviation deviationFromConstant(const FloatImage& img, double exact);

// The reference's own noise floor from two renders at a quarter of its samples with different seeds: a perfect
// renderer scores about relativeL1(a, b) / sqrt(4 + 1) against the full reference.
double noiseFloor(const FloatImage& quarterA, const FloatImage& quarterB, int block = 4);

// A constant RGB image (grey) of the given size: the exact answer of the furnace.
FloatImage constantImage(int width, int height, float value);

}  // namespace deepgi::bench
