// glTF 2.0 through tinygltf (Debian's shared library): buffers, accessors, meshes, materials,
// nodes and one animation for the whole run.
#include "export/scene_export.h"

#include <tandem/deformable_surface.h>
#include <tandem/shape_surface.h>

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>

namespace tandem::exporting {
namespace {

// Appends data to the one buffer as a view and an accessor; returns the accessor's index.
class ModelBuilder {
 public:
  explicit ModelBuilder(tinygltf::Model& model) : m_model(model) {
    if (m_model.buffers.empty()) m_model.buffers.emplace_back();
  }

  int floats(const std::vector<float>& values, int type, int components, bool withBounds, int target) {
    const int view = addView(values.data(), values.size() * sizeof(float), target);
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = type;
    accessor.count = values.size() / static_cast<size_t>(components);
    if (withBounds) {
      accessor.minValues.assign(static_cast<size_t>(components), INFINITY);
      accessor.maxValues.assign(static_cast<size_t>(components), -INFINITY);
      for (size_t i = 0; i < values.size(); ++i) {
        const size_t c = i % static_cast<size_t>(components);
        accessor.minValues[c] = std::min(accessor.minValues[c], double(values[i]));
        accessor.maxValues[c] = std::max(accessor.maxValues[c], double(values[i]));
      }
    }
    m_model.accessors.push_back(accessor);
    return static_cast<int>(m_model.accessors.size()) - 1;
  }

