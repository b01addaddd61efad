// deepgi compare A.exr B.exr: the error figures of A against the reference B, and a false-colour heat map.
#include "app/command.h"
#include "renderer/core/image_compare.h"
#include "renderer/core/image_io.h"

#include <cstdio>
#include <memory>
#include <stdexcept>

namespace deepgi {
namespace {

struct CompareArgs {
    std::string test, ref, out;
    float scale = 1.0f;
};

int runCompare(const CompareArgs& a) {
    const FloatImage t = readImage(a.test), r = readImage(a.ref);
    if (t.width != r.width || t.height != r.height)
        throw std::runtime_error("compare: " + a.test + " is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                 " but " + a.ref + " is " + std::to_string(r.width) + "x" + std::to_string(r.height));
    const ImageFigures f = compareImages(t, r);
    if (!f.valid) throw std::runtime_error("compare: no finite pixel pair in " + a.test + " and " + a.ref);
    std::printf("compare %s against %s (%dx%d, %zu pixels, Rec.709 luminance)\n", a.test.c_str(), a.ref.c_str(), t.width,
                t.height, f.pixels);
    std::printf("relMSE %.6g\n", f.relMse);
    std::printf("relative L1 %.6g\n", f.relL1);
    std::printf("relative L1 (4x4 blocks) %.6g\n", f.blockRelL1);
    std::printf("ratio of means %.6g\n", f.ratioOfMeans);
    std::printf("max |dL| %.6g at (%d, %d)\n", f.maxAbs, f.maxX, f.maxY);
    std::printf("mean L %.6g (A), %.6g (B)\n", f.meanTest, f.meanRef);
    if (!a.out.empty()) {
        writeHeatMapPng(a.out, relativeError(t, r), a.scale, "relative error of luminance, A vs B");
        std::printf("wrote %s (relative error, 0 .. %g%%)\n", a.out.c_str(), double(a.scale) * 100.0);
    }
    return 0;
}

const CommandRegistrar kCompare(
    "compare", "Error figures of an image against a reference (relMSE, relative L1, ratio of means, max) and a heat map", 45,
    [](CLI::App& sub) -> std::function<int()> {
        auto a = std::make_shared<CompareArgs>();
        sub.add_option("A", a->test, "Image to judge (EXR or any format OpenImageIO reads; linear values)")->required();
        sub.add_option("B", a->ref, "Reference image of the same size")->required();
        sub.add_option("--out", a->out, "Write the relative-error heat map with its legend to this PNG");
        sub.add_option("--scale", a->scale, "Relative error at the top of the heat map's scale (1 = 100%)")
            ->capture_default_str()
            ->check(CLI::Range(1e-6, 1e6));
        return [a] { return runCompare(*a); };
    });

}  // namespace
}  // namespace deepgi
