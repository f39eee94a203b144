// Mass-spring-damper model: a linear spring and a damper along every edge.
//
//   d = x_j − x_i,  n = d/|d|,  f_j = −[k (|d| − L) + c (v_j − v_i)·n] n,  f_i = −f_j
//
// Forces come in equal and opposite pairs along the edge: zero net force and torque, and zero
// force under any rigid motion (|d| = L and (v_j − v_i)·n = 0 when the edge only moves rigidly).
#pragma once

#include "solver/solver_state.h"

#include <cstdint>
#include <span>

namespace tandem {

struct EdgeSpring {
  int32_t nodeA = 0;
  int32_t nodeB = 0;
  double restLength = 0.0;
  double stiffness = 0.0;  // N/m
  double damping = 0.0;    // N·s/m
};

// Adds the springs' forces to `force`; the springs index `position`, `velocity` and `force`.
inline void addSpringForces(std::span<const EdgeSpring> springs, std::span<const Vec3> position,
                            std::span<const Vec3> velocity, std::span<Vec3> force) {
  for (const EdgeSpring& spring : springs) {
    const Vec3 d = position[spring.nodeB] - position[spring.nodeA];
    const double length = d.norm();
    if (length < 1e-12) continue;
    const Vec3 n = d / length;
    const double stretchRate = (velocity[spring.nodeB] - velocity[spring.nodeA]).dot(n);
    const Vec3 f = -(spring.stiffness * (length - spring.restLength) + spring.damping * stretchRate) * n;
    force[spring.nodeB] += f;
    force[spring.nodeA] -= f;
  }
}

inline void addSpringForces(std::span<const EdgeSpring> springs, NodeArrays& nodes) {
  addSpringForces(springs, nodes.position, nodes.velocity, nodes.force);
}

}  // namespace tandem
