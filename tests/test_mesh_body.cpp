// Rigid bodies from closed meshes (include/tandem/mesh_body.h): closure checks, volume integrals
// against analytic solids, principal frames, hulls, and the bodies they make in a World.
#include <tandem/mesh_body.h>
#include <tandem/shape_surface.h>
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

namespace tandem {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;
constexpr double kPi = std::numbers::pi;

struct Surface {
  std::vector<Vec3> positions;
  Triangles triangles;
};

// A box of sides `size` centred at the origin, wound outwards.
Surface boxSurface(const Vec3& size) {
  Surface s;
  for (int c = 0; c < 8; ++c)
    s.positions.push_back(0.5 * size.cwiseProduct(Vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1)));
  s.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return s;
}

// A closed cylinder about y: `segments` around, caps fanned from their centres.
Surface cylinderSurface(double radius, double height, int segments) {
  Surface s;
  for (int k = 0; k < segments; ++k) {
    const double angle = 2 * kPi * k / segments;
    for (double y : {-0.5 * height, 0.5 * height}) s.positions.emplace_back(radius * std::cos(angle), y, -radius * std::sin(angle));
  }
  const auto bottom = static_cast<int32_t>(s.positions.size());
  s.positions.emplace_back(0, -0.5 * height, 0);
  s.positions.emplace_back(0, 0.5 * height, 0);
  for (int32_t k = 0; k < segments; ++k) {
    const int32_t a = 2 * k, b = 2 * ((k + 1) % segments);  // bottom ring; +1: top ring
    s.triangles.push_back({a, b, b + 1});
    s.triangles.push_back({a, b + 1, a + 1});
    s.triangles.push_back({bottom, b, a});
    s.triangles.push_back({bottom + 1, a + 1, b + 1});
  }
  return s;
}

// An icosahedron subdivided `levels` times, its vertices pushed onto the sphere.
Surface sphereSurface(double radius, int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  Surface s;
  s.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  s.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int32_t, int32_t>, int32_t> middle;
    auto mid = [&](int32_t a, int32_t b) {
      const auto key = std::minmax(a, b);
      auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      s.positions.push_back(0.5 * (s.positions[a] + s.positions[b]));
      return middle[key] = static_cast<int32_t>(s.positions.size()) - 1;
    };
    Triangles finer;
    for (const auto& f : s.triangles) {
      const int32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    s.triangles = std::move(finer);
  }
  for (Vec3& p : s.positions) p = radius * p.normalized();
  return s;
}

Surface moved(Surface s, const Quat& rotation, const Vec3& offset) {
  for (Vec3& p : s.positions) p = rotation * p + offset;
  return s;
}

Mat3 boxInertia(const Vec3& size, double mass) {
  const Vec3 sq = size.cwiseProduct(size);
  return Vec3(mass / 12 * (sq.y() + sq.z()), mass / 12 * (sq.x() + sq.z()), mass / 12 * (sq.x() + sq.y())).asDiagonal();
}

std::string teapotFile() { return std::string(TANDEM_SOURCE_DIR) + "/scenes/meshes/teapot.obj"; }

// ---- Volume integrals against analytic solids ----------------------------------------------

TEST(MassProperties, BoxMatchesTheFormulasToRounding) {
  const Vec3 size(0.4, 0.1, 0.25);
  const Surface box = boxSurface(size);
  const Result<MassProperties> p = solidMassProperties(box.positions, box.triangles, "box");
  ASSERT_TRUE(p.ok()) << p.message();
  EXPECT_NEAR(p->volume, size.prod(), 1e-15);
  EXPECT_LT(p->centre.norm(), 1e-15);
  EXPECT_LT((p->inertia - boxInertia(size, size.prod())).norm(), 1e-16);
  // Distinct moments: the principal axes are the box's own (the nearest choice to the mesh's).
  EXPECT_LT((p->axes.toRotationMatrix() - Mat3::Identity()).norm(), 1e-12);
  EXPECT_NEAR(p->principalMoments.x(), boxInertia(size, size.prod())(0, 0), 1e-16);
}

