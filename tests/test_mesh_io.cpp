// Mesh files and the tetrahedral cylinder: geometry that adds up, and bad files named by line.
#include <tandem/mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>

#include <unistd.h>

namespace tandem {
namespace {

constexpr double kPi = 3.14159265358979323846;

double tetVolume(const DeformableMesh& mesh, const std::array<int32_t, 4>& t) {
  const auto& x = mesh.positions;
  return (x[t[1]] - x[t[0]]).dot((x[t[2]] - x[t[0]]).cross(x[t[3]] - x[t[0]])) / 6.0;
}

// Σ (centroid · n) area / 3 over the boundary: the enclosed volume when the normals point out.
double boundaryFlux(const DeformableMesh& mesh) {
  const auto& x = mesh.positions;
  double flux = 0.0;
  for (const auto& f : mesh.triangles)
    flux += ((x[f[0]] + x[f[1]] + x[f[2]]) / 3.0).dot(0.5 * (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]])) / 3.0;
  return flux;
}

TEST(MeshIO, TetCylinderFillsItsPrismWithOutwardBoundary) {
  const int rings = 3, sectors = 12, layers = 4;
  Result<DeformableMesh> cylinder = makeTetCylinder({1, 0, -1}, 0.2, 0.5, rings, sectors, layers, 2.0);
  ASSERT_TRUE(cylinder.ok()) << cylinder.message();
  EXPECT_EQ(cylinder->nodeCount(), (layers + 1) * (1 + rings * sectors));
  EXPECT_EQ(cylinder->tetrahedra.size(), static_cast<size_t>(layers * sectors * (3 + 6 * (rings - 1))));
  double volume = 0.0;
  for (const auto& t : cylinder->tetrahedra) {
    EXPECT_GT(tetVolume(*cylinder, t), 0.0);
    volume += tetVolume(*cylinder, t);
  }
  // The regular 12-gon prism the cylinder is made of.
  const double expected = 0.5 * sectors * 0.2 * 0.2 * std::sin(2 * kPi / sectors) * 0.5;
  EXPECT_NEAR(volume, expected, 1e-12);
  // Closed and outward: the boundary encloses the same volume (about the origin, shifted by
  // the base centre: the flux formula holds for any origin on a closed surface).
  EXPECT_NEAR(boundaryFlux(*cylinder), expected, 1e-12);
  EXPECT_NEAR(std::accumulate(cylinder->masses.begin(), cylinder->masses.end(), 0.0), 2.0, 1e-12);
  EXPECT_TRUE(validateMesh(*cylinder).ok());
  EXPECT_EQ(makeTetCylinder({0, 0, 0}, 0.2, 0.5, 1, 2, 1, 1.0).message(), "tet cylinder: sectors must be >= 3, got 2");
  EXPECT_EQ(makeTetCylinder({0, 0, 0}, -1, 0.5, 1, 6, 1, 1.0).message(),
            "tet cylinder: radius and height must be positive, got -1 and 0.5");
}

