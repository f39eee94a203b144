// `tandem view SCENE`: the scene in a window, in real time, with the mouse to grab and drag
// any dynamic rigid body or any point of a deformable, and panels for the solver.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace tandem::cli {

struct ViewOptions {
  std::string scene;
  int width = 1280;
  int height = 720;
  std::vector<double> camera;  // eye x y z, target x y z
  // For scripts and tests: stop after this many frames or wall seconds (0: when closed, on
  // Escape, or on SIGTERM or SIGINT, which is how a script that drives the window should stop it),
  // then write the last frame to a PNG; print the dynamic bodies' positions on exit.
  long frames = 0;
  double maxSeconds = 0.0;
  std::string screenshot;
  bool paused = false;
};

CLI::App* addViewCommand(CLI::App& app, ViewOptions& options);
int view(const ViewOptions& options);

}  // namespace tandem::cli
