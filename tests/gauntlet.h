// The solver's gauntlet (scenes/gauntlet/ and two paper scenes): each case loads its scene, runs
// it, and measures what the solver must get right against analytic mechanics, with the bound it
// must meet. Shared by the test (test_gauntlet.cpp) and the design study (bench/gauntlet_study.cpp),
// which runs the same cases under other solver settings.
#pragma once

#include <tandem/scene_file.h>
#include <tandem/world.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace tandem::gauntlet {

struct Measure {
  std::string name;
  double value = 0.0;
  double low = -INFINITY, high = INFINITY;  // the bound it must lie in
  bool pass() const { return value >= low && value <= high; }
};

struct Outcome {
  std::string scene;
  std::string error;  // a scene that could not load or diverged
  std::vector<Measure> measures;
  double msPerStep = 0.0;
  bool pass() const {
    if (!error.empty()) return false;
    return std::all_of(measures.begin(), measures.end(), [](const Measure& m) { return m.pass(); });
  }
};

// Solver settings to run a case with instead of the scene's (0: the scene's own).
struct Override {
  int iterations = 0;
  int substeps = 0;
};

// A loaded scene and its world, stepped with timing.
class Run {
 public:
  // `adjust`, when given, edits the loaded scene before it is built.
  Run(const std::string& file, const Override& override, Outcome& result,
      const std::function<void(Scene&)>& adjust = {})
      : m_result(result) {
    result.scene = file;
    tandem::Result<Scene> loaded = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/" + file);
    if (!loaded) {
      result.error = loaded.message();
      return;
    }
    scene = *loaded;
    if (override.iterations > 0) scene.settings.solver.iterations = override.iterations;
    if (override.substeps > 0) scene.settings.solver.substeps = override.substeps;
    if (adjust) adjust(scene);
    if (Status built = buildScene(scene, world); !built) result.error = built.message();
  }

  bool ok() const { return m_result.error.empty(); }
  double h() const { return scene.timeStep; }

  // Steps for `seconds` (the scene's duration when 0), calling `after` after every step.
  bool run(double seconds, const std::function<void()>& after) {
    if (!ok()) return false;
    const long steps = std::lround((seconds > 0 ? seconds : scene.duration) / scene.timeStep);
    for (long s = 0; s < steps; ++s) {
      const auto start = std::chrono::steady_clock::now();
      const Status status = world.step(scene.timeStep);
      m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++m_steps;
      if (!status) {
        m_result.error = status.message();
        return false;
      }
      after();
    }
    m_result.msPerStep = 1e3 * m_seconds / static_cast<double>(m_steps);
    return true;
  }

  RigidBodyId body(const char* name) const { return *world.findRigidBody(name); }
  DeformableId deformable(const char* name) const { return *world.findDeformable(name); }

  // The largest strain |x_j − x_i| / L − 1 over the deformable's rest edges.
  double worstStretch(DeformableId id) const {
    const DeformableMesh& rest = world.restMesh(id);
    const std::span<const Vec3> x = world.nodePositions(id);
    double worst = 0.0;
    for (const auto& e : rest.edges)
      worst = std::max(worst, (x[e[1]] - x[e[0]]).norm() / (rest.positions[e[1]] - rest.positions[e[0]]).norm() - 1.0);
    return worst;
  }
  // Its length over its rest length, minus 1 (a rope's overall stretch).
  double totalStretch(DeformableId id) const {
    const DeformableMesh& rest = world.restMesh(id);
    const std::span<const Vec3> x = world.nodePositions(id);
    double length = 0.0, restLength = 0.0;
    for (const auto& e : rest.edges) {
      length += (x[e[1]] - x[e[0]]).norm();
      restLength += (rest.positions[e[1]] - rest.positions[e[0]]).norm();
    }
    return length / restLength - 1.0;
  }
  double fastestNode(DeformableId id) const {
    double fastest = 0.0;
    for (const Vec3& v : world.nodeVelocities(id)) fastest = std::max(fastest, v.norm());
    return fastest;
  }
  // Kinetic plus gravitational energy of every rigid body and node, heights from y = 0.
  double energy() const { return kineticEnergy() + gravitationalEnergy(); }
  double kineticEnergy() const {
    double total = 0.0;
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const RigidBodyId id{b};
      if (world.rigidMass(id) == 0) continue;  // static or kinematic
      const Vec3 w = world.rigidAngularVelocity(id);
      total += 0.5 * world.rigidMass(id) * world.rigidLinearVelocity(id).squaredNorm() + 0.5 * w.dot(world.rigidInertia(id) * w);
    }
    for (int d = 0; d < world.deformableCount(); ++d) {
      const auto v = world.nodeVelocities(DeformableId{d});
      const auto w = world.nodeInverseMasses(DeformableId{d});
      for (size_t i = 0; i < v.size(); ++i)
        if (w[i] > 0) total += 0.5 * v[i].squaredNorm() / w[i];
    }
    return total;
  }
  double gravitationalEnergy() const {
    const double g = -world.settings().gravity.y();
    double total = 0.0;
    for (int b = 0; b < world.rigidBodyCount(); ++b)
      total += world.rigidMass(RigidBodyId{b}) * g * world.rigidPosition(RigidBodyId{b}).y();
    for (int d = 0; d < world.deformableCount(); ++d) {
      const auto x = world.nodePositions(DeformableId{d});
      const auto w = world.nodeInverseMasses(DeformableId{d});
      for (size_t i = 0; i < x.size(); ++i)
        if (w[i] > 0) total += g * x[i].y() / w[i];
    }
    return total;
  }

  Scene scene;
  World world;

 private:
  Outcome& m_result;
  double m_seconds = 0.0;
  long m_steps = 0;
};

