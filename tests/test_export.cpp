// `tandem export`: the glTF it writes is read back with tinygltf and matches the record of the
// same run (`tandem run --record --record-nodes`): node counts and names, frame times, a rigid
// body's pose and a rope node's position at one frame; the .glb holds the same; the OBJ folder
// has a file per frame whose rope vertex is the recorded node.
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(TANDEM_SOURCE_DIR) + "/scenes/rope_wheel.json";
constexpr double kFps = 25.0;   // two 20 ms steps a frame: every frame lands on a step
constexpr int kFrames = 26;     // 0 to 1 s
constexpr int kFrame = 10;      // checked against the record: t = 0.4 s, step 20

fs::path tempDir() {
  const fs::path dir = fs::temp_directory_path() / "tandem_export_tests";
  fs::create_directories(dir);
  return dir;
}

int run(const std::string& arguments) {
  return std::system((std::string(TANDEM_CLI) + " " + arguments + " > /dev/null").c_str());
}

// The record: (step, kind, name, index) → the row's numbers x, y, z, qw, qx, qy, qz.
struct Record {
  std::map<std::string, std::vector<double>> rows;
  std::vector<double> at(int step, const std::string& kind, const std::string& name, int index) const {
    const auto it = rows.find(std::to_string(step) + "," + kind + "," + name + "," + std::to_string(index));
    return it == rows.end() ? std::vector<double>{} : it->second;
  }
};

const Record& record() {
  static const Record recorded = [] {
    Record r;
    const std::string path = (tempDir() / "rope_wheel.csv").string();
    EXPECT_EQ(run("run " + kScene + " --seconds 1 --record " + path + " --record-nodes"), 0);
    std::ifstream file(path);
    std::string line;
    std::getline(file, line);
    while (std::getline(file, line)) {
      std::vector<std::string> cells;
      std::stringstream fields(line);
      for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
      std::vector<double> numbers;
      for (size_t c = 5; c < 12 && c < cells.size(); ++c) numbers.push_back(cells[c].empty() ? 0.0 : std::stod(cells[c]));
      r.rows[cells[0] + "," + cells[2] + "," + cells[3] + "," + cells[4]] = numbers;
    }
    return r;
  }();
  return recorded;
}

// An accessor's floats (tightly packed, as Tandem writes them).
std::vector<float> floats(const tinygltf::Model& model, int accessorIndex) {
  const tinygltf::Accessor& accessor = model.accessors.at(accessorIndex);
  const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
  EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  const size_t components = accessor.type == TINYGLTF_TYPE_SCALAR ? 1 : accessor.type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
  std::vector<float> values(accessor.count * components);
  std::memcpy(values.data(), model.buffers.at(view.buffer).data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(float));
  return values;
}

int nodeNamed(const tinygltf::Model& model, const std::string& name) {
  for (size_t n = 0; n < model.nodes.size(); ++n)
    if (model.nodes[n].name == name) return static_cast<int>(n);
  return -1;
}

// The output accessor of the channel animating `path` of `node`.
int channelOutput(const tinygltf::Model& model, int node, const std::string& path, int* input = nullptr) {
  const tinygltf::Animation& animation = model.animations.at(0);
  for (const tinygltf::AnimationChannel& channel : animation.channels)
    if (channel.target_node == node && channel.target_path == path) {
      if (input) *input = animation.samplers.at(channel.sampler).input;
      return animation.samplers.at(channel.sampler).output;
    }
  return -1;
}

