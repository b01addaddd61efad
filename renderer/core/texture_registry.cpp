#include "renderer/core/texture_registry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unistd.h>

namespace deepgi {

void SizeRule::resolve(int screenW, int screenH, int shadowSize, int& w, int& h) const {
    int bw = base == Base::Screen ? screenW : base == Base::ShadowMap ? shadowSize : fixedWidth;
    int bh = base == Base::Screen ? screenH : base == Base::ShadowMap ? shadowSize : fixedHeight;
    w = (bw > 0 ? int(std::ceil(double(bw) * scale)) : 0) + 2 * margin;
    h = (bh > 0 ? int(std::ceil(double(bh) * scale)) : 0) + 2 * margin;
    if (bw <= 0 || bh <= 0) w = h = 0;  // a minimised screen has no guard band either
}

std::string SizeRule::describe() const {
    std::string s = base == Base::Screen ? "screen" : base == Base::ShadowMap ? "shadow map"
                                                    : std::to_string(fixedWidth) + "x" + std::to_string(fixedHeight);
    if (scale != 1.0f) {
        if (scale < 1.0f && std::abs(1.0f / scale - std::round(1.0f / scale)) < 1e-4f) s += "/" + std::to_string(int(std::round(1.0f / scale)));
        else s += " x" + std::to_string(scale);
    }
    if (margin != 0) s += " + " + std::to_string(margin) + " each side";
    return s;
}

static bool sameDecl(const TextureDecl& a, const TextureDecl& b) {
    return a.name == b.name && a.layerNames == b.layerNames && a.format == b.format && a.target == b.target &&
           a.size == b.size && a.levels == b.levels;
}

uint64_t textureBytes(const TextureDecl& d, int w, int h, int levels) {
    uint64_t bytes = 0;
    for (int l = 0; l < levels; ++l) {
        uint64_t lw = std::max(1, w >> l), lh = std::max(1, h >> l);
        bytes += lw * lh * uint64_t(d.layers()) * gl::formatBits(d.format) / 8;
    }
    return bytes;
}

uint64_t TextureRegistry::memoryBudget() const {
    if (budget_ > 0) return budget_;
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) / 2 : uint64_t(4) << 30;
}

static std::string mib(uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

void TextureRegistry::reconcile(const std::vector<TextureDecl>& decls, int screenW, int screenH, int shadowSize) {
    // Before any allocation: every texture within the implementation's size limits, all of them within the budget.
    GLint maxSize = 0, maxCube = 0, maxLayers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &maxCube);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    uint64_t total = 0;
    for (const auto& d : decls) {
        const bool cube = d.target == GL_TEXTURE_CUBE_MAP_ARRAY;
        int w = 0, h = 0;
        d.size.resolve(screenW, screenH, shadowSize, w, h);
        const int limit = cube ? maxCube : maxSize;
        if (limit > 0 && (w > limit || h > limit))
            throw std::runtime_error("cannot allocate texture '" + d.name + "' at " + std::to_string(w) + "x" +
                                     std::to_string(h) + ": larger than the " + (cube ? "GL_MAX_CUBE_MAP_TEXTURE_SIZE" : "GL_MAX_TEXTURE_SIZE") +
                                     " of this OpenGL implementation (" + std::to_string(limit) + ")");
        const int layers = d.layers() * (cube ? 6 : 1);
        if (d.target != GL_TEXTURE_2D && maxLayers > 0 && layers > maxLayers)
            throw std::runtime_error("cannot allocate texture '" + d.name + "' with " + std::to_string(layers) +
                                     " layers: more than GL_MAX_ARRAY_TEXTURE_LAYERS (" + std::to_string(maxLayers) + ")");
        if (w > 0 && h > 0) {
            const int levels = std::min(std::max(d.levels, 1), 1 + int(std::log2(double(std::max(w, h)))));
            total += textureBytes(d, w, h, levels) * (cube ? 6 : 1);
        }
    }
    if (total > memoryBudget())
        throw std::runtime_error("the textures for " + std::to_string(screenW) + "x" + std::to_string(screenH) +
                                 " (shadow maps " + std::to_string(shadowSize) + ") need " + mib(total) +
                                 ", more than the memory budget of " + mib(memoryBudget()) +
                                 (budget_ > 0 ? "" : " (half of the physical memory)") + "; use a smaller size");

    std::vector<Entry> next;
    next.reserve(decls.size());
    for (const auto& d : decls) {
        int w = 0, h = 0;
        d.size.resolve(screenW, screenH, shadowSize, w, h);
        if (w <= 0 || h <= 0) throw std::runtime_error("texture '" + d.name + "' would have size 0");
        auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.decl.name == d.name; });
        if (it != entries_.end() && it->texture && sameDecl(it->decl, d) && it->width == w && it->height == h) {
            it->decl.description = d.description;
            it->decl.vis = d.vis;
            it->decl.group = d.group;
            next.push_back(std::move(*it));
            continue;
        }
        ++generation_;
        Entry e;
        e.serial = generation_;
        e.decl = d;
        e.width = w;
        e.height = h;
        const int maxLevels = 1 + int(std::log2(double(std::max(w, h))));
        e.decl.levels = std::min(std::max(d.levels, 1), maxLevels);
        e.texture = gl::createTexture(d.target, d.name);
        const GLuint t = e.texture.id();
        while (glGetError() != GL_NO_ERROR) {}
        if (d.target == GL_TEXTURE_2D) glTextureStorage2D(t, e.decl.levels, d.format, w, h);
        else glTextureStorage3D(t, e.decl.levels, d.format, w, h, d.target == GL_TEXTURE_CUBE_MAP_ARRAY ? d.layers() * 6 : d.layers());
        if (GLenum err = glGetError(); err != GL_NO_ERROR)
            throw std::runtime_error("cannot allocate texture '" + d.name + "' (" + gl::formatName(d.format) + ", " +
                                     std::to_string(w) + "x" + std::to_string(h) + "): GL error " + std::to_string(err) +
                                     (err == GL_OUT_OF_MEMORY ? " (out of memory)" : ""));
        const bool depth = gl::isDepthFormat(d.format);
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, depth || e.decl.levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, depth ? GL_NEAREST : GL_LINEAR);
        if (d.vis == Visualize::ShadowDepth) {
            glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        }
        glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        next.push_back(std::move(e));
    }
    if (next.size() != entries_.size()) ++generation_;
    entries_ = std::move(next);  // textures no longer declared are released here
}

