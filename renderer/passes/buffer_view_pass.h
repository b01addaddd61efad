#pragma once
// Display of any texture for the viewer and its inspector: a chosen layer/level, a window of texels (zoom and pan,
// nearest filtering, texel grid), channel, exposure, range, linearised depth, decoded normals, NaN/Inf/negative
// highlights and a vertical A/B split. Draws into its own RGBA8 texture (display-encoded), which the UI shows.
// Not a pipeline pass: it owns its output texture (one per BufferViewPass), which is therefore not in the registry
// and never in screenshots of "every buffer". Also: small-region readback for the pixel readout.
#include "renderer/core/image_io.h"
#include "renderer/core/texture_registry.h"
#include "renderer/gl/gl.h"
#include "renderer/gl/shader_library.h"

#include <glm/glm.hpp>
#include <memory>
#include <string>

namespace deepgi::gl {
template <class P> class ProgramSlot;
}

namespace deepgi {

// One layer of one texture, as the buffer view reads it.
struct BufferSource {
    GLuint texture = 0;
    GLenum target = GL_TEXTURE_2D;  // GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY or GL_TEXTURE_CUBE_MAP_ARRAY
    GLenum format = GL_RGBA8;
    int layer = 0;                  // array layer (cube arrays: the cube, shown as 6 faces side by side)
    int level = 0;
    int levels = 1;
    int width = 0, height = 0;      // of level 0 (one face for cubes)
    Visualize vis = Visualize::Color;
    bool valid() const { return texture != 0 && width > 0 && height > 0; }
    // Size of `level` as displayed (cube: 6 faces wide).
    int levelWidth() const;
    int levelHeight() const;
};

// Looks `layerName` up in the registry ("Depth 2", "Final Display", ...). Returns an invalid source if absent.
BufferSource bufferSource(const TextureRegistry& registry, const std::string& layerName, int level = 0);

enum class ViewChannel { RGB = 0, R, G, B, A, Luminance };
enum class ViewMode { Auto = 0, Raw, Radiance, Depth, Normal };  // Auto follows the texture's Visualize

struct BufferViewParams {
    ViewChannel channel = ViewChannel::RGB;
    ViewMode mode = ViewMode::Auto;
    float exposureEV = 0.0f;              // radiance: scale 2^EV before sRGB encoding
    float rangeMin = 0.0f, rangeMax = 1.0f;
    bool useRange = false;                // map [rangeMin, rangeMax] to [0, 1] (depth: auto near..far when off)
    bool highlight = true;                // NaN magenta, +Inf/-Inf yellow/cyan, negative blue tint
    // Visible texel window: texel coordinates (level-0 texels of the displayed level, origin bottom-left) of the
    // output's bottom-left corner, and texels per output pixel.
    glm::vec2 origin{0.0f};
    float texelsPerPixel = 1.0f;
    bool grid = true;                     // texel grid when a texel covers >= 8 output pixels
    glm::vec4 background{0.12f, 0.12f, 0.13f, 1.0f};  // outside the texture
    // Camera clip planes, for linear depth.
    float znear = 0.05f, zfar = 100.0f;
    bool perspective = true;
    // A/B: output pixels with x >= splitX (0..1 of the output width) show source B.
    float splitX = 0.5f;
    // Texels of source A's guard band on each side (Renderer::guardTexels): B spans A's centre, not all of it.
    glm::vec2 cropA{0.0f};
};

// Raw (or decoded) values of a small block of texels, for the readout under the cursor.
struct TexelBlock {
    int x0 = 0, y0 = 0, width = 0, height = 0, channels = 0;  // texel coordinates, origin bottom-left
    std::vector<float> values;                                // width*height*channels, row 0 = y0
    float at(int x, int y, int c) const { return values[(size_t(y - y0) * width + (x - x0)) * channels + c]; }
    bool contains(int x, int y) const { return x >= x0 && y >= y0 && x < x0 + width && y < y0 + height; }
};

class BufferViewPass {
public:
    BufferViewPass();
    ~BufferViewPass();
    // Draws `a` (and `b` right of the split, if valid) into the output texture of outW x outH.
    // Throws gl::ShaderError if buffer_view.frag has never compiled.
    void draw(gl::ShaderLibrary& shaders, const BufferSource& a, const BufferSource* b, const BufferViewParams& p,
              int outW, int outH);
    GLuint texture() const { return out_.id(); }
    int width() const { return outW_; }
    int height() const { return outH_; }

    // Reads texels [x0, x0+w) x [y0, y0+h) (clipped to the level) of a source, raw values (depth as stored,
    // normals as stored), without reading the rest of the texture.
    static TexelBlock readTexels(const BufferSource& s, int x0, int y0, int w, int h);

private:
    GLuint viewOf(const BufferSource& s);  // a 2D-array view of a cube-map array (cached)
    struct Program;
    std::unique_ptr<gl::ProgramSlot<Program>> program_;
    gl::TextureHandle out_;
    gl::FramebufferHandle fbo_;
    gl::VertexArrayHandle vao_;
    gl::SamplerHandle sampler_;  // no depth compare mode, nearest
    gl::TextureHandle cubeView_;
    GLuint cubeViewSource_ = 0;
    int outW_ = 0, outH_ = 0;
};

}  // namespace deepgi
