// Scene files: every shipped scene loads, a scene written and read back steps bit for bit the
// same, bad files are refused with a message naming file, JSON path and problem (and the
// command exits non-zero), and what the format adds to the API (fixed joints, anchors by
// nearest node or face, masses from density, recording) does what it says.
#include <tandem/record.h>
#include <tandem/scene_file.h>

#include <gtest/gtest.h>

#include "process_temp_folder.h"
#include "short_tests.h"

#include <cstdio>
#include <sys/wait.h>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tandem {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() { return processTempFolder("tandem_scene_tests"); }

std::string writeFile(const std::string& name, const std::string& text) {
  const fs::path path = tempDir() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(SceneFile, EveryShippedSceneValidates) {
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(TANDEM_SOURCE_DIR "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    Result<Scene> scene = loadScene(entry.path().string());
    ASSERT_TRUE(scene.ok()) << scene.message();
    World world;
    Status built = buildScene(*scene, world);
    EXPECT_TRUE(built.ok()) << built.message();
    EXPECT_FALSE(scene->description.empty()) << entry.path();
  }
  EXPECT_GE(count, 7 + 11);  // the paper's three, the small ones, the solver's gauntlet
}

// A rope laid along a path and the solver's substeps are written and read back as given.
TEST(SceneFile, RopeAlongAPathAndSubstepsRoundTrip) {
  const std::string json = R"({"format": 1, "name": "over", "solver": {"iterations": 2, "substeps": 4},
    "deformables": [{"name": "rope", "mesh": {"type": "rope", "path": [[-0.2, 0, 0], [-0.2, 1, 0], [0.2, 1, 0], [0.2, 0, 0]],
    "nodes": 25}, "mass": 0.1}]})";
  Result<Scene> scene = parseScene(json, "over.json", ".");
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_EQ(scene->settings.solver.substeps, 4);
  ASSERT_EQ(scene->deformables[0].mesh.path.size(), 4u);
  Result<Scene> reread = parseScene(sceneToJson(*scene), "again.json", ".");
  ASSERT_TRUE(reread.ok()) << reread.message();
  EXPECT_EQ(sceneToJson(*reread), sceneToJson(*scene));
  World world;
  ASSERT_TRUE(buildScene(*reread, world).ok());
  EXPECT_EQ(world.settings().solver.substeps, 4);
  const auto x = world.nodePositions(DeformableId{0});
  ASSERT_EQ(x.size(), 25u);
  EXPECT_NEAR((x.front() - Vec3(-0.2, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((x.back() - Vec3(0.2, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((x[12] - Vec3(0, 1, 0)).norm(), 0.0, 1e-12);  // half way along the 2.4 m path
}

// Colours: "#rrggbb" and [r, g, b] read as the same numbers, written back as [r, g, b], and a
// body without one has none (the renderer's palette).
TEST(SceneFile, ColoursReadAsHexOrNumbersAndWriteBack) {
  const std::string json = R"({"format": 1, "rigid_bodies": [
    {"name": "bar", "shape": {"type": "box", "half_extents": [0.3, 0.02, 0.1]}, "colour": "#5C3a21"},
    {"name": "plain", "shape": {"type": "sphere", "radius": 0.1}}],
    "deformables": [{"name": "rope", "mesh": {"type": "rope", "start": [0, 1, 0], "end": [0, 0, 0], "nodes": 5},
    "mass": 0.1, "colour": [0.25, 0.5, 1]}]})";
  Result<Scene> scene = parseScene(json, "colours.json", ".");
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_TRUE(scene->rigidBodies[0].colour.has_value());
  EXPECT_EQ(*scene->rigidBodies[0].colour, (Colour{0x5c / 255.0, 0x3a / 255.0, 0x21 / 255.0}));
  EXPECT_FALSE(scene->rigidBodies[1].colour.has_value());
  ASSERT_TRUE(scene->deformables[0].colour.has_value());
  EXPECT_EQ(*scene->deformables[0].colour, (Colour{0.25, 0.5, 1.0}));
  const std::string written = sceneToJson(*scene);
  Result<Scene> reread = parseScene(written, "again.json", ".");
  ASSERT_TRUE(reread.ok()) << reread.message();
  EXPECT_EQ(reread->rigidBodies[0].colour, scene->rigidBodies[0].colour);  // to the last bit
  EXPECT_FALSE(reread->rigidBodies[1].colour.has_value());
  EXPECT_EQ(reread->deformables[0].colour, scene->deformables[0].colour);
  EXPECT_EQ(sceneToJson(*reread), written);
}

// A scene made through the API with one of everything the format has.
Scene everythingScene() {
  Scene scene;
  scene.name = "everything";
  scene.timeStep = 1.0 / 60;
  scene.settings.solver.iterations = 6;
  scene.settings.solver.friction = FrictionModel::Pressure;
  scene.settings.gravity = {0.1, -9.7, 0.05};

  SceneRigidBody ground;
  ground.desc.name = "ground";
  ground.desc.shape = RigidShape::plane({0, 1, 0}, 0);
  ground.desc.motion = MotionType::Static;
  SceneRigidBody wheel;
  wheel.desc.name = "wheel";
  wheel.desc.shape = RigidShape::cylinder(0.2, 0.05);
  wheel.desc.position = {0, 1.5, 0};
  wheel.desc.orientation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  SceneRigidBody box;
  box.desc.name = "box";
  box.desc.shape = RigidShape::box({0.1, 0.1, 0.1});
  box.desc.mass = 0.7;
  box.desc.position = {0.5, 0.6, 0};
  box.desc.angularVelocity = {0, 1, 0};
  SceneRigidBody hull;
  hull.desc.name = "hull";
  hull.desc.shape = RigidShape::convexHull({{-0.1, 0, -0.1}, {0.1, 0, -0.1}, {0, 0, 0.1}, {0, 0.15, 0}});
  hull.desc.position = {-0.6, 0.3, 0.2};
  SceneRigidBody cap;
  cap.desc.name = "cap";
  cap.desc.shape = RigidShape::box({0.05, 0.02, 0.05});
  cap.desc.mass = 0.1;
  cap.desc.position = {-0.6, 0.47, 0.2};
  scene.rigidBodies = {ground, wheel, box, hull, cap};

  SceneJoint hinge;
  hinge.bodyA = "wheel";
  hinge.pivot = {0, 1.5, 0};
  hinge.axis = {0, 0, 1};
  SceneJoint fixed;
  fixed.kind = SceneJoint::Kind::Fixed;
  fixed.bodyA = "cap";
  fixed.bodyB = "hull";
  scene.joints = {hinge, fixed};

  SceneDeformable rope;
  rope.desc.name = "rope";
  rope.mesh.kind = SceneMesh::Kind::Rope;
  rope.mesh.start = {0.3, 1.5, 0};
  rope.mesh.end = {0.5, 0.75, 0};
  rope.mesh.nodes = 12;
  rope.density = 0.1;
  rope.desc.inextensibility.enabled = true;
  SceneDeformable cloth;
  cloth.desc.name = "cloth";
  cloth.mesh.corner = {-0.3, 1.0, -0.3};
  cloth.mesh.sideU = {0.6, 0, 0};
  cloth.mesh.sideV = {0, 0, 0.6};
  cloth.mesh.columns = 7;
  cloth.mesh.rows = 7;
  cloth.mass = 0.2;
  cloth.desc.inextensibility.enabled = true;
  cloth.desc.bending.enabled = true;
  cloth.desc.bending.maxForce = 0.2;
  cloth.initialVelocity = {0, 0, 0.3};
  SceneFixedNodes corners;
  corners.nodes = {0, 6};
  cloth.fixed.push_back(corners);
  SceneDeformable jelly;
  jelly.desc.name = "jelly";
  jelly.mesh.kind = SceneMesh::Kind::TetCylinder;
  jelly.mesh.baseCentre = {-0.2, 0.005, -0.4};
  jelly.mesh.rings = 1;
  jelly.mesh.sectors = 6;
  jelly.mesh.layers = 2;
  jelly.density = 1000;
  jelly.desc.paradigm.type = ParadigmType::CorotationalFem;
  jelly.desc.paradigm.youngsModulus = 20e3;
  SceneFixedNodes base;  // the jelly's bottom layer, by region
  base.region = std::array<Vec3, 2>{Vec3(-1, 0, -1), Vec3(1, 0.01, 1)};
  base.maxForce = 50;
  jelly.fixed.push_back(base);
  scene.deformables = {rope, cloth, jelly};

  SceneAnchor toWheel;
  toWheel.deformable = "rope";
  toWheel.node = 0;
  toWheel.body = "wheel";
  SceneAnchor toBox;
  toBox.deformable = "rope";
  toBox.nearest = Vec3(0.5, 0.7, 0);
  toBox.body = "box";
  toBox.maxForce = 100;
  SceneAnchor faceToBox;
  faceToBox.deformable = "cloth";
  faceToBox.face = 30;
  faceToBox.barycentric = {0.2, 0.3, 0.5};
  faceToBox.body = "hull";
  faceToBox.localPoint = Vec3(0, 0.2, 0);
  scene.anchors = {toWheel, toBox, faceToBox};
  return scene;
}

std::vector<Vec3> allNodes(const World& world) {
  std::vector<Vec3> nodes;
  for (int d = 0; d < world.deformableCount(); ++d)
    for (const Vec3& x : world.nodePositions(DeformableId{d})) nodes.push_back(x);
  return nodes;
}

TEST(SceneFile, WrittenAndReadBackStepsBitForBit) {
  const Scene original = everythingScene();
  const std::string json = sceneToJson(original);
  Result<Scene> reread = parseScene(json, "written.json", ".");
  ASSERT_TRUE(reread.ok()) << reread.message() << "\n" << json;
  EXPECT_EQ(sceneToJson(*reread), json);  // a fixed point of writing and reading

  World a, b;
  ASSERT_TRUE(buildScene(original, a).ok()) << buildScene(original, a).message();
  ASSERT_TRUE(buildScene(*reread, b).ok());
  for (int step = 0; step < 60; ++step) {
    { auto st = a.step(original.timeStep); ASSERT_TRUE(st.ok()) << "step " << step << ": " << st.message(); }
    ASSERT_TRUE(b.step(reread->timeStep).ok());
  }
  const std::vector<Vec3> nodesA = allNodes(a), nodesB = allNodes(b);
  ASSERT_EQ(nodesA.size(), nodesB.size());
  for (size_t n = 0; n < nodesA.size(); ++n) EXPECT_EQ(nodesA[n], nodesB[n]) << "node " << n;
  for (int r = 0; r < a.rigidBodyCount(); ++r) {
    EXPECT_EQ(a.rigidPosition(RigidBodyId{r}), b.rigidPosition(RigidBodyId{r}));
    EXPECT_EQ(a.rigidOrientation(RigidBodyId{r}).coeffs(), b.rigidOrientation(RigidBodyId{r}).coeffs());
  }
  // And it did something: the box hangs on the rope under the wheel, which has turned.
  const RigidBodyId wheel = *a.findRigidBody("wheel");
  EXPECT_GT(a.rigidAngularVelocity(wheel).norm(), 0.1);
}

TEST(SceneFile, MassesComeFromDensityOrTotalMass) {
  Scene scene = everythingScene();
  World world;
  ASSERT_TRUE(buildScene(scene, world).ok());
  auto total = [&](const char* name) {
    double sum = 0;
    for (double w : world.nodeInverseMasses(*world.findDeformable(name))) sum += 1.0 / w;
    return sum;
  };
  // The rope: 0.1 kg/m over its length; the cloth: 0.2 kg in all (its two pinned corners
  // included: fixed points keep their mass).
  EXPECT_NEAR(total("rope"), 0.1 * (scene.deformables[0].mesh.end - scene.deformables[0].mesh.start).norm(), 1e-12);
  EXPECT_NEAR(total("cloth"), 0.2, 1e-12);
  // The jelly: 1000 kg/m³ times its tets' volume, which for 6 sectors is the hexagonal prism's.
  const double hexagon = 1.5 * std::sqrt(3.0) * 0.1 * 0.1;
  EXPECT_NEAR(total("jelly"), 1000 * hexagon * 0.2, 1e-9);
}

TEST(SceneFile, AnchorsFindTheNearestNodeAndTheFacePoint) {
  Scene scene = everythingScene();
  World world;
  ASSERT_TRUE(buildScene(scene, world).ok());
  // The rope's nodes run from (0.3, 1.5) to (0.5, 0.75) in 11 gaps: (0.5, 0.7) is nearest the last.
  const AnchorState nearest = world.anchorState(AnchorId{1});
  EXPECT_LT((nearest.worldPointOnDeformable - world.nodePositions(*world.findDeformable("rope"))[11]).norm(), 1e-12);
  const auto& triangle = world.restMesh(*world.findDeformable("cloth")).triangles[30];
  const std::span<const Vec3> x = world.nodePositions(*world.findDeformable("cloth"));
  const Vec3 expected = 0.2 * x[triangle[0]] + 0.3 * x[triangle[1]] + 0.5 * x[triangle[2]];
  EXPECT_LT((world.anchorState(AnchorId{2}).worldPointOnDeformable - expected).norm(), 1e-12);
  // Its point on the hull is the given local point.
  const RigidBodyId hull = *world.findRigidBody("hull");
  EXPECT_LT((world.anchorState(AnchorId{2}).worldPointOnBody - (world.rigidPosition(hull) + Vec3(0, 0.2, 0))).norm(), 1e-12);
}

// Collision groups and masks, hinge limits and motors: read, written back, and built into a
// world that acts on them (the ghost falls through the ground; the motor turns its wheel).
TEST(SceneFile, CollisionFiltersDampingAndHingeMotorsRoundTripAndAct) {
  const std::string json = R"({"format": 1, "name": "filters",
    "rigid_bodies": [
      {"name": "ground", "shape": {"type": "plane", "normal": [0, 1, 0]}, "mass": 0, "collision_group": 2},
      {"name": "ghost", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "position": [0, 0.5, 0],
       "collision_mask": 4294967293, "linear_damping": 0.25, "angular_damping": 0.5},
      {"name": "wheel", "shape": {"type": "cylinder", "radius": 0.3, "half_height": 0.05}, "position": [2, 1, 0],
       "collision_group": 8, "collision_mask": 0}],
    "joints": [{"type": "hinge", "body_a": "wheel", "pivot": [2, 1, 0], "axis": [0, 1, 0],
                "limits": [-3, 3], "motor": {"target_speed": 2, "max_torque": 100}}],
    "deformables": [{"name": "rope", "mesh": {"type": "rope", "start": [1, 1, 0], "end": [1, 0.5, 0], "nodes": 5},
                     "mass": 0.1, "collision_group": 16, "collision_mask": 3}]})";
  Result<Scene> scene = parseScene(json, "filters.json", ".");
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_EQ(scene->rigidBodies[0].desc.collisionGroup, 2u);
  EXPECT_EQ(scene->rigidBodies[1].desc.collisionMask, 0xFFFFFFFDu);
  EXPECT_EQ(scene->rigidBodies[1].desc.collisionGroup, 1u);  // the default
  EXPECT_EQ(scene->rigidBodies[1].desc.linearDamping, 0.25);
  EXPECT_EQ(scene->rigidBodies[1].desc.angularDamping, 0.5);
  EXPECT_EQ(scene->rigidBodies[2].desc.linearDamping, 0.0);  // the default
  EXPECT_EQ(scene->deformables[0].desc.collision.group, 16u);
  EXPECT_EQ(scene->deformables[0].desc.collision.mask, 3u);
  EXPECT_EQ(scene->joints[0].lowerLimit, -3.0);
  EXPECT_EQ(scene->joints[0].upperLimit, 3.0);
  EXPECT_TRUE(scene->joints[0].motor);
  EXPECT_EQ(scene->joints[0].motorTargetSpeed, 2.0);
  EXPECT_EQ(scene->joints[0].motorMaxTorque, 100.0);
  const std::string written = sceneToJson(*scene);
  EXPECT_NE(written.find("\"collision_mask\": 4294967293"), std::string::npos) << written;
  EXPECT_NE(written.find("\"linear_damping\": 0.25"), std::string::npos) << written;
  EXPECT_NE(written.find("\"limits\": ["), std::string::npos);
  Result<Scene> reread = parseScene(written, "again.json", ".");
  ASSERT_TRUE(reread.ok()) << reread.message();
  EXPECT_EQ(sceneToJson(*reread), written);
  World world;
  ASSERT_TRUE(buildScene(*reread, world).ok());
  EXPECT_EQ(world.rigidCollisionMask(*world.findRigidBody("ghost")), 0xFFFFFFFDu);
  for (int step = 0; step < 60; ++step) ASSERT_TRUE(world.step(1.0 / 60).ok());
  EXPECT_LT(world.rigidPosition(*world.findRigidBody("ghost")).y(), -1.0);
  EXPECT_NEAR(world.hingeSpeed(JointId{0}), 2.0, 0.01);

  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {R"("collision_group": -1)", "/rigid_bodies/0/collision_group: must be an integer in [0, 4294967295]"},
           {R"("collision_mask": 4294967296)", "/rigid_bodies/0/collision_mask: must be an integer in [0, 4294967295]"},
           {R"("collision_mask": 1.5)", "/rigid_bodies/0/collision_mask: must be an integer"}}) {
    const std::string bad = R"({"format": 1, "name": "bad", "rigid_bodies": [{"name": "b",
      "shape": {"type": "sphere", "radius": 0.1}, )" + text + "}]}";
    Result<Scene> refused = parseScene(bad, "bad.json", ".");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find(message), std::string::npos) << refused.message();
  }
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {R"("type": "hinge", "pivot": [0, 0, 0], "axis": [0, 0, 1], "limits": [1, -1])",
            "/joints/0/limits: must be [lower, upper] with -pi <= lower <= upper <= pi rad, got [1, -1]"},
           {R"("type": "hinge", "pivot": [0, 0, 0], "axis": [0, 0, 1], "motor": {"target_speed": 1})",
            "/joints/0/motor: missing field 'max_torque'"},
           {R"("type": "fixed", "limits": [0, 1])", "/joints/0/limits: only a hinge has limits and a motor"}}) {
    const std::string bad = R"({"format": 1, "name": "bad", "rigid_bodies": [{"name": "b",
      "shape": {"type": "sphere", "radius": 0.1}}], "joints": [{"body_a": "b", )" + text + "}]}";
    Result<Scene> refused = parseScene(bad, "bad.json", ".");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find(message), std::string::npos) << refused.message();
  }
}

