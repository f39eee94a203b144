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

inline void addSpringForces(std::span<const EdgeSpring> springs, NodeArrays& nodes) {
  for (const EdgeSpring& spring : springs) {
    const Vec3 d = nodes.position[spring.nodeB] - nodes.position[spring.nodeA];
    const double length = d.norm();
    if (length < 1e-12) continue;
    const Vec3 n = d / length;
    const double stretchRate = (nodes.velocity[spring.nodeB] - nodes.velocity[spring.nodeA]).dot(n);
    const Vec3 force = -(spring.stiffness * (length - spring.restLength) + spring.damping * stretchRate) * n;
    nodes.force[spring.nodeB] += force;
    nodes.force[spring.nodeA] -= force;
  }
}

}  // namespace tandem
