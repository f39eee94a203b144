// One Wavefront OBJ per frame: every body's surface in world coordinates as its own object,
// colours in one material file shared by the frames.
#include "export/scene_export.h"

#include <tandem/deformable_surface.h>
#include <tandem/shape_surface.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace tandem::exporting {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// OBJ names may not hold spaces.
std::string objName(std::string name) {
  for (char& c : name)
    if (c == ' ' || c == '\t') c = '_';
  return name;
}

void writeSurface(std::FILE* out, const std::string& name, const std::string& material, const ShapeSurface& s,
                  const Vec3& position, const Quat& orientation, long& firstVertex) {
  std::fprintf(out, "o %s\nusemtl %s\n", name.c_str(), material.c_str());
  for (const Vec3& p : s.positions) {
    const Vec3 x = position + orientation * p;
    std::fprintf(out, "v %.9g %.9g %.9g\n", x.x(), x.y(), x.z());
  }
  for (const Vec3& n : s.normals) {
    const Vec3 m = orientation * n;
    std::fprintf(out, "vn %.6g %.6g %.6g\n", m.x(), m.y(), m.z());
  }
  for (const auto& t : s.triangles) {
    const long a = firstVertex + t[0], b = firstVertex + t[1], c = firstVertex + t[2];
    std::fprintf(out, "f %ld//%ld %ld//%ld %ld//%ld\n", a, a, b, b, c, c);
  }
  firstVertex += static_cast<long>(s.positions.size());
}

}  // namespace

Status writeObjFrames(const World& world, const std::vector<Frame>& frames, const ExportLooks& looks,
                      const std::string& folder) {
  const std::filesystem::path dir(folder);
  if (!std::filesystem::is_directory(dir)) return Error{"OBJ frames: folder '" + folder + "' does not exist"};
  {
    File materials(std::fopen((dir / "tandem.mtl").string().c_str(), "w"));
    if (!materials) return Error{"OBJ frames: cannot write '" + (dir / "tandem.mtl").string() + "'"};
    auto material = [&](const std::string& name, const std::optional<std::array<double, 3>>& colour,
                        const std::array<double, 3>& fallback) {
      const std::array<double, 3> c = colour ? *colour : fallback;
      std::fprintf(materials.get(), "newmtl %s\nKd %.4f %.4f %.4f\nKa 0 0 0\nKs 0.1 0.1 0.1\nNs 20\n\n", name.c_str(), c[0],
                   c[1], c[2]);
    };
    for (int b = 0; b < world.rigidBodyCount(); ++b)
      material("rigid_" + std::to_string(b),
               static_cast<size_t>(b) < looks.rigidColours.size() ? looks.rigidColours[b] : std::nullopt,
               world.rigidMass(RigidBodyId{b}) == 0.0 ? std::array<double, 3>{0.62, 0.63, 0.66}
                                                       : std::array<double, 3>{0.25, 0.45, 0.80});
    for (int d = 0; d < world.deformableCount(); ++d)
      material("deformable_" + std::to_string(d),
               static_cast<size_t>(d) < looks.deformableColours.size() ? looks.deformableColours[d] : std::nullopt,
               {0.86, 0.24, 0.14});
    if (std::ferror(materials.get())) return Error{"OBJ frames: writing '" + (dir / "tandem.mtl").string() + "' failed"};
  }
  std::vector<ShapeSurface> rigidSurfaces;
  for (int b = 0; b < world.rigidBodyCount(); ++b) rigidSurfaces.push_back(rigidExportSurface(world.rigidShape(RigidBodyId{b})));
  std::vector<DeformableSurface> deformableSurfaces;
  for (int d = 0; d < world.deformableCount(); ++d) deformableSurfaces.emplace_back(world.restMesh(DeformableId{d}));
  ShapeSurface surface;
  for (size_t k = 0; k < frames.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.obj", k);
    const std::string path = (dir / name).string();
    File out(std::fopen(path.c_str(), "w"));
    if (!out) return Error{"OBJ frames: cannot write '" + path + "'"};
    std::fprintf(out.get(), "# Tandem: frame %zu at t = %.9g s\nmtllib tandem.mtl\n", k, frames[k].time);
    long firstVertex = 1;
    for (int b = 0; b < world.rigidBodyCount(); ++b)
      writeSurface(out.get(), objName(world.rigidName(RigidBodyId{b})), "rigid_" + std::to_string(b), rigidSurfaces[b],
                   frames[k].rigidPositions[b], frames[k].rigidOrientations[b], firstVertex);
    for (int d = 0; d < world.deformableCount(); ++d) {
      deformableSurfaces[d].build(frames[k].nodePositions[d], surface);
      writeSurface(out.get(), objName(world.deformableName(DeformableId{d})), "deformable_" + std::to_string(d), surface,
                   Vec3::Zero(), Quat::Identity(), firstVertex);
    }
    if (std::ferror(out.get()) || std::fflush(out.get()) != 0) return Error{"OBJ frames: writing '" + path + "' failed"};
  }
  return {};
}

}  // namespace tandem::exporting
