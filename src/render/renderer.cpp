// The renderer: one lit-mesh program for shapes, surfaces and ground, one line program for
// grid-free overlays (wireframe, contacts, the grab), buffers refreshed each frame for what
// moves (deformables) and made once for what does not (rigid shapes, in their own frames).
#include "render/renderer.h"

#include "render/gl.h"

#include <tandem/deformable_surface.h>
#include <tandem/shape_surface.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace tandem::render {
namespace {

constexpr const char* kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 viewProjection;
uniform mat3 normalMatrix;
out vec3 worldPosition;
out vec3 worldNormal;
void main() {
  vec4 world = model * vec4(position, 1.0);
  worldPosition = world.xyz;
  worldNormal = normalMatrix * normal;
  gl_Position = viewProjection * world;
}
)";

// Two-sided Blinn-Phong with a key and a fill light and a sky/ground ambient; a ground plane
// gets anti-aliased grid lines from its world position (spacing 0: none). The key light casts
// shadows: a 3×3 percentage-closer lookup in its shadow map (shadowStrength 0: none).
constexpr const char* kMeshFragment = R"(#version 330 core
in vec3 worldPosition;
in vec3 worldNormal;
uniform vec3 colour;
uniform vec3 eye;
uniform float gridSpacing;
uniform vec3 gridU;
uniform vec3 gridV;
uniform vec3 keyDirection;
uniform mat4 lightViewProjection;
uniform sampler2DShadow shadowMap;
uniform float shadowStrength;
uniform float shadowTexel;
out vec4 fragmentColour;
float keyLight(vec3 n) {
  if (shadowStrength <= 0.0) return 1.0;
  vec4 light = lightViewProjection * vec4(worldPosition, 1.0);
  vec3 p = light.xyz / light.w * 0.5 + 0.5;
  if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;
  float lit = 0.0;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) lit += texture(shadowMap, vec3(p.xy + vec2(i, j) * shadowTexel, p.z));
  return 1.0 - shadowStrength * (1.0 - lit / 9.0);
}
void main() {
  vec3 n = normalize(worldNormal);
  vec3 toEye = normalize(eye - worldPosition);
  if (dot(n, toEye) < 0.0) n = -n;
  vec3 key = keyDirection;
  vec3 fill = normalize(vec3(-0.6, 0.35, -0.5));
  vec3 base = colour;
  if (gridSpacing > 0.0) {
    vec2 g = vec2(dot(worldPosition, gridU), dot(worldPosition, gridV)) / gridSpacing;
    vec2 d = abs(fract(g - 0.5) - 0.5) / max(fwidth(g), vec2(1e-6));
    float line = 1.0 - min(min(d.x, d.y), 1.0);
    float fade = clamp(1.0 - length(worldPosition - eye) / (60.0 * gridSpacing), 0.0, 1.0);
    base = mix(base, base * 0.55, line * fade);
  }
  float lit = keyLight(n);
  float diffuse = 0.75 * lit * max(dot(n, key), 0.0) + 0.3 * max(dot(n, fill), 0.0);
  float ambient = 0.22 + 0.12 * n.y;
  float specular = 0.2 * lit * pow(max(dot(n, normalize(key + toEye)), 0.0), 48.0);
  fragmentColour = vec4(base * (ambient + diffuse) + vec3(specular), 1.0);
}
)";

// Depth only, from the key light.
constexpr const char* kShadowVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 model;
uniform mat4 lightViewProjection;
void main() { gl_Position = lightViewProjection * model * vec4(position, 1.0); }
)";
constexpr const char* kShadowFragment = R"(#version 330 core
void main() {}
)";

constexpr const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 colour;
uniform mat4 viewProjection;
out vec3 lineColour;
void main() {
  lineColour = colour;
  gl_Position = viewProjection * vec4(position, 1.0);
}
)";

