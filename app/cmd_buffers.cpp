// deepgi buffers: the texture registry with bits per pixel and bytes, and the totals.
#include "app/command.h"
#include "app/options.h"
#include "renderer/gl/headless_context.h"
#include "renderer/renderer.h"
#include "renderer/scene/scene_gpu.h"
#include "renderer/scene/scene_loader.h"

#include <algorithm>
#include <cstdio>

namespace deepgi {
namespace {

CommandRegistrar registrar("buffers", "List every texture the renderer allocates, with bits per pixel and bytes", 20, [](CLI::App& sub) {
    auto scenePath = std::make_shared<std::string>();
    auto size = std::make_shared<std::string>("1280x720");
    auto settings = std::make_shared<SettingsOptions>();
    sub.add_option("scene", *scenePath, "glTF/glb or OBJ file (default: the atrium); the scene decides emission and shadow buffers");
    sub.add_option("--size", *size, "Screen size WxH")->capture_default_str();
    settings->add(sub);
    return [scenePath, size, settings]() {
        int w = 0, h = 0;
        parseSize(*size, w, h);
        const Settings s = settings->build();
        auto scene = std::make_shared<Scene>(loadScene(scenePath->empty() ? defaultScenePath() : *scenePath, withLoadProgress(gltfLoadOptions(s), *scenePath)));
        gl::HeadlessContext context;
        Renderer renderer;
        renderer.setScene(scene);
        renderer.resize(w, h);
        renderer.prepare(s);
        const MemoryReport r = renderer.textures().memoryReport();
        std::printf("%-28s %-20s %-10s %8s %14s\n", "buffer", "format", "counts in", "bits/px", "bytes");
        for (const auto& l : r.lines)
            std::printf("%-28s %-20s %-10s %8s %14llu\n", l.name.c_str(), l.format.c_str(), l.group.c_str(),
                        l.bitsPerPixel ? std::to_string(l.bitsPerPixel).c_str() : "-", (unsigned long long)l.bytes);
        std::printf("\nG-buffer:  %d bits per pixel, %llu bytes at %dx%d\n", r.gbufferBitsPerPixel, (unsigned long long)r.gbufferBytes, w, h);
        std::printf("radiosity: %d bits per pixel, %llu bytes\n", r.radiosityBitsPerPixel, (unsigned long long)r.radiosityBytes);
        std::printf("extra:     %d bits per pixel (screen-sized) + mips and shadow maps, %llu bytes\n", r.extraBitsPerPixel,
                    (unsigned long long)r.extraBytes);
        std::printf("scratch:   %d bits per pixel (content lives inside one pass: the blur's and temporal blend's ping-pong), %llu bytes\n",
                    r.scratchBitsPerPixel, (unsigned long long)r.scratchBytes);
        std::printf("total:     %llu bytes (%.1f MiB)\n", (unsigned long long)r.totalBytes, r.totalBytes / 1048576.0);
        // The scene on the GPU as SceneGpu uploads it: its vertex, part-index, index and object buffers, one RGBA8
        // texture with its full mip chain per Scene::textures entry.
        const uint64_t geometryBytes = SceneGpu::geometryBytes(*scene);
        uint64_t textureBytes = 0;
        for (const auto& t : scene->textures) {
            if (t.image < 0 || t.image >= int(scene->images.size())) continue;
            for (int w = scene->images[size_t(t.image)].width, h = scene->images[size_t(t.image)].height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
                textureBytes += uint64_t(w) * uint64_t(h) * 4;
                if (w == 1 && h == 1) break;
            }
        }
        std::printf("scene geometry: %llu bytes (%.1f MiB), %zu triangles\n", (unsigned long long)geometryBytes,
                    geometryBytes / 1048576.0, scene->triangleCount());
        std::printf("scene textures: %llu bytes (%.1f MiB), %zu textures with mipmaps\n", (unsigned long long)textureBytes,
                    textureBytes / 1048576.0, scene->textures.size());
        std::printf("scene load peak: %llu bytes (%.1f MiB) of a load.memory_budget of %d MiB\n",
                    (unsigned long long)scene->loadPeakBytes, scene->loadPeakBytes / 1048576.0, s.loadMemoryBudget);
        return 0;
    };
});

CommandRegistrar settingsRegistrar("settings", "List every setting with default, range, unit and effect", 30, [](CLI::App& sub) {
    return []() {
        std::string group;
        for (const auto& s : settingTable()) {
            if (group != s.group) std::printf("\n[%s]\n", (group = s.group).c_str());
            std::string range = s.type == SettingType::Enum ? "" : formatSettingValue(s, s.min) + ".." + formatSettingValue(s, s.max);
            if (s.type == SettingType::Enum) for (const auto& c : s.choices) range += (range.empty() ? "" : "|") + c;
            if (s.type == SettingType::Bool) range = "true|false";
            std::printf("  %-28s = %-10s %-22s %-12s %s\n", s.key, formatSettingValue(s, s.def).c_str(), range.c_str(), s.unit, s.effect);
        }
        return 0;
    };
});

}  // namespace
}  // namespace deepgi
