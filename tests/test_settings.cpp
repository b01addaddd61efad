#include "renderer/core/settings.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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

TEST(Settings, AssignmentParsesClampsAndRejects) {
    Settings s;
    applyAssignment(s, "radiosity.samples=30");
    EXPECT_EQ(s.numSamples, 30);
    applyAssignment(s, "radiosity.samples=1000");  // clamped to the declared max
    EXPECT_EQ(s.numSamples, 99);
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
    EXPECT_EQ(q.minMip, 1);
    EXPECT_THROW(applySettingsJson(q, nlohmann::json{{"blur.enabled", 3}}, "x.json"), std::runtime_error);
}
