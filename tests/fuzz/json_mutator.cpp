// Structure-aware mutation for the scene fuzzer: an input that parses as JSON is mutated as a
// JSON tree (a number, string, key or array length changed; a subtree removed, copied or moved
// to another type) and written back as JSON, so that mutations get past the strict reader and
// reach the checks on values, the builder and the solver. Inputs that do not parse are mutated
// byte by byte, as are one in kByteMutationOneIn of those that do (to keep exercising the
// reader's syntax errors).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t maxSize);

namespace {

using Json = nlohmann::json;

constexpr unsigned kByteMutationOneIn = 8;

// Words of the scene format (docs/scene-format.md): keys, and the values its enums take.
const std::vector<std::string> kWords{
    "format", "name", "description", "time_step", "duration", "gravity", "divergence_speed", "solver",
    "iterations", "substeps", "row_solver", "warm_start", "baumgarte", "contact_slop", "friction_model",
    "rigid_bodies", "shape", "type", "half_extents", "radius", "half_height", "normal", "offset", "points",
    "vertices", "triangles", "file", "mass", "position", "orientation", "euler_degrees", "linear_velocity",
    "angular_velocity", "friction", "restitution", "linear_damping", "angular_damping", "kinematic", "can_sleep", "joints", "body_a", "body_b",
    "pivot", "axis", "deformables", "mesh", "start", "end", "path", "nodes", "corner", "side_u", "side_v",
    "columns", "rows", "min", "max", "cells", "base_centre", "height", "rings", "sectors", "layers",
    "density", "initial_velocity", "paradigm", "spring_stiffness", "spring_damping", "stiffness", "damping",
    "youngs_modulus", "poisson_ratio", "implicit", "collision", "thickness", "self_collision",
    "inextensibility", "enabled", "mode", "shear_edges", "max_force", "bending", "damping_ratio",
    "frequency", "fixed", "region", "anchors", "deformable", "body", "node", "nearest", "face",
    "barycentric", "local_point", "box", "sphere", "cylinder", "capsule", "plane", "convex_hull",
    "triangle_mesh", "hinge", "rope", "cloth_grid", "tet_box", "tet_cylinder", "obj", "tetgen",
    "mass_spring", "shape_matching", "position_based", "corotational_fem", "resist_both",
    "resist_compression", "resist_stretch", "auto", "direct", "iterative", "coulomb", "pressure",
    "compound", "hulls", "inertia", "scale", "max_hull_vertices", "hull_per_group", "hull_per_piece",
    "meshes/dish.obj", "meshes/rope_strip.obj", "meshes/teapot.obj", "meshes", ""};

const std::vector<double> kInterestingNumbers{0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-300, -1e-300, 1e-12, 1e12,
                                              1e300, -1e300, 1.7976931348623157e308, 4.9e-324, 2147483647.0,
                                              2147483648.0, -2147483648.0, 1e6, 0.02, 9.81};

struct Node {
  Json* value;
  Json* parent;  // null for the root
};

void collect(Json& value, Json* parent, std::vector<Node>& nodes) {
  nodes.push_back({&value, parent});
  if (value.is_object() || value.is_array())
    for (Json& child : value) collect(child, &value, nodes);
}

Json randomScalar(std::mt19937_64& random) {
  switch (random() % 6) {
    case 0: return kInterestingNumbers[random() % kInterestingNumbers.size()];
    case 1: return static_cast<int64_t>(random() % 2000) - 1000;
    case 2: return kWords[random() % kWords.size()];
    case 3: return (random() & 1) != 0;
    case 4: return nullptr;
    default: return std::ldexp(static_cast<double>(random() % 2000) - 1000, static_cast<int>(random() % 40) - 30);
  }
}

void mutateNumber(Json& value, std::mt19937_64& random) {
  const double x = value.get<double>();
  switch (random() % 6) {
    case 0: value = kInterestingNumbers[random() % kInterestingNumbers.size()]; break;
    case 1: value = -x; break;
    case 2: value = x * std::ldexp(1.0, static_cast<int>(random() % 21) - 10); break;
    case 3: value = static_cast<int64_t>(std::isfinite(x) && std::abs(x) < 1e15 ? x : 0) + static_cast<int64_t>(random() % 5) - 2; break;
    case 4: value = x + (static_cast<double>(random() % 1000) - 500) * 1e-3; break;
    default: value = std::nextafter(x, (random() & 1) ? 1e308 : -1e308); break;
  }
}

void mutateString(Json& value, std::mt19937_64& random) {
  if (random() % 2 == 0) {
    value = kWords[random() % kWords.size()];
    return;
  }
  std::string text = value.get<std::string>();
  const size_t size = text.size();
  text.resize(size + 8);
  const size_t mutated = LLVMFuzzerMutate(reinterpret_cast<uint8_t*>(text.data()), size, text.size());
  text.resize(mutated);
  value = text;  // may be invalid UTF-8: dump() below replaces such bytes
}

void mutateArray(Json& value, std::mt19937_64& random) {
  switch (random() % 4) {
    case 0:
      if (!value.empty()) value.erase(value.begin() + static_cast<long>(random() % value.size()));
      break;
    case 1:
      if (!value.empty()) value.push_back(value[random() % value.size()]);
      else value.push_back(randomScalar(random));
      break;
    case 2: value.push_back(randomScalar(random)); break;
    default: {  // swap two elements
      if (value.size() >= 2) std::swap(value[random() % value.size()], value[random() % value.size()]);
      break;
    }
  }
}

void mutateObject(Json& value, std::mt19937_64& random, const std::vector<Node>& nodes) {
  switch (random() % 4) {
    case 0:  // remove a key
      if (!value.empty()) {
        auto it = value.begin();
        std::advance(it, static_cast<long>(random() % value.size()));
        value.erase(it);
      }
      break;
    case 1:  // rename a key to a word of the format
      if (!value.empty()) {
        auto it = value.begin();
        std::advance(it, static_cast<long>(random() % value.size()));
        Json moved = *it;
        const std::string key = it.key();
        value.erase(key);
        value[kWords[random() % kWords.size()]] = std::move(moved);
      }
      break;
    case 2:  // add a key with a subtree copied from elsewhere in the scene
      value[kWords[random() % kWords.size()]] = *nodes[random() % nodes.size()].value;
      break;
    default:  // add a key with a scalar
      value[kWords[random() % kWords.size()]] = randomScalar(random);
      break;
  }
}

void mutateTree(Json& root, std::mt19937_64& random) {
  std::vector<Node> nodes;
  collect(root, nullptr, nodes);
  const Node& chosen = nodes[random() % nodes.size()];
  Json& value = *chosen.value;
  if (random() % 10 == 0) {  // replace with another kind of value, or a copy of another subtree
    value = (random() & 1) ? randomScalar(random) : Json(*nodes[random() % nodes.size()].value);
    return;
  }
  if (value.is_number()) mutateNumber(value, random);
  else if (value.is_string()) mutateString(value, random);
  else if (value.is_array()) mutateArray(value, random);
  else if (value.is_object()) mutateObject(value, random, nodes);
  else value = randomScalar(random);
}

}  // namespace

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t maxSize, unsigned int seed) {
  std::mt19937_64 random(seed);
  if (random() % kByteMutationOneIn == 0) return LLVMFuzzerMutate(data, size, maxSize);
  Json tree = Json::parse(data, data + size, nullptr, false);
  if (tree.is_discarded()) return LLVMFuzzerMutate(data, size, maxSize);
  const int mutations = 1 + static_cast<int>(random() % 3);
  for (int m = 0; m < mutations; ++m) mutateTree(tree, random);
  // Invalid UTF-8 from a byte-mutated string is replaced, not thrown; compact or indented.
  const std::string text = tree.dump(random() % 2 ? -1 : 1, ' ', false, Json::error_handler_t::replace);
  if (text.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
  std::memcpy(data, text.data(), text.size());
  return text.size();
}
