// The pass tables (issue 8): the rules the renderer checks when it builds the pipeline, the order it derives, the
// bindings it makes, and the typed programs' uniform checks. Small fake passes state one broken rule each.
#include "gl_fixture.h"

#include "renderer/passes/composite_pass.h"
#include "renderer/passes/deep_gbuffer_pass.h"
#include "renderer/passes/pass_graph.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sys/wait.h>
#include <unistd.h>

using namespace deepgi;
using namespace deepgi::test;

// Every test of this binary runs with strict program checks (a uniform or sampler mistake throws, as in debug
// builds); the deepgi binary itself only warns in release builds.
static const bool kStrictPrograms = [] {
    gl::setProgramChecks(gl::ProgramChecks::Throw);
    return true;
}();

namespace {

TextureDecl screenTexture(const std::string& name) {
    return {name, {name}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra, Visualize::Radiance, "test"};
}

PassInfo pass(const std::string& name, const std::function<void(PassTable&)>& fill) {
    PassInfo p;
    p.name = name;
    fill(p.table);
    return p;
}

std::vector<std::string> names(const std::vector<PassInfo>& passes, const std::vector<size_t>& order) {
    std::vector<std::string> out;
    for (size_t i : order) out.push_back(passes[i].name);
    return out;
}

std::string scheduleError(const std::vector<PassInfo>& passes) {
    try {
        schedulePasses(passes);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::vector<PassInfo> standardTables(const PipelineConfig& c) {
    std::vector<PassInfo> out;
    for (const auto& p : Renderer::standardPasses()) {
        PassInfo info;
        info.name = p->name();
        p->table(c, info.table);
        info.enabled = p->enabled(c);
        out.push_back(std::move(info));
    }
    return out;
}

}  // namespace

TEST(PassTable, ReadOfATextureNoPassWritesIsAnErrorNamingPassAndTexture) {
    const std::vector<PassInfo> passes = {pass("Producer", [](PassTable& t) { t.write(screenTexture("A")); }),
                                          pass("Consumer", [](PassTable& t) { t.read("A"); t.read("Missing", "uMissing"); })};
    const std::string e = scheduleError(passes);
    EXPECT_TRUE(contains(e, "'Consumer'") && contains(e, "'Missing'") && contains(e, "no earlier pass writes")) << e;
    // The same read declared optional is allowed (the pass works without it).
    std::vector<PassInfo> optional = passes;
    optional[1] = pass("Consumer", [](PassTable& t) { t.read("A"); t.read("Missing", "uMissing").optional(); });
    EXPECT_EQ(scheduleError(optional), "");
    // A writer that is disabled in this pipeline does not count.
    std::vector<PassInfo> disabled = passes;
    disabled[1] = pass("Consumer", [](PassTable& t) { t.read("A"); });
    disabled[0].enabled = false;
    EXPECT_TRUE(contains(scheduleError(disabled), "'Consumer' reads 'A'")) << scheduleError(disabled);
}

TEST(PassTable, TwoWritersOfOneTextureAreAnError) {
    const std::vector<PassInfo> passes = {pass("First", [](PassTable& t) { t.write(screenTexture("A")); }),
                                          pass("Second", [](PassTable& t) { t.write(screenTexture("A")); })};
    const std::string e = scheduleError(passes);
    EXPECT_TRUE(contains(e, "'First'") && contains(e, "'Second'") && contains(e, "both write 'A'")) << e;
    EXPECT_THROW(allocations(passes), std::runtime_error) << "two declarations of one texture";
}

TEST(PassTable, UpdatesNeedAWriterAndAnOrder) {
    const std::string noWriter = scheduleError({pass("Filter", [](PassTable& t) { t.update("A"); })});
    EXPECT_TRUE(contains(noWriter, "'Filter' updates 'A', which no pass")) << noWriter;

    auto pipeline = [](const std::string& blurAfter, const std::string& temporalAfter) {
        return std::vector<PassInfo>{
            pass("Gather", [](PassTable& t) { t.write(screenTexture("E")); }),
            pass("Blur", [&](PassTable& t) { t.update("E").after(blurAfter); }),
            pass("Temporal", [&](PassTable& t) { t.update("E").after(temporalAfter); }),
            pass("Composite", [](PassTable& t) { t.read("E"); t.write(screenTexture("Final")); })};
    };
    const std::string unordered = scheduleError(pipeline("", ""));
    EXPECT_TRUE(contains(unordered, "'Blur'") && contains(unordered, "'Temporal'") && contains(unordered, "without an order")) << unordered;
    // after() decides the order of the updates; every reader runs after all of them.
    auto p1 = pipeline("", "Blur"), p2 = pipeline("Temporal", "");
    EXPECT_EQ(names(p1, schedulePasses(p1)), (std::vector<std::string>{"Gather", "Blur", "Temporal", "Composite"}));
    EXPECT_EQ(names(p2, schedulePasses(p2)), (std::vector<std::string>{"Gather", "Temporal", "Blur", "Composite"}));
    // after() naming a pass that does not update the texture, or no pass at all.
    EXPECT_TRUE(contains(scheduleError(pipeline("Gather", "")), "after 'Gather', which does not update it"));
    EXPECT_TRUE(contains(scheduleError(pipeline("Gahter", "")), "'Gahter', which is not a pass"));
}

TEST(PassTable, OrderIsTopologicalFromTheTables) {
    // Listed in the wrong order on purpose: the tables put the reader of last frame's E before E's writer and the
    // consumer after it.
    const std::vector<PassInfo> passes = {
        pass("Consumer", [](PassTable& t) { t.read("E"); t.read("H"); }),
        pass("Writer", [](PassTable& t) { t.write(screenTexture("E")); }),
        pass("Reprojector", [](PassTable& t) { t.history("E"); t.write(screenTexture("H")); })};
    EXPECT_EQ(names(passes, schedulePasses(passes)), (std::vector<std::string>{"Reprojector", "Writer", "Consumer"}));
    // A cycle is an error naming the passes in it.
    const std::string cycle = scheduleError({pass("A", [](PassTable& t) { t.read("Y"); t.write(screenTexture("X")); }),
                                             pass("B", [](PassTable& t) { t.read("X"); t.write(screenTexture("Y")); })});
    EXPECT_TRUE(contains(cycle, "cycle") && contains(cycle, "'A'") && contains(cycle, "'B'")) << cycle;
}

TEST(PassTable, ScratchIsPrivateToThePassesThatDeclareIt) {
    const std::string e = scheduleError({pass("Blur", [](PassTable& t) { t.scratch(screenTexture("S")); }),
                                         pass("Spy", [](PassTable& t) { t.read("S"); })});
    EXPECT_TRUE(contains(e, "'Spy' reads 'S', which is scratch of pass 'Blur'")) << e;
    // Two passes may share one scratch texture if they declare it alike; it is allocated once, as scratch.
    const std::vector<PassInfo> shared = {pass("Blur", [](PassTable& t) { t.scratch(screenTexture("S")); }),
                                          pass("Temporal", [](PassTable& t) { t.scratch(screenTexture("S")); })};
    EXPECT_EQ(scheduleError(shared), "");
    const auto decls = allocations(shared);
    ASSERT_EQ(decls.size(), 1u);
    EXPECT_EQ(decls[0].group, MemoryGroup::Scratch);
}

// Every pipeline the settings can build schedules without a rule broken, blur and temporal blend in the order of
// temporal.order (formerly a dynamic_cast swap in Renderer::render).
TEST(PassTable, EveryStandardPipelineIsValid) {
    int checked = 0;
    for (int bits = 0; bits < 256; ++bits) {
        PipelineConfig c;
        c.layer2 = bits & 1;
        c.emission = bits & 2;
        c.indirect = bits & 4;
        c.seedComposite = bits & 8;
        c.blur = bits & 16;
        c.temporal = bits & 32;
        c.temporalFirst = (bits & 64) && c.temporal;
        c.ao = bits & 128;
        c.depthPeel = c.layer2 && (bits % 3 == 0);
        c.shadowMapLayers = bits % 2;
        c.shadowCubeLayers = (bits / 2) % 2;
        const auto passes = standardTables(c);
        std::vector<size_t> order;
        ASSERT_NO_THROW(order = schedulePasses(passes)) << "config bits " << bits << ": " << scheduleError(passes);
        const auto n = names(passes, order);
        auto at = [&](const char* p) { return std::find(n.begin(), n.end(), p) - n.begin(); };
        EXPECT_EQ(n.back(), "Composite");
        if (c.indirect && c.blur && c.temporal)
            EXPECT_EQ(at("Temporal blend") < at("Bilateral blur"), c.temporalFirst) << "bits " << bits;
        if (c.indirect) EXPECT_LT(at("Reproject radiance"), at("Radiosity gather"));
        ++checked;
    }
    EXPECT_EQ(checked, 256);
}

// ---- The same rules through a real Renderer, with fake passes ------------------------------------------------

namespace {

// A pass over composite.frag whose table and program are given by the test.
class FakeCompositePass final : public RenderPass {
public:
    using Table = std::function<void(PassTable&)>;
    using Run = std::function<void(FrameContext&, gl::ShaderLibrary&)>;
    FakeCompositePass(Table table, Run run) : table_(std::move(table)), run_(std::move(run)) {}
    const char* name() const override { return "Fake"; }
    void table(const PipelineConfig&, PassTable& t) const override { table_(t); }
    void execute(FrameContext& ctx) override { run_(ctx, ctx.shaders); }

private:
    Table table_;
    Run run_;
};

struct CompositeProgram : gl::Program {
    using gl::Program::Program;
    gl::Uniform<float> exposure{*this, "uExposure"};
};
struct MisspeltProgram : gl::Program {
    using gl::Program::Program;
    gl::Uniform<float> exposure{*this, "uExposur"};
};

const gl::ProgramDesc kComposite{"fullscreen.vert", "", "composite.frag", "", {}};

// Renders one frame of a pipeline of the deep G-buffer and `fake`; returns the error message ("" if none).
std::string renderWith(std::unique_ptr<RenderPass> fake) {
    std::vector<std::unique_ptr<RenderPass>> passes;
    passes.push_back(std::make_unique<DeepGBufferPass>());
    passes.push_back(std::move(fake));
    Renderer r(RendererOptions{}, std::move(passes));
    auto scene = cornellScene();
    r.setScene(scene);
    r.resize(32, 24);
    r.setCamera(selectCamera(*scene, "front"));
    try {
        r.render(Settings{});
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

void fullComposite(PassTable& t) {
    t.read("Depth", "uDepth");
    t.read("Albedo", "uAlbedo");
    t.read("Normal", "uNormal");
    t.read("Emission", "uEmission").optional();
    t.read("Input Radiance", "uRadiance").optional();
    t.read("Output Radiance", "uIndirect").optional();
    t.read("Radiosity Geometry", "uGeometry").optional();
    readShadowMaps(t);  // the composite evaluates layer 1's direct light
    t.write({"Fake Output", {"Fake Output"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra, Visualize::Radiance, ""});
}

}  // namespace

TEST_F(GLTest, TableRulesFailAtPipelineBuildWithPassAndTexture) {
    // Missing writer: the composite alone reads the G-buffer that nothing writes.
    std::vector<std::unique_ptr<RenderPass>> passes;
    passes.push_back(std::make_unique<CompositePass>());
    Renderer r(RendererOptions{}, std::move(passes));
    r.resize(16, 16);
    try {
        r.prepare(Settings{});
        ADD_FAILURE() << "a pipeline without the G-buffer pass was built";
    } catch (const std::runtime_error& e) {
        const std::string m = e.what();
        EXPECT_TRUE(contains(m, "pass 'Composite' reads '") && contains(m, "', which no earlier pass writes")) << m;
        EXPECT_TRUE(contains(m, "'Depth'") || contains(m, "'Albedo'") || contains(m, "'Normal'")) << m;
    }
}

TEST_F(GLTest, ShaderSamplingATextureOutsideTheTableIsAnError) {
    // The table leaves out Albedo, which composite.frag samples (uAlbedo): an undeclared read.
    const std::string e = renderWith(std::make_unique<FakeCompositePass>(
        [](PassTable& t) {
            t.read("Depth", "uDepth");
            t.read("Normal", "uNormal");
            t.read("Emission", "uEmission").optional();
            t.read("Input Radiance", "uRadiance").optional();
            t.read("Output Radiance", "uIndirect").optional();
            readShadowMaps(t);
            t.write({"Fake Output", {"Fake Output"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra, Visualize::Radiance, ""});
        },
        [program = std::make_shared<gl::ProgramSlot<CompositeProgram>>()](FrameContext& ctx, gl::ShaderLibrary& lib) {
            ctx.bindSamplers(program->get(lib, kComposite));
        }));
    EXPECT_TRUE(contains(e, "pass 'Fake'") && contains(e, "composite.frag") && contains(e, "'uAlbedo'") && contains(e, "undeclared read")) << e;
}

TEST_F(GLTest, PassUsingATextureOutsideItsTableIsAnError) {
    const std::string e = renderWith(std::make_unique<FakeCompositePass>(
        fullComposite, [](FrameContext& ctx, gl::ShaderLibrary&) { ctx.texture("Last Depth"); }));
    EXPECT_TRUE(contains(e, "pass 'Fake' uses texture 'Last Depth', which its table does not declare")) << e;
}

TEST_F(GLTest, MisspeltUniformIsAnErrorNamingProgramAndUniform) {
    auto program = std::make_shared<gl::ProgramSlot<MisspeltProgram>>();
    const std::string e = renderWith(std::make_unique<FakeCompositePass>(
        fullComposite, [program](FrameContext& ctx, gl::ShaderLibrary& lib) { program->get(lib, kComposite); }));
    EXPECT_TRUE(contains(e, "program 'composite.frag' has no uniform 'uExposur'")) << e;
    // The correct name passes, and so does the whole fake pipeline.
    auto good = std::make_shared<gl::ProgramSlot<CompositeProgram>>();
    EXPECT_EQ(renderWith(std::make_unique<FakeCompositePass>(fullComposite, [good](FrameContext& ctx, gl::ShaderLibrary& lib) {
                  ctx.bindSamplers(good->get(lib, kComposite));
              })),
              "");
}

// Every standard program variant links with every uniform its class names (strict checks are on here): layer 2
// off (DEEPGI_SINGLE_LAYER), depth peeling, temporal_first, the seed composite, AO, emission and point lights.
TEST_F(GLTest, EveryProgramVariantHasTheUniformsItsClassNames) {
    auto scene = cornellScene();
    scene->materials[0].emissiveFactor = glm::vec3(0.5f);
    Light bulb;
    bulb.type = LightType::Point;
    bulb.position = glm::vec3(0.0f, 1.5f, 0.0f);
    scene->lights.push_back(bulb);
    for (const char* set : {"gbuffer.layer2=false", "gbuffer.generation=depth_peel", "temporal.order=temporal_first",
                            "composite.mode=seed", "ao.enabled=true", "radiosity.enabled=false"}) {
        auto r = rendererFor(scene, 32, 24, "front");
        Settings s;
        applyAssignment(s, set);
        EXPECT_NO_THROW(for (int i = 0; i < 2; ++i) r->render(s)) << set;
    }
}

// "Input Radiance 2" holds layer 2's input radiance after a whole frame (the blur and the temporal blend have their
// own scratch now): re-running the input-radiance pass alone reproduces it, up to the stores' stochastic rounding.
// Layer 2 is evaluated at the gather's finest tap level (radiosity.min_mip): that level is compared.
TEST_F(GLTest, InputRadiance2HoldsLayer2AfterTheFrame) {
    auto scene = cornellScene();
    Light bulb;  // lights the surfaces behind layer 1 too
    bulb.type = LightType::Point;
    bulb.position = glm::vec3(0.0f, 1.0f, 0.0f);
    bulb.intensity = 2.0f;
    scene->lights.push_back(bulb);
    auto r = rendererFor(scene, 64, 48, "front");
    Settings s;
    s.radius = 1.5f;
    s.minSeparation = 0.2f;
    for (int i = 0; i < 3; ++i) r->render(s);
    const FloatImage after = r->readLayer("Input Radiance 2", s.minMip);
    r->executePass("Input radiance", s);
    const FloatImage again = r->readLayer("Input Radiance 2", s.minMip);
    EXPECT_EQ(again.width, 64 >> s.minMip);
    double sum = 0.0, diff = 0.0;
    for (size_t i = 0; i < after.pixels.size(); ++i) {
        sum += std::abs(again.pixels[i]);
        diff += std::abs(after.pixels[i] - again.pixels[i]);
    }
    ASSERT_GT(sum, 0.0) << "layer 2 sees lit surfaces in this view";
    EXPECT_LT(diff / sum, 0.02) << "Input Radiance 2 was overwritten after the input-radiance pass";
    // The scratch is its own texture and reported as such.
    bool scratch = false;
    for (const auto& l : r->textures().memoryReport().lines)
        if (l.name == "Radiosity Scratch") scratch = l.group == "scratch";
    EXPECT_TRUE(scratch);
}

// Every texture the pipeline declares has a format the memory report and the read-back know: a name, its bits
// (the report's sums) and its channels (a depth format reads back as one). A format missing from renderer/gl's
// tables showed as "?" with 0 bytes (Gather Mask, Object ID) and read back as zeros.
TEST_F(GLTest, EveryDeclaredFormatIsKnown) {
    RendererOptions o;
    o.sceneEditing = true;  // Object ID and Motion too
    Renderer r(o);
    r.setScene(cornellScene());
    r.resize(64, 48);
    r.setCamera(selectCamera(r.scene(), "front"));
    Settings s;
    s.interleave = RadiosityInterleave::Four;  // Gather Mask
    s.aoEnabled = true;
    r.render(s);
    int checked = 0;
    for (const auto& e : r.textures().entries()) {
        ++checked;
        EXPECT_STRNE(gl::formatName(e.decl.format), "?") << e.decl.name;
        EXPECT_GT(gl::formatBits(e.decl.format), 0) << e.decl.name;
        if (gl::isDepthFormat(e.decl.format)) EXPECT_EQ(gl::formatChannels(e.decl.format), 1) << e.decl.name;
    }
    EXPECT_GT(checked, 20);
}

// Renderer::graph(): the default pipeline in execution order with what each pass reads and writes.
TEST_F(GLTest, GraphListsThePipelineInOrder) {
    auto scene = cornellScene();
    auto r = rendererFor(scene, 32, 24, "front");
    Settings s;
    r->prepare(s);
    const auto g = r->graph();
    std::vector<std::string> order;
    for (const auto& n : g) order.push_back(n.name + (n.enabled ? "" : " (off)"));
    EXPECT_EQ(order, (std::vector<std::string>{"Shadow maps", "Environment (off)", "Deep G-buffer", "Reproject radiance", "Probe update", "Input radiance",
                                               "Gather select", "Radiosity gather", "Ambient occlusion (off)", "Bilateral blur",
                                               "Temporal blend", "Composite"}));
    // On llvmpipe radiosity.interleave=auto interleaves: the selection gives the reused blocks the reprojected
    // history and masks them out of the gather, which updates the rest.
    const auto& select = g[6];
    EXPECT_EQ(select.reads, (std::vector<std::string>{"Depth", "Normal", "History Weight", "Reprojected Radiance"}));
    EXPECT_EQ(select.writes, (std::vector<std::string>{"Gather Mask", "Output Radiance", "Gather Coverage", "Radiosity Geometry"}));
    const auto& gather = g[7];
    EXPECT_EQ(gather.reads, (std::vector<std::string>{"Depth", "Normal", "Input Radiance", "Probe Irradiance", "Probe Depth", "Probe Data", "Probe Radiance", "Output Radiance", "Gather Coverage", "Gather Mask"}));
    EXPECT_EQ(gather.writes, (std::vector<std::string>{"Output Radiance", "Gather Coverage"}));
    // Units are distinct within a pass and never the material textures' 0 and 1.
    for (const auto& n : g) {
        std::vector<int> units;
        for (const auto& c : n.channels) if (c.unit >= 0) units.push_back(c.unit);
        std::sort(units.begin(), units.end());
        EXPECT_TRUE(std::adjacent_find(units.begin(), units.end()) == units.end()) << n.name;
        if (!units.empty()) EXPECT_GE(units.front(), 2) << n.name;
    }
    applyAssignment(s, "temporal.order=temporal_first");
    r->prepare(s);
    const auto g2 = r->graph();
    EXPECT_EQ(g2[9].name, "Temporal blend");
    EXPECT_EQ(g2[10].name, "Bilateral blur");
}

// `deepgi graph`: the default scene's pipeline in order with its textures, temporal_first reorders, --dot writes a
// Graphviz digraph with every pass and texture, a broken --set is a clear error.
TEST(GraphCli, PrintsThePipelineAndWritesGraphviz) {
    auto run = [](const std::string& args, std::string& out) {
        const std::string cmd = std::string(DEEPGI_BINARY) + " graph " + args + " 2>&1";
        FILE* p = popen(cmd.c_str(), "r");
        if (!p) return -1;
        char buf[4096];
        size_t n;
        out.clear();
        while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
        const int st = pclose(p);
        return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    };
    const std::string dot = ::testing::TempDir() + "deepgi_graph_" + std::to_string(::getpid()) + ".dot";
    std::string out;
    ASSERT_EQ(run("--size 64x48 --dot '" + dot + "'", out), 0) << out;
    for (const char* part : {" 1. Shadow maps", " 2. Deep G-buffer", " 4. Probe update", " 6. Gather select", " 7. Radiosity gather", "10. Composite",
                             "Ambient occlusion (disabled", "Radiosity Scratch", "R11F_G11F_B10F  64x48 (screen)", "uRadiance@"})
        EXPECT_TRUE(contains(out, part)) << part << "\n" << out;
    EXPECT_LT(out.find("Bilateral blur"), out.find("Temporal blend"));
    std::ifstream f(dot);
    const std::string text((std::istreambuf_iterator<char>(f)), {});
    EXPECT_EQ(text.rfind("// deepgi graph", 0), 0u);
    for (const char* part : {"digraph deepgi {", "\"pass:Composite\"", "\"tex:Output Radiance\"", "\"pass:Radiosity gather\" -> \"tex:Output Radiance\""})
        EXPECT_TRUE(contains(text, part)) << part;
    std::remove(dot.c_str());
    ASSERT_EQ(run("--size 64x48 --set temporal.order=temporal_first", out), 0) << out;
    EXPECT_GT(out.find("Bilateral blur"), out.find("Temporal blend"));
    EXPECT_TRUE(contains(out, "Temporal History"));
    EXPECT_NE(run("--set no.such=1", out), 0);
    EXPECT_TRUE(contains(out, "no.such")) << out;
}

// The enum class of each DEEPGI_ENUM setting lists its choices in the order of the choice string in settings.def.
TEST(SettingsGroups, EnumChoicesMatchTheirEnumerators) {
    Settings s;
    applyAssignment(s, "gbuffer.generation=depth_peel");
    EXPECT_EQ(s.generation, GBufferGeneration::DepthPeel);
    applyAssignment(s, "temporal.order=temporal_first");
    EXPECT_EQ(s.filterOrder, FilterOrder::TemporalFirst);
    applyAssignment(s, "composite.mode=seed");
    EXPECT_EQ(s.compositeMode, CompositeMode::Seed);
    applyAssignment(s, "composite.tonemap=aces");
    EXPECT_EQ(s.tonemap, Tonemap::Aces);
    // A pass sees its stage's group as a plain struct of the same values.
    const BlurSettings& blur = s;
    applyAssignment(s, "blur.radius=3");
    EXPECT_EQ(blur.blurRadius, 3);
    EXPECT_EQ(formatSettingValue(*findSetting("composite.mode"), double(int(CompositeMode::Physical))), "physical");
}