  int indices(const std::vector<uint32_t>& values) {
    const int view = addView(values.data(), values.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.type = TINYGLTF_TYPE_SCALAR;
    accessor.count = values.size();
    m_model.accessors.push_back(accessor);
    return static_cast<int>(m_model.accessors.size()) - 1;
  }

 private:
  int addView(const void* data, size_t bytes, int target) {
    std::vector<unsigned char>& buffer = m_model.buffers[0].data;
    while (buffer.size() % 4) buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    buffer.resize(buffer.size() + bytes);
    std::memcpy(buffer.data() + view.byteOffset, data, bytes);
    m_model.bufferViews.push_back(view);
    return static_cast<int>(m_model.bufferViews.size()) - 1;
  }

  tinygltf::Model& m_model;
};

std::vector<float> flatten(const std::vector<Vec3>& points) {
  std::vector<float> out;
  out.reserve(3 * points.size());
  for (const Vec3& p : points) out.insert(out.end(), {float(p.x()), float(p.y()), float(p.z())});
  return out;
}

std::vector<uint32_t> flatten(const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<uint32_t> out;
  out.reserve(3 * triangles.size());
  for (const auto& t : triangles) out.insert(out.end(), {uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2])});
  return out;
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

int addMaterial(tinygltf::Model& model, const std::string& name, const std::array<double, 3>& colour, bool doubleSided) {
  tinygltf::Material material;
  material.name = name;
  material.pbrMetallicRoughness.baseColorFactor = {srgbToLinear(colour[0]), srgbToLinear(colour[1]),
                                                   srgbToLinear(colour[2]), 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.6;
  material.doubleSided = doubleSided;
  model.materials.push_back(material);
  return static_cast<int>(model.materials.size()) - 1;
}

// A mesh with one triangle primitive; returns the mesh's index.
int addMesh(tinygltf::Model& model, ModelBuilder& builder, const std::string& name, const ShapeSurface& surface,
            int material) {
  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] =
      builder.floats(flatten(surface.positions), TINYGLTF_TYPE_VEC3, 3, true, TINYGLTF_TARGET_ARRAY_BUFFER);
  primitive.attributes["NORMAL"] =
      builder.floats(flatten(surface.normals), TINYGLTF_TYPE_VEC3, 3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
  primitive.indices = builder.indices(flatten(surface.triangles));
  primitive.material = material;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  return static_cast<int>(model.meshes.size()) - 1;
}

void addChannel(tinygltf::Animation& animation, int input, int output, int node, const std::string& path) {
  tinygltf::AnimationSampler sampler;
  sampler.input = input;
  sampler.output = output;
  sampler.interpolation = "LINEAR";
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
  channel.target_node = node;
  channel.target_path = path;
  animation.channels.push_back(channel);
}

std::array<double, 3> defaultColour(bool deformable, bool isStatic) {
  if (deformable) return {0.86, 0.24, 0.14};
  return isStatic ? std::array<double, 3>{0.62, 0.63, 0.66} : std::array<double, 3>{0.25, 0.45, 0.80};
}

}  // namespace

ShapeSurface rigidExportSurface(const RigidShape& shape, double planeHalfSize) {
  if (shape.type != ShapeType::Plane) return shapeSurface(shape, 32);
  const Vec3 n = shape.planeNormal.normalized();
  const Vec3 u = (std::abs(n.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitX()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  const Vec3 centre = shape.planeOffset * n;
  ShapeSurface square;
  for (const auto& [a, b] : std::array<std::pair<double, double>, 4>{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}}) {
    square.positions.push_back(centre + planeHalfSize * (a * u + b * v));
    square.normals.push_back(n);
  }
  // u × v = −n: (0, 2, 1) is counter-clockwise seen from the side n points to.
  square.triangles = {{0, 2, 1}, {0, 3, 2}};
  return square;
}

Status writeGltf(const World& world, const std::vector<Frame>& frames, const ExportLooks& looks,
                 const std::string& path) {
  const std::filesystem::path file(path);
  const bool binary = file.extension() == ".glb";
  if (!binary && file.extension() != ".gltf") return Error{"glTF '" + path + "': the file must end in .gltf or .glb"};
  if (frames.empty()) return Error{"glTF '" + path + "': no frames to write"};
  const std::filesystem::path parent = file.parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    return Error{"glTF '" + path + "': folder '" + parent.string() + "' does not exist"};

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Tandem";
  ModelBuilder builder(model);
  tinygltf::Scene scene;
  scene.name = "tandem";
  tinygltf::Animation animation;
  animation.name = "run";

  std::vector<float> times;
  for (const Frame& frame : frames) times.push_back(float(frame.time - frames.front().time));
  const bool animated = frames.size() > 1;
  const int timeAccessor = animated ? builder.floats(times, TINYGLTF_TYPE_SCALAR, 1, true, 0) : -1;

  for (int b = 0; b < world.rigidBodyCount(); ++b) {
    const RigidBodyId id{b};
    const std::string& name = world.rigidName(id);
    const bool isStatic = world.rigidMass(id) == 0.0;
    const auto& custom = static_cast<size_t>(b) < looks.rigidColours.size() ? looks.rigidColours[b] : std::nullopt;
    const int material = addMaterial(model, name, custom ? *custom : defaultColour(false, isStatic), false);
    tinygltf::Node node;
    node.name = name;
    node.mesh = addMesh(model, builder, name, rigidExportSurface(world.rigidShape(id)), material);
    const Vec3& p = frames.front().rigidPositions[b];
    const Quat& q = frames.front().rigidOrientations[b];
    node.translation = {p.x(), p.y(), p.z()};
    node.rotation = {q.x(), q.y(), q.z(), q.w()};
    model.nodes.push_back(node);
    const int nodeIndex = static_cast<int>(model.nodes.size()) - 1;
    scene.nodes.push_back(nodeIndex);
    if (!animated || world.rigidShape(id).type == ShapeType::Plane) continue;
    std::vector<float> translations, rotations;
    Quat previous = frames.front().rigidOrientations[b];
    for (const Frame& frame : frames) {
      const Vec3& x = frame.rigidPositions[b];
      Quat r = frame.rigidOrientations[b];
      if (r.dot(previous) < 0) r.coeffs() = -r.coeffs();  // the short way round between frames
      previous = r;
      translations.insert(translations.end(), {float(x.x()), float(x.y()), float(x.z())});
      rotations.insert(rotations.end(), {float(r.x()), float(r.y()), float(r.z()), float(r.w())});
    }
    addChannel(animation, timeAccessor, builder.floats(translations, TINYGLTF_TYPE_VEC3, 3, false, 0), nodeIndex,
               "translation");
    addChannel(animation, timeAccessor, builder.floats(rotations, TINYGLTF_TYPE_VEC4, 4, false, 0), nodeIndex, "rotation");
  }

  for (int d = 0; d < world.deformableCount(); ++d) {
    const DeformableId id{d};
    const std::string& name = world.deformableName(id);
    const auto& custom = static_cast<size_t>(d) < looks.deformableColours.size() ? looks.deformableColours[d] : std::nullopt;
    const int material = addMaterial(model, name, custom ? *custom : defaultColour(true, false), true);
    const DeformableSurface builderOfSurface(world.restMesh(id));
    const ShapeSurface first = builderOfSurface.build(frames.front().nodePositions[d]);
    tinygltf::Node node;
    node.name = name;
    node.mesh = addMesh(model, builder, name, first, material);
    tinygltf::Mesh& mesh = model.meshes[node.mesh];
    if (animated) {
      ShapeSurface surface;
      for (size_t k = 1; k < frames.size(); ++k) {
        builderOfSurface.build(frames[k].nodePositions[d], surface);
        std::vector<Vec3> positionOffsets(surface.positions.size()), normalOffsets(surface.normals.size());
        for (size_t i = 0; i < surface.positions.size(); ++i) {
          positionOffsets[i] = surface.positions[i] - first.positions[i];
          normalOffsets[i] = surface.normals[i] - first.normals[i];
        }
        std::map<std::string, int> target;
        target["POSITION"] =
            builder.floats(flatten(positionOffsets), TINYGLTF_TYPE_VEC3, 3, true, TINYGLTF_TARGET_ARRAY_BUFFER);
        target["NORMAL"] =
            builder.floats(flatten(normalOffsets), TINYGLTF_TYPE_VEC3, 3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
        mesh.primitives[0].targets.push_back(target);
      }
      mesh.weights.assign(frames.size() - 1, 0.0);
      // Target k - 1 holds frame k: at frame k's time only its weight is 1 (none at frame 0).
      const size_t targets = frames.size() - 1;
      std::vector<float> weights(frames.size() * targets, 0.0f);
      for (size_t k = 1; k < frames.size(); ++k) weights[k * targets + (k - 1)] = 1.0f;
      model.nodes.push_back(node);
      const int nodeIndex = static_cast<int>(model.nodes.size()) - 1;
      addChannel(animation, timeAccessor, builder.floats(weights, TINYGLTF_TYPE_SCALAR, 1, false, 0), nodeIndex,
                 "weights");
      scene.nodes.push_back(nodeIndex);
    } else {
      model.nodes.push_back(node);
      scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
    }
  }

  if (!animation.channels.empty()) model.animations.push_back(animation);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  if (!binary) model.buffers[0].uri = file.stem().string() + ".bin";
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path, false, binary, !binary, binary))
    return Error{"glTF '" + path + "': cannot write the file"};
  return {};
}

}  // namespace tandem::exporting