TEST(SceneFile, FixedJointsHoldTheirPose) {
  Scene scene;
  // Bullet solves joints iteratively: a 0.5 m lever on two fixed joints sags 14 cm at 4
  // iterations, 2 cm at 20 and nothing at 100.
  scene.settings.solver.iterations = 100;
  SceneRigidBody a, b;
  a.desc.name = "a";
  a.desc.shape = RigidShape::box({0.1, 0.1, 0.1});
  a.desc.position = {0, 2, 0};
  b.desc = a.desc;
  b.desc.name = "b";
  b.desc.position = {0.5, 2.2, 0};
  b.desc.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  scene.rigidBodies = {a, b};
  SceneJoint toWorld, between;
  toWorld.kind = between.kind = SceneJoint::Kind::Fixed;
  toWorld.bodyA = "a";
  between.bodyA = "b";
  between.bodyB = "a";
  scene.joints = {toWorld, between};
  World world;
  ASSERT_TRUE(buildScene(scene, world).ok());
  for (int step = 0; step < 120; ++step) ASSERT_TRUE(world.step(1.0 / 60).ok());
  EXPECT_LT((world.rigidPosition(RigidBodyId{0}) - Vec3(0, 2, 0)).norm(), 0.001);
  EXPECT_LT((world.rigidPosition(RigidBodyId{1}) - Vec3(0.5, 2.2, 0)).norm(), 0.003);
  EXPECT_LT(world.rigidOrientation(RigidBodyId{1}).angularDistance(b.desc.orientation), 0.02);
}

