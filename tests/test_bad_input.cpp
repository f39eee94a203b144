// Bad input to the API and the generators gets a clear error naming the problem, never a crash;
// a simulation that diverges says so.
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <limits>

namespace tandem {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

#define EXPECT_ERROR(expr, fragment)                                                              \
  do {                                                                                            \
    const auto result_ = (expr);                                                                  \
    ASSERT_FALSE(result_.ok()) << #expr " should fail";                                           \
    EXPECT_NE(result_.message().find(fragment), std::string::npos) << "message: " << result_.message(); \
  } while (0)

TEST(BadInput, Generators) {
  EXPECT_ERROR(makeRope({0, 0, 0}, {1, 0, 0}, 0, 1.0), "rope: node count must be >= 2, got 0");
  EXPECT_ERROR(makeRope({0, 0, 0}, {1, 0, 0}, 1, 1.0), "node count must be >= 2, got 1");
  EXPECT_ERROR(makeRope({0, 0, 0}, {1, 0, 0}, 5, -1.0), "total mass must be a positive number of kilograms, got -1");
  EXPECT_ERROR(makeRope({0, 0, 0}, {1, 0, 0}, 5, kNaN), "total mass must be a positive number");
  EXPECT_ERROR(makeRope({0, 0, 0}, {0, 0, 0}, 5, 1.0), "start and end coincide");
  EXPECT_ERROR(makeRope({kNaN, 0, 0}, {1, 0, 0}, 5, 1.0), "start is not finite");
  EXPECT_ERROR(makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 1, 5, 1.0), "cloth grid: columns must be >= 2, got 1");
  EXPECT_ERROR(makeClothGrid({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, 4, 4, 1.0), "sides are parallel or zero");
  EXPECT_ERROR(makeTetBox({0, 0, 0}, {1, 1, 1}, 0, 1, 1, 1.0), "tet box: cells along x must be >= 1, got 0");
  EXPECT_ERROR(makeTetBox({0, 0, 0}, {1, -1, 1}, 1, 1, 1, 1.0), "max corner must exceed min corner");
}

// Sizes: each generator bounds its total nodes, triangles and tetrahedra before allocating any
// (a 3000 x 3000 cloth, a tet box of 1000^3 cells and a tet cylinder of 10^5 rings, sectors and
// layers each hung with gigabytes allocated; past 2^31 nodes the int32 indices overflowed).
TEST(BadInput, GeneratorsBoundTheirTotalSizes) {
  EXPECT_ERROR(makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 3000, 3000, 1.0),
               "cloth grid: 3000 x 3000 nodes is 9000000 nodes, more than the limit of 1000000 (Limits::maxNodes; "
               "the API can raise it)");
  EXPECT_ERROR(makeRope({0, 0, 0}, {1, 0, 0}, std::numeric_limits<int>::max(), 1.0),
               "rope: the node count is 2147483647 nodes, more than the limit of 1000000");
  EXPECT_ERROR(makeRopeAlongPath({{0, 0, 0}, {1, 0, 0}}, 2'000'000, 1.0), "rope: the node count is 2000000 nodes");
  EXPECT_ERROR(makeTetBox({0, 0, 0}, {1, 1, 1}, 1000, 1000, 1000, 1.0),
               "tet box: 1000 x 1000 x 1000 cells is 1003003001 nodes, more than the limit of 1000000");
  EXPECT_ERROR(makeTetCylinder({0, 0, 0}, 1, 1, 100000, 100000, 100000, 1.0),
               "tet cylinder: 100000 rings x 100000 sectors x 100000 layers is 1000010000100001 nodes");
  // Raising the limits past 32-bit indices does not let a mesh overflow them.
  Limits unlimited;
  unlimited.maxNodes = unlimited.maxTriangles = unlimited.maxTetrahedra = std::numeric_limits<int64_t>::max();
  EXPECT_ERROR(makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 100000, 100000, 1.0, unlimited),
               "is 10000000000 nodes, more than the limit of 2147483647 (Limits::maxNodes");
  EXPECT_ERROR(makeTetBox({0, 0, 0}, {1, 1, 1}, 2000, 2000, 2000, 1.0, unlimited), "more than the limit of 2147483647");
}

