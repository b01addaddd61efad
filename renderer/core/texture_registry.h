#pragma once
// Every texture the renderer allocates is declared here once: name, format, size rule, description and how to
// visualise it. The memory report, `--buffers` dumps, screenshots, the inspector and the tests read this registry.
#include "renderer/gl/gl.h"

#include <cstdint>
#include <string>
#include <vector>

namespace deepgi {

// How a texture's level-0 size follows the frame: a base (the screen, the shadow-map size or a fixed size), times
// `scale`, plus `margin` texels on every side (a guard band). Extensible by kind without touching the passes.
struct SizeRule {
    enum class Base { Screen, ShadowMap, Fixed };
    Base base = Base::Screen;
    float scale = 1.0f;   // of the base size (0.5 = half resolution), rounded up
    int margin = 0;       // texels added on each side
    int fixedWidth = 0, fixedHeight = 0;  // Base::Fixed only

    static SizeRule screen(float scale = 1.0f, int margin = 0) { return {Base::Screen, scale, margin, 0, 0}; }
    static SizeRule shadowMap() { return {Base::ShadowMap, 1.0f, 0, 0, 0}; }
    static SizeRule fixed(int w, int h) { return {Base::Fixed, 1.0f, 0, w, h}; }
    // Level-0 size for a screen of screenW x screenH and shadow maps of shadowSize.
    void resolve(int screenW, int screenH, int shadowSize, int& w, int& h) const;
    bool screenSized() const { return base == Base::Screen && scale == 1.0f && margin == 0; }
    std::string describe() const;  // "screen", "screen/2 + 16", "shadow map", "256x256"
    bool operator==(const SizeRule& o) const {
        return base == o.base && scale == o.scale && margin == o.margin && fixedWidth == o.fixedWidth && fixedHeight == o.fixedHeight;
    }
    bool operator!=(const SizeRule& o) const { return !(*this == o); }
};
// Color: linear [0,1] colour (albedo); Display: already sRGB-encoded for the screen.
enum class Visualize { Color, Radiance, Depth, Normal, ShadowDepth, Display, ObjectId };  // ObjectId: R32UI, a colour per id
// Which total a texture counts towards in the memory report.
// Scratch: content that lives only inside one pass (ping-pong targets); never a frame's result.
enum class MemoryGroup { GBuffer, Radiosity, Extra, Scratch };

struct TextureDecl {
    std::string name;                     // unique, e.g. "Depth"
    std::vector<std::string> layerNames;  // one per layer, e.g. {"Depth 1", "Depth 2"}; size = layer count
    GLenum format = GL_RGBA8;
    GLenum target = GL_TEXTURE_2D;        // GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY or GL_TEXTURE_CUBE_MAP_ARRAY
    SizeRule size = SizeRule::screen();
    int levels = 1;
    MemoryGroup group = MemoryGroup::Extra;
    Visualize vis = Visualize::Color;
    std::string description;
    int layers() const { return int(layerNames.size()); }
};

struct MemoryLine {
    std::string name, format, group;
    int bitsPerPixel = 0;  // per screen pixel (0 for shadow maps, which are not screen-sized)
    uint64_t bytes = 0;
};

struct MemoryReport {
    std::vector<MemoryLine> lines;
    int gbufferBitsPerPixel = 0, radiosityBitsPerPixel = 0, extraBitsPerPixel = 0, scratchBitsPerPixel = 0;
    uint64_t gbufferBytes = 0, radiosityBytes = 0, extraBytes = 0, scratchBytes = 0, totalBytes = 0;
};

class TextureRegistry {
public:
    struct Entry {
        TextureDecl decl;
        gl::TextureHandle texture;
        int width = 0, height = 0;  // of level 0
        // Which allocation this is: no other texture this registry creates gets the same number, so a pass that
        // fills a texture once and keeps it (shadow maps, probe atlases) knows whether it still holds its content.
        uint64_t serial = 0;
    };

    // Replaces the declaration set: textures whose declaration is unchanged and whose size still fits are kept
    // (their content survives), the others are (re)created. Throws std::runtime_error on allocation failure.
    void reconcile(const std::vector<TextureDecl>& decls, int screenW, int screenH, int shadowSize);

    bool has(const std::string& name) const;
    GLuint id(const std::string& name) const;  // throws std::out_of_range naming the texture if it is not declared
    const Entry& entry(const std::string& name) const;
    const std::vector<Entry>& entries() const { return entries_; }

    // Finds "Depth 2" -> (entry "Depth", layer 1), or a texture name -> layer 0.
    bool findLayer(const std::string& layerName, const Entry** entry, int* layer) const;
    std::vector<std::string> layerNames() const;  // every viewable layer, in declaration order

    MemoryReport memoryReport() const;
    // The most bytes the declared textures may need together; 0 (default) = half of the physical memory. Checked
    // with GL_MAX_TEXTURE_SIZE before anything is allocated: a size too large is a clear std::runtime_error,
    // never a driver that tries (llvmpipe keeps textures in system memory and would take it all).
    void setMemoryBudget(uint64_t bytes) { budget_ = bytes; }
    uint64_t memoryBudget() const;
    // Changes whenever a texture is created or released (framebuffers that attach textures must be rebuilt); a
    // texture kept through a reconcile() keeps its Entry::serial.
    uint64_t generation() const { return generation_; }

private:
    std::vector<Entry> entries_;
    uint64_t generation_ = 1;
    uint64_t budget_ = 0;
};

uint64_t textureBytes(const TextureDecl& d, int w, int h, int levels);

}  // namespace deepgi