constexpr const char* kLineFragment = R"(#version 330 core
in vec3 lineColour;
out vec4 fragmentColour;
void main() { fragmentColour = vec4(lineColour, 1.0); }
)";

Result<GLuint> compile(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  char log[2048] = {};
  glGetShaderInfoLog(shader, sizeof log, nullptr, log);
  glDeleteShader(shader);
  return Error{std::string("renderer: shader does not compile: ") + log};
}

Result<GLuint> link(const char* vertexSource, const char* fragmentSource) {
  Result<GLuint> vertex = compile(GL_VERTEX_SHADER, vertexSource);
  if (!vertex) return vertex;
  Result<GLuint> fragment = compile(GL_FRAGMENT_SHADER, fragmentSource);
  if (!fragment) {
    glDeleteShader(*vertex);
    return fragment;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, *vertex);
  glAttachShader(program, *fragment);
  glLinkProgram(program);
  glDeleteShader(*vertex);
  glDeleteShader(*fragment);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok) return program;
  char log[2048] = {};
  glGetProgramInfoLog(program, sizeof log, nullptr, log);
  glDeleteProgram(program);
  return Error{std::string("renderer: shaders do not link: ") + log};
}

// Interleaved position and normal (or colour), as floats.
struct Vertex {
  float a[3];
  float b[3];
};
Vertex vertex(const Vec3& p, const Vec3& n) {
  return {{float(p.x()), float(p.y()), float(p.z())}, {float(n.x()), float(n.y()), float(n.z())}};
}
Vertex vertex(const Vec3& p, const std::array<float, 3>& c) {
  return {{float(p.x()), float(p.y()), float(p.z())}, {c[0], c[1], c[2]}};
}

// A vertex array with one interleaved buffer and an index buffer.
struct GpuMesh {
  GLuint array = 0, vertices = 0, indices = 0;
  GLsizei indexCount = 0;

  void create() {
    glGenVertexArrays(1, &array);
    glGenBuffers(1, &vertices);
    glGenBuffers(1, &indices);
    glBindVertexArray(array);
    glBindBuffer(GL_ARRAY_BUFFER, vertices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), nullptr);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(3 * sizeof(float)));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glBindVertexArray(0);
  }
  void upload(const std::vector<Vertex>& data, const std::vector<uint32_t>& index, GLenum usage) {
    if (!array) create();
    glBindVertexArray(array);  // the element buffer binding belongs to the vertex array
    glBindBuffer(GL_ARRAY_BUFFER, vertices);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(Vertex)), data.data(), usage);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(index.size() * sizeof(uint32_t)), index.data(),
                 usage);
    indexCount = static_cast<GLsizei>(index.size());
    glBindVertexArray(0);
  }
  void draw(GLenum mode) const {
    if (!indexCount) return;
    glBindVertexArray(array);
    glDrawElements(mode, indexCount, GL_UNSIGNED_INT, nullptr);
  }
  void destroy() {
    if (!array) return;
    glDeleteBuffers(1, &vertices);
    glDeleteBuffers(1, &indices);
    glDeleteVertexArrays(1, &array);
    array = 0;
  }
};

Eigen::Matrix4f toFloat(const Mat4& m) { return m.cast<float>(); }

std::array<float, 3> brighter(std::array<float, 3> c) {
  for (float& x : c) x = std::min(1.0f, 0.35f + 0.8f * x);
  return c;
}

// The key light: from above, in front and to the right of the default camera.
const Vec3 kKeyDirection = Vec3(0.4, 1.0, 0.35).normalized();
constexpr int kShadowMapSize = 2048;