// Atwood machine over a hinged wheel with inertia: no slip, and the analytic acceleration.
inline Outcome atwood(const Override& override = {}) {
  Outcome result;
  Run run("gauntlet/atwood.json", override, result);
  if (!run.ok()) return result;
  const RigidBodyId wheel = run.body("wheel"), light = run.body("light"), heavy = run.body("heavy");
  const double m1 = run.world.rigidMass(light), m2 = run.world.rigidMass(heavy), m = run.world.rigidMass(wheel);
  const double r = 0.2, ropeRadius = 0.202, ropeMass = 0.02, g = 9.81;
  const double inertia = 0.5 * m * r * r;
  const double expected = g * (m2 - m1) / (m1 + m2 + inertia / (ropeRadius * ropeRadius) + ropeMass);
  // Slip is the rope creeping over the rim: the heavy end's travel against the rim's, from 0.2 s
  // on. The speeds' ratio at single steps also swings with chordal action (a rope of 4.3 cm
  // links wrapped on a 0.2 m wheel is a polygon whose nodes step on and off the rim), so it
  // gets a looser bound.
  double worstSpeedRatio = 0.0, t = 0.0, speedAtStart = 0.0, timeAtStart = 0.0;
  double ropeTravel = 0.0, rimTravel = 0.0;
  run.run(0, [&] {
    t += run.h();
    const double ropeSpeed = -run.world.rigidLinearVelocity(heavy).y();
    const double rimSpeed = -run.world.rigidAngularVelocity(wheel).z() * ropeRadius;
    if (t < 0.2 - 1e-9) return;
    if (timeAtStart == 0.0) {
      timeAtStart = t;
      speedAtStart = ropeSpeed;
      return;
    }
    ropeTravel += ropeSpeed * run.h();
    rimTravel += rimSpeed * run.h();
    worstSpeedRatio = std::max(worstSpeedRatio, std::abs(rimSpeed / ropeSpeed - 1.0));
  });
  const double acceleration = (-run.world.rigidLinearVelocity(heavy).y() - speedAtStart) / (t - timeAtStart);
  result.measures = {{"slip |rim travel/rope travel - 1| after 0.2 s", std::abs(rimTravel / ropeTravel - 1.0), -INFINITY, 0.02},
                     {"worst |rim speed/rope speed - 1| at one step", worstSpeedRatio, -INFINITY, 0.05},
                     {"acceleration / analytic", acceleration / expected, 0.95, 1.05}};
  return result;
}

// Capstan: a rope half round a static post holds below e^{μθ} and slides above it.
inline Outcome capstan(bool hold, const Override& override = {}) {
  Outcome result;
  Run run(hold ? "gauntlet/capstan_hold.json" : "gauntlet/capstan_slide.json", override, result);
  if (!run.ok()) return result;
  const RigidBodyId heavy = run.body("heavy");
  const double start = run.world.rigidPosition(heavy).y();
  run.run(0, [] {});
  const double moved = start - run.world.rigidPosition(heavy).y();
  if (hold) {
    result.measures = {{"heavy end moved (m), 0.8 e^(mu theta)", moved, -0.01, 0.01}};
  } else {
    const double ratio = std::exp(0.3 * std::numbers::pi), m1 = 1.0, m2 = run.world.rigidMass(heavy);
    const double a = 9.81 * (m2 - m1 * ratio) / (m2 + m1 * ratio), seconds = run.scene.duration;
    result.measures = {{"heavy end moved / analytic, 1.2 e^(mu theta)", moved / (0.5 * a * seconds * seconds), 0.8, 1.2}};
  }
  return result;
}

