// Mesh files: TetGen .node/.ele/.face and Wavefront OBJ.
#include <tandem/mesh.h>
#include <tandem/mesh_body.h>

#include "format.h"
#include "input_file.h"
#include "mesh_internal.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace tandem {
namespace {

// The numbers on the non-empty, non-comment lines of a TetGen file, with their line numbers.
struct TetGenFile {
  std::string path;
  std::vector<std::pair<int, std::vector<double>>> lines;
  size_t next = 0;

  Error error(int line, const std::string& message) const {
    return Error{path + ":" + std::to_string(line) + ": " + message};
  }
};

Result<TetGenFile> readTetGenFile(const std::string& path, const Limits& limits) {
  Result<std::string> text_ = readInputFile(path, limits.maxMeshFileBytes, "TetGen file", "Limits::maxMeshFileBytes");
  if (!text_) return Error{text_.message()};
  std::istringstream in(std::move(text_).value());
  TetGenFile file{path, {}, 0};
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    const size_t comment = text.find('#');
    if (comment != std::string::npos) text.erase(comment);
    std::istringstream words(text);
    std::vector<double> values;
    std::string word;
    while (words >> word) {
      char* end = nullptr;
      const double value = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') return file.error(number, "'" + word + "' is not a number");
      values.push_back(value);
    }
    if (!values.empty()) file.lines.emplace_back(number, std::move(values));
  }
  if (file.lines.empty()) return Error{path + ": the file is empty"};
  return file;
}

bool isCount(double value) { return value >= 0 && value == std::floor(value) && value < 1e9; }

// Reads "<count> <per-entry...>" then `count` entries of at least `minimumWidth` numbers whose
// first is the entry's index (consecutive, from 0 or 1). Returns the entries without the index.
Result<std::vector<std::pair<int, std::vector<double>>>> readEntries(TetGenFile& file, const char* what,
                                                                     size_t minimumWidth, int& base) {
  const auto& [headerLine, header] = file.lines[0];
  if (!isCount(header[0])) return file.error(headerLine, std::string("the number of ") + what + " is not a count");
  const size_t count = static_cast<size_t>(header[0]);
  if (file.lines.size() - 1 < count)
    return file.error(file.lines.back().first, "expected " + std::to_string(count) + " " + what + ", found " +
                                                   std::to_string(file.lines.size() - 1));
  std::vector<std::pair<int, std::vector<double>>> entries;
  for (size_t i = 0; i < count; ++i) {
    const auto& [line, values] = file.lines[1 + i];
    if (values.size() < minimumWidth)
      return file.error(line, "expected " + std::to_string(minimumWidth) + " numbers, found " +
                                  std::to_string(values.size()));
    if (i == 0 && base < 0) {
      if (values[0] != 0 && values[0] != 1)
        return file.error(line, "the first index must be 0 or 1, got " + formatNumber(values[0]));
      base = static_cast<int>(values[0]);
    }
    if (values[0] != static_cast<double>(base) + static_cast<double>(i))
      return file.error(line, "index " + formatNumber(values[0]) + " out of sequence (expected " +
                                  std::to_string(base + static_cast<int>(i)) + ")");
    entries.emplace_back(line, std::vector<double>(values.begin() + 1, values.end()));
  }
  return entries;
}

Result<int32_t> nodeIndex(const TetGenFile& file, int line, double value, int base, int32_t nodeCount) {
  const double index = value - base;
  if (index != std::floor(index) || index < 0 || index >= nodeCount)
    return file.error(line, "node " + formatNumber(value) + " does not exist (nodes are " + std::to_string(base) +
                                " to " + std::to_string(base + nodeCount - 1) + ")");
  return static_cast<int32_t>(index);
}

// Refuses an entry count past its limit before the entries are read into a mesh.
Status checkEntryCount(const TetGenFile& file, double count, double limit, const char* what, const char* limitName) {
  if (count <= limit) return {};
  return file.error(file.lines[0].first, "the file declares " + formatNumber(count) + " " + what +
                                             ", more than the limit of " + formatNumber(limit) + " (" + limitName +
                                             "; the API can raise it)");
}

}  // namespace