// An orthographic view from the key light over the box [low, high] (grown a little), deep
// enough to hold the ground far below: what casts shadows is inside, what receives them may be
// anywhere in its footprint.
Eigen::Matrix4f lightViewProjection(const Vec3& low, const Vec3& high) {
  const Vec3 centre = (low + high) / 2;
  const double radius = std::max(0.5 * (high - low).norm(), 0.05) * 1.1;
  const Vec3 forward = -kKeyDirection;
  const Vec3 right = forward.cross(Vec3::UnitY()).normalized();
  const Vec3 up = right.cross(forward);
  const Vec3 eye = centre - 2.0 * radius * forward;
  Mat4 view = Mat4::Identity();
  view.block<1, 3>(0, 0) = right.transpose();
  view.block<1, 3>(1, 0) = up.transpose();
  view.block<1, 3>(2, 0) = -forward.transpose();
  view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * eye;
  const double nearPlane = 0.0, farPlane = 2.0 * radius + std::max(50.0, 20.0 * radius);
  Mat4 projection = Mat4::Identity();
  projection(0, 0) = 1.0 / radius;
  projection(1, 1) = 1.0 / radius;
  projection(2, 2) = -2.0 / (farPlane - nearPlane);
  projection(2, 3) = -(farPlane + nearPlane) / (farPlane - nearPlane);
  return toFloat(projection * view);
}

}  // namespace

std::array<float, 3> deformableColour(int index) {
  static constexpr std::array<std::array<float, 3>, 4> kWarm{
      {{0.86f, 0.24f, 0.14f}, {0.85f, 0.55f, 0.10f}, {0.72f, 0.20f, 0.55f}, {0.40f, 0.70f, 0.20f}}};
  return kWarm[static_cast<size_t>(index) % kWarm.size()];
}

std::array<float, 3> rigidColour(int index, bool isStatic) {
  static constexpr std::array<std::array<float, 3>, 4> kCool{
      {{0.25f, 0.45f, 0.80f}, {0.20f, 0.62f, 0.62f}, {0.45f, 0.40f, 0.78f}, {0.35f, 0.55f, 0.40f}}};
  if (isStatic) return {0.62f, 0.63f, 0.66f};
  return kCool[static_cast<size_t>(index) % kCool.size()];
}

struct Renderer::Impl {
  GLuint meshProgram = 0, lineProgram = 0, shadowProgram = 0;
  GLuint shadowFramebuffer = 0, shadowTexture = 0;
  std::vector<GpuMesh> rigidMeshes;       // by rigid body, in the body's frame
  std::vector<GpuMesh> deformableMeshes;  // by deformable, refreshed every frame
  std::vector<std::unique_ptr<DeformableSurface>> deformableSurfaces;  // by deformable: rims found once
  ShapeSurface surface;                   // the deformable being uploaded
  std::vector<Vertex> vertexData;
  std::vector<uint32_t> indexData;
  GpuMesh ground;                         // a unit square, scaled onto each plane
  GpuMesh lines;
  std::vector<Vertex> lineData;
  std::vector<uint32_t> lineIndex;

  ~Impl() {
    for (GpuMesh& mesh : rigidMeshes) mesh.destroy();
    for (GpuMesh& mesh : deformableMeshes) mesh.destroy();
    ground.destroy();
    lines.destroy();
    if (meshProgram) glDeleteProgram(meshProgram);
    if (lineProgram) glDeleteProgram(lineProgram);
    if (shadowProgram) glDeleteProgram(shadowProgram);
    if (shadowFramebuffer) glDeleteFramebuffers(1, &shadowFramebuffer);
    if (shadowTexture) glDeleteTextures(1, &shadowTexture);
  }