TEST(MassProperties, OffCentreRotatedBoxGivesItsCentreAndAxes) {
  const Vec3 size(0.5, 0.2, 0.1), offset(1.5, -2.0, 0.7);
  const Quat rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).normalized();
  const Surface box = moved(boxSurface(size), rotation, offset);
  const Result<MassProperties> p = solidMassProperties(box.positions, box.triangles, "box");
  ASSERT_TRUE(p.ok()) << p.message();
  EXPECT_NEAR(p->volume, size.prod(), 1e-14);
  EXPECT_LT((p->centre - offset).norm(), 1e-13);
  const Mat3 R = rotation.toRotationMatrix();
  const Mat3 expected = R * boxInertia(size, size.prod()) * R.transpose();
  EXPECT_LT((p->inertia - expected).norm(), 1e-14);
  // The principal axes are the rotated box's axes, up to sign and order; with moments in the
  // matching order they give back the tensor.
  const Mat3 axes = p->axes.toRotationMatrix();
  for (int k = 0; k < 3; ++k) {
    double best = 0.0;
    for (int j = 0; j < 3; ++j) best = std::max(best, std::abs(axes.col(k).dot(R.col(j))));
    EXPECT_NEAR(best, 1.0, 1e-12) << "axis " << k;
  }
  EXPECT_LT((axes * p->principalMoments.asDiagonal() * axes.transpose() - expected).norm(), 1e-14);
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
}

TEST(MassProperties, CylinderOf256SegmentsIsWithinItsPolygonsError) {
  const double radius = 0.3, height = 0.8;
  const Surface cylinder = cylinderSurface(radius, height, 256);
  const Result<MassProperties> p = solidMassProperties(cylinder.positions, cylinder.triangles, "cylinder");
  ASSERT_TRUE(p.ok()) << p.message();
  const double volume = kPi * radius * radius * height;
  // A 256-gon's area is the circle's times 1 − (2π/256)²/6 + ...: 1.0e-4 less.
  EXPECT_NEAR(p->volume / volume, 1.0, 2e-4);
  EXPECT_LT(p->centre.norm(), 1e-12);
  const double m = p->volume;
  const Vec3 expected(m * (3 * radius * radius + height * height) / 12, m * radius * radius / 2,
                      m * (3 * radius * radius + height * height) / 12);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p->inertia(k, k) / expected[k], 1.0, 3e-4) << k;
  EXPECT_LT(std::abs(p->inertia(0, 1)) + std::abs(p->inertia(0, 2)) + std::abs(p->inertia(1, 2)), 1e-12);
}

TEST(MassProperties, IcosphereConvergesOnTheSphere) {
  const double radius = 0.2;
  double previousError = 1.0;
  for (int levels : {3, 4, 5}) {
    const Surface sphere = sphereSurface(radius, levels);
    const Result<MassProperties> p = solidMassProperties(sphere.positions, sphere.triangles, "sphere");
    ASSERT_TRUE(p.ok()) << p.message();
    const double volumeError = std::abs(p->volume / (4.0 / 3 * kPi * std::pow(radius, 3)) - 1);
    EXPECT_LT(volumeError, previousError / 3.5) << levels;  // second order: a quarter per level
    previousError = volumeError;
    const double ratio = p->principalMoments.mean() / (p->volume * radius * radius);  // 2/5 for a ball
    EXPECT_NEAR(ratio, 0.4, 4 * volumeError) << levels;
    EXPECT_LT(p->centre.norm(), 1e-15);
    EXPECT_LT((p->principalMoments.maxCoeff() - p->principalMoments.minCoeff()) / p->principalMoments.mean(), 1e-3);
  }
  EXPECT_LT(previousError, 1.5e-3);  // 20,480 triangles
}

// ---- Surfaces that bound no solid are refused, naming the mesh ----------------------------