TEST(SceneFile, RecordsEveryStepInColumnsThatReadBack) {
  const Scene scene = everythingScene();
  World world;
  ASSERT_TRUE(buildScene(scene, world).ok());
  const std::string path = (tempDir() / "record.csv").string();
  {
    Result<StepRecorder> recorder = StepRecorder::open(path, true);
    ASSERT_TRUE(recorder.ok());
    ASSERT_TRUE(recorder->write(world).ok());
    for (int step = 0; step < 3; ++step) {
      ASSERT_TRUE(world.step(scene.timeStep).ok());
      ASSERT_TRUE(recorder->write(world).ok());
    }
  }
  std::ifstream file(path);
  std::string line;
  std::getline(file, line);
  EXPECT_EQ(line, "step,time,kind,name,index,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  int rigidRows = 0, nodeRows = 0;
  std::string last;
  while (std::getline(file, line)) {
    std::stringstream fields(line);
    std::vector<std::string> cells;
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    if (cells.size() == 17) cells.push_back("");  // a trailing empty field
    ASSERT_EQ(cells.size(), 18u) << line;
    (cells[2] == "rigid" ? rigidRows : nodeRows)++;
    last = line;
    if (cells[0] == "3" && cells[2] == "rigid" && cells[3] == "box") {
      const RigidBodyId box = *world.findRigidBody("box");
      EXPECT_EQ(std::stod(cells[6]), world.rigidPosition(box).y());  // to the last bit
      EXPECT_EQ(std::stod(cells[17]), world.rigidAngularVelocity(box).z());
    }
  }
  EXPECT_EQ(rigidRows, 4 * world.rigidBodyCount());
  EXPECT_EQ(nodeRows, 4 * static_cast<int>(allNodes(world).size()));
  EXPECT_EQ(last.substr(0, 2), "3,");
  EXPECT_FALSE(StepRecorder::open("/no/such/folder/record.csv", false).ok());
}

// ---- Bad files --------------------------------------------------------------------------------

struct BadScene {
  const char* name;
  std::string json;
  std::string message;  // what the error must say (after the file name)
};

// A valid scene to break: {BODIES} and {DEFORMABLES} and {ANCHORS} are filled per case.
std::string scene(const std::string& rigid, const std::string& deformables = "", const std::string& anchors = "",
                  const std::string& extra = "") {
  return R"({"format": 1, "rigid_bodies": [)" + rigid + R"(], "deformables": [)" + deformables +
         R"(], "anchors": [)" + anchors + "]" + extra + "}";
}
const std::string kBox = R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}})";
const std::string kRope =
    R"({"name": "rope", "mesh": {"type": "rope", "start": [0, 1, 0], "end": [0, 0, 0], "nodes": 5}, "mass": 0.1})";