// A 500 kg box on a 30 g rope released at 60°: the anchor holds, the rope does not stretch, the
// energy never grows, and it swings with the large-amplitude pendulum's period.
inline Outcome heavyPendulum(const Override& override = {}) {
  Outcome result;
  Run run("gauntlet/heavy_pendulum.json", override, result);
  if (!run.ok()) return result;
  const RigidBodyId load = run.body("load");
  const DeformableId rope = run.deformable("rope");
  const double start = run.energy(), swing = run.world.rigidMass(load) * 9.81 * 0.5;  // m g L (1 − cos 60°)
  double worstGap = 0.0, worstStretch = 0.0, mostEnergy = -INFINITY, t = 0.0, previousX = run.world.rigidPosition(load).x();
  std::vector<double> crossings;  // times x goes through 0 towards −x
  run.run(0, [&] {
    t += run.h();
    const AnchorState anchor = run.world.anchorState(AnchorId{0});
    worstGap = std::max(worstGap, (anchor.worldPointOnBody - anchor.worldPointOnDeformable).norm());
    worstStretch = std::max(worstStretch, run.worstStretch(rope));
    mostEnergy = std::max(mostEnergy, (run.energy() - start) / swing);
    const double x = run.world.rigidPosition(load).x();
    if (previousX > 0 && x <= 0) crossings.push_back(t - run.h() * x / (x - previousX));
    previousX = x;
  });
  // T = 4 √(L/g) K(sin(θ₀/2)), K(1/2) = 1.685750354812596 (complete elliptic integral, k = 1/2).
  const double period = 4.0 * std::sqrt(1.0 / 9.81) * 1.685750354812596;
  const double measured = crossings.size() >= 2 ? (crossings.back() - crossings.front()) / (crossings.size() - 1) : 0.0;
  result.measures = {{"anchor gap (m)", worstGap, -INFINITY, 0.01},
                     {"rope stretch", worstStretch, -INFINITY, 0.01},
                     {"energy gain / swing energy", mostEnergy, -INFINITY, 0.01},
                     {"period / analytic", measured / period, 0.98, 1.02}};
  return result;
}

// 3,000 nodes holding 2 kg under the default settings.
inline Outcome longRope(const Override& override = {}) {
  Outcome result;
  Run run("gauntlet/long_rope.json", override, result);
  if (!run.ok()) return result;
  const DeformableId rope = run.deformable("rope");
  double worstTotal = 0.0, worstEdge = 0.0;
  run.run(0, [&] {
    worstTotal = std::max(worstTotal, run.totalStretch(rope));
    worstEdge = std::max(worstEdge, run.worstStretch(rope));
  });
  result.measures = {{"rope stretch (length)", worstTotal, -INFINITY, 0.01},
                     {"worst edge stretch", worstEdge, -INFINITY, 0.01}};
  return result;
}

// An undamped rope pendulum keeps its energy: at least 90 % over 10 s, never more than it had.
inline Outcome freeSwing(const Override& override = {}) {
  Outcome result;
  Run run("gauntlet/free_swing.json", override, result);
  if (!run.ok()) return result;
  // Energy above the rest state (everything hanging straight down from the fixed point).
  const DeformableId rope = run.deformable("rope");
  const auto w = run.world.nodeInverseMasses(rope);
  const size_t n = w.size();
  double rest = run.world.rigidMass(run.body("ball")) * 9.81 * 1.0;  // ball centre at y = 1
  for (size_t i = 0; i < n; ++i)
    if (w[i] > 0) rest += 9.81 * (2.0 - static_cast<double>(i) / static_cast<double>(n - 1)) / w[i];
  const double start = run.energy() - rest;
  double least = INFINITY, most = -INFINITY;
  run.run(0, [&] {
    const double e = (run.energy() - rest) / start;
    least = std::min(least, e);
    most = std::max(most, e);
  });
  result.measures = {{"least energy / start", least, 0.9, INFINITY}, {"most energy / start", most, -INFINITY, 1.01}};
  return result;
}

