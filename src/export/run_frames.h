// A run sampled at a frame rate, for exporting it: each frame's time, rigid poses and deformable
// node positions. The world is stepped with its own time step; a frame is taken when the clock
// reaches the frame's time (to within half a step), so a frame rate that divides the step rate
// lands exactly on steps (the record of `tandem run --record` has the same states).
#pragma once

#include <tandem/world.h>

#include <functional>
#include <vector>

namespace tandem::exporting {

struct Frame {
  double time = 0.0;  // s, the world's clock when the frame was taken
  std::vector<Vec3> rigidPositions;  // by rigid body index
  std::vector<Quat> rigidOrientations;
  std::vector<std::vector<Vec3>> nodePositions;  // by deformable index
};

Frame captureFrame(const World& world);

// Frames at t = 0, 1/fps, 2/fps, ... up to `seconds` (the first is the world as it is now, at
// time 0 of the export). `progress(done, total)` is called after each frame when given.
Result<std::vector<Frame>> captureRun(World& world, double timeStep, double fps, double seconds,
                                      const std::function<void(int, int)>& progress = {});

}  // namespace tandem::exporting