// The counts the limits are checked against are the meshes' own: a mesh of exactly the limit
// is made, one more of anything is refused naming that limit.
TEST(BadInput, SizeLimitsAreExact) {
  auto exactly = [](const DeformableMesh& mesh) {
    Limits limits;
    limits.maxNodes = mesh.nodeCount();
    limits.maxTriangles = static_cast<int64_t>(mesh.triangles.size());
    limits.maxTetrahedra = static_cast<int64_t>(mesh.tetrahedra.size());
    return limits;
  };
  auto oneShort = [](Limits limits, int which) {
    (which == 0 ? limits.maxNodes : which == 1 ? limits.maxTriangles : limits.maxTetrahedra) -= 1;
    return limits;
  };
  const char* names[] = {"Limits::maxNodes", "Limits::maxTriangles", "Limits::maxTetrahedra"};
  const DeformableMesh cloth = *makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 7, 5, 1.0);
  const DeformableMesh box = *makeTetBox({0, 0, 0}, {1, 1, 1}, 3, 4, 5, 1.0);
  const DeformableMesh cylinder = *makeTetCylinder({0, 0, 0}, 0.2, 0.5, 3, 12, 4, 1.0);
  EXPECT_TRUE(makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 7, 5, 1.0, exactly(cloth)).ok());
  EXPECT_TRUE(makeTetBox({0, 0, 0}, {1, 1, 1}, 3, 4, 5, 1.0, exactly(box)).ok());
  EXPECT_TRUE(makeTetCylinder({0, 0, 0}, 0.2, 0.5, 3, 12, 4, 1.0, exactly(cylinder)).ok());
  for (int which = 0; which < 3; ++which) {
    if (which < 2) EXPECT_ERROR(makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 7, 5, 1.0, oneShort(exactly(cloth), which)), names[which]);
    EXPECT_ERROR(makeTetBox({0, 0, 0}, {1, 1, 1}, 3, 4, 5, 1.0, oneShort(exactly(box), which)), names[which]);
    EXPECT_ERROR(makeTetCylinder({0, 0, 0}, 0.2, 0.5, 3, 12, 4, 1.0, oneShort(exactly(cylinder), which)), names[which]);
  }
}

// Using an error as a value is a programmer error: it stops with the error's message (it threw
// std::bad_variant_access, which says nothing of what went wrong). An ok Result has no message.
TEST(BadInputDeathTest, AnErrorUsedAsAValueStopsWithItsMessage) {
  EXPECT_DEATH((void)*makeRope({0, 0, 0}, {1, 0, 0}, 1, 1.0),
               "a Result holding an error was used as its value: rope: node count must be >= 2, got 1");
  EXPECT_DEATH((void)makeRope({0, 0, 0}, {0, 0, 0}, 5, 1.0)->nodeCount(), "start and end coincide");
  EXPECT_EQ(makeRope({0, 0, 0}, {1, 0, 0}, 5, 1.0).message(), "");
}