Result<DeformableMesh> loadTetGen(const std::string& basePath, double density, const Limits& limits) {
  if (!(std::isfinite(density) && density > 0))
    return Error{basePath + ": density must be a positive number of kg/m³, got " + formatNumber(density)};
  DeformableMesh mesh;

  // .node: "<points> 3 <attributes> <markers>", then "<index> x y z ..."
  Result<TetGenFile> nodeFile = readTetGenFile(basePath + ".node", limits);
  if (!nodeFile) return Error{nodeFile.message()};
  if (Status s = checkEntryCount(*nodeFile, nodeFile->lines[0].second[0],
                                 double(std::min(limits.maxNodes, kMaxIndexableNodes)), "points", "Limits::maxNodes");
      !s)
    return Error{s.message()};
  if (nodeFile->lines[0].second.size() >= 2 && nodeFile->lines[0].second[1] != 3)
    return nodeFile->error(nodeFile->lines[0].first, "only 3-dimensional points are supported");
  int base = -1;
  auto points = readEntries(*nodeFile, "points", 4, base);
  if (!points) return Error{points.message()};
  for (const auto& [line, values] : *points) {
    const Vec3 p(values[0], values[1], values[2]);
    if (!p.allFinite()) return nodeFile->error(line, "the point's coordinates are not finite");
    mesh.positions.push_back(p);
  }
  const int32_t nodeCount = mesh.nodeCount();

  // .ele: "<tets> 4 <attributes>", then "<index> n1 n2 n3 n4 ..."
  Result<TetGenFile> eleFile = readTetGenFile(basePath + ".ele", limits);
  if (!eleFile) return Error{eleFile.message()};
  if (Status s = checkEntryCount(*eleFile, eleFile->lines[0].second[0], double(limits.maxTetrahedra), "tetrahedra",
                                 "Limits::maxTetrahedra");
      !s)
    return Error{s.message()};
  if (eleFile->lines[0].second.size() >= 2 && eleFile->lines[0].second[1] != 4)
    return eleFile->error(eleFile->lines[0].first, "only 4-node tetrahedra are supported");
  int tetBase = -1;
  auto tets = readEntries(*eleFile, "tetrahedra", 5, tetBase);
  if (!tets) return Error{tets.message()};
  mesh.masses.assign(nodeCount, 0.0);
  for (size_t t = 0; t < tets->size(); ++t) {
    const auto& [line, values] = (*tets)[t];
    std::array<int32_t, 4> tet;
    for (int k = 0; k < 4; ++k) {
      Result<int32_t> n = nodeIndex(*eleFile, line, values[k], base, nodeCount);
      if (!n) return Error{n.message()};
      tet[k] = *n;
    }
    const auto& x = mesh.positions;
    double sixVolume = (x[tet[1]] - x[tet[0]]).dot((x[tet[2]] - x[tet[0]]).cross(x[tet[3]] - x[tet[0]]));
    const double edge = (x[tet[1]] - x[tet[0]]).norm();
    if (std::abs(sixVolume) <= 1e-9 * edge * edge * edge)
      return eleFile->error(line, "tetrahedron " + std::to_string(t) + " is degenerate (zero volume)");
    if (sixVolume < 0) {  // wound the other way round (TetGen's convention): turned round
      std::swap(tet[2], tet[3]);
      sixVolume = -sixVolume;
    }
    for (int32_t n : tet) mesh.masses[n] += density * sixVolume / 24.0;  // a quarter of ρV each
    mesh.tetrahedra.push_back(tet);
  }
  for (int32_t n = 0; n < nodeCount; ++n)
    if (mesh.masses[n] == 0.0)
      return Error{basePath + ".node: point " + std::to_string(base + n) + " belongs to no tetrahedron"};

  // .face (optional): "<faces> <markers>", then "<index> n1 n2 n3 ...", wound outwards here.
  std::ifstream probe(basePath + ".face");
  if (probe) {
    Result<TetGenFile> faceFile = readTetGenFile(basePath + ".face", limits);
    if (!faceFile) return Error{faceFile.message()};
    if (Status s = checkEntryCount(*faceFile, faceFile->lines[0].second[0], double(limits.maxTriangles), "faces",
                                   "Limits::maxTriangles");
        !s)
      return Error{s.message()};
    std::map<std::array<int32_t, 3>, int32_t> opposite;  // a tet face (sorted) → the tet's other node
    for (const auto& t : mesh.tetrahedra)
      for (int k = 0; k < 4; ++k) {
        std::array<int32_t, 3> face{t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]};
        std::sort(face.begin(), face.end());
        opposite[face] = t[k];
      }
    int faceBase = -1;
    auto faces = readEntries(*faceFile, "faces", 4, faceBase);
    if (!faces) return Error{faces.message()};
    for (const auto& [line, values] : *faces) {
      std::array<int32_t, 3> face;
      for (int k = 0; k < 3; ++k) {
        Result<int32_t> n = nodeIndex(*faceFile, line, values[k], base, nodeCount);
        if (!n) return Error{n.message()};
        face[k] = *n;
      }
      std::array<int32_t, 3> key = face;
      std::sort(key.begin(), key.end());
      const auto found = opposite.find(key);
      if (found == opposite.end()) return faceFile->error(line, "the face is not a face of any tetrahedron");
      const auto& x = mesh.positions;
      const Vec3 normal = (x[face[1]] - x[face[0]]).cross(x[face[2]] - x[face[0]]);
      if (normal.dot(x[found->second] - x[face[0]]) > 0) std::swap(face[1], face[2]);  // away from the tet
      mesh.triangles.push_back(face);
    }
  }
  addTetEdgesAndBoundary(mesh);
  if (Status s = validateMesh(mesh); !s) return Error{basePath + ": " + s.message()};
  return mesh;
}