  void setMatrix(GLuint program, const char* name, const Eigen::Matrix4f& m) {
    glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, m.data());
  }
  void setVector(const char* name, const Vec3& v) {
    glUniform3f(glGetUniformLocation(meshProgram, name), float(v.x()), float(v.y()), float(v.z()));
  }
  void setColour(const std::array<float, 3>& c) {
    glUniform3f(glGetUniformLocation(meshProgram, "colour"), c[0], c[1], c[2]);
  }
  void setModel(GLuint program, const Eigen::Matrix4f& model) {
    setMatrix(program, "model", model);
    if (program != meshProgram) return;
    const Eigen::Matrix3f normal = model.block<3, 3>(0, 0).inverse().transpose();
    glUniformMatrix3fv(glGetUniformLocation(meshProgram, "normalMatrix"), 1, GL_FALSE, normal.data());
  }

  // A depth texture the key light draws into; lookups outside it read "lit".
  void createShadowMap() {
    glGenTextures(1, &shadowTexture);
    glBindTexture(GL_TEXTURE_2D, shadowTexture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize, 0, GL_DEPTH_COMPONENT,
                 GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float border[] = {1.0f, 1.0f, 1.0f, 1.0f};
    glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &shadowFramebuffer);
    GLint previous = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowTexture, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
  }

  void line(const Vec3& a, const Vec3& b, const std::array<float, 3>& colour) {
    const auto first = static_cast<uint32_t>(lineData.size());
    lineData.push_back(vertex(a, colour));
    lineData.push_back(vertex(b, colour));
    lineIndex.insert(lineIndex.end(), {first, first + 1});
  }

  void drawLines(const Eigen::Matrix4f& viewProjection, bool depthTested) {
    if (lineIndex.empty()) return;
    glUseProgram(lineProgram);
    setMatrix(lineProgram, "viewProjection", viewProjection);
    lines.upload(lineData, lineIndex, GL_STREAM_DRAW);
    if (!depthTested) glDisable(GL_DEPTH_TEST);
    lines.draw(GL_LINES);
    glEnable(GL_DEPTH_TEST);
    lineData.clear();
    lineIndex.clear();
  }

  void upload(GpuMesh& mesh, const ShapeSurface& s, GLenum usage) {
    vertexData.clear();
    indexData.clear();
    for (size_t i = 0; i < s.positions.size(); ++i) vertexData.push_back(vertex(s.positions[i], s.normals[i]));
    for (const auto& t : s.triangles) indexData.insert(indexData.end(), {uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2])});
    mesh.upload(vertexData, indexData, usage);
  }

  void refreshMeshes(const World& world) {
    while (static_cast<int>(rigidMeshes.size()) < world.rigidBodyCount()) {
      const RigidShape& shape = world.rigidShape(RigidBodyId{static_cast<int32_t>(rigidMeshes.size())});
      upload(rigidMeshes.emplace_back(), shapeSurface(shape, 40), GL_STATIC_DRAW);
    }
    deformableMeshes.resize(std::max(deformableMeshes.size(), static_cast<size_t>(world.deformableCount())));
    deformableSurfaces.resize(world.deformableCount());
    for (int d = 0; d < world.deformableCount(); ++d) {
      if (!deformableSurfaces[d]) deformableSurfaces[d] = std::make_unique<DeformableSurface>(world.restMesh(DeformableId{d}));
      deformableSurfaces[d]->build(world.nodePositions(DeformableId{d}), surface);
      upload(deformableMeshes[d], surface, GL_STREAM_DRAW);
    }
  }

  // Every body but planes, with `program` (the mesh or the shadow program); `colourOf` sets
  // each one's colour (mesh program only).
  template <class SetColour>
  void drawBodies(const World& world, GLuint program, SetColour setColourOf) {
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const RigidBodyId id{b};
      if (world.rigidShape(id).type == ShapeType::Plane) continue;
      Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
      model.block<3, 3>(0, 0) = world.rigidOrientation(id).normalized().toRotationMatrix().cast<float>();
      model.block<3, 1>(0, 3) = world.rigidPosition(id).cast<float>();
      setModel(program, model);
      setColourOf(std::optional<RigidBodyId>(id), std::optional<DeformableId>());
      rigidMeshes[b].draw(GL_TRIANGLES);
    }
    setModel(program, Eigen::Matrix4f::Identity());
    for (int d = 0; d < world.deformableCount(); ++d) {
      setColourOf(std::optional<RigidBodyId>(), std::optional<DeformableId>(DeformableId{d}));
      deformableMeshes[d].draw(GL_TRIANGLES);
    }
  }

  // The key light's depth over everything but planes, into the shadow map; the caller's
  // framebuffer and viewport are put back.
  void drawShadowMap(const World& world, const Eigen::Matrix4f& light) {
    GLint previous = 0, viewport[4] = {};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
    glGetIntegerv(GL_VIEWPORT, viewport);
    glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer);
    glViewport(0, 0, kShadowMapSize, kShadowMapSize);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 4.0f);
    glUseProgram(shadowProgram);
    setMatrix(shadowProgram, "lightViewProjection", light);
    drawBodies(world, shadowProgram, [](auto, auto) {});
    glDisable(GL_POLYGON_OFFSET_FILL);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  }

  // An infinite plane as a square of 40 m (or 80 camera distances) around the point under the
  // camera's target, with grid lines every 0.25 m.
  void drawPlane(const RigidShape& plane, const Camera& camera, const std::array<float, 3>& colour) {
    const Vec3 n = plane.planeNormal.normalized();
    const Vec3 u = (std::abs(n.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitX()).cross(n).normalized();
    const Vec3 v = n.cross(u);
    const Vec3 centre = camera.target - (n.dot(camera.target) - plane.planeOffset) * n;
    const double half = std::max(20.0, 40.0 * camera.distance);
    Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
    model.block<3, 1>(0, 0) = (half * u).cast<float>();
    model.block<3, 1>(0, 1) = (half * n).cast<float>();
    model.block<3, 1>(0, 2) = (half * v).cast<float>();
    model.block<3, 1>(0, 3) = centre.cast<float>();
    setModel(meshProgram, model);
    setColour(colour);
    glUniform1f(glGetUniformLocation(meshProgram, "gridSpacing"), 0.25f);
    setVector("gridU", u);
    setVector("gridV", v);
    ground.draw(GL_TRIANGLES);
    glUniform1f(glGetUniformLocation(meshProgram, "gridSpacing"), 0.0f);
  }
};

