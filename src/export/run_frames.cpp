#include "export/run_frames.h"

#include <cmath>
#include <string>

namespace tandem::exporting {

Frame captureFrame(const World& world) {
  Frame frame;
  frame.time = world.time();
  for (int b = 0; b < world.rigidBodyCount(); ++b) {
    frame.rigidPositions.push_back(world.rigidPosition(RigidBodyId{b}));
    frame.rigidOrientations.push_back(world.rigidOrientation(RigidBodyId{b}).normalized());
  }
  for (int d = 0; d < world.deformableCount(); ++d) {
    const auto x = world.nodePositions(DeformableId{d});
    frame.nodePositions.emplace_back(x.begin(), x.end());
  }
  return frame;
}

Result<std::vector<Frame>> captureRun(World& world, double timeStep, double fps, double seconds,
                                      const std::function<void(int, int)>& progress) {
  if (!(timeStep > 0) || !std::isfinite(timeStep)) return Error{"export: the time step must be > 0"};
  if (!(fps > 0) || !std::isfinite(fps)) return Error{"export: the frame rate must be > 0"};
  if (!(seconds >= 0) || !std::isfinite(seconds)) return Error{"export: the length must be >= 0 s"};
  const long total = static_cast<long>(std::floor(seconds * fps + 1e-9)) + 1;
  if (total > 100000) return Error{"export: " + std::to_string(total) + " frames is more than 100000; lower --fps or --seconds"};
  const double start = world.time();
  std::vector<Frame> frames;
  frames.reserve(static_cast<size_t>(total));
  for (long k = 0; k < total; ++k) {
    const double time = start + static_cast<double>(k) / fps;
    while (world.time() + 0.5 * timeStep < time)
      if (Status s = world.step(timeStep); !s) return Error{s.message()};
    frames.push_back(captureFrame(world));
    if (progress) progress(static_cast<int>(k + 1), static_cast<int>(total));
  }
  return frames;
}

}  // namespace tandem::exporting