namespace {

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf", "1e999", "x") as 0: the
// vertex lines are checked first, so such a file is refused with the line named.
Status checkObjVertices(const std::string& path, const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword) || keyword != "v") continue;
    std::string word;
    for (int k = 0; k < 3; ++k) {
      if (!(words >> word)) return Error{path + ":" + std::to_string(number) + ": a vertex needs x, y and z"};
      char* end = nullptr;
      const double value = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0' || !std::isfinite(value))
        return Error{path + ":" + std::to_string(number) + ": vertex coordinate '" + word + "' is not a finite number"};
    }
  }
  return {};
}

// Reads and parses an OBJ file within the limits, faces triangulated; errors name the file.
Status parseObj(const std::string& path, const Limits& limits, tinyobj::ObjReader& reader) {
  Result<std::string> text = readInputFile(path, limits.maxMeshFileBytes, "OBJ file", "Limits::maxMeshFileBytes");
  if (!text) return Error{text.message()};
  if (Status s = checkObjVertices(path, *text); !s) return s;
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  if (!reader.ParseFromString(*text, "", config)) {
    std::string message = reader.Error();
    while (!message.empty() && message.back() == '\n') message.pop_back();
    return Error{path + ": " + (message.empty() ? "cannot read the file" : message)};
  }
  return {};
}

}  // namespace

Result<DeformableMesh> loadObj(const std::string& path, double totalMass, const Limits& limits) {
  if (!(std::isfinite(totalMass) && totalMass > 0))
    return Error{path + ": total mass must be a positive number of kilograms, got " + formatNumber(totalMass)};
  tinyobj::ObjReader reader;
  if (Status s = parseObj(path, limits, reader); !s) return Error{s.message()};
  const auto& vertices = reader.GetAttrib().vertices;
  DeformableMesh mesh;
  for (size_t i = 0; i + 2 < vertices.size(); i += 3)
    mesh.positions.emplace_back(vertices[i], vertices[i + 1], vertices[i + 2]);
  for (const auto& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (size_t i = 0; i + 2 < indices.size(); i += 3)
      mesh.triangles.push_back({indices[i].vertex_index, indices[i + 1].vertex_index, indices[i + 2].vertex_index});
  }
  if (mesh.triangles.empty()) return Error{path + ": the file has no faces"};
  if (Status s = checkMeshSize(double(mesh.positions.size()), double(mesh.triangles.size()), 0, limits, path,
                               "the file");
      !s)
    return Error{s.message()};
  // Mass lumped by area: a third of each triangle's share to each of its vertices.
  mesh.masses.assign(mesh.positions.size(), 0.0);
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    if (std::max({t[0], t[1], t[2]}) >= mesh.nodeCount() || std::min({t[0], t[1], t[2]}) < 0)
      return Error{path + ": a face refers to a vertex that does not exist"};
    const auto& x = mesh.positions;
    const double a = 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
    area += a;
    for (int32_t n : t) mesh.masses[n] += a / 3.0;
  }
  if (!(area > 0)) return Error{path + ": the surface has no area"};
  for (double& m : mesh.masses) m *= totalMass / area;
  std::map<std::pair<int32_t, int32_t>, bool> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}] = true;
  for (const auto& [edge, unused] : edges) mesh.edges.push_back({edge.first, edge.second});
  for (int32_t n = 0; n < mesh.nodeCount(); ++n)
    if (mesh.masses[n] == 0.0) return Error{path + ": vertex " + std::to_string(n + 1) + " belongs to no face"};
  if (Status s = validateMesh(mesh); !s) return Error{path + ": " + s.message()};
  return mesh;
}

Result<SurfaceMesh> loadObjSurface(const std::string& path, const Limits& limits) {
  tinyobj::ObjReader reader;
  if (Status s = parseObj(path, limits, reader); !s) return Error{s.message()};
  const auto& vertices = reader.GetAttrib().vertices;
  SurfaceMesh mesh;
  for (size_t i = 0; i + 2 < vertices.size(); i += 3)
    mesh.positions.emplace_back(vertices[i], vertices[i + 1], vertices[i + 2]);
  // Objects and groups of the same name (a group reopened later in the file) are one part.
  for (const auto& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    if (indices.empty()) continue;
    const auto named = std::find(mesh.groupNames.begin(), mesh.groupNames.end(), shape.name);
    const auto group = static_cast<int32_t>(named - mesh.groupNames.begin());
    if (named == mesh.groupNames.end()) mesh.groupNames.push_back(shape.name);
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
      const std::array<int32_t, 3> t{indices[i].vertex_index, indices[i + 1].vertex_index, indices[i + 2].vertex_index};
      if (std::max({t[0], t[1], t[2]}) >= static_cast<int32_t>(mesh.positions.size()) || std::min({t[0], t[1], t[2]}) < 0)
        return Error{path + ": a face refers to a vertex that does not exist"};
      mesh.triangles.push_back(t);
      mesh.triangleGroup.push_back(group);
    }
  }
  if (mesh.triangles.empty()) return Error{path + ": the file has no faces"};
  if (Status s = checkMeshSize(double(mesh.positions.size()), double(mesh.triangles.size()), 0, limits, path,
                               "the file");
      !s)
    return Error{s.message()};
  return mesh;
}

}  // namespace tandem
