#include "renderer/passes/environment_pass.h"

#include "renderer/scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace deepgi {

void EnvironmentPass::table(const PipelineConfig& c, PassTable& t) const {
    if (!c.environmentMap) return;
    const int w = std::max(1, c.environmentMapSize[0]), h = std::max(1, c.environmentMapSize[1]);
    const int levels = 1 + int(std::floor(std::log2(double(std::max(w, h)))));
    t.write({"Environment Map", {"Environment Map"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::fixed(w, h), levels,
             MemoryGroup::Extra, Visualize::Radiance,
             "The environment map (--environment), equirectangular: u = 0.5 + atan2(z, x) / 2pi, top row = +Y; "
             "radiance before environment.intensity, clamped to 65504 (half floats) for display only"});
}

void EnvironmentPass::execute(FrameContext& ctx) {
    const EnvironmentMap* map = ctx.environment;
    if (!map) return;
    if (map == uploadedMap_ && uploadedTextures_ == ctx.writtenTexturesKey()) return;
    const GLuint tex = ctx.texture("Environment Map");
    const auto& e = ctx.entry("Environment Map");
    if (e.width != map->width || e.height != map->height) return;  // the config follows the map on the next frame
    // Half floats: a sun brighter than 65504 would turn to infinity (and the composite's sanitize to black).
    std::vector<float> rgba(size_t(map->width) * map->height * 4, 1.0f);
    for (size_t i = 0; i < size_t(map->width) * map->height; ++i)
        for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = std::min(map->rgb[i * 3 + c], 65504.0f);
    GLint alignment = 4, rowLength = 0;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &rowLength);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    // Row 0 of the map is its top (the zenith); GL's row 0 is t = 0 in the shader, which reads t from the top too.
    glTextureSubImage2D(tex, 0, 0, 0, map->width, map->height, GL_RGBA, GL_FLOAT, rgba.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, rowLength);
    glGenerateTextureMipmap(tex);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    uploadedMap_ = map;
    uploadedTextures_ = ctx.writtenTexturesKey();
}

glm::vec4 environmentUniform(const FrameContext& ctx) {
    const EnvironmentSettings& s = ctx.settings;
    const float intensity = std::max(0.0f, s.environmentIntensity);
    return {std::max(0.0f, s.skyRadiance) * intensity, intensity, ctx.config.environmentMap ? 1.0f : 0.0f,
            glm::radians(s.environmentRotation)};
}

void readEnvironmentMap(const PipelineConfig& c, PassTable& t) {
    t.read("Environment Map", "uEnvironmentMap").optional(!c.environmentMap);
}

}  // namespace deepgi