TEST(BadInput, Meshes) {
  DeformableMesh good = *makeRope({0, 0, 0}, {1, 0, 0}, 3, 0.3);
  EXPECT_TRUE(validateMesh(good).ok());

  DeformableMesh empty;
  EXPECT_ERROR(validateMesh(empty), "mesh has no nodes");
  DeformableMesh mesh = good;
  mesh.masses.pop_back();
  EXPECT_ERROR(validateMesh(mesh), "mesh has 3 positions but 2 masses");
  mesh = good;
  mesh.masses[1] = -0.5;
  EXPECT_ERROR(validateMesh(mesh), "node 1 has mass -0.5 kg");
  mesh = good;
  mesh.masses[2] = kNaN;
  EXPECT_ERROR(validateMesh(mesh), "node 2 has mass nan kg");
  mesh = good;
  mesh.positions[0].x() = kNaN;
  EXPECT_ERROR(validateMesh(mesh), "node 0 has a non-finite position");
  mesh = good;
  mesh.edges.push_back({0, 7});
  EXPECT_ERROR(validateMesh(mesh), "edge 2 refers to node 7, but the mesh has 3 nodes");
  mesh = good;
  mesh.edges.push_back({1, 1});
  EXPECT_ERROR(validateMesh(mesh), "edge 2 uses node 1 twice");
  mesh = good;
  mesh.positions[1] = mesh.positions[0];
  EXPECT_ERROR(validateMesh(mesh), "edge 0 has zero length");
  mesh = *makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 2, 2, 1.0);
  mesh.positions[3] = mesh.positions[0] + 0.5 * (mesh.positions[1] - mesh.positions[0]);
  mesh.edges.clear();
  EXPECT_ERROR(validateMesh(mesh), "is degenerate (zero area)");
  mesh = *makeTetBox({0, 0, 0}, {1, 1, 1}, 1, 1, 1, 1.0);
  std::swap(mesh.tetrahedra[2][0], mesh.tetrahedra[2][1]);
  EXPECT_ERROR(validateMesh(mesh), "tetrahedron 2 is inverted (negative volume)");
}