std::string rope(const std::string& fields) {
  return R"({"name": "rope", "mesh": {"type": "rope", "start": [0, 1, 0], "end": [0, 0, 0], "nodes": 5}, )" + fields + "}";
}
std::string jelly(const std::string& paradigm) {
  return R"({"name": "jelly", "mesh": {"type": "tet_cylinder", "base_centre": [0, 0, 0], "radius": 0.1, "height": 0.2, "rings": 1, "sectors": 6, "layers": 2}, "density": 1000, "paradigm": )" +
         paradigm + "}";
}

const std::vector<BadScene> kBadScenes{
    {"syntax", R"({"format": 1,})", "not valid JSON: parse error at line 1, column 14"},
    {"nan", R"({"format": 1, "time_step": NaN})", "not valid JSON: parse error at line 1, column 28"},
    {"not_object", "[1, 2]", "/: must be an object, got an array"},
    {"no_format", "{}", "/: missing field 'format'"},
    {"format_2", R"({"format": 2})", "/format: this Tandem reads format 1, the file has 2"},
    {"format_string", R"({"format": "1"})", "/format: must be an integer, got a string"},
    {"unknown_top", R"({"format": 1, "gravty": [0, -9.81, 0]})", "/gravty: unknown field 'gravty'"},
    {"duplicate", R"({"format": 1, "time_step": 0.01, "time_step": 0.02})", "field 'time_step' appears twice"},
    {"time_step_zero", R"({"format": 1, "time_step": 0})", "/time_step: must be in [1e-06, 1], got 0"},
    {"time_step_huge", R"({"format": 1, "time_step": 5})", "/time_step: must be in [1e-06, 1], got 5"},
    // Physical magnitudes a run cannot survive (Limits): validate refuses what run would (each
    // of these validated before and failed, hung or crashed at run time).
    {"time_step_tiny", R"({"format": 1, "time_step": 1e-9})", "/time_step: must be in [1e-06, 1], got 1e-09"},
    {"too_many_steps", R"({"format": 1, "time_step": 1e-6, "duration": 1000})",
     "/duration: 1000 s at a time step of 1e-06 s is 1e+09 steps, more than a run's 10000000 (Limits::maxSteps)"},
    {"gravity_huge", R"({"format": 1, "gravity": [0, -1e300, 0]})",
     "/gravity: 1e+300 m/s^2 is more than 10000 m/s^2 (Limits::maxGravity)"},
    {"position_far", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "position": [0, 0, 1e308]})"),
     "/rigid_bodies/0/position/2: 1e+308 m is farther from the origin than 1e+08 m (Limits::maxCoordinate)"},
    {"radius_huge", scene(R"({"name": "ball", "shape": {"type": "sphere", "radius": 1e308}})"),
     "/rigid_bodies/0/shape/radius: 1e+308 m is outside [0.0001, 1e+06] m (Limits::minSize, maxSize)"},
    {"half_extent_tiny", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [1e-9, 0.1, 0.1]}})"),
     "/rigid_bodies/0/shape/half_extents/0: 1e-09 m is outside [0.0001, 1e+06] m"},
    {"speed_huge", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "linear_velocity": [1e300, 0, 0]})"),
     "/rigid_bodies/0/linear_velocity: a speed of 1e+300 m/s is not below the divergence speed of 10000 m/s"},
    {"speed_over_divergence", R"({"format": 1, "divergence_speed": 50, "rigid_bodies": [{"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "linear_velocity": [0, 60, 0]}]})",
     "/rigid_bodies/0/linear_velocity: a speed of 60 m/s is not below the divergence speed of 50 m/s"},
    {"spin_huge", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "angular_velocity": [0, 1e300, 0]})"),
     "/rigid_bodies/0/angular_velocity: 1e+300 rad/s is faster than 10000 rad/s (Limits::maxAngularSpeed)"},
    {"mass_tiny", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "mass": 1e-300})"),
     "/rigid_bodies/0/mass: 1e-300 kg is outside [1e-06, 1e+09] kg (Limits::minMass, maxMass)"},
    {"deformable_mass_huge", scene(kBox, rope(R"("mass": 1e12)")), "/deformables/0/mass: 1e+12 kg is outside [1e-06, 1e+09] kg"},
    {"density_mass_huge", scene(kBox, R"({"name": "jelly", "mesh": {"type": "tet_box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}, "density": 1e12})"),
     "/deformables/0/density: the total mass, 1e+12 kg, is outside [1e-06, 1e+09] kg"},
    {"mass_ratio", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "mass": 1e8})", kRope),
     "/deformables/0/mass: a node of 0.02 kg against the body of 1e+08 kg (/rigid_bodies/0/mass) is a mass ratio of "
     "5e+09, more than 1e+08 (Limits::maxMassRatio)"},
    {"rope_far", scene(kBox, R"({"name": "rope", "mesh": {"type": "rope", "start": [0, 1e300, 0], "end": [0, 0, 0], "nodes": 5}, "mass": 0.1})"),
     "/deformables/0/mesh/start/1: 1e+300 m is farther from the origin than 1e+08 m"},
    {"initial_velocity_huge", scene(kBox, rope(R"("mass": 0.1, "initial_velocity": [0, 0, -2e4])")),
     "/deformables/0/initial_velocity: a speed of 20000 m/s is not below the divergence speed of 10000 m/s"},
    {"hinge_far", scene(kBox, "", "", R"(, "joints": [{"type": "hinge", "body_a": "box", "pivot": [1e10, 0, 0], "axis": [0, 0, 1]}])"),
     "/joints/0/pivot/0: 1e+10 m is farther from the origin than 1e+08 m"},
    // Sizes whose products no one bounded: each hung with gigabytes allocated (int32 indices
    // overflowed past 2^31 nodes).
    {"cloth_huge", scene(kBox, R"({"name": "c", "mesh": {"type": "cloth_grid", "corner": [0, 0, 0], "side_u": [1, 0, 0], "side_v": [0, 0, 1], "columns": 3000, "rows": 3000}, "mass": 1})"),
     "/deformables/0/mesh: cloth grid: 3000 x 3000 nodes is 9000000 nodes, more than the limit of 1000000 "
     "(Limits::maxNodes; the API can raise it)"},
    {"tet_box_huge", scene(kBox, R"({"name": "c", "mesh": {"type": "tet_box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [1000, 1000, 1000]}, "mass": 1})"),
     "/deformables/0/mesh: tet box: 1000 x 1000 x 1000 cells is 1003003001 nodes, more than the limit of 1000000"},
    {"tet_box_many_tets", scene(kBox, R"({"name": "c", "mesh": {"type": "tet_box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [400, 400, 2]}, "mass": 1})"),
     "tet box: 400 x 400 x 2 cells is 1600000 tetrahedra, more than the limit of 1000000 (Limits::maxTetrahedra"},
    {"tet_cylinder_huge", scene(kBox, R"({"name": "c", "mesh": {"type": "tet_cylinder", "base_centre": [0, 0, 0], "radius": 1, "height": 1, "rings": 100000, "sectors": 100000, "layers": 100000}, "mass": 1})"),
     "tet cylinder: 100000 rings x 100000 sectors x 100000 layers is 1000010000100001 nodes, more than the limit"},
    {"obj_dev_zero", scene(kBox, R"({"name": "c", "mesh": {"type": "obj", "file": "/dev/zero"}, "mass": 1})"),
     "/deformables/0/mesh: /dev/zero: is not a regular file (a device, pipe or socket); OBJ files must be regular files"},
    {"gravity_short", R"({"format": 1, "gravity": [0, -9.81]})", "/gravity: must be an array of 3 numbers"},
    {"gravity_overflow", R"({"format": 1, "gravity": [0, -1e999, 0]})", "not valid JSON: number overflow parsing '-1e999'"},
    {"iterations_zero", R"({"format": 1, "solver": {"iterations": 0}})", "/solver/iterations: must be in [1, 1000], got 0"},
    {"iterations_real", R"({"format": 1, "solver": {"iterations": 2.5}})", "/solver/iterations: must be an integer, got a number"},
    {"friction_model", R"({"format": 1, "solver": {"friction_model": "magic"}})",
     "/solver/friction_model: unknown value 'magic' (expected one of: coulomb, pressure)"},
    {"damping_negative", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "linear_damping": -0.1})"),
     "/rigid_bodies/0/linear_damping: must be in [0, 1], got -0.1"},
    {"negative_mass", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "mass": -1})"),
     "/rigid_bodies/0/mass: must be >= 0, got -1"},
    {"no_shape", scene(R"({"name": "box"})"), "/rigid_bodies/0: missing field 'shape'"},
    {"shape_type", scene(R"({"name": "box", "shape": {"type": "cube"}})"),
     "/rigid_bodies/0/shape/type: unknown value 'cube' (expected one of: box, sphere, cylinder, capsule, plane, "
     "convex_hull, triangle_mesh, compound, mesh)"},
    {"density_of_a_box", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "density": 500})"),
     "/rigid_bodies/0/density: only a mesh shape has a density (give 'mass')"},
    {"mesh_mass_and_density", scene(R"({"name": "pot", "shape": {"type": "mesh", "file": "pot.obj"}, "mass": 1, "density": 500})"),
     "/rigid_bodies/0/density: give either 'mass' or 'density', not both"},
    {"mesh_collision", scene(R"({"name": "pot", "shape": {"type": "mesh", "file": "pot.obj", "collision": "hulls"}})"),
     "/rigid_bodies/0/shape/collision: unknown value 'hulls' (expected one of: convex_hull, hull_per_group, hull_per_piece)"},
    {"mesh_hull_vertices", scene(R"({"name": "pot", "shape": {"type": "mesh", "file": "pot.obj", "max_hull_vertices": 3}})"),
     "/rigid_bodies/0/shape/max_hull_vertices: must be in [4, 4096], got 3"},
    {"mesh_scale", scene(R"({"name": "pot", "shape": {"type": "mesh", "file": "pot.obj", "scale": 0}})"),
     "/rigid_bodies/0/shape/scale: must be > 0, got 0"},
    {"mesh_inertia", scene(R"({"name": "pot", "shape": {"type": "mesh", "file": "pot.obj"}, "inertia": [1, 1, 1]})"),
     "/rigid_bodies/0/inertia: a mesh shape's inertia comes from its mesh"},
    {"mesh_missing_file", scene(R"({"name": "pot", "shape": {"type": "mesh", "file": "no_such_pot.obj"}})"),
     "/rigid_bodies/0/shape/file: "},
    {"mesh_no_file", scene(R"({"name": "pot", "shape": {"type": "mesh"}})"), "/rigid_bodies/0/shape: missing field 'file'"},
    {"inertia_impossible", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "inertia": [1, 1, 5]})"),
     "/rigid_bodies/0: rigid body 'box': inertia 1, 1, 5 kg·m² is no body's: moment 2 is more than the sum of the other two"},
    {"compound_short_hull", scene(R"({"name": "c", "shape": {"type": "compound", "hulls": [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]]}})"),
     "/rigid_bodies/0/shape/hulls/0: a hull needs at least 4 points"},
    {"flat_box", scene(R"({"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0, 0.1]}})"),
     "/rigid_bodies/0/shape/half_extents: must all be > 0"},
    {"sphere_field", scene(R"({"name": "ball", "shape": {"type": "sphere", "radius": 1, "half_extents": [1, 1, 1]}})"),
     "/rigid_bodies/0/shape/half_extents: unknown field 'half_extents'"},
    {"dynamic_plane", scene(R"({"name": "ground", "shape": {"type": "plane", "normal": [0, 1, 0]}, "mass": 1})"),
     "/rigid_bodies/0/mass: a plane or triangle mesh must be static (mass 0) or kinematic"},
    {"bad_quaternion", scene(R"({"name": "box", "shape": {"type": "sphere", "radius": 1}, "orientation": [1, 1, 0, 0]})"),
     "/rigid_bodies/0/orientation: must be a unit quaternion [w, x, y, z], its norm is 1.41421"},
    {"two_orientations",
     scene(R"({"name": "box", "shape": {"type": "sphere", "radius": 1}, "orientation": [1, 0, 0, 0], "euler_degrees": [0, 0, 0]})"),
     "/rigid_bodies/0/euler_degrees: give either 'orientation' or 'euler_degrees', not both"},
    {"missing_hull_file", scene(R"({"name": "hull", "shape": {"type": "convex_hull", "file": "no_such.obj"}})"),
     "/rigid_bodies/0/shape/file: "},
    {"same_names", scene(kBox + ", " + kBox), "/rigid_bodies/1/name: another rigid body is already named 'box'"},
    {"hinge_unknown_body", scene(kBox, "", "", R"(, "joints": [{"type": "hinge", "body_a": "wheel", "pivot": [0, 0, 0], "axis": [0, 0, 1]}])"),
     "/joints/0/body_a: no rigid body is named 'wheel'"},
    {"hinge_zero_axis", scene(kBox, "", "", R"(, "joints": [{"type": "hinge", "body_a": "box", "pivot": [0, 0, 0], "axis": [0, 0, 0]}])"),
     "/joints/0/axis: must not be zero"},
    {"no_mass", scene("", R"({"name": "rope", "mesh": {"type": "rope", "start": [0, 1, 0], "end": [0, 0, 0], "nodes": 5}})"),
     "/deformables/0: give either 'mass' (kg, in all) or 'density'"},
    {"one_node_rope", scene("", R"({"name": "rope", "mesh": {"type": "rope", "start": [0, 1, 0], "end": [0, 0, 0], "nodes": 1}, "mass": 1})"),
     "/deformables/0/mesh/nodes: must be in [2, 100000], got 1"},
    {"zero_length_rope", scene("", R"({"name": "rope", "mesh": {"type": "rope", "start": [0, 1, 0], "end": [0, 1, 0], "nodes": 3}, "mass": 1})"),
     "/deformables/0/mesh: "},
    {"rope_path_one_point", scene("", R"({"name": "rope", "mesh": {"type": "rope", "path": [[0, 0, 0]], "nodes": 3}, "mass": 1})"),
     "/deformables/0/mesh/path: must be an array of 2 to 10000 [x, y, z] points"},
    {"rope_path_not_a_point", scene("", R"({"name": "rope", "mesh": {"type": "rope", "path": [[0, 0, 0], [1, 0]], "nodes": 3}, "mass": 1})"),
     "/deformables/0/mesh/path/1: "},
    {"rope_path_zero_length", scene("", R"({"name": "rope", "mesh": {"type": "rope", "path": [[0, 1, 0], [0, 1, 0]], "nodes": 3}, "mass": 1})"),
     "/deformables/0/mesh: "},
    {"zero_substeps", R"({"format": 1, "name": "s", "solver": {"substeps": 0}})", "/solver/substeps: must be in [1, 1000], got 0"},
    {"mesh_type", scene("", R"({"name": "rope", "mesh": {"type": "string"}, "mass": 1})"),
     "/deformables/0/mesh/type: unknown value 'string'"},
    {"missing_obj", scene("", R"({"name": "sheet", "mesh": {"type": "obj", "file": "missing.obj"}, "mass": 1})"),
     "/deformables/0/mesh: "},
    {"missing_tetgen", scene("", R"({"name": "blob", "mesh": {"type": "tetgen", "file": "missing"}, "density": 1000})"),
     "/deformables/0/mesh: "},
    {"youngs_negative", scene("", jelly(R"({"type": "corotational_fem", "youngs_modulus": -5})")),
     "/deformables/0/paradigm/youngs_modulus: must be > 0, got -5"},
    {"poisson_half", scene("", jelly(R"({"type": "corotational_fem", "poisson_ratio": 0.5})")),
     "/deformables/0/paradigm/poisson_ratio: must be in [0, 0.4999], got 0.5"},
    {"stiffness_zero", scene("", jelly(R"({"type": "shape_matching", "stiffness": 0})")),
     "/deformables/0/paradigm/stiffness: must be in (0, 1], got 0"},
    {"damping_above_one", scene("", jelly(R"({"type": "position_based", "damping": 1.5})")),
     "/deformables/0/paradigm/damping: must be in [0, 1], got 1.5"},
    {"field_of_other_paradigm", scene("", jelly(R"({"type": "shape_matching", "youngs_modulus": 1000})")),
     "/deformables/0/paradigm/youngs_modulus: unknown field 'youngs_modulus'"},
    {"fem_on_rope", scene("", rope(R"("mass": 1, "paradigm": {"type": "corotational_fem"})")),
     "/deformables/0: deformable 'rope': co-rotational FEM needs a tetrahedral mesh"},
    {"negative_density", scene("", rope(R"("density": -2)")), "/deformables/0/density: must be > 0, got -2"},
    {"negative_thickness", scene("", rope(R"("mass": 1, "thickness": -0.1)")), "/deformables/0/thickness: must be >= 0, got -0.1"},
    {"inextensibility_mode", scene("", rope(R"("mass": 1, "inextensibility": {"mode": "rigid"})")),
     "/deformables/0/inextensibility/mode: unknown value 'rigid'"},
    {"fixed_out_of_range", scene("", rope(R"("mass": 1, "fixed": [{"nodes": [0, 7]}])")),
     "/deformables/0/fixed/0/nodes/1: node 7 is out of range (the mesh has 5 nodes)"},
    {"fixed_empty_region", scene("", rope(R"("mass": 1, "fixed": [{"region": {"min": [5, 5, 5], "max": [6, 6, 6]}}])")),
     "/deformables/0/fixed/0/region: holds no node of the mesh"},
    {"anchor_unknown_deformable", scene(kBox, kRope, R"({"deformable": "cloth", "node": 0, "body": "box"})"),
     "/anchors/0/deformable: no deformable is named 'cloth'"},
    {"anchor_node_out_of_range", scene(kBox, kRope, R"({"deformable": "rope", "node": 9, "body": "box"})"),
     "/anchors/0/node: node 9 is out of range (the mesh has 5 nodes)"},
    {"anchor_two_ways", scene(kBox, kRope, R"({"deformable": "rope", "node": 0, "nearest": [0, 0, 0], "body": "box"})"),
     "/anchors/0: give exactly one of 'node' (an index), 'nearest' (a point) or 'face' (a triangle index)"},
    {"anchor_face_on_rope", scene(kBox, kRope, R"({"deformable": "rope", "face": 0, "body": "box"})"),
     "/anchors/0/face: triangle 0 is out of range (the mesh has 0 triangles)"},
    {"colour_too_bright", scene(R"({"name": "box", "shape": {"type": "sphere", "radius": 1}, "colour": [0.5, 1.5, 0]})"),
     "/rigid_bodies/0/colour/1: must be in [0, 1], got 1.5"},
    {"colour_short", scene(R"({"name": "box", "shape": {"type": "sphere", "radius": 1}, "colour": [0.5, 0.5]})"),
     "/rigid_bodies/0/colour: must be [r, g, b] with each in [0, 1], or \"#rrggbb\", got an array"},
    {"colour_bad_hex", scene("", rope(R"("mass": 1, "colour": "#12345g")")),
     "/deformables/0/colour: must be [r, g, b] with each in [0, 1], or \"#rrggbb\", got \"#12345g\""},
    {"colour_name", scene("", rope(R"("mass": 1, "colour": "brown")")),
     "/deformables/0/colour: must be [r, g, b] with each in [0, 1], or \"#rrggbb\", got \"brown\""},
    {"color_spelling", scene(R"({"name": "box", "shape": {"type": "sphere", "radius": 1}, "color": [1, 0, 0]})"),
     "/rigid_bodies/0/color: unknown field 'color'"},
    {"anchor_barycentric_sum", scene(kBox, kRope, R"({"deformable": "rope", "face": 0, "barycentric": [0.5, 0.5, 0.5], "body": "box"})"),
     "/anchors/0/barycentric: must sum to 1, they sum to 1.5"},
};

void PrintTo(const BadScene& bad, std::ostream* out) { *out << bad.name; }

class BadSceneFile : public testing::TestWithParam<BadScene> {};

TEST_P(BadSceneFile, IsRefusedWithItsMessage) {
  const BadScene& bad = GetParam();
  const std::string path = writeFile(std::string(bad.name) + ".json", bad.json);
  Result<Scene> scene = loadScene(path);
  World world;
  const Status status = scene ? buildScene(*scene, world) : scene.status();
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind(path + ": ", 0), 0u) << status.message();
  EXPECT_NE(status.message().find(bad.message), std::string::npos) << status.message();
  // The command says the same on stderr and exits non-zero.
  const std::string command = std::string(TANDEM_CLI) + " validate " + path + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  const int exitStatus = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(exitStatus)) << output;  // not a crash
  EXPECT_EQ(WEXITSTATUS(exitStatus), 3) << output;  // bad input (README: exit codes)
  EXPECT_NE(output.find(bad.message), std::string::npos) << output;
}

