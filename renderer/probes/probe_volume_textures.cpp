// The GL side of ProbeVolume: texture descriptions, the uniform block, uploads.
#include "renderer/probes/probe_volume.h"

#include <string>

namespace deepgi {

std::vector<ProbeTextureDesc> ProbeVolume::textures() const {
    const int irrW = tilesPerRow_ * (irrN_ + 2), irrH = tileRows_ * (irrN_ + 2);
    const int depW = tilesPerRow_ * (depthN_ + 2), depH = tileRows_ * (depthN_ + 2);
    return {
        {"Probe Irradiance", GL_RGBA32F, GL_RGBA, irrW, irrH, 4, irradiance_.data(),
         "Irradiance (W/m^2) per octahedral direction of each probe, " + std::to_string(irrN_) + "x" +
             std::to_string(irrN_) + " texels + 1-texel border per tile"},
        {"Probe Depth", GL_RG32F, GL_RG, depW, depH, 2, depth_.data(),
         "Mean distance and mean squared distance (scene units) to the first surface per octahedral direction, " +
             std::to_string(depthN_) + "x" + std::to_string(depthN_) + " texels + border per tile"},
        {"Probe Data", GL_RGBA32F, GL_RGBA, tilesPerRow_, tileRows_, 4, data_.data(),
         "Per probe: xyz = offset from its grid position (scene units), w = state (1 active, 0 inside geometry, "
         "-1 unused)"},
        {"Probe Radiance", GL_RGBA32F, GL_RGBA, tilesPerRow_ * (radN_ + 2), tileRows_ * (radN_ + 2), 4, radiance_.data(),
         "Radiance arriving at each probe per octahedral direction (rgb; a = mean distance to the surfaces its rays hit), " +
             std::to_string(radN_) + "x" + std::to_string(radN_) + " texels + border per tile"},
    };
}

ProbeTextureDesc ProbeVolume::skyTexture() const {
    return {"Probe Sky Irradiance", GL_RGBA32F, GL_RGBA, tilesPerRow_ * (irrN_ + 2), tileRows_ * (irrN_ + 2), 4,
            sky_.data(),
            "Irradiance (W/m^2) from the environment per octahedral direction of each probe: its rays that leave the "
            "scene, laid out as Probe Irradiance"};
}

void ProbeVolume::uploadSkyTexture(GLuint skyTex, bool all) const {
    if (!skyTex || sky_.empty()) return;
    const int lo = all || !uploadedOnce_ ? 0 : dirtyRowLo_, hi = all || !uploadedOnce_ ? tileRows_ : dirtyRowHi_;
    if (lo >= hi) return;
    const ProbeTextureDesc d = skyTexture();
    const int texelsPerTileRow = d.height / tileRows_;
    GLint alignment = 4, rowLength = 0;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &rowLength);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTextureSubImage2D(skyTex, 0, 0, lo * texelsPerTileRow, d.width, (hi - lo) * texelsPerTileRow, GL_RGBA, GL_FLOAT,
                        d.data + size_t(lo) * texelsPerTileRow * d.width * 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, rowLength);
}

ProbeVolumeUniforms ProbeVolume::uniforms() const {
    ProbeVolumeUniforms u{};
    for (int a = 0; a < 3; ++a) {
        u.lo[a] = grid_.lo[a];
        u.spacing[a] = grid_.spacing[a];
        u.counts[a] = grid_.counts[a];
    }
    u.bias[0] = normalBias_;
    u.bias[1] = viewBias_;
    u.spacing[3] = converging() ? 0.0f : 1.0f;
    u.counts[3] = tilesPerRow_;
    u.texels[0] = irrN_;
    u.texels[1] = depthN_;
    u.texels[2] = activeProbeCount();
    u.texels[3] = radN_;
    return u;
}

void ProbeVolume::uploadTextures(GLuint irradianceTex, GLuint depthTex, GLuint dataTex, GLuint radianceTex, bool all) {
    if (all || !uploadedOnce_) {
        dirtyRowLo_ = 0;
        dirtyRowHi_ = tileRows_;
    }
    GLint alignment = 4, rowLength = 0, skipRows = 0, skipPixels = 0;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &rowLength);
    glGetIntegerv(GL_UNPACK_SKIP_ROWS, &skipRows);
    glGetIntegerv(GL_UNPACK_SKIP_PIXELS, &skipPixels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    const std::vector<ProbeTextureDesc> descs = textures();
    const GLuint ids[4] = {irradianceTex, depthTex, dataTex, radianceTex};
    if (dirtyRowLo_ < dirtyRowHi_)
        for (int t = 0; t < 4; ++t) {
            if (!ids[t]) continue;
            const ProbeTextureDesc& d = descs[t];
            const int texelsPerTileRow = d.height / tileRows_;
            const int y0 = dirtyRowLo_ * texelsPerTileRow, rows = (dirtyRowHi_ - dirtyRowLo_) * texelsPerTileRow;
            glTextureSubImage2D(ids[t], 0, 0, y0, d.width, rows, d.uploadFormat, GL_FLOAT,
                                d.data + size_t(y0) * d.width * d.channels);
        }
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, rowLength);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, skipRows);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, skipPixels);
    dirtyRowLo_ = dirtyRowHi_ = 0;
    uploadedOnce_ = true;
}

void ProbeVolume::uploadUniforms(GLuint uniformBuffer) const {
    const ProbeVolumeUniforms u = uniforms();
    glNamedBufferSubData(uniformBuffer, 0, sizeof u, &u);
}

}  // namespace deepgi
