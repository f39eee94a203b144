// Writing a scene and reading it back is a fixed point: every shipped scene and every seed of the
// scene fuzzer, read, written, read again and written again, gives the same text to the last
// bit (the fuzzer, tests/fuzz, checks the same on its inputs; this is its regression test).
#include <tandem/scene_file.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace tandem {
namespace {

namespace fs = std::filesystem;

void expectFixedPoint(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  // Meshes are found beside the shipped scenes, as the fuzzer finds them.
  Result<Scene> read = parseScene(text.str(), file.string(), TANDEM_SOURCE_DIR "/scenes");
  ASSERT_TRUE(read.ok()) << read.message();
  const std::string written = sceneToJson(*read);
  Result<Scene> reread = parseScene(written, "written.json", TANDEM_SOURCE_DIR "/scenes");
  ASSERT_TRUE(reread.ok()) << reread.message();
  EXPECT_EQ(sceneToJson(*reread), written) << file;
}

TEST(SceneRoundTrip, EveryShippedSceneAndFuzzSeed) {
  int count = 0;
  for (const char* folder : {TANDEM_SOURCE_DIR "/scenes", TANDEM_SOURCE_DIR "/tests/fuzz/seeds"})
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.path().extension() == ".json") {
        ++count;
        expectFixedPoint(entry.path());
      }
  EXPECT_GE(count, 18 + 10);
}

// The fuzzer's first finding: a body turned by Euler angles (friction_slope.json's 20° slope)
// read back with its quaternion normalised a second time, one bit off in w and z.
TEST(SceneRoundTrip, AQuaternionUnitToRoundingIsKeptBitForBit) {
  const std::string json = R"({"format": 1, "rigid_bodies": [{"name": "slope", "mass": 0,
    "shape": {"type": "box", "half_extents": [1, 0.05, 1]}, "euler_degrees": [0, 0, -20]}]})";
  Result<Scene> read = parseScene(json, "slope.json", ".");
  ASSERT_TRUE(read.ok()) << read.message();
  Result<Scene> reread = parseScene(sceneToJson(*read), "written.json", ".");
  ASSERT_TRUE(reread.ok()) << reread.message();
  const Quat a = read->rigidBodies[0].desc.orientation, b = reread->rigidBodies[0].desc.orientation;
  EXPECT_EQ(a.w(), b.w());
  EXPECT_EQ(a.x(), b.x());
  EXPECT_EQ(a.y(), b.y());
  EXPECT_EQ(a.z(), b.z());
  // A quaternion off unit by more than rounding (but within the reader's 1e-3) is still normalised.
  Result<Scene> loose = parseScene(R"({"format": 1, "rigid_bodies": [{"name": "b", "mass": 1,
    "shape": {"type": "sphere", "radius": 0.1}, "orientation": [1.0005, 0, 0, 0]}]})", "loose.json", ".");
  ASSERT_TRUE(loose.ok()) << loose.message();
  EXPECT_EQ(loose->rigidBodies[0].desc.orientation.w(), 1.0);
}

// The fuzzer's second finding: a plane normal of [0, -1e300, 0] was accepted, normalised through
// an overflowing norm to [0, 0, 0] and written so; reading that back failed ("must not be zero").
TEST(SceneRoundTrip, AHugePlaneNormalIsNormalisedWithoutOverflow) {
  for (const char* normal : {"[0, -1e300, 0]", "[1e-300, 1e-300, 0]", "[1, 1, 0]"}) {
    const std::string json = std::string(R"({"format": 1, "rigid_bodies": [{"name": "ground", "mass": 0,
      "shape": {"type": "plane", "normal": )") + normal + "}}]}";
    Result<Scene> read = parseScene(json, "plane.json", ".");
    if (std::string(normal) == "[1e-300, 1e-300, 0]") {  // a zero normal to all intents: refused, named
      ASSERT_FALSE(read.ok());
      EXPECT_NE(read.message().find("/rigid_bodies/0/shape/normal: must not be zero"), std::string::npos) << read.message();
      continue;
    }
    ASSERT_TRUE(read.ok()) << read.message();
    const Vec3 n = read->rigidBodies[0].desc.shape.planeNormal;
    EXPECT_NEAR(n.norm(), 1.0, 1e-15) << normal;
    Result<Scene> reread = parseScene(sceneToJson(*read), "written.json", ".");
    ASSERT_TRUE(reread.ok()) << reread.message();
    EXPECT_EQ(sceneToJson(*reread), sceneToJson(*read)) << normal;
  }
}

}  // namespace
}  // namespace tandem
