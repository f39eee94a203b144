// Limits on what Tandem accepts as input: how big a generated or loaded mesh and an input file
// may be, and the physical magnitudes a scene file may hold so that what validates also runs.
//
// The defaults (docs/reliability.md says why each is what it is) refuse sizes that would take
// minutes and gigabytes to build, and magnitudes a step cannot survive, with a message naming
// the limit. A caller with a bigger machine or a stranger scene raises them: every generator,
// mesh reader and scene function takes a `Limits` (defaulted to these values).
#pragma once

#include <cstdint>
#include <limits>

namespace tandem {

struct Limits {
  // ---- Sizes (generators, OBJ and TetGen readers, scene files) ----
  // Nodes of one mesh. Node indices are 32-bit: a larger value is used as 2^31 - 1.
  int64_t maxNodes = 1'000'000;
  int64_t maxTriangles = 2'000'000;   // surface triangles of one mesh
  int64_t maxTetrahedra = 1'000'000;  // tetrahedra of one mesh
  int64_t maxMeshFileBytes = 256ll << 20;  // an OBJ or a TetGen file (256 MiB)
  int64_t maxSceneFileBytes = 16ll << 20;  // a scene file (16 MiB)

  // ---- Physical magnitudes a scene file may hold (checked by loadScene and buildScene) ----
  // m: |x|, |y|, |z| of any position, point or pivot. Past about 3e8 m a double resolves less
  // than the continuous collision test's touch tolerance (1e-6 of a cell: 50 nm for 5 cm cells),
  // and a cloth folding onto itself crosses itself (measured: none at 2^28 m, 4 faces at 2^31 m).
  double maxCoordinate = 1e8;
  double minSize = 1e-4;          // m: shape radii, half extents, half heights
  double maxSize = 1e6;           // m
  double minMass = 1e-6;          // kg: a rigid body's mass, a deformable's total mass
  double maxMass = 1e9;           // kg
  double maxMassRatio = 1e8;      // heaviest / lightest dynamic mass (rigid bodies and deformable nodes)
  double maxGravity = 1e4;        // m/s²: |g|, about 1,000 g
  double maxAngularSpeed = 1e4;   // rad/s: |ω| of a rigid body at the start
  double minTimeStep = 1e-6;      // s
  int64_t maxSteps = 10'000'000;  // duration / time_step (what `tandem run` runs at most)
  // Speeds (rigid bodies' and deformables' starting velocities) must be below the scene's own
  // divergence speed: a faster state is a diverged one (WorldSettings::divergenceSpeed).
};

// The 32-bit node index's ceiling: Limits::maxNodes above it is used as it.
inline constexpr int64_t kMaxIndexableNodes = std::numeric_limits<int32_t>::max();

}  // namespace tandem