INSTANTIATE_TEST_SUITE_P(Table, BadSceneFile, testing::ValuesIn(kBadScenes),
                         [](const testing::TestParamInfo<BadScene>& param) { return std::string(param.param.name); });

// The scene reader's own limits: a device is not read (it never ends), a file past the size
// limit is refused before it is read, and a caller can raise the limits.
TEST(SceneFile, DevicesAndOversizedFilesAreRefusedAndTheLimitsCanBeRaised) {
  EXPECT_EQ(loadScene("/dev/zero").message(),
            "/dev/zero: is not a regular file (a device, pipe or socket); scene files must be regular files");
  const std::string path = writeFile("small.json", R"({"format": 1, "description": "twenty-odd bytes"})");
  Limits limits;
  limits.maxSceneFileBytes = 20;
  EXPECT_NE(loadScene(path, limits).message().find("small.json: the scene file has 48 bytes, more than the limit of 20 "
                                                   "(Limits::maxSceneFileBytes; the API can raise it)"),
            std::string::npos)
      << loadScene(path, limits).message();
  EXPECT_TRUE(loadScene(path).ok());

  // Physical bounds and sizes are raised the same way: gravity past the default, a cloth past
  // the default node count (then built: 1,001 x 1,000 nodes).
  const std::string heavy = writeFile("heavy.json", R"({"format": 1, "gravity": [0, -2e4, 0], "deformables": [
      {"name": "c", "mesh": {"type": "cloth_grid", "corner": [0, 0, 0], "side_u": [1, 0, 0], "side_v": [0, 0, 1],
       "columns": 1001, "rows": 1000}, "mass": 1}]})");
  EXPECT_NE(loadScene(heavy).message().find("/gravity: 20000 m/s^2 is more than 10000 m/s^2"), std::string::npos);
  Limits raised;
  raised.maxGravity = 3e4;
  Result<Scene> scene = loadScene(heavy, raised);
  ASSERT_TRUE(scene.ok()) << scene.message();
  World refused;
  EXPECT_NE(buildScene(*scene, refused).message().find("1001 x 1000 nodes is 1001000 nodes, more than the limit of 1000000"),
            std::string::npos);
  if (shortTests()) return;  // building a million nodes: 22 s under the sanitizers
  raised.maxNodes = 1'001'000;
  World built;
  ASSERT_TRUE(buildScene(*scene, built, raised).ok());
  EXPECT_EQ(built.nodePositions(DeformableId{0}).size(), 1'001'000u);
}