bool TextureRegistry::has(const std::string& name) const {
    return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.decl.name == name; });
}

const TextureRegistry::Entry& TextureRegistry::entry(const std::string& name) const {
    for (const auto& e : entries_) if (e.decl.name == name) return e;
    throw std::out_of_range("texture '" + name + "' is not declared in the registry");
}

GLuint TextureRegistry::id(const std::string& name) const { return entry(name).texture.id(); }

bool TextureRegistry::findLayer(const std::string& layerName, const Entry** out, int* layer) const {
    for (const auto& e : entries_) {
        for (int l = 0; l < e.decl.layers(); ++l)
            if (e.decl.layerNames[l] == layerName) { *out = &e; *layer = l; return true; }
        if (e.decl.name == layerName) { *out = &e; *layer = 0; return true; }
    }
    return false;
}

std::vector<std::string> TextureRegistry::layerNames() const {
    std::vector<std::string> names;
    for (const auto& e : entries_) for (const auto& l : e.decl.layerNames) names.push_back(l);
    return names;
}

MemoryReport TextureRegistry::memoryReport() const {
    MemoryReport r;
    for (const auto& e : entries_) {
        const TextureDecl& d = e.decl;
        const int bits = gl::formatBits(d.format);
        // Per screen pixel: a grid scaled by s holds s^2 texels per pixel (half resolution: a quarter of the bits).
        const bool screenGrid = d.size.base == SizeRule::Base::Screen && d.size.margin == 0;
        const int pixelBits = screenGrid ? int(std::lround(double(bits) * d.size.scale * d.size.scale)) : 0;
        const char* groupName = d.group == MemoryGroup::GBuffer ? "G-buffer" : d.group == MemoryGroup::Radiosity ? "radiosity"
                                : d.group == MemoryGroup::Scratch ? "scratch" : "extra";
        const int faces = d.target == GL_TEXTURE_CUBE_MAP_ARRAY ? 6 : 1;
        for (int l = 0; l < d.layers(); ++l) {
            MemoryLine line{d.layerNames[l], gl::formatName(d.format), groupName, pixelBits,
                            uint64_t(e.width) * e.height * bits / 8 * faces};
            r.lines.push_back(line);
        }
        if (e.decl.levels > 1) {
            uint64_t all = textureBytes(d, e.width, e.height, e.decl.levels) * faces;
            uint64_t base = textureBytes(d, e.width, e.height, 1) * faces;
            MemoryLine mips{d.name + " mips 1-" + std::to_string(e.decl.levels - 1), gl::formatName(d.format), "extra",
                            0, all - base};
            r.lines.push_back(mips);
        }
    }
    for (const auto& l : r.lines) {
        if (l.group == "G-buffer") { r.gbufferBitsPerPixel += l.bitsPerPixel; r.gbufferBytes += l.bytes; }
        else if (l.group == "radiosity") { r.radiosityBitsPerPixel += l.bitsPerPixel; r.radiosityBytes += l.bytes; }
        else if (l.group == "scratch") { r.scratchBitsPerPixel += l.bitsPerPixel; r.scratchBytes += l.bytes; }
        else { r.extraBitsPerPixel += l.bitsPerPixel; r.extraBytes += l.bytes; }
        r.totalBytes += l.bytes;
    }
    return r;
}

}  // namespace deepgi
