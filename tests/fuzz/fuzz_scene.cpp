// libFuzzer harness for scene files: whatever the input, Tandem reads it or refuses it with a
// message; what it reads it writes back and reads again to the same scene; what it builds it
// steps a few times without a crash, a sanitizer report, a hang or a silent non-finite state.
//
// Any of these stops the fuzzer with the input saved (a finding):
//   - a crash, an uncaught exception, an AddressSanitizer or UndefinedBehaviorSanitizer report;
//   - a scene the writer wrote that the reader refuses, or that reads back to another scene;
//   - a step that reports success with a non-finite node or body state;
//   - an input slower than libFuzzer's -timeout, or past its -rss_limit_mb.
//
// The harness keeps each input cheap so that the fuzzer runs thousands of them a second: scenes
// whose meshes would have more than kNodeBudget nodes are read and written but not built, and
// scenes that name mesh files outside the scenes folder (absolute paths, "..") are not built
// (the library's own limits on sizes and files are tested in tests/, not here).
#include <tandem/scene_file.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace {

using tandem::Scene;
using tandem::SceneMesh;

constexpr double kNodeBudget = 400;    // nodes a built scene may have (estimated from its meshes)
constexpr int kSteps = 3;              // steps per built scene ...
constexpr double kStepSeconds = 0.1;   // ... unless they take longer than this, wall clock

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "tandem fuzz finding: %s\n%s\n", what, detail.c_str());
  std::abort();
}

// Nodes the mesh generators would make, as a double so that no product overflows.
double estimatedNodes(const SceneMesh& mesh) {
  switch (mesh.kind) {
    case SceneMesh::Kind::Rope: return mesh.nodes;
    case SceneMesh::Kind::ClothGrid: return double(mesh.columns + 1) * (mesh.rows + 1);
    case SceneMesh::Kind::TetBox: return double(mesh.cells[0] + 1) * (mesh.cells[1] + 1) * (mesh.cells[2] + 1);
    case SceneMesh::Kind::TetCylinder: return (double(mesh.rings) * mesh.sectors + 1) * (mesh.layers + 1);
    case SceneMesh::Kind::Obj:
    case SceneMesh::Kind::TetGen: return 0;  // files under scenes/: small
  }
  return 0;
}

bool staysInSceneFolder(const std::string& file) {
  return file.empty() || (file.front() != '/' && file.find("..") == std::string::npos);
}

bool cheapToBuild(const Scene& scene) {
  double nodes = 0;
  for (const tandem::SceneDeformable& deformable : scene.deformables) {
    nodes += estimatedNodes(deformable.mesh);
    if (!staysInSceneFolder(deformable.mesh.file)) return false;
  }
  for (const tandem::SceneRigidBody& body : scene.rigidBodies)
    if (!staysInSceneFolder(body.shapeFile)) return false;
  return nodes <= kNodeBudget;
}

bool finite(const tandem::Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// After a step that reported success, every state the API shows must be a number.
void checkFiniteState(const tandem::World& world, int step) {
  for (int b = 0; b < world.rigidBodyCount(); ++b) {
    const tandem::RigidBodyId id{b};
    if (!finite(world.rigidPosition(id)) || !finite(world.rigidLinearVelocity(id)) ||
        !finite(world.rigidAngularVelocity(id)))
      finding("a step reported success with a non-finite rigid body state",
              "body '" + world.rigidName(id) + "' after step " + std::to_string(step));
  }
  for (int d = 0; d < world.deformableCount(); ++d) {
    const tandem::DeformableId id{d};
    for (const tandem::Vec3& x : world.nodePositions(id))
      if (!finite(x)) finding("a step reported success with a non-finite node position",
                              "deformable '" + world.deformableName(id) + "' after step " + std::to_string(step));
    for (const tandem::Vec3& v : world.nodeVelocities(id))
      if (!finite(v)) finding("a step reported success with a non-finite node velocity",
                              "deformable '" + world.deformableName(id) + "' after step " + std::to_string(step));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const tandem::Result<Scene> read = tandem::parseScene(text, "fuzz.json", TANDEM_SCENE_DIR);
  if (!read.ok()) {
    if (read.message().empty()) finding("a refused scene without a message", std::string(text));
    return 0;
  }

  // Round trip: what was read is written, read again and written again to the same text (the
  // writer writes every field, numbers to the last bit, so equal text is an equal scene).
  const std::string written = tandem::sceneToJson(*read);
  const tandem::Result<Scene> reread = tandem::parseScene(written, "fuzz-written.json", TANDEM_SCENE_DIR);
  if (!reread.ok()) finding("the reader refuses what the writer wrote", reread.message() + "\n" + written);
  const std::string rewritten = tandem::sceneToJson(*reread);
  if (rewritten != written) finding("a scene written, read and written again changed", written + "\n---\n" + rewritten);

  if (!cheapToBuild(*reread)) return 0;
  tandem::World world;
  if (!tandem::buildScene(*reread, world).ok()) return 0;
  const auto start = std::chrono::steady_clock::now();
  for (int step = 1; step <= kSteps; ++step) {
    if (!world.step(reread->timeStep).ok()) break;  // refused or diverged, with a message: fine
    checkFiniteState(world, step);
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > kStepSeconds) break;
  }
  return 0;
}