// The paper's cloth on a sphere at one resolution: stretch after first contact, and cost.
inline Outcome clothOnSphere(const std::string& file, double seconds, const Override& override = {}) {
  Outcome result;
  Run run(file, override, result);
  if (!run.ok()) return result;
  const DeformableId cloth = run.deformable("cloth");
  double worst = 0.0;
  bool touched = false;
  run.run(seconds, [&] {
    touched = touched || !run.world.contacts().empty();
    if (touched) worst = std::max(worst, run.worstStretch(cloth));
  });
  result.measures = {{"worst edge stretch after contact", worst, -INFINITY, 0.02}};
  return result;
}

// A small fast ball into a cloth pinned along its edges never ends up on its far side.
// `launchSpeed` (m/s, downwards), when given, replaces the scene's: the same ball dropped gently.
inline Outcome projectile(int speed, const Override& override = {}, std::optional<double> launchSpeed = {}) {
  Outcome result;
  Run run("gauntlet/projectile_" + std::to_string(speed) + ".json", override, result);
  if (!run.ok()) return result;
  const RigidBodyId ball = run.body("ball");
  if (launchSpeed && !run.world.setRigidLinearVelocity(ball, Vec3(0, -*launchSpeed, 0)).ok()) {
    result.error = "could not set the ball's speed";
    return result;
  }
  const DeformableId cloth = run.deformable("cloth");
  double lowest = INFINITY;  // of the ball's centre above the cloth node nearest it across
  run.run(0, [&] {
    const Vec3 c = run.world.rigidPosition(ball);
    double nearest = INFINITY, above = 0.0;
    for (const Vec3& x : run.world.nodePositions(cloth)) {
      const double across = std::hypot(x.x() - c.x(), x.z() - c.z());
      if (across < nearest) {
        nearest = across;
        above = c.y() - x.y();
      }
    }
    lowest = std::min(lowest, above);
  });
  result.measures = {{"ball centre above the cloth (m)", lowest, 0.0, INFINITY}};
  return result;
}

// The paper's rope over a wheel: the hinge holds its pivot, and once the heavy body has landed
// everything comes to rest.
inline Outcome ropeWheel(const Override& override = {}) {
  Outcome result;
  Run run("rope_wheel.json", override, result);
  if (!run.ok()) return result;
  const RigidBodyId wheel = run.body("wheel");
  const Vec3 pivot = run.world.rigidPosition(wheel);
  double worstSag = 0.0, fastest = 0.0, t = 0.0;
  run.run(0, [&] {
    t += run.h();
    worstSag = std::max(worstSag, (run.world.rigidPosition(wheel) - pivot).norm());
    if (t < 6.0) return;
    for (const char* name : {"light", "heavy"}) fastest = std::max(fastest, run.world.rigidLinearVelocity(run.body(name)).norm());
    fastest = std::max(fastest, run.world.rigidAngularVelocity(wheel).norm() * 0.25);
    fastest = std::max(fastest, run.fastestNode(run.deformable("rope")));
  });
  result.measures = {{"wheel off its pivot (m)", worstSag, -INFINITY, 0.001},
                     {"fastest body or node after 6 s (m/s)", fastest, -INFINITY, 0.001}};
  return result;
}

// Bodies resting on cloth come to rest: every body and node under 1 mm/s over the last second.
inline Outcome restOnCloth(const std::string& file, const char* clothName, const Override& override = {}) {
  Outcome result;
  Run run(file, override, result);
  if (!run.ok()) return result;
  double fastestBody = 0.0, fastestNode = 0.0, t = 0.0;
  run.run(0, [&] {
    t += run.h();
    if (t < run.scene.duration - 1.0) return;
    for (int b = 0; b < run.world.rigidBodyCount(); ++b)
      fastestBody = std::max(fastestBody, run.world.rigidLinearVelocity(RigidBodyId{b}).norm());
    fastestNode = std::max(fastestNode, run.fastestNode(run.deformable(clothName)));
  });
  result.measures = {{"fastest body over the last second (m/s)", fastestBody, -INFINITY, 0.001},
                     {"fastest node over the last second (m/s)", fastestNode, -INFINITY, 0.001}};
  return result;
}

}  // namespace tandem::gauntlet
