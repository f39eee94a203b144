// A captured run (export/run_frames.h) written for other tools: glTF 2.0 (.gltf with a .bin
// beside it, or one .glb) and a folder with one OBJ per frame.
//
// glTF: one node per rigid body, holding its shape as a mesh in the body's frame, animated by
// translation and rotation channels (linear, spherical-linear between frames); static bodies
// are not animated; planes are 20 m squares. One node per deformable, holding its surface
// (deformable_surface.h: ropes and rims as tubes) at the first frame with one morph target per
// later frame (position and normal offsets) and a weights channel that is one-hot at each
// frame's time, linear in between: the surface moves through the frames as a linear blend of
// neighbours, in Blender (shape keys) and three.js (morph targets) alike. Colours become
// materials (sRGB converted to glTF's linear base colour).
#pragma once

#include "export/run_frames.h"

#include <tandem/shape_surface.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace tandem::exporting {

// Colours by body index (red, green, blue in [0, 1], as displayed); unset: a default.
struct ExportLooks {
  std::vector<std::optional<std::array<double, 3>>> rigidColours;
  std::vector<std::optional<std::array<double, 3>>> deformableColours;
};

// `path` ends in .gltf (its buffer in PATH-without-.gltf.bin beside it) or .glb.
Status writeGltf(const World& world, const std::vector<Frame>& frames, const ExportLooks& looks,
                 const std::string& path);

// frame_00000.obj, frame_00001.obj, ... in `folder` (which must exist), one object per body
// in world coordinates, with materials in tandem.mtl beside them.
Status writeObjFrames(const World& world, const std::vector<Frame>& frames, const ExportLooks& looks,
                      const std::string& folder);

// What both formats draw for a rigid body: its shape's surface; a plane as a square of
// `planeHalfSize` m about the point of the plane nearest the origin.
ShapeSurface rigidExportSurface(const RigidShape& shape, double planeHalfSize = 10.0);

}  // namespace tandem::exporting
