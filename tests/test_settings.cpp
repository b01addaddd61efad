#include "renderer/core/settings.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <functional>

using namespace deepgi;

TEST(Settings, DefaultsMatchDeclaration) {
    Settings s;
    for (const auto& info : settingTable()) {
        EXPECT_EQ(info.get(s), info.def) << info.key;
        EXPECT_LE(info.min, info.def) << info.key;
        EXPECT_GE(info.max, info.def) << info.key;
        EXPECT_STRNE(info.effect, "") << info.key;
    }
}

TEST(Settings, AssignmentParsesAndRejects) {
    Settings s;
    applyAssignment(s, "radiosity.samples=30");
    EXPECT_EQ(s.numSamples, 30);
    applyAssignment(s, "gbuffer.generation=depth_peel");
    EXPECT_EQ(s.generation, GBufferGeneration::DepthPeel);
    applyAssignment(s, "blur.enabled=off");
    EXPECT_FALSE(s.blur);
    EXPECT_THROW(applyAssignment(s, "radiosity.samples=abc"), std::runtime_error);
    EXPECT_THROW(applyAssignment(s, "no.such=1"), std::runtime_error);
    EXPECT_THROW(applyAssignment(s, "gbuffer.generation=magic"), std::runtime_error);
    EXPECT_THROW(applyAssignment(s, "radiosity.radius=nan"), std::runtime_error);
}

TEST(Settings, JsonRoundTripAndPresets) {
    Settings a;
    a.radius = 2.5f;
    a.filterOrder = FilterOrder::TemporalFirst;
    a.layer2 = false;
    Settings b;
    applySettingsJson(b, settingsToJson(a), "test");
    EXPECT_TRUE(a == b);
    for (const auto& p : presetNames()) {
        Settings s;
        applyPreset(s, p);
        EXPECT_GE(s.numSamples, 1) << p;
    }
    Settings q;
    applyPreset(q, "quality");
    EXPECT_EQ(q.numSamples, 30);
    EXPECT_EQ(q.visibilitySteps, 8);
    EXPECT_EQ(q.radiosityResolution, RadiosityResolution::Auto);  // chosen on the hard suite (BENCHMARKS sessions 11, 14)
    EXPECT_EQ(q.interleave, RadiosityInterleave::Off);
    Settings perf;
    applyPreset(perf, "performance");
    EXPECT_EQ(perf.radiosityResolution, RadiosityResolution::Quarter);  // the fastest at every height (BENCHMARKS session 26)
    EXPECT_THROW(applySettingsJson(q, nlohmann::json{{"blur.enabled", 3}}, "x.json"), std::runtime_error);
}

namespace {
std::string errorOf(const std::function<void()>& f) {
    try { f(); } catch (const std::runtime_error& e) { return e.what(); }
    return "";
}
}  // namespace

// silent clamp: every out-of-range value the audit tried is an error naming key, value and range, at --set and in
// a --settings file; the viewer's saved state clamps with a warning instead.
TEST(Settings, OutOfRangeIsAnErrorNamingKeyValueAndRange) {
    const std::vector<std::string> bad = {"radiosity.samples=0", "radiosity.samples=1000", "temporal.alpha=1",
                                          "light.sun_intensity=-1", "blur.radius=7", "radiosity.min_mip=-1",
                                          "composite.exposure=17", "light.shadow_map_size=32", "blur.step=0",
                                          "radiosity.bounce_damping=1.5", "load.memory_budget=1"};
    for (const auto& kv : bad) {
        Settings s;
        const std::string msg = errorOf([&] { applyAssignment(s, kv); });
        const std::string key = kv.substr(0, kv.find('=')), value = kv.substr(kv.find('=') + 1);
        EXPECT_NE(msg.find("'" + key + "'"), std::string::npos) << kv << ": " << msg;
        EXPECT_NE(msg.find(value), std::string::npos) << kv << ": " << msg;
        EXPECT_NE(msg.find("out of range ["), std::string::npos) << kv << ": " << msg;
        EXPECT_TRUE(s == Settings{}) << kv << " changed the settings";
    }
    EXPECT_NE(errorOf([] { Settings s; applyAssignment(s, "radiosity.samples=0"); }).find("[1, 99] taps"),
              std::string::npos);
    EXPECT_NE(errorOf([] { Settings s; applyAssignment(s, "radiosity.samples=2.5"); }).find("integer"),
              std::string::npos);
    // the ends of the range are accepted
    Settings edge;
    applyAssignment(edge, "temporal.alpha=0.995");
    applyAssignment(edge, "radiosity.samples=99");
    EXPECT_EQ(edge.numSamples, 99);
    // a --settings file
    Settings f;
    const std::string msg = errorOf([&] { applySettingsJson(f, nlohmann::json{{"temporal.alpha", 1.0}}, "my.json"); });
    EXPECT_NE(msg.find("my.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'temporal.alpha' = 1 is out of range [0, 0.995]"), std::string::npos) << msg;
    // saved viewer state: clamped, with a warning that says so; unknown keys skipped with a warning
    Settings v;
    const auto warnings = applySettingsJsonLeniently(
        v, nlohmann::json{{"temporal.alpha", 1.0}, {"radiosity.samples", 20}, {"no.such", 1}}, "state.json");
    ASSERT_EQ(warnings.size(), 2u);
    Settings text;  // a number given as a string is range-checked the same way
    EXPECT_EQ(applySettingsJsonLeniently(text, nlohmann::json{{"radiosity.samples", "1000"}}, "s").size(), 1u);
    EXPECT_EQ(text.numSamples, 99);
    EXPECT_FLOAT_EQ(v.hysteresis, 0.995f);
    EXPECT_EQ(v.numSamples, 20);
    EXPECT_NE(warnings[0].find("no.such"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[1].find("temporal.alpha"), std::string::npos) << warnings[1];
    EXPECT_NE(warnings[1].find("using 0.995"), std::string::npos) << warnings[1];
}
