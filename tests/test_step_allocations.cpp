// The step's working memory is kept between steps, so that stepping allocates nothing once it
// has grown to the scene: every global operator new in this executable is counted, and every
// malloc, calloc and realloc (Eigen's and Bullet's heap memory goes there directly) where the C
// library is glibc and no sanitizer replaces them. (Checked for the models' stage, a whole step
// of a jelly resting on the ground and the paper's jelly scene; what still allocates is in
// docs/architecture.md.)
#include "models/position_based.h"

#include <tandem/mesh.h>
#include <tandem/scene_file.h>
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>

#include "short_tests.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// The replacements pair malloc with free throughout; gcc cannot see that across inlining.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || __has_feature(thread_sanitizer)
#define TANDEM_SANITIZED_MALLOC 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TANDEM_SANITIZED_MALLOC 1
#endif
#if defined(__GLIBC__) && !defined(TANDEM_SANITIZED_MALLOC)
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* malloc(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, size);
}
}
#endif

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace tandem {
namespace {

constexpr double kStep = 1.0 / 50.0;

// A jelly's mesh, its nodes falling at 1 m/s, and each paradigm's model over it.
struct Jelly {
  DeformableMesh mesh = *makeTetCylinder({0, 0.1, 0}, 0.1, 0.2, 2, 8, 3, 0.5);
  NodeArrays nodes;
  PositionBasedRest rest = positionBasedRest(mesh.positions, mesh.edges, mesh.tetrahedra);
  PositionBasedBody model{0, mesh.nodeCount(), mesh.positions, mesh.edges, mesh.tetrahedra, &rest, 1.0, 0.05, 20,
                          {}, {}, {}};
  Jelly() {
    nodes.position = mesh.positions;
    nodes.velocity.assign(mesh.positions.size(), Vec3(0, -1, 0));
    nodes.force.assign(mesh.positions.size(), Vec3::Zero());
    for (double m : mesh.masses) nodes.inverseMass.push_back(1.0 / m);
  }
};

// The models' stage keeps its working memory (predicted positions, goals, weights, supports) in
// a scratch that outlives the step, and PBD's rest lengths and volumes are computed when the body
// is made: once the scratch has grown to a body, applying its paradigm allocates nothing.
TEST(StepAllocations, PositionBasedParadigmsAllocateNothingOnceTheirScratchHasGrown) {
  Jelly jelly;
  PositionBasedScratch scratch;
  applyPositionBasedDynamics(jelly.model, jelly.nodes, kStep, scratch);
  applyShapeMatching(jelly.model, jelly.nodes, kStep, scratch);
  const long before = g_allocations.load();
  for (int step = 0; step < 5; ++step) {
    applyPositionBasedDynamics(jelly.model, jelly.nodes, kStep, scratch);
    applyShapeMatching(jelly.model, jelly.nodes, kStep, scratch);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  // The counter counts: the first use of a fresh scratch allocates.
  PositionBasedScratch fresh;
  applyShapeMatching(jelly.model, jelly.nodes, kStep, fresh);
  EXPECT_GT(g_allocations.load() - before, 0);
  for (const Vec3& v : jelly.nodes.velocity) ASSERT_TRUE(v.allFinite());
}

// PBD's rest geometry: each edge's length and each tetrahedron's six volumes, positive for the
// generator's tetrahedra, summing to six times the cylinder's volume (its polygonal section);
// every edge and tetrahedron of the mesh there once (in the projections' colour order).
TEST(StepAllocations, PositionBasedRestHoldsEdgeLengthsAndVolumes) {
  const Jelly jelly;
  ASSERT_EQ(jelly.rest.edges.size(), jelly.mesh.edges.size());
  ASSERT_EQ(jelly.rest.tetrahedra.size(), jelly.mesh.tetrahedra.size());
  std::vector<std::array<int32_t, 2>> edges;
  for (const PositionBasedRest::Edge& edge : jelly.rest.edges) {
    const auto& e = edge.node;
    EXPECT_DOUBLE_EQ(edge.length, (jelly.mesh.positions[e[1]] - jelly.mesh.positions[e[0]]).norm());
    edges.push_back(e);
  }
  std::vector<std::array<int32_t, 2>> meshEdges(jelly.mesh.edges.begin(), jelly.mesh.edges.end());
  std::sort(edges.begin(), edges.end());
  std::sort(meshEdges.begin(), meshEdges.end());
  EXPECT_EQ(edges, meshEdges);
  std::vector<std::array<int32_t, 4>> tetrahedra;
  double volume = 0.0;
  for (const PositionBasedRest::Tetrahedron& tetrahedron : jelly.rest.tetrahedra) {
    EXPECT_GT(tetrahedron.sixVolume, 0.0);
    volume += tetrahedron.sixVolume / 6.0;
    tetrahedra.push_back(tetrahedron.node);
  }
  std::vector<std::array<int32_t, 4>> meshTetrahedra(jelly.mesh.tetrahedra.begin(), jelly.mesh.tetrahedra.end());
  std::sort(tetrahedra.begin(), tetrahedra.end());
  std::sort(meshTetrahedra.begin(), meshTetrahedra.end());
  EXPECT_EQ(tetrahedra, meshTetrahedra);
  const int sectors = 8;  // the generator's: a regular octagon of radius 0.1, 0.2 high
  const double octagon = 0.5 * sectors * 0.1 * 0.1 * std::sin(2 * 3.14159265358979323846 / sectors);
  EXPECT_NEAR(volume, octagon * 0.2, 1e-12);
}

// A whole step of a world holding one position-based, shape-matched or FEM jelly at rest on the
// ground: models (the implicit solve's conjugate gradients too), Bullet's stages, contact
// detection, rows, sweeps, integration, strain limiting, impact zones, report.
class RestingJellyStep : public ::testing::TestWithParam<ParadigmType> {};

TEST_P(RestingJellyStep, AllocatesNothingOnceGrown) {
  World world;
  RigidBodyDesc ground;
  ground.name = "ground";
  ground.shape = RigidShape::plane({0, 1, 0}, 0.0);
  ground.motion = MotionType::Static;
  ASSERT_TRUE(world.addRigidBody(ground).ok());
  DeformableDesc jelly;
  jelly.name = "jelly";
  jelly.mesh = *makeTetCylinder({0, 0.01, 0}, 0.1, 0.2, 2, 8, 3, 0.5);
  jelly.paradigm.type = GetParam();
  jelly.paradigm.stiffness = GetParam() == ParadigmType::PositionBased ? 1.0 : 0.5;
  jelly.paradigm.iterations = 20;
  jelly.paradigm.damping = 0.05;
  jelly.paradigm.youngsModulus = 50000;  // the paper's FEM jelly
  jelly.paradigm.poissonRatio = 0.3;
  const DeformableId id = *world.addDeformable(jelly);
  for (int step = 0; step < 100; ++step) ASSERT_TRUE(world.step(kStep).ok());
  const long before = g_allocations.load();
  for (int step = 0; step < 20; ++step) ASSERT_TRUE(world.step(kStep).ok());
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_FALSE(world.contacts().empty());  // it rests on the ground: contacts found every step
  double lowest = INFINITY;
  for (const Vec3& x : world.nodePositions(id)) lowest = std::min(lowest, x.y());
  EXPECT_NEAR(lowest, 0.0, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Paradigms, RestingJellyStep,
                         ::testing::Values(ParadigmType::ShapeMatching, ParadigmType::PositionBased,
                                           ParadigmType::CorotationalFem),
                         [](const auto& param) {
                           switch (param.param) {
                             case ParadigmType::PositionBased: return "PositionBased";
                             case ParadigmType::ShapeMatching: return "ShapeMatching";
                             default: return "CorotationalFem";
                           }
                         });

// The paper's jelly scene once settled: four jellies of the four paradigms and a bar in a dish,
// the bar moving in the FEM and mass-spring jellies' joint implicit solve (models/supports.h),
// contacts between the jellies, impact zones over four surfaces: no step allocates. (When the
// jellies and the bar were a direct block, a step that factorised it afresh allocated inside
// Eigen; the scene has no block now.)
TEST(StepAllocations, ThePapersJellySceneAllocatesNothingOnceSettled) {
  // Under the sanitizers (TANDEM_SHORT_TESTS=1, scripts/sanitize.sh) its 220 steps took 257 s;
  // what it counts does not depend on them, and the jelly scene's memory is checked there by the
  // paper-scene tests.
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  Result<Scene> scene = loadScene(TANDEM_SOURCE_DIR "/scenes/jelly_dish.json");
  ASSERT_TRUE(scene.ok()) << scene.message();
  World world;
  ASSERT_TRUE(buildScene(*scene, world).ok());
  for (int step = 0; step < 200; ++step) ASSERT_TRUE(world.step(scene->timeStep).ok());  // 4 s
  for (int step = 0; step < 20; ++step) {
    const long before = g_allocations.load();
    ASSERT_TRUE(world.step(scene->timeStep).ok());
    EXPECT_EQ(g_allocations.load() - before, 0) << "step " << step;
    EXPECT_EQ(world.lastReport().blockFactorisations, 0) << "step " << step;
  }
  EXPECT_GT(world.lastReport().rows(RowType::Contact), 0);
}

}  // namespace
}  // namespace tandem
