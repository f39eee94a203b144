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
//     build/tests/test_determinism --gtest_filter='*GoldenHash*'
// which prints, for each scene that differs, the line to paste into kGolden.
#include <tandem/scene_file.h>

#include <gtest/gtest.h>

#include <bit>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "short_tests.h"

namespace tandem {
namespace {

// Each scene has two checkpoints on one run: a hash after `shortSteps` and one after `steps`.
// The Release suite checks both; the sanitizer suite (TANDEM_SHORT_TESTS=1, scripts/sanitize.sh),
// where a step of the jelly scene takes seconds, stops at the first and checks its hash alone.
struct Golden {
  const char* file;  // under scenes/
  int shortSteps;    // at the file's own time step
  uint64_t shortHash;
  int steps;
  uint64_t hash;
};
void PrintTo(const Golden& golden, std::ostream* out) { *out << golden.file << ", " << golden.steps << " steps"; }

// clang-format off
constexpr Golden kGolden[] = {
    {"rope_wheel.json", 30, 0xc560057e961db962ULL, 150, 0x3cfe645efee71112ULL},  // bending's warm start carried onto its new Jacobian
    {"cloth_sphere.json", 15, 0xa8ab84d7e014fe51ULL, 60, 0x2f60047d31814a59ULL},  // bending's warm start carried onto its new Jacobian
    {"jelly_dish.json", 9, 0xeecbfc4a07857f48ULL, 60, 0x37b996b5c4492375ULL},  // the implicit solve preconditioned by 3 x 3 node blocks
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

std::string hexOf(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, value);
  return text;
}

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

// Loads and builds a scene, steps it up to each of `checkpoints` (step counts, ascending) and
// returns the state's hash at each.
std::vector<uint64_t> runAndHash(const std::string& file, const std::vector<int>& checkpoints) {
  std::vector<uint64_t> hashes;
  Result<Scene> scene = loadScene(TANDEM_SOURCE_DIR "/scenes/" + file);
  EXPECT_TRUE(scene.ok()) << scene.message();
  if (!scene.ok()) return hashes;
  World world;
  const Status built = buildScene(*scene, world);
  EXPECT_TRUE(built.ok()) << built.message();
  int s = 0;
  for (const int steps : checkpoints) {
    for (; s < steps; ++s) {
      const Status stepped = world.step(scene->timeStep);
      EXPECT_TRUE(stepped.ok()) << file << " step " << s << ": " << stepped.message();
      if (!stepped.ok()) return hashes;
    }
    hashes.push_back(hashState(world));
  }
  return hashes;
}
uint64_t runAndHash(const std::string& file, int steps) {
  const std::vector<uint64_t> hashes = runAndHash(file, std::vector<int>{steps});
  return hashes.empty() ? 0 : hashes.front();
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
  std::vector<int> checkpoints{golden.shortSteps};
  if (!shortTests()) checkpoints.push_back(golden.steps);
  const std::vector<uint64_t> hashes = runAndHash(golden.file, checkpoints);
  ASSERT_EQ(hashes.size(), checkpoints.size()) << golden.file << ": a step failed";
  const uint64_t fullHash = shortTests() ? 0 : hashes[1];
  const std::string line = "{\"" + std::string(golden.file) + "\", " + std::to_string(golden.shortSteps) + ", 0x" +
                           hexOf(hashes[0]) + "ULL, " + std::to_string(golden.steps) + ", 0x" +
                           (shortTests() ? hexOf(golden.hash) : hexOf(fullHash)) + "ULL},";
  EXPECT_EQ(hashes[0], golden.shortHash) << golden.file << " after " << golden.shortSteps
                                         << " steps: state hash differs. If the change is meant, the line for "
                                         << "kGolden in tests/test_determinism.cpp is\n    " << line;
  if (!shortTests()) {
    EXPECT_EQ(fullHash, golden.hash) << golden.file << " after " << golden.steps
                                     << " steps: state hash differs. If the change is meant, the line for "
                                     << "kGolden in tests/test_determinism.cpp is\n    " << line;
  }
}

// Two worlds built from the same file in one process step to the same bits (no dependence on
// addresses, uninitialised memory or state left over between worlds).
TEST_P(GoldenScene, SameBitsTwiceInOneProcess) {
  const Golden& golden = GetParam();
  const int steps = (shortTests() ? golden.shortSteps : golden.steps) / 3;
  EXPECT_EQ(runAndHash(golden.file, steps), runAndHash(golden.file, steps)) << golden.file;
}

INSTANTIATE_TEST_SUITE_P(PaperScenes, GoldenScene, testing::ValuesIn(kGolden),
                         [](const testing::TestParamInfo<Golden>& param) {
                           std::string name = param.param.file;
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace tandem