// Mesh files: coordinates tinyobjloader would read as 0 are refused with the line; points past
// Limits::maxCoordinate are refused with the point.
TEST(SceneFile, MeshFilesWithBadOrFarCoordinatesAreRefused) {
  writeFile("nan.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n");
  writeFile("far.obj", "v 2e9 0 0\nv 2e9 1000 0\nv 2e9 0 1000\nf 1 2 3\n");
  for (const auto& [file, message] :
       std::vector<std::pair<std::string, std::string>>{{"nan.obj", "nan.obj:2: vertex coordinate 'nan' is not a finite number"},
                                                        {"far.obj", "/deformables/0/mesh: point 0 at 2e+09 m from the origin "
                                                                    "along an axis is farther than 1e+08 m (Limits::maxCoordinate)"}}) {
    const std::string path = writeFile("mesh_" + file + ".json", R"({"format": 1, "deformables": [{"name": "c", "mesh": {"type": "obj", "file": ")" +
                                                                   file + R"("}, "mass": 1}]})");
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.message();
    World world;
    const Status status = buildScene(*scene, world);
    EXPECT_NE(status.message().find(message), std::string::npos) << status.message();
  }
  // TetGen files are read through the same door: a .node that is a device is refused.
  const fs::path zero = tempDir() / "zero.node";
  fs::remove(zero);
  fs::create_symlink("/dev/zero", zero);
  EXPECT_EQ(loadTetGen((tempDir() / "zero").string(), 1000.0).message(),
            zero.string() + ": is not a regular file (a device, pipe or socket); TetGen files must be regular files");
}