TEST(MassProperties, BadSurfacesAreRefusedWithWhatIsWrong) {
  const Surface box = boxSurface({1, 1, 1});
  auto refusal = [](const Surface& s) {
    const Result<MassProperties> p = solidMassProperties(s.positions, s.triangles, "mug.obj");
    return p.ok() ? std::string("accepted") : p.message();
  };
  Surface open = box;
  open.triangles.pop_back();
  EXPECT_NE(refusal(open).find("mug.obj: the surface is open: the edge from vertex"), std::string::npos) << refusal(open);

  Surface inverted = box;
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  EXPECT_NE(refusal(inverted).find("mug.obj: the surface is wound inwards"), std::string::npos) << refusal(inverted);

  Surface oneFlipped = box;
  std::swap(oneFlipped.triangles[3][1], oneFlipped.triangles[3][2]);
  EXPECT_NE(refusal(oneFlipped).find("is used the same way round by triangles"), std::string::npos) << refusal(oneFlipped);

  Surface flat;  // a tetrahedron's four faces on four points of one plane: closed, bounding nothing
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
  flat.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_NE(refusal(flat).find("encloses no volume"), std::string::npos) << refusal(flat);

  Surface notFinite = box;
  notFinite.positions[5].y() = std::nan("");
  EXPECT_EQ(refusal(notFinite), "mug.obj: vertex 6 is not a finite point");

  Surface pastTheEnd = box;
  pastTheEnd.triangles[0][2] = 8;
  EXPECT_NE(refusal(pastTheEnd).find("triangle 1 refers to vertex 9, which does not exist"), std::string::npos);

  Surface empty;
  EXPECT_EQ(refusal(empty), "mug.obj: the surface has no triangles");
}

TEST(MassProperties, VerticesSplitAtTheSamePointStayClosed) {
  Surface box = boxSurface({1, 2, 3});
  // Give the last two triangles their own copies of their corners, as an exporter splitting at
  // a texture seam would.
  for (size_t t = box.triangles.size() - 2; t < box.triangles.size(); ++t)
    for (int32_t& v : box.triangles[t]) {
      box.positions.push_back(box.positions[v]);
      v = static_cast<int32_t>(box.positions.size()) - 1;
    }
  const Result<MassProperties> p = solidMassProperties(box.positions, box.triangles, "split.obj");
  ASSERT_TRUE(p.ok()) << p.message();
  EXPECT_NEAR(p->volume, 6.0, 1e-14);
}

// ---- Mesh bodies ---------------------------------------------------------------------------

TEST(MeshBody, TeapotFileIsClosedWithThreeClosedParts) {
  const Result<SurfaceMesh> teapot = loadObjSurface(teapotFile());
  ASSERT_TRUE(teapot.ok()) << teapot.message();
  EXPECT_EQ(teapot->groupNames, (std::vector<std::string>{"body", "spout", "handle"}));
  EXPECT_LT(teapot->triangles.size(), 5000u);  // a few thousand
  ASSERT_TRUE(checkClosedSurface(teapot->positions, teapot->triangles, "teapot").ok());
  for (int32_t g = 0; g < 3; ++g) {
    Triangles part;
    for (size_t t = 0; t < teapot->triangles.size(); ++t)
      if (teapot->triangleGroup[t] == g) part.push_back(teapot->triangles[t]);
    const Result<MassProperties> p = solidMassProperties(teapot->positions, part, teapot->groupNames[g]);
    ASSERT_TRUE(p.ok()) << p.message();
    EXPECT_GT(p->volume, 1e-5) << teapot->groupNames[g];  // 15 cm³ at least
  }
}

