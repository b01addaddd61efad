// The viewer's editing without a window: Blender's modal transform tool (G / R / S, constraints, typed values,
// cancel) against analytic answers, the undo history, and the scene's edit state (selection, capture / apply,
// Euler angles, the default sun's angles, light icons). One file over 500 lines: they share the view and helpers.
#include "app/edit/scene_edit.h"
#include "app/edit/transform_tool.h"
#include "app/edit/undo_history.h"

#include "renderer/renderer.h"
#include "renderer/scene/lighting.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace deepgi;
using namespace deepgi::edit;

namespace {

constexpr float kW = 400.0f, kH = 300.0f;

// Front view: the eye on +Z at distance `dist` looking at the origin down -Z, +Y up, 60 degrees vertical fov.
ToolView frontView(float dist = 10.0f) {
    ToolView v;
    v.camera.cameraToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, dist));
    v.camera.perspective = true;
    v.camera.yfov = glm::radians(60.0f);
    v.camera.znear = 0.1f;
    v.camera.zfar = 100.0f;
    v.width = kW;
    v.height = kH;
    return v;
}
// World units per pointer unit at distance d in front of the front view.
float unitsPerPixel(float d) { return 2.0f * std::tan(glm::radians(30.0f)) * d / kH; }
const glm::vec2 kCentre(kW * 0.5f, kH * 0.5f);

TransformTarget at(const glm::vec3& p) {
    TransformTarget t;
    t.local.translation = p;
    return t;
}

void typeString(TransformTool& tool, const std::string& s) {
    for (char c : s) ASSERT_TRUE(tool.type(c)) << c;
}

void expectVec(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
// Quaternions q and -q are the same rotation.
void expectRotation(const glm::quat& a, const glm::quat& b, float tol = 1e-5f) {
    EXPECT_NEAR(std::abs(glm::dot(a, b)), 1.0f, tol) << "got (" << a.w << " " << a.x << " " << a.y << " " << a.z << ")";
}

}  // namespace

// ---- translate -----------------------------------------------------------------------------------------------

TEST(ViewerTransformTool, TypedMoveAlongAnAxis) {  // G X 2 Enter
    TransformTool tool;
    ASSERT_TRUE(tool.begin(ToolMode::Translate, {at({1, 2, 3})}, {1, 2, 3}, frontView(), kCentre));
    tool.pointer(kCentre + glm::vec2(37, -12));  // typed values win over the pointer
    tool.axis(0, false);
    typeString(tool, "2");
    const auto r = tool.confirm();
    ASSERT_EQ(r.size(), 1u);
    expectVec(r[0].translation, {3, 2, 3}, 0.0f);
    EXPECT_FALSE(tool.active());
}

TEST(ViewerTransformTool, TypedMoveWithoutAxisIsXThenTabYZ) {  // Blender: G 1 Tab 2 Tab -3
    TransformTool tool;
    tool.begin(ToolMode::Translate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre);
    typeString(tool, "1");
    expectVec(tool.current()[0].translation, {1, 0, 0}, 0.0f);
    tool.tab();
    typeString(tool, "2");
    tool.tab();
    typeString(tool, "3-");  // '-' negates the value wherever it is typed
    expectVec(tool.confirm()[0].translation, {1, 2, -3}, 0.0f);
}

TEST(ViewerTransformTool, MinusDotBackspaceAndReciprocal) {
    TransformTool tool;
    tool.begin(ToolMode::Translate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre);
    tool.axis(1, false);
    typeString(tool, "-2.5");
    EXPECT_FLOAT_EQ(tool.current()[0].translation.y, -2.5f);
    typeString(tool, ".7");  // a second '.' is ignored: -2.57
    EXPECT_FLOAT_EQ(tool.current()[0].translation.y, -2.57f);
    tool.backspace();  // -2.5
    tool.backspace();  // -2.
    EXPECT_FLOAT_EQ(tool.current()[0].translation.y, -2.0f);
    typeString(tool, "-");  // negation toggles off
    EXPECT_FLOAT_EQ(tool.current()[0].translation.y, 2.0f);
    typeString(tool, "/");  // reciprocal: 1/2.
    EXPECT_FLOAT_EQ(tool.current()[0].translation.y, 0.5f);
    EXPECT_FALSE(tool.type('q')) << "not a numeric character: left for the viewer";
    // Backspace until nothing is left: typing ends and the pointer drives again.
    for (int i = 0; i < 4; ++i) tool.backspace();
    EXPECT_FALSE(tool.typing());
    tool.pointer(kCentre + glm::vec2(0, -30));  // 30 px up along Y at distance 10
    EXPECT_NEAR(tool.current()[0].translation.y, 30.0f * unitsPerPixel(10.0f), 1e-4f);
}

