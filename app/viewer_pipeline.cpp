// The Pipeline panel's graph, filled from Renderer::graph() (the pass tables, in execution order) and timings().
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

namespace deepgi {

namespace {
// Settings that shape each pass (settings.def keys by prefix): shown when the pass is clicked.
std::vector<std::string> settingKeysOf(const std::string& pass) {
    static const std::vector<std::pair<std::string, std::string>> prefix = {
        {"Shadow maps", "light."}, {"Probe update", "probes."}, {"Deep G-buffer", "gbuffer."}, {"Input radiance", "radiosity.bounce_damping"},
        {"Gather select", "radiosity.interleave"}, {"Radiosity gather", "radiosity."}, {"Ambient occlusion", "ao."}, {"Bilateral blur", "blur."},
        {"Temporal blend", "temporal."}, {"Reproject radiance", "temporal."}, {"Composite", "composite."}};
    std::vector<std::string> keys;
    for (const auto& [name, p] : prefix)
        if (name == pass)
            for (const auto& info : settingTable())
                if (std::string(info.key).rfind(p, 0) == 0) keys.push_back(info.key);
    return keys;
}
}  // namespace

ui::PipelineGraph pipelineGraph(const Renderer& renderer, const Settings&) {
    ui::PipelineGraph g;
    for (const auto& node : renderer.graph()) {  // the pass tables, in execution order
        ui::PipelineNode n;
        n.name = node.name;
        n.reads = node.reads;
        n.writes = node.writes;
        n.enabled = node.enabled;
        for (const auto& t : renderer.timings())
            if (t.name == n.name) n.ms = t.ms;
        n.settingKeys = settingKeysOf(n.name);
        g.passes.push_back(std::move(n));
    }
    return g;
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
