// Soak: each paper scene run well past the moment it comes to rest, checking every step that
// nothing is NaN and that energy does not grow, and measuring creep: how fast the bodies that
// should rest (the jellies and the bar in the dish, the cloth on the sphere, the boxes, wheel and
// rope once the heavy box is down) still move, as the drift of each body's centroid (a rigid
// body's position, a deformable's mean node position) between the end of settling and the end
// of the run, and the mean displacement of its nodes over the same window.
//
// ctest runs each scene for its `seconds` below. scripts/soak.py runs the same code for longer
// (TANDEM_SOAK_SECONDS) and plots what TANDEM_SOAK_CSV asks it to write (docs/reliability.md,
// "Soak"). Under the sanitizers (TANDEM_SHORT_TESTS=1) the runs are cut to 1 s: NaN and energy
// are still checked, creep is not (nothing has settled yet).
#include <tandem/scene_file.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "short_tests.h"

namespace tandem {
namespace {

struct RestingBody {
  const char* name;   // a deformable or a rigid body of the scene
  double creepToday;  // m/s: what main measured from `settle` to `seconds` (ctest's run), and the
                      // regression bound, with a margin of 1.5 (a body creeping faster fails)
};

struct SoakCase {
  const char* file;        // under scenes/
  double seconds;          // run length in ctest
  double settle;           // s: from here on the resting bodies should stay put
  std::vector<RestingBody> resting;
  bool staysPut = false;   // its bodies meet the stay-put bound already: asserted in ctest's run
};
void PrintTo(const SoakCase& soak, std::ostream* out) { *out << soak.file << ", " << soak.seconds << " s"; }

// A body at rest stays put: less than 0.1 mm/s, i.e. 1 mm over a 10 s window (the issue's
// "a body at rest should stay put", in numbers). Asserted for the scenes marked staysPut, and
// for all by DISABLED_RestingBodiesStayPut.
constexpr double kStayPutBound = 1e-4;
constexpr double kRegressionMargin = 1.5;
constexpr double kRegressionFloor = 1e-5;  // m/s: 0.01 mm/s, below which creep is not told apart

double envSeconds(const char* name) {
  const char* text = std::getenv(name);
  return text ? std::atof(text) : 0.0;
}
bool finite(const Vec3& v) { return v.allFinite(); }

struct Energy {
  double kinetic = 0, potential = 0;
  double total() const { return kinetic + potential; }
};

// Kinetic and gravitational energy of everything dynamic (elastic energy is not visible through
// the API: it only ever came from these two, so their sum must not grow).
Energy energyOf(const World& world) {
  Energy e;
  const Vec3 g = world.settings().gravity;
  for (int b = 0; b < world.rigidBodyCount(); ++b) {
    const RigidBodyId id{b};
    const double m = world.rigidMass(id);
    if (m <= 0) continue;
    const Vec3 w = world.rigidAngularVelocity(id);
    e.kinetic += 0.5 * m * world.rigidLinearVelocity(id).squaredNorm() + 0.5 * w.dot(world.rigidInertia(id) * w);
    e.potential -= m * g.dot(world.rigidPosition(id));
  }
  for (int d = 0; d < world.deformableCount(); ++d) {
    const DeformableId id{d};
    const auto x = world.nodePositions(id);
    const auto v = world.nodeVelocities(id);
    const auto inverseMass = world.nodeInverseMasses(id);
    for (size_t n = 0; n < x.size(); ++n) {
      if (inverseMass[n] <= 0) continue;
      const double m = 1.0 / inverseMass[n];
      e.kinetic += 0.5 * m * v[n].squaredNorm();
      e.potential -= m * g.dot(x[n]);
    }
  }
  return e;
}

// One resting body: a deformable's nodes, or a rigid body's position as its one "node".
struct Resting {
  std::string name;
  std::optional<DeformableId> deformable;
  std::optional<RigidBodyId> rigid;
  std::vector<Vec3> points(const World& world) const {
    if (rigid) return {world.rigidPosition(*rigid)};
    const auto x = world.nodePositions(*deformable);
    return {x.begin(), x.end()};
  }
};

Vec3 centroid(const std::vector<Vec3>& points) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  return sum / double(points.size());
}

double meanDisplacement(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  double sum = 0;
  for (size_t i = 0; i < from.size(); ++i) sum += (to[i] - from[i]).norm();
  return sum / double(from.size());
}

struct Creep {
  std::string name;
  double speed = 0;             // m/s: the centroid's drift over the window, divided by its length
  double meanDisplacement = 0;  // m: of its nodes over the window
  double today = 0;             // m/s: RestingBody::creepToday
};

struct SoakMeasures {
  double seconds = 0;
  double startEnergy = 0, highest = 0, highestAt = 0;  // J, J, s
  double settledEnergy = 0, highestAfterSettling = 0;  // J
  double lateKineticMax = 0;                           // J, after settling
  double kineticFirstHalf = 0, kineticSecondHalf = 0;  // J: the most in each half of the window
  double tolerance = 0;                                // J
  bool creepMeasured = false;
  std::vector<Creep> creep;
};

// Runs the case for its ctest length (or TANDEM_SOAK_SECONDS, or 1 s with TANDEM_SHORT_TESTS),
// asserting every step that the step succeeds and the energy is finite.
void runSoak(const SoakCase& soak, SoakMeasures& out) {
  double seconds = soak.seconds;
  if (envSeconds("TANDEM_SOAK_SECONDS") > 0) seconds = envSeconds("TANDEM_SOAK_SECONDS");
  if (shortTests()) seconds = std::min(seconds, 1.0);  // the jelly scene: about 100 s under ASan
  out.seconds = seconds;
  out.creepMeasured = seconds >= soak.settle + 2.0;

  Result<Scene> scene = loadScene(TANDEM_SOURCE_DIR "/scenes/" + std::string(soak.file));
  ASSERT_TRUE(scene.ok()) << scene.message();
  World world;
  ASSERT_TRUE(buildScene(*scene, world).ok());
  std::vector<Resting> resting;
  for (const RestingBody& body : soak.resting) {
    Resting r{body.name, world.findDeformable(body.name), world.findRigidBody(body.name)};
    ASSERT_TRUE(r.deformable || r.rigid) << body.name;
    resting.push_back(r);
  }

  std::ofstream csv;
  if (const char* folder = std::getenv("TANDEM_SOAK_CSV")) {
    const std::string file = soak.file;
    csv.open(std::string(folder) + "/" + file.substr(0, file.find('.')) + ".csv");
    csv << "time,kinetic,potential,total";
    for (const Resting& r : resting) csv << ",drift " << r.name << ",mean displacement " << r.name;
    csv << "\n";
    csv.precision(10);
  }

  // Energy may fall (damping, friction, inelastic contact) but not rise. Allowed: the energy of
  // lifting everything that moves by 1 mm.
  double mass = 0;
  for (int b = 0; b < world.rigidBodyCount(); ++b) mass += world.rigidMass(RigidBodyId{b});
  for (int d = 0; d < world.deformableCount(); ++d)
    for (double w : world.nodeInverseMasses(DeformableId{d})) mass += w > 0 ? 1 / w : 0;
  out.tolerance = mass * world.settings().gravity.norm() * 1e-3;
  out.startEnergy = out.highest = energyOf(world).total();

  std::vector<std::vector<Vec3>> settled(resting.size());
  const long steps = std::lround(seconds / scene->timeStep);
  const long settleStep = std::lround(soak.settle / scene->timeStep);
  for (long s = 1; s <= steps; ++s) {
    const Status status = world.step(scene->timeStep);
    ASSERT_TRUE(status.ok()) << soak.file << " step " << s << ": " << status.message();
    const Energy e = energyOf(world);
    ASSERT_TRUE(std::isfinite(e.total())) << soak.file << ": non-finite state at step " << s;
    if (e.total() > out.highest) {
      out.highest = e.total();
      out.highestAt = world.time();
    }
    if (s == settleStep) {
      out.settledEnergy = out.highestAfterSettling = e.total();
      for (size_t r = 0; r < resting.size(); ++r) settled[r] = resting[r].points(world);
    }
    if (s > settleStep) {
      out.lateKineticMax = std::max(out.lateKineticMax, e.kinetic);
      double& half = 2 * (s - settleStep) <= steps - settleStep ? out.kineticFirstHalf : out.kineticSecondHalf;
      half = std::max(half, e.kinetic);
      out.highestAfterSettling = std::max(out.highestAfterSettling, e.total());
    }
    if (csv.is_open()) {
      csv << world.time() << "," << e.kinetic << "," << e.potential << "," << e.total();
      for (size_t r = 0; r < resting.size(); ++r) {
        if (s < settleStep) {
          csv << ",,";
        } else {
          const std::vector<Vec3> now = resting[r].points(world);
          csv << "," << (centroid(now) - centroid(settled[r])).norm() << "," << meanDisplacement(settled[r], now);
        }
      }
      csv << "\n";
    }
  }
  for (int d = 0; d < world.deformableCount(); ++d)
    for (const Vec3& x : world.nodePositions(DeformableId{d})) ASSERT_TRUE(finite(x));
  std::printf("%s, %.0f s: energy at start %.4f J, highest %.4f J (t = %.2f s; allowed %.4f J above the start)\n",
              soak.file, seconds, out.startEnergy, out.highest, out.highestAt, out.tolerance);
  if (!out.creepMeasured) return;

  const double window = seconds - soak.settle;
  std::printf("  after %.0f s: kinetic + gravitational energy %.4f J, highest %.4f J; kinetic energy at most %.3g J "
              "(%.3g J in the window's first half, %.3g J in its second)\n",
              soak.settle, out.settledEnergy, out.highestAfterSettling, out.lateKineticMax, out.kineticFirstHalf,
              out.kineticSecondHalf);
  for (size_t r = 0; r < resting.size(); ++r) {
    const std::vector<Vec3> now = resting[r].points(world);
    const double drift = (centroid(now) - centroid(settled[r])).norm();
    out.creep.push_back({resting[r].name, drift / window, meanDisplacement(settled[r], now), soak.resting[r].creepToday});
    std::printf("  %-22s creep from %.0f s to %.0f s: centroid %.3f mm (%.4f mm/s), nodes %.3f mm on average\n",
                resting[r].name.c_str(), soak.settle, seconds, 1e3 * drift, 1e3 * drift / window,
                1e3 * out.creep.back().meanDisplacement);
  }
}

class Soak : public testing::TestWithParam<SoakCase> {};

void expectStaysPut(const SoakMeasures& measures) {
  for (const Creep& c : measures.creep)
    EXPECT_LT(c.speed, kStayPutBound) << c.name << " creeps " << 1e3 * c.speed << " mm/s";
  // At rest, the bodies' motion does not grow: the most kinetic energy in the window's second
  // half is no more than in its first. (Kinetic + gravitational energy may rise a little after
  // settling, as bending energy stored while settling is given back: it is printed, not tested.)
  EXPECT_LE(measures.kineticSecondHalf, std::max(measures.kineticFirstHalf, 1e-6)) << "motion grows at rest";
}

// No NaN, no energy growth over the run, and no creep faster than main's today (a regression
// bound: creep, and motion growing at rest, are known limits, below); the scenes that already
// stay put must keep doing so.
TEST_P(Soak, NoNanNoEnergyGrowthNoWorseCreep) {
  SoakMeasures measures;
  runSoak(GetParam(), measures);
  if (HasFatalFailure()) return;
  EXPECT_LE(measures.highest - measures.startEnergy, measures.tolerance) << "energy grew, at t = " << measures.highestAt;
  if (!measures.creepMeasured) return;
  for (const Creep& c : measures.creep)
    EXPECT_LT(c.speed, std::max(kRegressionMargin * c.today, kRegressionFloor)) << c.name << " creeps " << 1e3 * c.speed << " mm/s, faster than the "
                                                     << 1e3 * c.today << " mm/s measured when this test was written";
  if (GetParam().staysPut) expectStaysPut(measures);
}

// Known limit for rope_wheel, disabled until the solver holds its resting bodies still (its creep
// today is creepToday below; jelly_dish stays put since its jellies came to carry the bar (in a
// block, now in their own solves), and cloth_sphere since its swept edges are solved together:
// both are asserted above). On main at
// 31d5220 the (13) measures were: the FEM jelly 0.4 mm/s, the PBD jelly 12 mm over
// 50 s; rope_wheel's motion grew at rest (the most kinetic energy in the window's second half
// 2.35 mJ against 0.97 mJ in its first).
// Run it with --gtest_also_run_disabled_tests; scripts/soak.py plots the drift over 60 s.
TEST_P(Soak, DISABLED_RestingBodiesStayPut) {
  SoakMeasures measures;
  runSoak(GetParam(), measures);
  if (HasFatalFailure()) return;
  ASSERT_TRUE(measures.creepMeasured) << "run at least " << GetParam().settle + 2 << " s";
  expectStaysPut(measures);
}

const SoakCase kCases[] = {
    // rope_wheel re-measured after its hinged wheel stopped sagging (docs/solver.md, mechanism 6):
    // the wheel holds still (0.000), the light box swings on as an undamped pendulum, which moves
    // the boxes' and the rope's centroids more than the sag's damping let them before.
    // Re-measured when the loads became teapots (mesh bodies): the rope creeps 0.34 mm/s (boxes: 0.22).
    // And when strain limiting came to hold anchored nodes (heavy / light / rope 0.89 / 0.91 /
    // 0.23 mm/s on main before it).
    // And when Bullet's contacts came to be warm started with their whole impulses (heavy / light /
    // rope 0.66 / 0.50 / 0.092 mm/s before).
    // And when a block's anchors to dynamic bodies came to be warm started (heavy / light / rope
    // 0.41 / 0.33 / 0.14 mm/s before): the landed teapot no longer rocks on the floor; the light
    // one still swings.
    // And when the bending rows' warm start came to carry last step's impulse onto their new
    // Jacobians (constraints/bending.h; heavy / light / rope 0.10 / 0.14 / 0.030 mm/s before): the
    // landed teapot, nudged by the light one's swing, shifts 4.4 mm by 14 s and then stays (4.3 mm
    // from 6 s to 32 s, against 0.7 / 1.9 / 5.8 mm at 14 / 26 / 32 s before, walking on).
    {"rope_wheel.json", 20.0, 6.0, {{"heavy", 0.32e-3}, {"light", 0.20e-3}, {"wheel", 0.029e-3}, {"rope", 0.030e-3}}},
    // cloth_sphere re-measured when the swept edges got their geometric stiffness (0.53 mm/s on
    // main before it; the nodes' own drift 12.5 → 4.3 mm on average from 8 s to 20 s).
    // Since the swept edges are solved together (solver/swept_edge_solve.h) it stays put: 0.0095
    // mm/s (0.26 before), and is asserted to.
    {"cloth_sphere.json", 20.0, 8.0, {{"cloth", 0.0095e-3}}, true},
    // jelly_dish re-measured when friction came to be bounded by the supports' load as well
    // (constraints/contact.h): the FEM jelly crept 1.14 mm/s, the PBD one 0.48, the bar 0.32; and
    // when shape matching's fit stopped holding along the supports (0.0011 mm/s before); and at
    // 52d5d21, unchanged by kept factorisations. And when the jellies came to be swept, the bar
    // moving in the implicit jellies' solve (models/supports.h): every body 0.0001 mm/s or less
    // (bar 0.049, FEM jelly 0.0124, shape-matching jelly 0.0191 before).
    {"jelly_dish.json", 20.0, 8.0,
     {{"chocolate bar", 0.0001e-3}, {"mass-spring jelly", 0.0001e-3}, {"FEM jelly", 0.0001e-3}, {"PBD jelly", 0.0001e-3},
      {"shape-matching jelly", 0.0001e-3}},
     true},
};

INSTANTIATE_TEST_SUITE_P(PaperScenes, Soak, testing::ValuesIn(kCases), [](const testing::TestParamInfo<SoakCase>& param) {
  std::string name = param.param.file;
  return name.substr(0, name.find('.'));
});

}  // namespace
}  // namespace tandem
