#pragma once
// Image error metrics and the Pareto front for `deepgi bench`. Images are linear RGB FloatImages (only the first
// three channels are read); a and b must have the same size.
#include "renderer/core/image_io.h"

#include <vector>

namespace deepgi::bench {

// Relative MSE: mean over pixels and channels of (a - r)^2 / (r^2 + eps).
double relativeMse(const FloatImage& a, const FloatImage& ref, double eps = 1e-2);
// Mean relative error: mean over pixels and channels of |a - r| / (|r| + eps).
double meanRelativeError(const FloatImage& a, const FloatImage& ref, double eps = 1e-2);
// Display luminance: sRGB encoding of the clamped linear channels, then Rec.709 weights (values in [0,1]).
std::vector<float> displayLuminance(const FloatImage& img);
// Mean SSIM of two single-channel images in [0,1] (w x h), 7x7 uniform windows (clamped at the borders),
// C1 = 0.01^2, C2 = 0.03^2.
double ssim(const std::vector<float>& a, const std::vector<float>& b, int w, int h);
// SSIM of the tone-mapped (sRGB, clamped) luminance of two linear images.
double ssimDisplay(const FloatImage& a, const FloatImage& ref);
// a - b per channel (first three channels), as a 3-channel image.
FloatImage subtract(const FloatImage& a, const FloatImage& b);
// The first three channels of img (missing ones 0).
FloatImage rgb(const FloatImage& img);
// Channels first .. first + count - 1 of img as a new image (the parts of a stacked EXR).
FloatImage channelRange(const FloatImage& img, int first, int count = 3);
// The RGB of each part side by side in the channels (3 per part): one EXR for final, direct and indirect.
FloatImage stackRgb(const std::vector<const FloatImage*>& parts);
// Mean |a - b| over pixels and channels divided by the mean |b| (0 if b is black): frame-to-frame change.
double relativeChange(const FloatImage& a, const FloatImage& b);

struct Point2 {
    double x, y;  // both minimised (time, error)
};
// Indices of the points not dominated by another (x' <= x and y' <= y, one strictly), sorted by x.
std::vector<int> paretoFront(const std::vector<Point2>& points);

}  // namespace deepgi::bench