Renderer::Renderer() : m_impl(std::make_unique<Impl>()) {}

void Renderer::forgetWorld() {
  for (GpuMesh& mesh : m_impl->rigidMeshes) mesh.destroy();
  m_impl->rigidMeshes.clear();
  m_impl->deformableSurfaces.clear();
}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create() {
  std::unique_ptr<Renderer> renderer(new Renderer());
  Impl& r = *renderer->m_impl;
  Result<GLuint> mesh = link(kMeshVertex, kMeshFragment);
  if (!mesh) return Error{mesh.message()};
  r.meshProgram = *mesh;
  Result<GLuint> lines = link(kLineVertex, kLineFragment);
  if (!lines) return Error{lines.message()};
  r.lineProgram = *lines;
  Result<GLuint> shadow = link(kShadowVertex, kShadowFragment);
  if (!shadow) return Error{shadow.message()};
  r.shadowProgram = *shadow;
  r.createShadowMap();
  const Vec3 up = Vec3::UnitY();  // the unit ground square, in the plane's (u, n, v) frame
  r.ground.upload({vertex(Vec3(-1, 0, -1), up), vertex(Vec3(1, 0, -1), up), vertex(Vec3(1, 0, 1), up),
                   vertex(Vec3(-1, 0, 1), up)},
                  {0, 2, 1, 0, 3, 2}, GL_STATIC_DRAW);
  return renderer;
}

