// The orbit camera of the viewer and of `tandem render`: where it looks from, its matrices,
// and the pixel ↔ world maths that picking needs. No OpenGL here, so it is tested headless.
//
// Pixels: x to the right, y down, (0, 0) the top-left corner of the top-left pixel. View and
// projection follow OpenGL: the camera looks down its −z, clip depth in [−1, 1].
#pragma once

#include <tandem/shape_surface.h>
#include <tandem/world.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tandem::render {

using Mat4 = Eigen::Matrix4d;

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit
};

struct Camera {
  Vec3 target{0.0, 0.5, 0.0};
  double yaw = 0.6;     // rad about +y; 0 looks along −z
  double pitch = 0.35;  // rad above the horizon
  double distance = 4.0;
  double fovY = 45.0 * std::numbers::pi / 180.0;

  Vec3 eye() const {
    return target + distance * Vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  }

  Mat4 view() const {
    const Vec3 forward = (target - eye()).normalized();
    const Vec3 right = forward.cross(Vec3::UnitY()).normalized();
    const Vec3 up = right.cross(forward);
    Mat4 m = Mat4::Identity();
    m.block<1, 3>(0, 0) = right.transpose();
    m.block<1, 3>(1, 0) = up.transpose();
    m.block<1, 3>(2, 0) = -forward.transpose();
    m.block<3, 1>(0, 3) = -m.block<3, 3>(0, 0) * eye();
    return m;
  }

  double nearPlane() const { return std::max(1e-3, 0.01 * distance); }
  double farPlane() const { return 200.0 * distance; }

  Mat4 projection(double aspect) const {
    const double f = 1.0 / std::tan(fovY / 2), n = nearPlane(), fa = farPlane();
    Mat4 m = Mat4::Zero();
    m(0, 0) = f / aspect;
    m(1, 1) = f;
    m(2, 2) = (fa + n) / (n - fa);
    m(2, 3) = 2 * fa * n / (n - fa);
    m(3, 2) = -1;
    return m;
  }

  // The ray from the eye through pixel position (x, y) of a width × height image.
  Ray ray(double x, double y, int width, int height) const {
    const double aspect = static_cast<double>(width) / height;
    const double t = std::tan(fovY / 2);
    const double ndcX = 2.0 * x / width - 1.0, ndcY = 1.0 - 2.0 * y / height;
    const Mat4 v = view();
    const Vec3 right = v.block<1, 3>(0, 0).transpose(), up = v.block<1, 3>(1, 0).transpose();
    const Vec3 forward = -v.block<1, 3>(2, 0).transpose();
    return {eye(), (forward + ndcX * aspect * t * right + ndcY * t * up).normalized()};
  }

  // Where a world point lands in the image (pixels), and its distance in front of the eye.
  Eigen::Vector3d project(const Vec3& point, int width, int height) const {
    const Eigen::Vector4d clip = projection(static_cast<double>(width) / height) * view() * point.homogeneous();
    const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
    return {(ndc.x() + 1) / 2 * width, (1 - ndc.y()) / 2 * height, clip.w()};
  }

  // Mouse motions, in pixels of a viewport `height` tall.
  void orbit(double dx, double dy) {
    yaw -= 0.01 * dx;
    pitch = std::clamp(pitch + 0.01 * dy, -1.5, 1.5);
  }
  void pan(double dx, double dy, int height) {
    const double metresPerPixel = 2 * distance * std::tan(fovY / 2) / height;
    const Mat4 v = view();
    target += metresPerPixel * (-dx * v.block<1, 3>(0, 0).transpose() + dy * v.block<1, 3>(1, 0).transpose());
  }
  void zoom(double wheelSteps) { distance = std::clamp(distance * std::pow(0.9, wheelSteps), 0.05, 500.0); }

  // A camera at yaw and pitch looking at the middle of the box [low, high], as near as it can be
  // with every corner inside the middle 90% of an image of this aspect (width / height).
  static Camera framing(const Vec3& low, const Vec3& high, double aspect, double yaw = 0.6, double pitch = 0.35) {
    Camera camera;
    camera.target = (low + high) / 2;
    camera.yaw = yaw;
    camera.pitch = pitch;
    camera.distance = 1.0;
    const Mat4 v = camera.view();
    const Vec3 right = v.block<1, 3>(0, 0).transpose(), up = v.block<1, 3>(1, 0).transpose();
    const Vec3 forward = -v.block<1, 3>(2, 0).transpose();
    const double tanY = 0.9 * std::tan(camera.fovY / 2), tanX = aspect * tanY;
    // A corner p (from the target) is in view when |p·right| ≤ tanX (d − p·forward), and so for up.
    double distance = 0.1;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p = Vec3((corner & 1) ? high.x() : low.x(), (corner & 2) ? high.y() : low.y(),
                          (corner & 4) ? high.z() : low.z()) - camera.target;
      distance = std::max({distance, std::abs(p.dot(right)) / tanX + p.dot(forward),
                           std::abs(p.dot(up)) / tanY + p.dot(forward)});
    }
    camera.distance = distance;
    return camera;
  }
  // A camera at `eye` looking at `target`.
  static Camera lookAt(const Vec3& eye, const Vec3& target) {
    Camera camera;
    const Vec3 offset = eye - target;
    camera.target = target;
    camera.distance = std::max(offset.norm(), 1e-3);
    camera.pitch = std::asin(std::clamp(offset.y() / camera.distance, -1.0, 1.0));
    camera.yaw = std::atan2(offset.x(), offset.z());
    return camera;
  }
};

// The box holding every deformable node and every rigid body but infinite planes (with
// `movingOnly`, only the dynamic ones); empty (infinite corners) when there is nothing.
inline std::pair<Vec3, Vec3> bodyBounds(const World& world, bool movingOnly) {
  Vec3 low = Vec3::Constant(INFINITY), high = Vec3::Constant(-INFINITY);
  for (const DeformableId d : world.deformableIds())
    for (const Vec3& p : world.nodePositions(d)) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  for (const RigidBodyId id : world.rigidBodies()) {
    if (movingOnly && world.rigidMass(id) == 0.0) continue;
    const Quat orientation = world.rigidOrientation(id);
    for (const Vec3& p : shapeSurface(world.rigidShape(id), 8).positions) {  // nothing for planes
      const Vec3 q = world.rigidPosition(id) + orientation * p;
      low = low.cwiseMin(q);
      high = high.cwiseMax(q);
    }
  }
  return {low, high};
}

// The box for framing a scene.
inline std::pair<Vec3, Vec3> sceneBounds(const World& world) {
  const auto bounds = bodyBounds(world, false);
  if (!bounds.first.allFinite()) return {Vec3(-1, 0, -1), Vec3(1, 1, 1)};  // nothing but planes
  return bounds;
}

// The box holding what moves: every deformable node and every dynamic rigid body; the scene's
// bounds when nothing moves.
inline std::pair<Vec3, Vec3> movingBounds(const World& world) {
  const auto bounds = bodyBounds(world, true);
  if (!bounds.first.allFinite()) return sceneBounds(world);
  return bounds;
}

// Keeps what moves in view: the camera turns to look at the middle of what moves and backs off
// when it would not all fit; it never comes nearer, so the picture does not pump.
inline void follow(Camera& camera, const World& world, double aspect) {
  const auto [low, high] = movingBounds(world);
  const Camera framed = Camera::framing(low, high, aspect, camera.yaw, camera.pitch);
  camera.target = framed.target;
  camera.distance = std::max(camera.distance, framed.distance);
}

}  // namespace tandem::render