void checkAgainstRecord(const tinygltf::Model& model) {
  // Six rigid bodies and one rope, by name, all in the scene.
  ASSERT_EQ(model.nodes.size(), 7u);
  ASSERT_EQ(model.scenes.size(), 1u);
  EXPECT_EQ(model.scenes[0].nodes.size(), 7u);
  for (const char* name : {"floor", "wheel", "flange front", "flange back", "light", "heavy", "rope"})
    EXPECT_GE(nodeNamed(model, name), 0) << name;
  ASSERT_EQ(model.animations.size(), 1u);
  EXPECT_LT(channelOutput(model, nodeNamed(model, "floor"), "translation"), 0);  // static: not animated

  // Frame times 0, 1/25, ..., 1 s.
  const int heavy = nodeNamed(model, "heavy");
  int input = -1;
  const int translation = channelOutput(model, heavy, "translation", &input);
  ASSERT_GE(translation, 0);
  const std::vector<float> times = floats(model, input);
  ASSERT_EQ(times.size(), static_cast<size_t>(kFrames));
  for (int k = 0; k < kFrames; ++k) EXPECT_NEAR(times[k], k / kFps, 1e-6) << k;

  // The heavy body's position and the wheel's orientation at frame 10 are the recorded ones at
  // step 20 (to float precision).
  const std::vector<double> heavyRow = record().at(2 * kFrame, "rigid", "heavy", 5);
  ASSERT_EQ(heavyRow.size(), 7u);
  const std::vector<float> heavyPath = floats(model, translation);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(heavyPath[3 * kFrame + c], heavyRow[c], 1e-6);
  EXPECT_LT(heavyRow[1], 0.41 - 0.01);  // it has moved: the check is not of the start
  const int wheel = nodeNamed(model, "wheel");
  const std::vector<float> rotations = floats(model, channelOutput(model, wheel, "rotation"));
  const std::vector<double> wheelRow = record().at(2 * kFrame, "rigid", "wheel", 1);
  ASSERT_EQ(wheelRow.size(), 7u);
  const Eigen::Quaterniond recorded(wheelRow[3], wheelRow[4], wheelRow[5], wheelRow[6]);
  const Eigen::Quaterniond written(rotations[4 * kFrame + 3], rotations[4 * kFrame], rotations[4 * kFrame + 1],
                                   rotations[4 * kFrame + 2]);
  EXPECT_NEAR(std::abs(recorded.dot(written)), 1.0, 1e-6);
  const std::vector<double> wheelStart = record().at(0, "rigid", "wheel", 1);
  ASSERT_EQ(wheelStart.size(), 7u);
  const Eigen::Quaterniond start(wheelStart[3], wheelStart[4], wheelStart[5], wheelStart[6]);
  EXPECT_GT(recorded.angularDistance(start), 0.05);  // the wheel has turned: the check is not of the start

  // The rope: node 0 is vertex 0 of its surface; at frame 10 it is the base plus target 9, and
  // the weights are one-hot on target 9 at frame 10's time.
  const tinygltf::Node& ropeNode = model.nodes[nodeNamed(model, "rope")];
  const tinygltf::Primitive& rope = model.meshes.at(ropeNode.mesh).primitives.at(0);
  ASSERT_EQ(rope.targets.size(), static_cast<size_t>(kFrames - 1));
  const std::vector<float> base = floats(model, rope.attributes.at("POSITION"));
  const std::vector<float> offset = floats(model, rope.targets[kFrame - 1].at("POSITION"));
  const std::vector<double> nodeRow = record().at(2 * kFrame, "node", "rope", 0);
  ASSERT_EQ(nodeRow.size(), 7u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(base[c] + offset[c], nodeRow[c], 2e-6);
  const std::vector<float> weights = floats(model, channelOutput(model, nodeNamed(model, "rope"), "weights"));
  ASSERT_EQ(weights.size(), static_cast<size_t>(kFrames * (kFrames - 1)));
  for (int t = 0; t < kFrames - 1; ++t) EXPECT_EQ(weights[kFrame * (kFrames - 1) + t], t == kFrame - 1 ? 1.0f : 0.0f);
}

TEST(Export, GltfReadsBackAsTheRecordedRun) {
  const std::string path = (tempDir() / "rope_wheel.gltf").string();
  ASSERT_EQ(run("export " + kScene + " --out " + path + " --fps 25 --seconds 1"), 0);
  EXPECT_TRUE(fs::exists(tempDir() / "rope_wheel.bin"));
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadASCIIFromFile(&model, &error, &warning, path)) << error;
  EXPECT_EQ(model.asset.version, "2.0");
  checkAgainstRecord(model);
  // The scene's colours are the materials' (sRGB #5c... converted to linear): the heavy body is
  // "#2f5d8a", whose blue 0x8a = 138 is 0.2542 linear.
  const tinygltf::Material& material =
      model.materials.at(model.meshes.at(model.nodes[nodeNamed(model, "heavy")].mesh).primitives[0].material);
  EXPECT_NEAR(material.pbrMetallicRoughness.baseColorFactor[2], 0.2542, 1e-3);
}

TEST(Export, GlbHoldsTheSame) {
  const std::string path = (tempDir() / "rope_wheel.glb").string();
  ASSERT_EQ(run("export " + kScene + " --out " + path + " --fps 25 --seconds 1"), 0);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path)) << error;
  checkAgainstRecord(model);
}

TEST(Export, ObjFolderHasAFramePerStepOfTheRate) {
  const fs::path dir = tempDir() / "obj_frames";
  fs::remove_all(dir);
  ASSERT_EQ(run("export " + kScene + " --out " + dir.string() + "/ --fps 5 --seconds 1"), 0);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.path().extension() == ".obj";
  EXPECT_EQ(files, 6);  // t = 0, 0.2, ..., 1 s
  EXPECT_TRUE(fs::exists(dir / "tandem.mtl"));
  // Frame 2 is t = 0.4 s (step 20): the rope object's first vertex is node 0 as recorded.
  std::ifstream file(dir / "frame_00002.obj");
  std::string line;
  bool inRope = false;
  std::vector<double> first;
  int objects = 0;
  while (std::getline(file, line)) {
    if (line.rfind("o ", 0) == 0) {
      ++objects;
      inRope = line == "o rope";
    }
    if (inRope && first.empty() && line.rfind("v ", 0) == 0) {
      std::stringstream numbers(line.substr(2));
      double x = 0, y = 0, z = 0;
      numbers >> x >> y >> z;
      first = {x, y, z};
    }
  }
  EXPECT_EQ(objects, 7);
  const std::vector<double> nodeRow = record().at(20, "node", "rope", 0);
  ASSERT_EQ(first.size(), 3u);
  ASSERT_EQ(nodeRow.size(), 7u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(first[c], nodeRow[c], 1e-7);
}

TEST(Export, RefusesWhatItCannotWrite) {
  EXPECT_NE(run("export " + kScene + " --out " + (tempDir() / "x.txt").string() + " --seconds 0.1 2> /dev/null"), 0);
  EXPECT_NE(run("export " + kScene + " --out /no/such/folder/x.gltf --seconds 0.1 2> /dev/null"), 0);
  EXPECT_NE(run("export " + kScene + " --out x.gltf --fps nan 2> /dev/null"), 0);
}

}  // namespace