TEST(ViewerTransformTool, PointerMoveFollowsThePointerInTheViewPlane) {
    // The object at the pivot, 10 in front of the eye: 80 px right and 40 px down move it by the analytic amount.
    TransformTool tool;
    tool.begin(ToolMode::Translate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(5, 5));
    tool.pointer(kCentre + glm::vec2(85, 45));
    const float k = unitsPerPixel(10.0f);
    expectVec(tool.current()[0].translation, {80 * k, -40 * k, 0}, 1e-4f);
}

TEST(ViewerTransformTool, PointerMoveAlongAnAxisIgnoresTheOtherDirection) {
    TransformTool tool;
    tool.begin(ToolMode::Translate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre);
    tool.axis(0, false);
    tool.pointer(kCentre + glm::vec2(60, -90));  // X only takes the pointer's horizontal part in the front view
    expectVec(tool.current()[0].translation, {60 * unitsPerPixel(10.0f), 0, 0}, 1e-4f);
    // Shift+Z: the XY plane (the view plane here) takes both.
    tool.axis(2, true);
    expectVec(tool.current()[0].translation, {60 * unitsPerPixel(10.0f), 90 * unitsPerPixel(10.0f), 0}, 1e-4f);
    // Shift+X: the YZ plane, seen edge-on from the front, takes only the vertical part.
    tool.axis(0, true);
    expectVec(tool.current()[0].translation, {0, 90 * unitsPerPixel(10.0f), 0}, 1e-4f);
}

TEST(ViewerTransformTool, SameAxisAgainGoesGlobalLocalOff) {
    // An object turned 90 degrees about Z: its local X is the world's Y.
    TransformTarget t = at({0, 0, 0});
    t.local.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
    TransformTool tool;
    tool.begin(ToolMode::Translate, {t}, {0, 0, 0}, frontView(), kCentre);
    typeString(tool, "2");
    tool.axis(0, false);
    EXPECT_EQ(tool.orientation(), Orientation::Global);
    expectVec(tool.current()[0].translation, {2, 0, 0});
    tool.axis(0, false);
    EXPECT_EQ(tool.orientation(), Orientation::Local);
    expectVec(tool.current()[0].translation, {0, 2, 0});
    tool.axis(0, false);
    EXPECT_EQ(tool.constraintAxis(), -1) << "a third press turns the constraint off";
    expectVec(tool.current()[0].translation, {2, 0, 0});  // typed without an axis: X
    tool.axis(0, false);
    tool.axis(1, false);  // another axis starts again at Global
    EXPECT_EQ(tool.constraintAxis(), 1);
    EXPECT_EQ(tool.orientation(), Orientation::Global);
    expectVec(tool.current()[0].translation, {0, 2, 0});
}

TEST(ViewerTransformTool, MoveUnderAScaledParentMovesTheWorldPositionByTheTypedAmount) {
    TransformTarget t = at({1, 0, 0});
    t.parentWorld = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
    TransformTool tool;
    tool.begin(ToolMode::Translate, {t}, glm::vec3(t.world()[3]), frontView(), kCentre);
    tool.axis(0, false);
    typeString(tool, "2");
    TransformTarget moved = t;
    moved.local = tool.confirm()[0];
    expectVec(glm::vec3(moved.world()[3]), glm::vec3(t.world()[3]) + glm::vec3(2, 0, 0));
    expectVec(moved.local.translation, {2, 0, 0});  // 1 + 2 / the parent's scale of 2
}

