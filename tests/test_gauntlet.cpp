// The solver's gauntlet (tests/gauntlet.h): each case at its scene's settings must meet every
// bound; on failure the measures are printed with their bounds. Cases the solver does not pass
// yet are DISABLED_, with what they measure today in docs/solver.md (run them with
// --gtest_also_run_disabled_tests, or all settings with build/bench/gauntlet_study).
#include "gauntlet.h"
#include "short_tests.h"

#include <gtest/gtest.h>

namespace tandem::gauntlet {
namespace {

void expectPasses(const Outcome& result) {
  EXPECT_TRUE(result.error.empty()) << result.scene << ": " << result.error;
  for (const Measure& m : result.measures)
    EXPECT_TRUE(m.pass()) << result.scene << ": " << m.name << " = " << m.value << ", must be in [" << m.low << ", "
                          << m.high << "]";
}

TEST(Gauntlet, AtwoodMachineOverAHingedWheelDoesNotSlipAndAcceleratesAsAnalytic) {
  expectPasses(atwood());
  expectPasses(atwood({.iterations = 2, .substeps = 1}));  // the paper's settings
  expectPasses(atwood({.iterations = 4, .substeps = 1}));  // the default
}
TEST(Gauntlet, CapstanHoldsBelowTheCapstanRatio) { expectPasses(capstan(true)); }
TEST(Gauntlet, CapstanSlidesAboveTheCapstanRatio) { expectPasses(capstan(false)); }
// The same rope sliding round its post at K = 4 (the file's 4 substeps): the contacts of its wrap
// that the rope's block let go used to stay with the sweep while its edges stayed in the block,
// and the two took the wrap in turns: from 0.6 s the node where the light strand meets the post
// was driven into it ever faster (51 m/s by 0.92 s), its edges stretched up to 85 %, 22 steps
// reported a torn edge, and the heavy end fell 4.9 times as far as the capstan's acceleration
// gives. A rope's contacts rejoin its block every step now (solver/direct_block.cpp).
TEST(Gauntlet, CapstanSlidesSmoothlyAtFourIterations) {
  Outcome result;
  gauntlet::Run run("gauntlet/capstan_slide.json", {.iterations = 4}, result);
  ASSERT_TRUE(run.ok()) << result.error;
  const DeformableId rope = run.deformable("rope");
  double worst = 0.0;
  int violated = 0;
  ASSERT_TRUE(run.run(0, [&] {
    worst = std::max(worst, run.worstStretch(rope));
    violated += !run.world.lastReport().violations.empty();
  })) << result.error;
  EXPECT_EQ(violated, 0) << "steps that reported a violated row";
  EXPECT_LT(worst, 0.02) << "worst edge stretch";  // measured 1.0 % (the light end reaching the post)
  expectPasses(capstan(false, {.iterations = 4}));
}
// At the scene's n = 4, and without substeps at the paper's K = 2 and the default K = 4: the
// rope's block moves the box by position with its nodes (1.66 % stretched at n = 1 before: the
// strain-limiting passes cannot shorten a chain between a pin and a held body; docs/solver.md).
TEST(Gauntlet, HeavyPendulumOnALightRopeHoldsAndKeepsItsPeriod) {
  expectPasses(heavyPendulum());
  expectPasses(heavyPendulum({.iterations = 2, .substeps = 1}));
  expectPasses(heavyPendulum({.iterations = 4, .substeps = 1}));
}
TEST(Gauntlet, LongRopeHoldsItsLoadUnderDefaultSettings) { expectPasses(longRope()); }
TEST(Gauntlet, FreeSwingKeepsItsEnergy) { expectPasses(freeSwing()); }
// The same pendulum's block moves its ball by position, but only an edge's stretch past the
// projection's band: within it, the rows' bias gives back the energy the velocity rows turned into
// stretch. Projected whole, the swing kept 0.914 of its energy over 10 s instead of 0.987.
TEST(Gauntlet, FreeSwingLosesNoEnergyToTheBlocksPositionProjection) {
  const Outcome result = freeSwing();
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_GE(result.measures.at(0).value, 0.98) << result.measures.at(0).name;
}
// The paper's 51 × 51 cloth and one of 101 × 101: 2.6 % and 4.4 % before their sheets' edges were
// projected together in the strain-limiting passes (docs/solver.md, twentieth session), 1.1 %
// since.
// Under the sanitizers (TANDEM_SHORT_TESTS=1) each cloth runs its impact and first drape only:
// the paper's 51 × 51 its first 1.2 s (first contact at 0.38 s; its 3 s took 85 s there), the
// 101 × 101 its first 0.6 s (first contact at 0.12 s; its 2 s took 400 of the sanitizer suite's
// 1,500 s).
TEST(Gauntlet, PaperClothOnSphereStaysWithinItsStretchLimit) {
  expectPasses(clothOnSphere("cloth_sphere.json", shortTests() ? 1.2 : 3.0));
}
TEST(Gauntlet, WiderClothOnSphereStaysWithinItsStretchLimit) {
  // 83 s under the sanitizers even for 0.6 s of the scene; PaperClothOnSphere takes the same path.
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  expectPasses(clothOnSphere("gauntlet/cloth_sphere_101.json", 2.0));
}
// The 101 × 101 cloth made four times lighter (11 mg nodes, those of the 201 × 201 cloth) with
// bending four times stiffer (20 Hz), at K = 2 with 4 substeps: its skirt whips past the sphere at
// up to 17 m/s, ten edge lengths a substep, and the bending rows' warm start applied last
// substep's λ along wings that had swung, kicks of up to F h = 0.25 mN·s that the two sweeps did
// not take back: it diverged at step 28 (the 201 × 201 cloth of the gauntlet at 2:4 at step 32).
// Carrying the impulse onto the new Jacobian (constraints/bending.h): every edge within 1.06 %,
// the energy never above its start.
TEST(Gauntlet, FineLightClothWithStiffBendingDrapesWithSubsteps) {
  // 204 s under the sanitizers (3.5 s in Release), and it needs its 28 steps to show anything.
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  Outcome result;
  gauntlet::Run run("gauntlet/cloth_sphere_101.json", {2, 4}, result, [](Scene& scene) {
    scene.deformables.at(0).density = 0.05;  // kg/m², against 0.2
    scene.deformables.at(0).desc.bending.frequency = 20.0;
  });
  ASSERT_TRUE(run.ok()) << result.error;
  const DeformableId cloth = run.deformable("cloth");
  const double start = run.energy();
  double worst = 0.0, highest = start;
  run.run(0.8, [&] {  // 40 steps
    worst = std::max(worst, run.worstStretch(cloth));
    highest = std::max(highest, run.energy());
  });
  EXPECT_TRUE(result.error.empty()) << result.error;
  EXPECT_LT(worst, 0.02);
  EXPECT_LE(highest, start);
}
// 3.5 % at 201 × 201 (8.2 % before).
TEST(Gauntlet, DISABLED_LargeClothOnSphereStaysWithinItsStretchLimit) {
  expectPasses(clothOnSphere("gauntlet/cloth_sphere_201.json", 2.0));
}
// The projectile cases' cloth (31 × 31, 1 m, pinned along its four edges, its edges swept) with
// the ball taken away, at the scene's K = 2: it sags and should then hang. With the swept edges'
// conjugate gradients in both sweeps (nothing smoothing what they leave before the
// strain-limiting passes) it kept moving at 0.32 m/s RMS from its 2nd to its 8th second; with
// them in the first only, 0.034 (solver/swept_edge_solve.h, sweepSolvesSweptEdges).
TEST(Gauntlet, ProjectileCasesClothHangsWithoutTheBall) {
  Outcome result;
  gauntlet::Run run("gauntlet/projectile_20.json", {}, result);
  ASSERT_TRUE(run.ok()) << result.error;
  ASSERT_TRUE(run.world.removeRigidBody(run.body("ball")).ok());
  const DeformableId cloth = run.deformable("cloth");
  double sum = 0.0;
  int samples = 0;
  // 45 s under the sanitizers for the 8 s: there the cloth hangs for 3 s, measured over the last 1.
  const double seconds = shortTests() ? 3.0 : 8.0;
  ASSERT_TRUE(run.run(seconds, [&] {
    if (++samples <= 100) return;  // the first 2 s
    double squares = 0.0;
    const std::span<const Vec3> v = run.world.nodeVelocities(cloth);
    for (const Vec3& u : v) squares += u.squaredNorm();
    sum += std::sqrt(squares / static_cast<double>(v.size()));
  })) << result.error;
  EXPECT_LT(sum / (samples - 100), 0.1);  // m/s RMS
}
TEST(Gauntlet, DISABLED_FastProjectileDoesNotPassThroughCloth) {
  expectPasses(projectile(20));
  expectPasses(projectile(60));
}
// The same ball dropped from 0.3 m above the cloth at 0.5 m/s. It fell through the swept 31 × 31
// cloth as if nothing were there (docs/solver.md, tenth session) until the sheet's projection took
// the ball's contacts and moved the ball with the sheet (strain_limiting.h); at K = 2 and 4 it now
// rests 2.7 and 2.8 cm above the cloth.
TEST(Gauntlet, BallDroppedGentlyOnClothIsHeld) {
  expectPasses(projectile(20, {}, 0.5));
  // 42 s under the sanitizers for both: there the default settings only.
  if (shortTests()) return;
  expectPasses(projectile(20, {.iterations = 4, .substeps = 1}, 0.5));
}
// The wheel is hinged to the world: Tandem's rows move it only about its axle (RigidSolverState).
TEST(Gauntlet, RopeOverWheelHoldsItsPivot) {
  // 50 s under the sanitizers for the three: there the default settings only.
  for (const Override& settings :
       casesToRun({Override{}, Override{.iterations = 2, .substeps = 1}, Override{.iterations = 2, .substeps = 4}})) {
    const Outcome result = ropeWheel(settings);
    ASSERT_TRUE(result.error.empty()) << result.error;
    const Measure& sag = result.measures.at(0);
    EXPECT_TRUE(sag.pass()) << sag.name << " = " << sag.value << " at K = " << settings.iterations;
  }
}
// Three boxes dropped onto a hammock come down off their stack and lie in it, moving at a few
// cm/s (not at rest: DISABLED_BodiesOnClothComeToRest). The cloth's direct block lets contacts
// that would pull go in up to three rounds a solve; those still pulling after the last round
// used to be let go without solving again, which left every other row's impulse unbalanced:
// at K = 2, 5.8 s in, a sweep threw 0.45 g nodes at 51 m/s and the boxes at 11 rad/s, the
// kinetic energy from 4 to 330 mJ in one step. Measured since: at most 10 mJ (K = 2) and 25 mJ
// (K = 4) after 2.5 s, the pile's fall over by then.
TEST(Gauntlet, BoxStackOnClothIsNeverThrown) {
  // 2.6 s a run in Release (some 150 s under the sanitizers), and the burst came after 5.8 s.
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  for (const int iterations : {2, 4}) {
    Outcome result;
    gauntlet::Run run("gauntlet/box_stack_on_cloth.json", {iterations, 1}, result);
    ASSERT_TRUE(run.ok()) << result.error;
    double t = 0.0, most = 0.0;
    ASSERT_TRUE(run.run(0, [&] {
      t += run.h();
      if (t > 2.5) most = std::max(most, run.kineticEnergy());
    })) << result.error;
    EXPECT_LT(most, 0.06) << "J at K = " << iterations;  // 1.5 kg of boxes at 0.28 m/s
  }
}
// After the heavy body lands, the light one swings on the rope as an undamped pendulum (about
// 0.1–0.3 m/s, no growth: docs/solver.md); nothing in the scene damps it.
TEST(Gauntlet, DISABLED_RopeOverWheelComesToRest) { expectPasses(ropeWheel()); }
TEST(Gauntlet, DISABLED_BodiesOnClothComeToRest) {
  expectPasses(restOnCloth("hammock.json", "hammock"));
  expectPasses(restOnCloth("gauntlet/box_stack_on_cloth.json", "hammock"));
}

}  // namespace
}  // namespace tandem::gauntlet