TEST(MeshBody, TeapotHullPerGroupIsInItsPrincipalFrame) {
  const Result<SurfaceMesh> teapot = loadObjSurface(teapotFile());
  ASSERT_TRUE(teapot.ok()) << teapot.message();
  MeshBodyOptions options;
  options.collision = MeshCollision::HullPerGroup;
  options.maxHullVertices = 48;
  options.scale = 2.0;
  const Result<MeshBody> body = makeMeshBody(*teapot, options, "teapot.obj");
  ASSERT_TRUE(body.ok()) << body.message();
  ASSERT_EQ(body->shape.type, ShapeType::Compound);
  EXPECT_EQ(body->hullCount, 3);
  ASSERT_EQ(body->shape.hulls.size(), 3u);
  for (const auto& hull : body->shape.hulls) EXPECT_LE(hull.size(), 48u);
  // The visual mesh, in the body's frame, has its centre of mass at the origin and a diagonal
  // inertia tensor: the frame is the principal frame.
  const Result<MassProperties> inBody =
      solidMassProperties(body->shape.visual.positions, body->shape.visual.triangles, "visual");
  ASSERT_TRUE(inBody.ok()) << inBody.message();
  const double size = std::cbrt(inBody->volume);
  EXPECT_LT(inBody->centre.norm(), 1e-12 * size);
  const Mat3& J = inBody->inertia;
  EXPECT_LT(std::abs(J(0, 1)) + std::abs(J(0, 2)) + std::abs(J(1, 2)), 1e-10 * J.trace());
  EXPECT_LT((J.diagonal() - body->massProperties.principalMoments).norm(), 1e-10 * J.trace());
  // Scaled by 2: eight times the volume of the file's teapot.
  const Result<MassProperties> unscaled = solidMassProperties(teapot->positions, teapot->triangles, "teapot");
  EXPECT_NEAR(body->massProperties.volume / unscaled->volume, 8.0, 1e-9);
  // An upright teapot: the body's axes stay near the mesh's (the nearest principal choice).
  EXPECT_GT((body->axes() * Vec3::UnitY()).y(), 0.99);
  // A mass's inertia and a point in the mesh's frame in the body's.
  EXPECT_LT((body->inertia(2.6) - 2.6 / body->massProperties.volume * body->massProperties.principalMoments).norm(), 1e-15);
  EXPECT_LT(body->toBodyFrame(body->centre()).norm(), 1e-15);
}

TEST(MeshBody, HullPerPieceFindsTheConnectedPieces) {
  Surface two = boxSurface({0.2, 0.2, 0.2});
  const Surface other = moved(boxSurface({0.1, 0.3, 0.1}), Quat::Identity(), Vec3(1, 0, 0));
  for (auto t : other.triangles) {
    for (int32_t& v : t) v += 8;
    two.triangles.push_back(t);
  }
  two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
  SurfaceMesh mesh{two.positions, two.triangles, {}, {}};
  MeshBodyOptions options;
  options.collision = MeshCollision::HullPerPiece;
  const Result<MeshBody> body = makeMeshBody(mesh, options, "two.obj");
  ASSERT_TRUE(body.ok()) << body.message();
  EXPECT_EQ(body->hullCount, 2);
  // Volumes 0.008 and 0.003 m³: the centre of mass lies 3/11 of the way to the second box.
  EXPECT_NEAR(body->massProperties.volume, 0.011, 1e-15);
  EXPECT_NEAR(body->centre().x(), 3.0 / 11.0, 1e-14);
  // One hull of everything instead: a single convex hull.
  options.collision = MeshCollision::ConvexHull;
  const Result<MeshBody> single = makeMeshBody(mesh, options, "two.obj");
  ASSERT_TRUE(single.ok());
  EXPECT_EQ(single->shape.type, ShapeType::ConvexHull);
  EXPECT_EQ(single->shape.points.size(), 16u);
}

TEST(MeshBody, SimplifiedHullKeepsFewerOfItsVerticesAndMostOfItsVolume) {
  const Surface sphere = sphereSurface(0.5, 3);  // 642 vertices, all on the hull
  SurfaceMesh mesh{sphere.positions, sphere.triangles, {}, {}};
  MeshBodyOptions options;
  options.maxHullVertices = 32;
  const Result<MeshBody> body = makeMeshBody(mesh, options, "ball.obj");
  ASSERT_TRUE(body.ok()) << body.message();
  const std::vector<Vec3>& hull = body->shape.points;
  EXPECT_LE(hull.size(), 32u);
  EXPECT_GE(hull.size(), 24u);
  for (const Vec3& p : hull) EXPECT_NEAR(p.norm(), 0.5, 1e-12);  // a subset of the sphere's vertices
  const ShapeSurface surface = shapeSurface(RigidShape::convexHull(hull));
  const Result<MassProperties> kept = solidMassProperties(surface.positions, surface.triangles, "hull");
  ASSERT_TRUE(kept.ok()) << kept.message();
  EXPECT_GT(kept->volume / body->massProperties.volume, 0.75);
}