// ---- rotate --------------------------------------------------------------------------------------------------

TEST(ViewerTransformTool, TypedRotationAboutAnAxisIsRightHanded) {  // R X 90 Enter
    TransformTool tool;
    tool.begin(ToolMode::Rotate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(50, 0));
    tool.axis(0, false);
    typeString(tool, "90");
    const Trs r = tool.confirm()[0];
    expectRotation(r.rotation, glm::angleAxis(glm::radians(90.0f), glm::vec3(1, 0, 0)));
    // +Y goes to +Z under +90 degrees about +X.
    expectVec(r.rotation * glm::vec3(0, 1, 0), {0, 0, 1});
    expectVec(r.translation, {0, 0, 0});
}

TEST(ViewerTransformTool, RotationTurnsOtherSelectedObjectsAboutThePivot) {
    TransformTool tool;
    tool.begin(ToolMode::Rotate, {at({0, 0, 0}), at({1, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(50, 0));
    tool.axis(2, false);
    typeString(tool, "90");
    const auto r = tool.confirm();
    expectVec(r[1].translation, {0, 1, 0});
    expectRotation(r[1].rotation, glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1)));
}

TEST(ViewerTransformTool, PointerRotationFollowsThePointerAroundThePivot) {
    // From right of the pivot to above it: a quarter turn counter-clockwise on the screen, i.e. +90 degrees about
    // the axis towards the viewer (+Z in the front view).
    TransformTool tool;
    tool.begin(ToolMode::Rotate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(100, 0));
    tool.pointer(kCentre + glm::vec2(70, -70));
    tool.pointer(kCentre + glm::vec2(0, -100));
    expectRotation(tool.current()[0].rotation, glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1)), 1e-4f);
    // Z points at the viewer: the same turn. Constrained to -Z's direction seen from behind it would flip.
    tool.axis(2, false);
    expectRotation(tool.current()[0].rotation, glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1)), 1e-4f);
    // Typed without an axis: positive is clockwise on the screen (Blender's manual), i.e. about -Z here.
    tool.axis(2, false);
    tool.axis(2, false);
    typeString(tool, "30");
    expectRotation(tool.current()[0].rotation, glm::angleAxis(glm::radians(-30.0f), glm::vec3(0, 0, 1)));
}

TEST(ViewerTransformTool, PointerRotationAccumulatesFullTurns) {
    TransformTool tool;
    tool.begin(ToolMode::Rotate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(100, 0));
    for (int i = 1; i <= 16; ++i) {  // once round, counter-clockwise, then a quarter more
        const float a = glm::radians(22.5f * float(i)) + (i == 16 ? glm::radians(90.0f) : 0.0f);
        tool.pointer(kCentre + 100.0f * glm::vec2(std::cos(a), -std::sin(a)));
    }
    EXPECT_NEAR(tool.amount().x, 450.0f, 1e-2f);
}

// ---- scale ---------------------------------------------------------------------------------------------------

TEST(ViewerTransformTool, TypedScaleUniformAxisAndPlane) {
    TransformTool tool;
    tool.begin(ToolMode::Scale, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(50, 0));
    typeString(tool, "2");
    expectVec(tool.current()[0].scale, {2, 2, 2}, 0.0f);
    tool.axis(0, false);  // S X 2
    expectVec(tool.current()[0].scale, {2, 1, 1}, 0.0f);
    tool.axis(2, true);  // S Shift+Z 2: X and Y
    expectVec(tool.current()[0].scale, {2, 2, 1}, 0.0f);
    typeString(tool, "-");  // mirror
    expectVec(tool.confirm()[0].scale, {-2, -2, 1}, 0.0f);
}