void Renderer::draw(const World& world, const Camera& camera, int width, int height, const RenderOptions& options) {
  Impl& r = *m_impl;
  r.refreshMeshes(world);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // cloth has two sides
  const auto [low, high] = sceneBounds(world);
  const Eigen::Matrix4f light = lightViewProjection(low, high);
  if (options.shadows) r.drawShadowMap(world, light);

  glViewport(options.viewportX, 0, width, height);
  glClearColor(0.19f, 0.21f, 0.25f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const Eigen::Matrix4f viewProjection = toFloat(camera.projection(double(width) / height) * camera.view());
  glUseProgram(r.meshProgram);
  r.setMatrix(r.meshProgram, "viewProjection", viewProjection);
  r.setMatrix(r.meshProgram, "lightViewProjection", light);
  r.setVector("eye", camera.eye());
  r.setVector("keyDirection", kKeyDirection);
  glUniform1f(glGetUniformLocation(r.meshProgram, "gridSpacing"), 0.0f);
  glUniform1f(glGetUniformLocation(r.meshProgram, "shadowStrength"), options.shadows ? 0.85f : 0.0f);
  glUniform1f(glGetUniformLocation(r.meshProgram, "shadowTexel"), 1.0f / kShadowMapSize);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.shadowTexture);
  glUniform1i(glGetUniformLocation(r.meshProgram, "shadowMap"), 1);
  glActiveTexture(GL_TEXTURE0);

  auto colourOf = [&](std::optional<RigidBodyId> rigid, std::optional<DeformableId> deformable) {
    std::array<float, 3> colour{};
    if (rigid) {
      const size_t b = static_cast<size_t>(rigid->index);
      colour = b < options.rigidColours.size() && options.rigidColours[b]
                   ? *options.rigidColours[b]
                   : rigidColour(rigid->index, world.rigidMass(*rigid) == 0.0);
      if (options.highlightRigid == rigid) colour = brighter(colour);
    } else {
      const size_t d = static_cast<size_t>(deformable->index);
      colour = d < options.deformableColours.size() && options.deformableColours[d] ? *options.deformableColours[d]
                                                                                   : deformableColour(deformable->index);
      if (options.highlightDeformable == deformable) colour = brighter(colour);
    }
    return colour;
  };
  for (int b = 0; b < world.rigidBodyCount(); ++b)
    if (world.rigidShape(RigidBodyId{b}).type == ShapeType::Plane) {
      const bool custom = static_cast<size_t>(b) < options.rigidColours.size() && options.rigidColours[b];
      r.drawPlane(world.rigidShape(RigidBodyId{b}), camera,
                  custom ? *options.rigidColours[b] : std::array<float, 3>{0.55f, 0.56f, 0.58f});
    }
  r.drawBodies(world, r.meshProgram, [&](auto rigid, auto deformable) { r.setColour(colourOf(rigid, deformable)); });
  if (options.wireframe) {  // the edges over the shading, pulled a little towards the eye
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glEnable(GL_POLYGON_OFFSET_LINE);
    glPolygonOffset(-1.0f, -1.0f);
    r.drawBodies(world, r.meshProgram, [&](auto, auto) { r.setColour({0.05f, 0.05f, 0.05f}); });
    glDisable(GL_POLYGON_OFFSET_LINE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }

  if (options.contacts) {
    const double h = world.lastTimeStep();
    for (const ContactReport& contact : world.contacts()) {
      const double size = 0.01;
      for (int axis = 0; axis < 3; ++axis)
        r.line(contact.point - size * Vec3::Unit(axis), contact.point + size * Vec3::Unit(axis), {1.0f, 0.9f, 0.2f});
      const Vec3 force = h > 0 ? Vec3((contact.normalImpulse * contact.normal + contact.frictionImpulse) / h) : Vec3::Zero();
      if (force.norm() > 1e-9) r.line(contact.point, contact.point + options.forceScale * force, {0.3f, 1.0f, 0.4f});
    }
  }
  r.drawLines(viewProjection, true);  // contacts: hidden behind what is in front of them
  if (options.grabLine) r.line(options.grabLine->first, options.grabLine->second, {1.0f, 1.0f, 1.0f});
  r.drawLines(viewProjection, false);  // the grab: always seen
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace tandem::render