TEST(MeshBody, BadOptionsAndOpenPartsAreRefused) {
  const Surface box = boxSurface({1, 1, 1});
  SurfaceMesh mesh{box.positions, box.triangles, std::vector<int32_t>(12, 0), {"lid"}};
  for (int t = 6; t < 12; ++t) mesh.triangleGroup[t] = 1;
  mesh.groupNames.push_back("pot");
  MeshBodyOptions options;
  options.maxHullVertices = 3;
  EXPECT_EQ(makeMeshBody(mesh, options, "box.obj").message(), "box.obj: max hull vertices must be in [4, 4096], got 3");
  options = {};
  options.scale = -1;
  EXPECT_EQ(makeMeshBody(mesh, options, "box.obj").message(), "box.obj: scale must be a positive number, got -1");
  options = {};
  options.collision = MeshCollision::HullPerGroup;  // each half of a box is open
  const std::string message = makeMeshBody(mesh, options, "box.obj").message();
  EXPECT_NE(message.find("box.obj: part 'lid': the surface is open"), std::string::npos) << message;
}

TEST(MeshBody, ObjFilesAreReadWithTheirGroupsAndBadOnesNamed) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "tandem_mesh_body_test";
  std::filesystem::create_directories(folder);
  const std::string good = (folder / "two.obj").string(), bad = (folder / "bad.obj").string();
  {
    std::ofstream out(good);
    const Surface box = boxSurface({1, 1, 1});
    for (const Vec3& p : box.positions) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    out << "g bottom\n";
    for (int t = 0; t < 6; ++t) out << "f " << box.triangles[t][0] + 1 << " " << box.triangles[t][1] + 1 << " " << box.triangles[t][2] + 1 << "\n";
    out << "g top\n";
    for (int t = 6; t < 12; ++t) out << "f " << box.triangles[t][0] + 1 << " " << box.triangles[t][1] + 1 << " " << box.triangles[t][2] + 1 << "\n";
    std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n";
  }
  const Result<SurfaceMesh> mesh = loadObjSurface(good);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->groupNames, (std::vector<std::string>{"bottom", "top"}));
  EXPECT_EQ(mesh->triangles.size(), 12u);
  EXPECT_EQ(mesh->triangleGroup[0], 0);
  EXPECT_EQ(mesh->triangleGroup[11], 1);
  EXPECT_EQ(loadObjSurface(bad).message(), bad + ":3: vertex coordinate 'nan' is not a finite number");
  EXPECT_NE(loadObjSurface((folder / "none.obj").string()).message().find("none.obj"), std::string::npos);
  std::filesystem::remove_all(folder);
}

// ---- In a world ----------------------------------------------------------------------------