TEST(BadInput, WorldRefusesBadBodiesAndConstraints) {
  World world;
  DeformableDesc rope;
  rope.name = "rope";
  rope.mesh = *makeRope({0, 1, 0}, {0, 0, 0}, 4, 0.1);
  rope.mesh.masses[2] = -1.0;
  EXPECT_ERROR(world.addDeformable(rope), "deformable 'rope': node 2 has mass -1 kg");
  rope.mesh = *makeRope({0, 1, 0}, {0, 0, 0}, 4, 0.1);
  rope.springs.stiffness = -5;
  EXPECT_ERROR(world.addDeformable(rope), "spring stiffness and damping must be >= 0");
  rope.springs.stiffness = 0;
  rope.inextensibility.enabled = true;
  rope.inextensibility.maxForce = 0;
  EXPECT_ERROR(world.addDeformable(rope), "inextensibility max force must be positive");
  rope.inextensibility.maxForce = kUnbounded;
  const DeformableId id = *world.addDeformable(rope);

  RigidBodyDesc body;
  body.name = "crate";
  body.mass = -2;
  EXPECT_ERROR(world.addRigidBody(body), "rigid body 'crate': mass must be positive and finite for a dynamic body, got -2");
  body.mass = kNaN;
  EXPECT_ERROR(world.addRigidBody(body), "got nan kg");
  body.mass = 1;
  body.position.y() = kNaN;
  EXPECT_ERROR(world.addRigidBody(body), "position is not finite");
  body.position.setZero();
  body.shape = RigidShape::sphere(0);
  EXPECT_ERROR(world.addRigidBody(body), "sphere radius must be positive, got 0");
  body.shape = RigidShape::plane({0, 1, 0}, 0);
  EXPECT_ERROR(world.addRigidBody(body), "a plane or a triangle mesh can only be static");
  body.shape = RigidShape::box({0.1, 0.1, 0.1});
  body.orientation = Quat(0, 0, 0, 0);
  EXPECT_ERROR(world.addRigidBody(body), "orientation must be a finite non-zero quaternion");
  body.orientation = Quat::Identity();
  body.restitution = 2;
  EXPECT_ERROR(world.addRigidBody(body), "restitution must be in [0, 1], got 2");
  body.restitution = 0;
  body.linearDamping = 1.5;
  EXPECT_ERROR(world.addRigidBody(body), "linear damping must be in [0, 1], got 1.5");
  body.linearDamping = 0;
  body.angularDamping = kNaN;
  EXPECT_ERROR(world.addRigidBody(body), "angular damping must be in [0, 1], got nan");
  body.angularDamping = 0;
  const RigidBodyId crate = *world.addRigidBody(body);

  EXPECT_ERROR(world.addFixedPoint(id, 9, {0, 0, 0}), "fixed point: node 9 is out of range for deformable 'rope' (4 nodes)");
  EXPECT_ERROR(world.addFixedPoint(DeformableId{5}, 0, {0, 0, 0}), "fixed point: deformable 5: no such deformable (the world has 1 slot)");
  EXPECT_ERROR(world.addFixedPoint(id, 0, {kNaN, 0, 0}), "target is not finite");
  EXPECT_ERROR(world.addFixedPoint(id, 0, {0, 0, 0}, -3), "max force must be positive, got -3");
  EXPECT_ERROR(world.addAnchor(AnchorDesc::node(id, 0, RigidBodyId{9})), "anchor: rigid body 9: no such rigid body (the world has 1 slot)");
  EXPECT_ERROR(world.addAnchor(AnchorDesc::node(id, -1, crate)), "node -1 is out of range");
  AnchorDesc anchor = AnchorDesc::node(id, 0, crate);
  anchor.nodeCount = 2;
  anchor.nodes[1] = 1;
  anchor.weights = {0.7, 0.7, 0, 0};
  EXPECT_ERROR(world.addAnchor(anchor), "weights must sum to 1, got 1.4");
  anchor.nodeCount = 5;
  EXPECT_ERROR(world.addAnchor(anchor), "node count must be 1 to 4, got 5");
  EXPECT_ERROR(world.addHinge({crate, crate, {0, 0, 0}, {0, 0, 1}}), "body A and body B are the same body");
  EXPECT_ERROR(world.addHinge({crate, std::nullopt, {0, 0, 0}, {0, 0, 0}}), "axis must be a finite non-zero vector");
  EXPECT_ERROR(world.setNodeVelocity(id, 0, {kNaN, 0, 0}), "velocity is not finite");
  EXPECT_ERROR(world.fixNode(id, 4), "node 4 is out of range");
  EXPECT_ERROR(world.setNodePosition(id, 0, {0, kNaN, 0}), "set node position: position is not finite");
  EXPECT_ERROR(world.setNodePosition(id, -1, {0, 0, 0}), "set node position: node -1 is out of range");

  WorldSettings settings;
  settings.solver.iterations = 0;
  EXPECT_ERROR(world.setSettings(settings), "solver iterations must be in [1, 1000], got 0");
  settings.solver.iterations = 4;
  settings.solver.baumgarte = -0.1;
  EXPECT_ERROR(world.setSettings(settings), "baumgarte");
  settings.solver.baumgarte = 0.1;
  settings.gravity.x() = kNaN;
  EXPECT_ERROR(world.setSettings(settings), "gravity must be finite");
  EXPECT_EQ(world.settings().solver.iterations, 4);  // nothing changed

  EXPECT_ERROR(world.step(0.0), "time step must be in (0, 1] seconds, got 0");
  EXPECT_ERROR(world.step(-0.01), "got -0.01");
  EXPECT_ERROR(world.step(kNaN), "got nan");
  EXPECT_ERROR(world.step(5.0), "got 5");
  EXPECT_EQ(world.stepCount(), 0);
  EXPECT_TRUE(world.step(1.0 / 60).ok());
}

TEST(BadInput, DivergenceIsReportedNotPrinted) {
  World world;
  DeformableDesc rope;
  rope.name = "stiff rope";
  rope.mesh = *makeRope({0, 1, 0}, {1, 1, 0}, 10, 0.01);
  rope.springs.stiffness = 1e7;  // explicit springs this stiff cannot be stepped at 1/60 s
  rope.springs.implicit = false;
  const DeformableId id = *world.addDeformable(rope);
  ASSERT_TRUE(world.setNodeVelocity(id, 3, {0, 1, 0}).ok());
  Status status;
  int step = 0;
  for (; step < 200 && status.ok(); ++step) status = world.step(1.0 / 60);
  ASSERT_FALSE(status.ok()) << "the explicit springs should have diverged";
  EXPECT_NE(status.message().find("deformable 'stiff rope' node"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("the simulation diverged"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace tandem