TEST(ViewerTransformTool, PointerScaleIsTheDistanceRatioToThePivot) {
    TransformTool tool;
    tool.begin(ToolMode::Scale, {at({0, 0, 0}), at({1, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(40, 30));
    tool.pointer(kCentre + glm::vec2(80, 60));  // 50 px -> 100 px
    auto r = tool.current();
    expectVec(r[0].scale, {2, 2, 2}, 1e-5f);
    expectVec(r[1].translation, {2, 0, 0}, 1e-5f);  // the other object moves away from the pivot
    tool.pointer(kCentre - glm::vec2(40, 30));  // past the pivot: mirrored
    expectVec(tool.current()[0].scale, {-1, -1, -1}, 1e-5f);
}

TEST(ViewerTransformTool, GlobalAxisScaleOfATurnedObjectScalesItsWorldExtent) {
    // Turned 90 degrees about Z: the world's X is its local -Y. S X 3 (global) must stretch the world X extent.
    TransformTarget t = at({0, 0, 0});
    t.local.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
    TransformTool tool;
    tool.begin(ToolMode::Scale, {t}, {0, 0, 0}, frontView(), kCentre + glm::vec2(50, 0));
    tool.axis(0, false);
    typeString(tool, "3");
    TransformTarget s = t;
    s.local = tool.current()[0];
    expectVec(s.local.scale, {1, 3, 1});
    const glm::mat3 expected = glm::mat3(glm::scale(glm::mat4(1.0f), glm::vec3(3, 1, 1))) * glm::mat3(t.world());
    for (int c = 0; c < 3; ++c) expectVec(glm::mat3(s.world())[c], expected[c]);
    tool.axis(0, false);  // local X: the object's own X
    expectVec(tool.current()[0].scale, {3, 1, 1});
}

TEST(ViewerTransformTool, ZeroScaleIsKeptInvertibleAndSaysSo) {
    TransformTool tool;
    tool.begin(ToolMode::Scale, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre + glm::vec2(50, 0));
    typeString(tool, "0");
    EXPECT_FLOAT_EQ(tool.current()[0].scale.x, 1e-4f);
    EXPECT_NE(tool.header().find("degenerate"), std::string::npos) << tool.header();
}

// ---- cancel --------------------------------------------------------------------------------------------------

TEST(ViewerTransformTool, CancelRestoresExactly) {
    TransformTarget t = at({0.1f, -0.2f, 0.3f});
    t.local.rotation = glm::normalize(glm::quat(0.9f, 0.1f, 0.3f, -0.2f));
    t.local.scale = {0.7f, 1.3f, 2.1f};
    t.parentWorld = glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0, 1, 0));
    for (ToolMode m : {ToolMode::Translate, ToolMode::Rotate, ToolMode::Scale}) {
        TransformTool tool;
        tool.begin(m, {t}, glm::vec3(t.world()[3]), frontView(), kCentre + glm::vec2(20, 10));
        tool.pointer(kCentre + glm::vec2(130, -70));
        tool.axis(1, false);
        tool.axis(1, false);
        EXPECT_NE(tool.current()[0], t.local);
        const auto r = tool.cancel();
        ASSERT_EQ(r.size(), 1u);
        EXPECT_EQ(r[0], t.local) << "bit for bit";
        EXPECT_FALSE(tool.active());
    }
}

TEST(ViewerTransformTool, NothingSelectedStartsNothing) {
    TransformTool tool;
    EXPECT_FALSE(tool.begin(ToolMode::Translate, {}, {0, 0, 0}, frontView(), kCentre));
    EXPECT_FALSE(tool.active());
    EXPECT_TRUE(tool.current().empty());
}

TEST(ViewerTransformTool, HeaderSaysWhatIsApplied) {
    TransformTool tool;
    tool.begin(ToolMode::Translate, {at({0, 0, 0})}, {0, 0, 0}, frontView(), kCentre);
    tool.axis(0, false);
    tool.axis(0, false);
    typeString(tool, "2");
    const std::string h = tool.header();
    EXPECT_NE(h.find("Move"), std::string::npos) << h;
    EXPECT_NE(h.find("local X"), std::string::npos) << h;
    EXPECT_NE(h.find("[2|]"), std::string::npos) << h;
}

// ---- undo ----------------------------------------------------------------------------------------------------

TEST(ViewerUndo, UndoRedoAndANewEditDropsTheRedo) {
    UndoHistory<int> h;
    EXPECT_FALSE(h.canUndo());
    EXPECT_EQ(h.undo(), nullptr);
    EXPECT_TRUE(h.push("a", 0, 1));
    EXPECT_TRUE(h.push("b", 1, 2));
    EXPECT_FALSE(h.push("nothing", 2, 2)) << "an edit that changes nothing is no step";
    std::string label;
    ASSERT_NE(h.undo(&label), nullptr);
    EXPECT_EQ(label, "b");
    EXPECT_EQ(*h.undo(), 0);
    EXPECT_EQ(h.undo(), nullptr);
    EXPECT_EQ(*h.redo(&label), 1);
    EXPECT_EQ(label, "a");
    EXPECT_TRUE(h.canRedo());
    h.push("c", 1, 5);  // drops "b"
    EXPECT_FALSE(h.canRedo());
    EXPECT_EQ(h.size(), 2u);
    EXPECT_EQ(*h.undo(), 1);
    EXPECT_EQ(*h.redo(), 5);
}

TEST(ViewerUndo, KeepsTheNewestSteps) {
    UndoHistory<int> h(3);
    for (int i = 0; i < 5; ++i) h.push("s" + std::to_string(i), i, i + 1);
    EXPECT_EQ(h.size(), 3u);
    EXPECT_EQ(*h.undo(), 4);
    EXPECT_EQ(*h.undo(), 3);
    EXPECT_EQ(*h.undo(), 2);
    EXPECT_EQ(h.undo(), nullptr) << "the oldest steps were dropped";
}

// ---- the scene's edit state ----------------------------------------------------------------------------------

namespace {
// root (a light below it) -> child; and a second root with a part.
Scene smallTree() {
    Scene s;
    const int root = s.addNode("root");
    s.addNode("child", root);
    const int lamp = s.addNode("lamp", root);
    const int other = s.addNode("other");
    Light l;
    l.type = LightType::Point;
    l.node = lamp;
    s.lights.push_back(l);
    MeshPart p;
    p.node = other;
    p.vertices = {{{0, 0, 0}, {0, 0, 1}, {0, 0}}, {{1, 0, 0}, {0, 0, 1}, {0, 0}}, {{0, 1, 0}, {0, 0, 1}, {0, 0}}};
    p.indices = {0, 1, 2};
    s.parts.push_back(p);
    s.ensureNodes();
    s.computeBounds();
    s.updateWorldTransforms();
    return s;
}
}  // namespace

TEST(ViewerSceneEdit, ShiftClickFollowsBlender) {
    Selection s;
    s.click(3, false);
    EXPECT_EQ(s.items, std::vector<int>({3}));
    s.click(5, true);  // added, active
    EXPECT_EQ(s.items, std::vector<int>({3, 5}));
    EXPECT_EQ(s.active, 5);
    s.click(3, true);  // selected, not active: becomes active
    EXPECT_EQ(s.items.size(), 2u);
    EXPECT_EQ(s.active, 3);
    s.click(3, true);  // the active one: deselected
    EXPECT_EQ(s.items, std::vector<int>({5}));
    EXPECT_EQ(s.active, -1);
    s.click(-1, true);  // Shift-click on nothing keeps it
    EXPECT_EQ(s.items, std::vector<int>({5}));
    s.click(-1, false);  // a click on nothing deselects
    EXPECT_TRUE(s.items.empty());
}

TEST(ViewerSceneEdit, CaptureAndApplyRestoreExactlyWithTheRightChanges) {
    Scene scene = smallTree();
    Settings settings;
    Selection sel;
    const EditState before = captureState(scene, settings, sel);
    scene.nodes[0].local.translation = {1, 2, 3};
    scene.nodes[3].visible = false;
    scene.lights[0].intensity = 7.0f;
    sel.click(3, false);
    scene.updateWorldTransforms();
    const EditState after = captureState(scene, settings, sel);
    EXPECT_FALSE(before == after);
    const unsigned changes = applyState(scene, settings, sel, before);
    EXPECT_TRUE(captureState(scene, settings, sel) == before);
    EXPECT_EQ(changes, unsigned(SceneChange::Transforms) | unsigned(SceneChange::Visibility) | unsigned(SceneChange::Lights));
    EXPECT_EQ(glm::vec3(scene.nodes[0].world[3]), glm::vec3(0.0f)) << "world transforms recomputed";
    // Only the selection: nothing for the renderer.
    EditState selOnly = before;
    selOnly.selection.click(1, false);
    EXPECT_EQ(applyState(scene, settings, sel, selOnly), 0u);
    EXPECT_EQ(sel.items, std::vector<int>({1}));
}

TEST(ViewerSceneEdit, ChildrenMoveWithTheirParentOnceAndLightsFollow) {
    Scene scene = smallTree();
    Selection sel;
    sel.items = {1, 0, 3};  // child, its parent, another root
    EXPECT_EQ(transformRoots(scene, sel), std::vector<int>({0, 3}));
    const std::vector<int> roots = {0};
    Trs moved;
    moved.translation = {0, 5, 0};
    EXPECT_EQ(setLocals(scene, roots, {moved}), unsigned(SceneChange::Transforms) | unsigned(SceneChange::Lights))
        << "the lamp is below the moved root";
    EXPECT_NEAR(scene.lights[0].position.y, 5.0f, 1e-6f);
    EXPECT_EQ(setLocals(scene, {3}, {moved}), unsigned(SceneChange::Transforms)) << "no light below 'other'";
    EXPECT_EQ(setVisible(scene, 3, false), unsigned(SceneChange::Visibility));
    EXPECT_EQ(setVisible(scene, 3, false), 0u) << "already hidden";
    EXPECT_EQ(setVisible(scene, 0, false), unsigned(SceneChange::Visibility) | unsigned(SceneChange::Lights));
}

TEST(ViewerSceneEdit, EulerDegreesRoundTrip) {
    for (const glm::vec3 e : {glm::vec3(30, -20, 75), glm::vec3(0, 0, 90), glm::vec3(-170, 10, 5), glm::vec3(0, 89, 0)}) {
        const glm::quat q = fromEulerDegrees(e);
        expectVec(eulerDegrees(q), e, 1e-3f);
    }
    // Blender's XYZ order: X first, then Y, then Z (R = Rz Ry Rx).
    const glm::quat q = fromEulerDegrees({90, 0, 90});
    expectVec(q * glm::vec3(0, 1, 0), glm::vec3(0, 0, 1) /* X turns +Y to +Z; Z keeps +Z */);
}

TEST(ViewerSceneEdit, SunAnglesInvertTheRenderersSunDirection) {
    Settings s;
    for (float az : {0.0f, 30.0f, 135.0f, 300.0f})
        for (float el : {5.0f, 45.0f, 80.0f}) {
            s.sunAzimuth = az;
            s.sunElevation = el;
            const glm::vec2 back = sunAngles(defaultSunDirection(s));
            EXPECT_NEAR(back.x, az, 1e-3f);
            EXPECT_NEAR(back.y, el, 1e-3f);
        }
    EXPECT_NEAR(sunAngles(glm::vec3(0, 1, 0)).y, 1.0f, 1e-6f) << "from below: the setting's lowest elevation";
}

TEST(ViewerSceneEdit, LightIconsProjectAndPick) {
    Scene scene = smallTree();
    scene.nodes[2].local.translation = {0, 0, 0};
    scene.updateWorldTransforms();
    Settings settings;
    const ToolView v = frontView();
    const auto icons = lightIcons(scene, settings, v);
    ASSERT_EQ(icons.size(), 1u);
    EXPECT_TRUE(icons[0].onScreen);
    EXPECT_NEAR(icons[0].screen.x, kCentre.x, 1e-3f);
    EXPECT_NEAR(icons[0].screen.y, kCentre.y, 1e-3f);
    EXPECT_EQ(pickLight(icons, kCentre + glm::vec2(6, 0), 10.0f), 2);
    EXPECT_EQ(pickLight(icons, kCentre + glm::vec2(16, 0), 10.0f), -1);
    scene.lights.clear();  // the default sun
    const auto sun = lightIcons(scene, settings, v);
    ASSERT_EQ(sun.size(), 1u);
    EXPECT_EQ(sun[0].item, kDefaultSun);
}
