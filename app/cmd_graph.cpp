// deepgi graph: the pass pipeline that a scene and settings build, from the pass tables, in execution order, with
// every texture each pass reads and writes (size, format); --dot writes the same graph for Graphviz.
#include "app/command.h"
#include "app/options.h"
#include "renderer/gl/headless_context.h"
#include "renderer/renderer.h"
#include "renderer/scene/scene_loader.h"

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

namespace deepgi {
namespace {

std::string textureSummary(const Renderer& r, const std::string& name) {
    if (!r.textures().has(name)) return "(absent in this pipeline)";
    const auto& e = r.textures().entry(name);
    const TextureDecl& d = e.decl;
    std::ostringstream os;
    os << gl::formatName(d.format) << "  " << e.width << "x" << e.height << " (" << d.size.describe() << ")";
    if (d.target == GL_TEXTURE_CUBE_MAP_ARRAY) os << ", " << d.layers() << (d.layers() == 1 ? " cube" : " cubes");
    else if (d.target == GL_TEXTURE_2D_ARRAY) os << ", " << d.layers() << (d.layers() == 1 ? " layer" : " layers");
    if (d.levels > 1) os << ", " << d.levels << " mips";
    if (d.group == MemoryGroup::Scratch) os << ", scratch";
    return os.str();
}

std::string channelLabel(const PassGraphChannel& c) { return accessName(c.access); }

std::string textureLabel(const PassGraphChannel& c) {
    return c.texture + (c.levels == Levels::Base ? " [level 0]" : c.levels == Levels::Mips ? " [mips]" : "");
}

std::string dotEscape(const std::string& s) {
    std::string o;
    for (char ch : s) {
        if (ch == '"' || ch == '\\') o += '\\';
        o += ch;
    }
    return o;
}

void writeDot(const Renderer& r, const std::vector<PassGraphNode>& g, const std::string& path) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error(path + ": cannot write the Graphviz file");
    f << "// deepgi graph --dot: passes (boxes, in execution order) and textures (ellipses)\n";
    f << "digraph deepgi {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n  edge [fontname=\"Helvetica\", fontsize=9];\n";
    std::map<std::string, bool> textures;
    int step = 0;
    for (const auto& n : g) {
        const std::string label = n.enabled ? dotEscape(std::to_string(++step) + ". " + n.name) : dotEscape(n.name) + "\\n(disabled)";
        f << "  \"pass:" << dotEscape(n.name) << "\" [shape=box, style=\"" << (n.enabled ? "filled" : "dashed")
          << "\", fillcolor=\"#dde8f5\", label=\"" << label << "\"" << (n.enabled ? "" : ", color=gray, fontcolor=gray") << "];\n";
        for (const auto& c : n.channels) textures[c.texture] = textures[c.texture] || c.present;
    }
    for (const auto& [name, present] : textures) {
        std::string info = present ? textureSummary(r, name) : "absent";
        f << "  \"tex:" << dotEscape(name) << "\" [shape=ellipse, label=\"" << dotEscape(name) << "\\n" << dotEscape(info) << "\""
          << (present ? "" : ", style=dashed, color=gray, fontcolor=gray") << "];\n";
    }
    for (const auto& n : g) {
        const std::string p = "\"pass:" + dotEscape(n.name) + "\"", grey = n.enabled ? "" : ", color=gray";
        for (const auto& c : n.channels) {
            const std::string t = "\"tex:" + dotEscape(c.texture) + "\"";
            switch (c.access) {
            case Access::Read: f << "  " << t << " -> " << p << " [" << (c.optional ? "style=dashed, label=\"optional\"" : "style=solid") << grey << "];\n"; break;
            case Access::History: f << "  " << t << " -> " << p << " [style=dashed, label=\"last frame\", constraint=false" << grey << "];\n"; break;
            case Access::Write: f << "  " << p << " -> " << t << " [style=bold" << grey << "];\n"; break;
            case Access::Update: f << "  " << p << " -> " << t << " [dir=both, label=\"update\"" << grey << "];\n"; break;
            case Access::Scratch: f << "  " << p << " -> " << t << " [dir=both, style=dotted, label=\"scratch\"" << grey << "];\n"; break;
            }
        }
    }
    f << "}\n";
}

CommandRegistrar registrar("graph", "Print the pass pipeline a scene and settings build (order, reads, writes, texture sizes); --dot for Graphviz", 25, [](CLI::App& sub) {
    auto scenePath = std::make_shared<std::string>();
    auto size = std::make_shared<std::string>("1280x720");
    auto dot = std::make_shared<std::string>();
    auto settings = std::make_shared<SettingsOptions>();
    sub.add_option("scene", *scenePath, "glTF/glb or OBJ file (default: the atrium); the scene decides emission and shadow buffers");
    sub.add_option("--size", *size, "Screen size WxH")->capture_default_str();
    sub.add_option("--dot", *dot, "Also write the graph as a Graphviz file (render with: dot -Tsvg FILE -o graph.svg)");
    settings->add(sub);
    return [scenePath, size, dot, settings]() {
        int w = 0, h = 0;
        parseSize(*size, w, h);
        const Settings s = settings->build();
        const std::string path = scenePath->empty() ? defaultScenePath() : *scenePath;
        auto scene = std::make_shared<Scene>(loadScene(path));
        gl::HeadlessContext context;
        Renderer renderer;
        renderer.setScene(scene);
        renderer.resize(w, h);
        renderer.prepare(s);  // builds and checks the pipeline from the pass tables
        const std::vector<PassGraphNode> g = renderer.graph();
        int enabled = 0;
        for (const auto& n : g) enabled += n.enabled;
        std::printf("pipeline of %s at %dx%d: %d of %zu passes run, in this order\n", path.c_str(), w, h, enabled, g.size());
        int step = 0;
        for (const auto& n : g) {
            if (n.enabled) std::printf("\n%2d. %s\n", ++step, n.name.c_str());
            else std::printf("\n    %s (disabled by these settings)\n", n.name.c_str());
            for (const auto& c : n.channels) {
                std::string sampler = c.sampler.empty() ? "" : c.sampler + "@" + std::to_string(c.unit);
                std::printf("      %-19s %-32s %-17s %s%s\n", channelLabel(c).c_str(), textureLabel(c).c_str(), sampler.c_str(),
                            c.present ? textureSummary(renderer, c.texture).c_str() : "(absent)",
                            c.optional ? " [optional]" : "");
            }
        }
        if (!dot->empty()) {
            writeDot(renderer, g, *dot);
            std::printf("\nGraphviz: %s\n", dot->c_str());
        }
        return 0;
    };
});

}  // namespace
}  // namespace deepgi