TEST(MeshBody, WorldBodyHasTheMeshsMassPropertiesAndPose) {
  const Vec3 size(0.3, 0.1, 0.2), offset(0.05, 0.02, -0.03);
  const Quat tilt = Quat(Eigen::AngleAxisd(0.4, Vec3(0, 0, 1))).normalized();
  const Surface box = moved(boxSurface(size), tilt, offset);  // in the mesh's frame
  const Result<MeshBody> mesh = makeMeshBody(SurfaceMesh{box.positions, box.triangles, {}, {}}, {}, "box.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  World world;
  const Vec3 position(1, 2, 3);
  const Quat orientation = Quat(Eigen::AngleAxisd(1.1, Vec3(1, 1, 0).normalized())).normalized();
  const double mass = 3.0;
  const RigidBodyId id = *world.addRigidBody(mesh->desc("brick", mass, position, orientation));
  EXPECT_DOUBLE_EQ(world.rigidMass(id), mass);
  EXPECT_LT((world.rigidPosition(id) - (position + orientation * offset)).norm(), 1e-12);
  // The world inertia is the box's, turned by the mesh's tilt and the placement.
  const Mat3 R = (orientation * tilt).toRotationMatrix();
  const Mat3 expected = R * boxInertia(size, mass) * R.transpose();
  EXPECT_LT((world.rigidInertia(id) - expected).norm(), 1e-12 * expected.norm());
}

TEST(MeshBody, DroppedTeapotRestsOnItsFootAsAHullPerGroup) {
  const Result<SurfaceMesh> teapot = loadObjSurface(teapotFile());
  ASSERT_TRUE(teapot.ok()) << teapot.message();
  MeshBodyOptions options;
  options.collision = MeshCollision::HullPerGroup;
  const Result<MeshBody> mesh = makeMeshBody(*teapot, options, "teapot.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  World world;
  RigidBodyDesc floor;
  floor.name = "floor";
  floor.shape = RigidShape::plane({0, 1, 0}, 0);
  floor.motion = MotionType::Static;
  ASSERT_TRUE(world.addRigidBody(floor).ok());
  const RigidBodyId id = *world.addRigidBody(mesh->desc("teapot", 1.0, Vec3(0, 0.2, 0)));
  for (int step = 0; step < 120; ++step) ASSERT_TRUE(world.step(1.0 / 60).ok());
  // Upright on its flat foot (y = 0 in the mesh): the centre of mass at its height over the
  // foot, within Bullet's hull margin, and still.
  EXPECT_NEAR(world.rigidPosition(id).y(), mesh->centre().y(), 0.004);
  EXPECT_GT((world.rigidOrientation(id) * mesh->axes().conjugate() * Vec3::UnitY()).y(), 0.999);
  EXPECT_LT(world.rigidLinearVelocity(id).norm(), 0.01);
}

TEST(MeshBody, BadInertiaAndVisualMeshesAreRefused) {
  World world;
  RigidBodyDesc desc;
  desc.name = "odd";
  desc.shape = RigidShape::box({0.1, 0.1, 0.1});
  desc.inertia = Vec3(1, 1, 3);
  EXPECT_EQ(world.addRigidBody(desc).message(),
            "rigid body 'odd': inertia 1, 1, 3 kg·m² is no body's: moment 2 is more than the sum of the other two");
  desc.inertia = Vec3(1, 0, 1);
  EXPECT_NE(world.addRigidBody(desc).message().find("must be three positive principal moments"), std::string::npos);
  desc.inertia.reset();
  desc.shape.visual.positions = {{0, 0, 0}, {1, 0, 0}};
  desc.shape.visual.triangles = {{0, 1, 2}};
  EXPECT_EQ(world.addRigidBody(desc).message(), "rigid body 'odd': visual mesh triangle 0 refers to vertex 2 (there are 2)");
  desc.shape = RigidShape::compound({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}});
  EXPECT_EQ(world.addRigidBody(desc).message(), "rigid body 'odd': compound hull 0's points are flat (no volume)");
  EXPECT_EQ(world.rigidBodyCount(), 0);
}

TEST(MeshBody, VisualMeshIsDrawnWithSmoothNormalsSplitAtCreases) {
  const Surface cylinder = cylinderSurface(0.1, 0.2, 32);
  RigidShape shape = RigidShape::box({0.1, 0.1, 0.1});
  shape.visual = {cylinder.positions, cylinder.triangles};
  const ShapeSurface surface = shapeSurface(shape);
  ASSERT_EQ(surface.triangles.size(), cylinder.triangles.size());
  // The side's rim vertices get a radial normal and a cap normal: split once at each rim, the
  // caps' centres once: 32·2·2 + 2 vertices.
  EXPECT_EQ(surface.positions.size(), 32u * 4 + 2);
  for (size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& f = surface.triangles[t];
    const Vec3 face = (surface.positions[f[1]] - surface.positions[f[0]]).cross(surface.positions[f[2]] - surface.positions[f[0]]).normalized();
    for (int32_t v : f) {
      EXPECT_NEAR(surface.normals[v].norm(), 1.0, 1e-12);
      EXPECT_GT(surface.normals[v].dot(face), std::cos(50 * kPi / 180));
    }
  }
  // A side vertex's normal is radial: smooth round the side.
  for (size_t v = 0; v < surface.positions.size(); ++v) {
    const Vec3& p = surface.positions[v];
    if (std::abs(surface.normals[v].y()) < 1e-9) {
      EXPECT_LT((surface.normals[v] - Vec3(p.x(), 0, p.z()).normalized()).norm(), 1e-12);
    }
  }
}

}  // namespace
}  // namespace tandem
