// Determinism, guarded: each paper scene stepped a fixed number of steps ends in the same state
// to the last bit as when the golden values below were recorded (the model: Box2D v3's
// determinism test, which hashes the bodies' final transforms against a committed value).
//
// The hash covers the full state the API shows: every rigid body's position, orientation, linear
// and angular velocity, and every deformable node's position and velocity, as bit patterns
// (FNV-1a, 64 bits, over the IEEE-754 doubles in that order).
//
// The golden values are for Debian 12 on x86-64 (GCC 12 or clang 14, Debian's Bullet 3.24 in
// double precision, Eigen 3.4; docs/reliability.md, "Determinism"). A change to the solver,
// the models, collision or the scene files changes them on purpose: check that the change is
// meant, then regenerate them with
//     build/tests/test_determinism --gtest_filter='Determinism.*GoldenHash*'
// which prints, for each scene that differs, the line to paste into kGolden.
#include <tandem/scene_file.h>

#include <gtest/gtest.h>

#include <bit>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <string>

namespace tandem {
namespace {

struct Golden {
  const char* file;  // under scenes/
  int steps;         // at the file's own time step
  uint64_t hash;
};
void PrintTo(const Golden& golden, std::ostream* out) { *out << golden.file << ", " << golden.steps << " steps"; }

// clang-format off
constexpr Golden kGolden[] = {
    {"rope_wheel.json", 150, 0xf7ade6ad75ff6102ULL},  // teapots landing on the plane get their whole contact patch
    {"cloth_sphere.json", 60, 0x47c867bd13bfd974ULL},
    {"jelly_dish.json", 60, 0x3e168fe1a6e2fb81ULL},
};
// clang-format on

class StateHash {
 public:
  void add(double value) {
    const uint64_t bits = std::bit_cast<uint64_t>(value);
    for (int byte = 0; byte < 8; ++byte) {
      m_hash ^= (bits >> (8 * byte)) & 0xffu;
      m_hash *= 0x100000001b3ULL;  // FNV-1a's 64-bit prime
    }
  }
  void add(const Vec3& v) {
    add(v.x());
    add(v.y());
    add(v.z());
  }
  void add(const Quat& q) {
    add(q.w());
    add(q.x());
    add(q.y());
    add(q.z());
  }
  uint64_t value() const { return m_hash; }

 private:
  uint64_t m_hash = 0xcbf29ce484222325ULL;  // FNV-1a's 64-bit offset basis
};

uint64_t hashState(const World& world) {
  StateHash hash;
  for (int b = 0; b < world.rigidBodyCount(); ++b) {
    const RigidBodyId id{b};
    hash.add(world.rigidPosition(id));
    hash.add(world.rigidOrientation(id));
    hash.add(world.rigidLinearVelocity(id));
    hash.add(world.rigidAngularVelocity(id));
  }
  for (int d = 0; d < world.deformableCount(); ++d) {
    for (const Vec3& x : world.nodePositions(DeformableId{d})) hash.add(x);
    for (const Vec3& v : world.nodeVelocities(DeformableId{d})) hash.add(v);
  }
  return hash.value();
}

// Loads and builds a scene into `world`, steps it `steps` times and returns the state's hash.
uint64_t runAndHash(const std::string& file, int steps) {
  Result<Scene> scene = loadScene(TANDEM_SOURCE_DIR "/scenes/" + file);
  EXPECT_TRUE(scene.ok()) << scene.message();
  if (!scene.ok()) return 0;
  World world;
  const Status built = buildScene(*scene, world);
  EXPECT_TRUE(built.ok()) << built.message();
  for (int s = 0; s < steps; ++s) {
    const Status stepped = world.step(scene->timeStep);
    EXPECT_TRUE(stepped.ok()) << file << " step " << s << ": " << stepped.message();
    if (!stepped.ok()) return 0;
  }
  return hashState(world);
}

TEST(Determinism, TheHashSeesEveryBit) {
  // One ulp in one coordinate of one node changes the hash; so does -0.0 against 0.0.
  StateHash a, b, c;
  a.add(Vec3(0.1, 0.2, 0.0));
  b.add(Vec3(0.1, std::nextafter(0.2, 1.0), 0.0));
  c.add(Vec3(0.1, 0.2, -0.0));
  EXPECT_NE(a.value(), b.value());
  EXPECT_NE(a.value(), c.value());
}

class GoldenScene : public testing::TestWithParam<Golden> {};

TEST_P(GoldenScene, GoldenHashAfterFixedSteps) {
  const Golden& golden = GetParam();
  const uint64_t hash = runAndHash(golden.file, golden.steps);
  EXPECT_EQ(hash, golden.hash) << golden.file << " after " << golden.steps << " steps: state hash differs. If the "
                               << "change is meant, the line for kGolden in tests/test_determinism.cpp is\n"
                               << "    {\"" << golden.file << "\", " << golden.steps << ", 0x" << std::hex
                               << hash << "ULL},";
}

// Two worlds built from the same file in one process step to the same bits (no dependence on
// addresses, uninitialised memory or state left over between worlds).
TEST_P(GoldenScene, SameBitsTwiceInOneProcess) {
  const Golden& golden = GetParam();
  const int steps = golden.steps / 3;
  EXPECT_EQ(runAndHash(golden.file, steps), runAndHash(golden.file, steps)) << golden.file;
}

INSTANTIATE_TEST_SUITE_P(PaperScenes, GoldenScene, testing::ValuesIn(kGolden),
                         [](const testing::TestParamInfo<Golden>& param) {
                           std::string name = param.param.file;
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace tandem
