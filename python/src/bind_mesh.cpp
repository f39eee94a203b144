// Deformable meshes and their generators and file readers.
#include "bindings.h"

#include <tandem/mesh.h>

namespace tandem::python {

void bindMesh(py::module_& module) {
  py::class_<DeformableMesh> mesh(module, "DeformableMesh",
                                  "A deformable body's nodes and topology, as plain data. Every property reads "
                                  "and writes a copy as a NumPy array (positions (N, 3) m, masses (N,) kg, "
                                  "edges (E, 2), shear_edges (S, 2), triangles (T, 3), tetrahedra (M, 4) int32); "
                                  "write a whole property to change it. Checked when added to a World, or by "
                                  "validate_mesh().");
  defKeywordInit<DeformableMesh>(mesh);
  mesh.def_property(
          "positions", [](const DeformableMesh& m) { return toArray(m.positions); },
          [](DeformableMesh& m, const py::handle& a) { m.positions = toVec3s(a, "DeformableMesh.positions"); },
          "Node positions, world frame (m): an (N, 3) array (a copy).")
      .def_property(
          "masses", [](const DeformableMesh& m) { return toArray(m.masses); },
          [](DeformableMesh& m, const py::handle& a) { m.masses = toDoubles(a, "DeformableMesh.masses"); },
          "Node masses (kg), each > 0: an (N,) array (a copy).")
      .def_property(
          "edges", [](const DeformableMesh& m) { return toArray(m.edges); },
          [](DeformableMesh& m, const py::handle& a) { m.edges = toIndexTuples<2>(a, "DeformableMesh.edges"); },
          "Structural edges: an (E, 2) int32 array of node indices (a copy).")
      .def_property(
          "shear_edges", [](const DeformableMesh& m) { return toArray(m.shearEdges); },
          [](DeformableMesh& m, const py::handle& a) {
            m.shearEdges = toIndexTuples<2>(a, "DeformableMesh.shear_edges");
          },
          "Edges that only resist shear (a cloth's diagonals): an (S, 2) int32 array (a copy).")
      .def_property(
          "triangles", [](const DeformableMesh& m) { return toArray(m.triangles); },
          [](DeformableMesh& m, const py::handle& a) {
            m.triangles = toIndexTuples<3>(a, "DeformableMesh.triangles");
          },
          "Surface triangles, counter-clockwise seen from outside: a (T, 3) int32 array (a copy).")
      .def_property(
          "tetrahedra", [](const DeformableMesh& m) { return toArray(m.tetrahedra); },
          [](DeformableMesh& m, const py::handle& a) {
            m.tetrahedra = toIndexTuples<4>(a, "DeformableMesh.tetrahedra");
          },
          "Tetrahedra: an (M, 4) int32 array (a copy).")
      .def_property_readonly("node_count", &DeformableMesh::nodeCount, "Number of nodes.")
      .def("__repr__", [](const DeformableMesh& m) {
        return "DeformableMesh(" + std::to_string(m.positions.size()) + " nodes, " + std::to_string(m.edges.size()) +
               " edges, " + std::to_string(m.triangles.size()) + " triangles, " +
               std::to_string(m.tetrahedra.size()) + " tetrahedra)";
      });

  module.def(
      "validate_mesh", [](const DeformableMesh& m) { check(validateMesh(m)); }, py::arg("mesh"),
      "Raises tandem.Error naming the first problem (sizes, non-finite values, masses, index ranges, "
      "zero-length edges, degenerate triangles and tetrahedra); returns None when the mesh is good.");
  module.def(
      "make_rope",
      [](const Vec3& start, const Vec3& end, int nodeCount, double totalMass) {
        return unwrap(makeRope(start, end, nodeCount, totalMass));
      },
      py::arg("start"), py::arg("end"), py::arg("node_count"), py::arg("total_mass"),
      "A straight rope of node_count nodes from start to end (m), total_mass (kg) spread evenly.");
  module.def(
      "make_rope_along_path",
      [](const py::handle& path, int nodeCount, double totalMass) {
        return unwrap(makeRopeAlongPath(toVec3s(path, "make_rope_along_path: path"), nodeCount, totalMass));
      },
      py::arg("path"), py::arg("node_count"), py::arg("total_mass"),
      "A rope of node_count nodes along the polyline through path ((K, 3), K >= 2), evenly spaced by arc length.");
  module.def(
      "make_cloth_grid",
      [](const Vec3& corner, const Vec3& sideU, const Vec3& sideV, int columns, int rows, double totalMass) {
        return unwrap(makeClothGrid(corner, sideU, sideV, columns, rows, totalMass));
      },
      py::arg("corner"), py::arg("side_u"), py::arg("side_v"), py::arg("columns"), py::arg("rows"),
      py::arg("total_mass"),
      "A cloth of columns x rows nodes spanning corner to corner + side_u + side_v; node (c, r) is r * columns + c. "
      "Structural edges along both directions, diagonals as shear edges.");
  module.def(
      "make_tet_box",
      [](const Vec3& minCorner, const Vec3& maxCorner, std::array<int, 3> cells, double totalMass) {
        return unwrap(makeTetBox(minCorner, maxCorner, cells[0], cells[1], cells[2], totalMass));
      },
      py::arg("min_corner"), py::arg("max_corner"), py::arg("cells"), py::arg("total_mass"),
      "An axis-aligned box split into cells = (x, y, z) cubes of five tetrahedra each.");
  module.def(
      "make_tet_cylinder",
      [](const Vec3& baseCentre, double radius, double height, int rings, int sectors, int layers, double totalMass) {
        return unwrap(makeTetCylinder(baseCentre, radius, height, rings, sectors, layers, totalMass));
      },
      py::arg("base_centre"), py::arg("radius"), py::arg("height"), py::arg("rings"), py::arg("sectors"),
      py::arg("layers"), py::arg("total_mass"),
      "A tetrahedral cylinder along +y from base_centre: rings across the radius, sectors around, layers along.");
  module.def(
      "load_obj", [](const std::string& path, double totalMass) { return unwrap(loadObj(path, totalMass)); },
      py::arg("path"), py::arg("total_mass"),
      "A surface mesh from a Wavefront OBJ file, total_mass lumped by area. Problems name the file and line.");
  module.def(
      "load_tetgen", [](const std::string& basePath, double density) { return unwrap(loadTetGen(basePath, density)); },
      py::arg("base_path"), py::arg("density"),
      "A TetGen mesh from base_path.node and .ele (and .face if there), masses lumped from density (kg/m^3).");
}

}  // namespace tandem::python