class TempDir {
 public:
  TempDir() : m_path(std::filesystem::temp_directory_path() / ("tandem_mesh_io_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(m_path);
  }
  ~TempDir() { std::filesystem::remove_all(m_path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(m_path / name) << text;
    return (m_path / name).string();
  }
  std::string base(const std::string& name) const { return (m_path / name).string(); }

 private:
  std::filesystem::path m_path;
};

// A unit cube as 5 tets, 1-based, the way TetGen writes them (a comment and attributes too).
const char* kCubeNode =
    "# unit cube\n8 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n5 0 0 1\n6 1 0 1\n7 0 1 1\n8 1 1 1\n";
const char* kCubeEle = "5 4 0\n1 1 2 3 5\n2 4 3 2 8\n3 6 5 8 2\n4 7 8 5 3\n5 2 3 5 8\n";

TEST(MeshIO, TetGenCubeLoadsWithMassesAndOutwardBoundary) {
  TempDir dir;
  dir.write("cube.node", kCubeNode);
  dir.write("cube.ele", kCubeEle);
  Result<DeformableMesh> cube = loadTetGen(dir.base("cube"), 1000.0);
  ASSERT_TRUE(cube.ok()) << cube.message();
  EXPECT_EQ(cube->nodeCount(), 8);
  EXPECT_EQ(cube->tetrahedra.size(), 5u);
  for (const auto& t : cube->tetrahedra) EXPECT_GT(tetVolume(*cube, t), 0.0);  // all turned the right way
  EXPECT_NEAR(std::accumulate(cube->masses.begin(), cube->masses.end(), 0.0), 1000.0, 1e-9);
  EXPECT_EQ(cube->triangles.size(), 12u);
  EXPECT_NEAR(boundaryFlux(*cube), 1.0, 1e-12);
  EXPECT_EQ(cube->edges.size(), 18u);  // 12 cube edges and 6 face diagonals

  // A .face file of the same boundary, every other face wound inwards: they come out outwards.
  std::string faces = std::to_string(cube->triangles.size()) + " 0\n";
  for (size_t f = 0; f < cube->triangles.size(); ++f) {
    auto t = cube->triangles[f];
    if (f % 2) std::swap(t[1], t[2]);
    faces += std::to_string(f + 1) + " " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
             std::to_string(t[2] + 1) + "\n";
  }
  dir.write("cube.face", faces);
  Result<DeformableMesh> faced = loadTetGen(dir.base("cube"), 1000.0);
  ASSERT_TRUE(faced.ok()) << faced.message();
  EXPECT_EQ(faced->triangles.size(), 12u);
  EXPECT_NEAR(boundaryFlux(*faced), 1.0, 1e-12);
}

struct BadTetGen {
  const char* name;
  const char* node;
  const char* ele;
  const char* expected;  // the end of the message; the file and line come before it
};

class MalformedTetGen : public ::testing::TestWithParam<BadTetGen> {};

TEST_P(MalformedTetGen, IsRefusedNamingFileAndLine) {
  const BadTetGen& bad = GetParam();
  TempDir dir;
  dir.write("m.node", bad.node);
  dir.write("m.ele", bad.ele);
  Result<DeformableMesh> mesh = loadTetGen(dir.base("m"), 1000.0);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.message(), dir.base("m") + bad.expected);
}

INSTANTIATE_TEST_SUITE_P(
    Files, MalformedTetGen,
    ::testing::Values(
        BadTetGen{"too_few_points", "# cube\n8 3 0 0\n1 0 0 0\n2 1 0 0\n", kCubeEle, ".node:4: expected 8 points, found 2"},
        BadTetGen{"nan_coordinate", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 nan 0\n4 0 0 1\n", "1 4 0\n1 1 2 3 4\n",
                  ".node:4: the point's coordinates are not finite"},
        BadTetGen{"not_a_number", "4 3 0 0\n1 0 0 0\n2 1 0 x\n3 0 1 0\n4 0 0 1\n", "1 4 0\n1 1 2 3 4\n",
                  ".node:3: 'x' is not a number"},
        BadTetGen{"out_of_range", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 0\n1 1 2 3 9\n",
                  ".ele:2: node 9 does not exist (nodes are 1 to 4)"},
        BadTetGen{"out_of_sequence", "4 3 0 0\n1 0 0 0\n3 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 0\n1 1 2 3 4\n",
                  ".node:3: index 3 out of sequence (expected 2)"},
        BadTetGen{"too_few_tets", kCubeNode, "5 4 0\n1 1 2 3 5\n", ".ele:2: expected 5 tetrahedra, found 1"},
        BadTetGen{"short_line", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 0\n1 1 2 3\n",
                  ".ele:2: expected 5 numbers, found 4"},
        BadTetGen{"degenerate", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n", "1 4 0\n1 1 2 3 4\n",
                  ".ele:2: tetrahedron 0 is degenerate (zero volume)"},
        BadTetGen{"ten_node_tets", kCubeNode, "5 10 0\n", ".ele:1: only 4-node tetrahedra are supported"},
        BadTetGen{"orphan_point", "5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 3 3 3\n", "1 4 0\n1 1 2 3 4\n",
                  ".node: point 5 belongs to no tetrahedron"},
        BadTetGen{"empty", "# nothing\n", kCubeEle, ".node: the file is empty"}),
    [](const ::testing::TestParamInfo<BadTetGen>& param) { return std::string(param.param.name); });

TEST(MeshIO, MissingTetGenFilesAreNamed) {
  TempDir dir;
  dir.write("half.node", kCubeNode);
  EXPECT_EQ(loadTetGen(dir.base("half"), 1000.0).message(), dir.base("half") + ".ele: cannot open the TetGen file");
  EXPECT_EQ(loadTetGen(dir.base("none"), 1000.0).message(), dir.base("none") + ".node: cannot open the TetGen file");
  EXPECT_EQ(loadTetGen(dir.base("half"), -1.0).message(),
            dir.base("half") + ": density must be a positive number of kg/m³, got -1");
}

// A folder given where a file belongs is named as such (it read as a file with no faces).
TEST(MeshIO, AFolderIsNotAMeshFile) {
  TempDir dir;
  const std::string folder = dir.base("");
  EXPECT_EQ(loadObj(folder, 1.0).message(), folder + ": is a folder, not an OBJ file");
}

// A device is not read (/dev/zero never ends), a file past the size limit is refused before it
// is read, a mesh past the node limit after; the limits are named and can be raised.
TEST(MeshIO, DevicesAndOversizedFilesAreRefused) {
  EXPECT_EQ(loadObj("/dev/zero", 1.0).message(),
            "/dev/zero: is not a regular file (a device, pipe or socket); OBJ files must be regular files");
  TempDir dir;
  const std::string path = dir.write("triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Limits limits;
  limits.maxMeshFileBytes = 30;
  EXPECT_EQ(loadObj(path, 1.0, limits).message(),
            path + ": the OBJ file has 32 bytes, more than the limit of 30 (Limits::maxMeshFileBytes; the API can raise it)");
  limits.maxMeshFileBytes = 32;
  limits.maxNodes = 2;
  EXPECT_EQ(loadObj(path, 1.0, limits).message(),
            path + ": the file is 3 nodes, more than the limit of 2 (Limits::maxNodes; the API can raise it)");
  limits.maxNodes = 3;
  EXPECT_TRUE(loadObj(path, 1.0, limits).ok());
  dir.write("big.node", kCubeNode);
  dir.write("big.ele", kCubeEle);
  limits.maxMeshFileBytes = 1 << 20;
  limits.maxNodes = 7;
  EXPECT_NE(loadTetGen(dir.base("big"), 1000.0, limits).message().find(".node:2: the file declares 8 points, more than the limit of 7 (Limits::maxNodes"),
            std::string::npos)
      << loadTetGen(dir.base("big"), 1000.0, limits).message();
}

TEST(MeshIO, ObjSurfaceLoadsTriangulatedWithAreaMasses) {
  TempDir dir;
  // A 2 m × 1 m rectangle as one quad and a 1 m² square as two triangles beside it.
  const std::string path = dir.write("sheet.obj",
                                     "# sheet\nv 0 0 0\nv 2 0 0\nv 2 0 1\nv 0 0 1\nv 3 0 0\nv 3 0 1\n"
                                     "f 1 2 3 4\nf 2 5 6\nf 2 6 3\n");
  Result<DeformableMesh> sheet = loadObj(path, 3.0);
  ASSERT_TRUE(sheet.ok()) << sheet.message();
  EXPECT_EQ(sheet->nodeCount(), 6);
  EXPECT_EQ(sheet->triangles.size(), 4u);
  EXPECT_EQ(sheet->edges.size(), 9u);
  EXPECT_NEAR(std::accumulate(sheet->masses.begin(), sheet->masses.end(), 0.0), 3.0, 1e-12);
  EXPECT_NEAR(sheet->masses[4], 3.0 / 3.0 * 0.5 / 3.0, 1e-6);  // one third of one triangle's area share
  EXPECT_EQ(loadObj(dir.base("absent.obj"), 1.0).ok(), false);
  const std::string points = dir.write("points.obj", "v 0 0 0\nv 1 0 0\n");
  EXPECT_EQ(loadObj(points, 1.0).message(), points + ": the file has no faces");
}

}  // namespace
}  // namespace tandem