// Mesh bodies: mass from density times the mesh's volume, the body at the mesh's centre of mass,
// anchors' local points in the mesh's frame, written back as given; a mesh that bounds no solid
// is refused naming the file and the fault.
TEST(SceneFile, MeshBodiesBuildFromTheirVolumeAndRoundTrip) {
  // A 0.2 x 0.1 x 0.4 box whose corner is at the mesh's origin: centre (0.1, 0.05, 0.2).
  std::ostringstream obj;
  for (int c = 0; c < 8; ++c) obj << "v " << (c & 1 ? 0.2 : 0) << " " << (c & 2 ? 0.1 : 0) << " " << (c & 4 ? 0.4 : 0) << "\n";
  const char* faces = "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
  writeFile("brick.obj", obj.str() + faces);
  writeFile("open_brick.obj", obj.str() + std::string(faces).substr(0, std::string(faces).rfind("f 2 8 6")));
  const std::string json = R"({"format": 1, "name": "bricks", "rigid_bodies": [
      {"name": "brick", "shape": {"type": "mesh", "file": "brick.obj", "scale": 2}, "density": 500,
       "position": [1, 2, 3], "euler_degrees": [0, 90, 0]}],
    "deformables": [{"name": "rope", "mesh": {"type": "rope", "start": [1, 3, 3], "end": [1, 4, 3], "nodes": 5}, "mass": 0.1}],
    "anchors": [{"deformable": "rope", "node": 0, "body": "brick", "local_point": [0.2, 0.2, 0.8]}]})";
  Result<Scene> scene = parseScene(json, "bricks.json", tempDir().string());
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_TRUE(scene->rigidBodies[0].meshShape.has_value());
  EXPECT_EQ(scene->rigidBodies[0].meshShape->options.scale, 2.0);
  Result<Scene> reread = parseScene(sceneToJson(*scene), "again.json", tempDir().string());
  ASSERT_TRUE(reread.ok()) << reread.message();
  EXPECT_EQ(sceneToJson(*reread), sceneToJson(*scene));
  World world;
  const Status built = buildScene(*scene, world);
  ASSERT_TRUE(built.ok()) << built.message();
  const RigidBodyId brick = *world.findRigidBody("brick");
  // Scaled by 2: 0.4 x 0.2 x 0.8 = 0.064 m³ of 500 kg/m³.
  // (OBJ coordinates are read in single precision: 0.1 is 0.1 to 1.5e-9.)
  EXPECT_NEAR(world.rigidMass(brick), 32.0, 1e-5);
  // Turned 90° about y, the mesh's centre (0.2, 0.1, 0.4) lands at (0.4, 0.1, -0.2) from its origin.
  EXPECT_LT((world.rigidPosition(brick) - Vec3(1.4, 2.1, 2.8)).norm(), 1e-7);
  const Mat3 inertia = world.rigidInertia(brick);
  EXPECT_NEAR(inertia(1, 1), 32.0 / 12 * (0.4 * 0.4 + 0.8 * 0.8), 1e-6);
  // The anchor's local point, given in the mesh's frame: the mesh's (0.2, 0.2, 0.8) is 0.1 above
  // the centre and 0.4 along the mesh's z, which the turn takes to world +x.
  const AnchorState anchor = world.anchorState(AnchorId{0});
  EXPECT_LT((anchor.worldPointOnBody - (Vec3(1, 2, 3) + Vec3(0.8, 0.2, -0.2))).norm(), 1e-7);

  std::string open = json;
  open.replace(open.find("brick.obj"), 9, "open_brick.obj");
  Result<Scene> openScene = parseScene(open, "bricks.json", tempDir().string());
  ASSERT_TRUE(openScene.ok());
  World refused;
  const std::string message = buildScene(*openScene, refused).message();
  EXPECT_NE(message.find("bricks.json: /rigid_bodies/0/shape/file: " + (tempDir() / "open_brick.obj").string() +
                         ": the surface is open: the edge from vertex"),
            std::string::npos)
      << message;
}

TEST(SceneFile, AMissingFileIsNamed) {
  EXPECT_EQ(loadScene("/no/such/scene.json").message(), "/no/such/scene.json: cannot open the scene file");
  // A folder is named as such (it read as an empty file: "unexpected end of input").
  EXPECT_EQ(loadScene(tempDir().string()).message(), tempDir().string() + ": is a folder, not a scene file");
}

}  // namespace
}  // namespace tandem
