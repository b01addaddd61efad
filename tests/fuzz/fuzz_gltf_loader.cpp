// libFuzzer target for the glTF loader: the input is written to a temp file (.glb when it starts with the GLB
// magic's first byte 'g', .gltf otherwise) and loaded. Loading may fail, but only with SceneLoadError.
#include "renderer/scene/gltf_loader.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() / ("deepgi_fuzz_" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const std::filesystem::path file = dir / (size > 0 && data[0] == 'g' ? "input.glb" : "input.gltf");
    {
        std::ofstream f(file, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    deepgi::GltfLoadOptions options;
    options.maxElements = 1u << 20;     // keep allocations well under libFuzzer's RSS limit
    options.maxImagePixels = 1u << 22;
    options.memoryBudget = uint64_t(256) << 20;  // the budget check itself is fuzzed, under -rss_limit_mb=2048
    options.maxTextureSize = 256;                // and the downscale path with it
    try {
        deepgi::Scene scene = deepgi::loadGltf(file.string(), options);
        (void)scene;
    } catch (const deepgi::SceneLoadError&) {
    }
    std::error_code ec;
    std::filesystem::remove(file, ec);
    return 0;
}
