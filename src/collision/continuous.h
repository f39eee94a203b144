// Continuous collision tests between moving features: does a node pass through a moving
// triangle, or an edge through a moving edge, while every point moves on a straight line from
// its start to its end of the step?
//
// Four points x_i(t) = x_i + t d_i, t ∈ [0, 1], are coplanar where
//   f(t) = (B(t) × C(t)) · P(t) = 0,
// with B, C, P three of them taken from the fourth (node–face: b − a, c − a, p − a;
// edge–edge: p1 − p0, q1 − q0, q0 − p0). Each is linear in t, so f is a cubic
//   f(t) = c0 + c1 t + c2 t² + c3 t³,
//   c0 = (B×C)·P,  c1 = (dB×C + B×dC)·P + (B×C)·dP,
//   c2 = (dB×dC)·P + (dB×C + B×dC)·dP,  c3 = (dB×dC)·dP.
// Its roots in [0, 1] are found in order by splitting [0, 1] at the roots of f' (where f is
// monotone in between) and bisecting each piece whose ends differ in sign. At each root the
// features are in one plane; they collide there if the node is on the face (edges: the two
// edges meet) to within `tolerance`. A motion that stays in one plane (f ≡ 0, a flat sheet
// sliding in itself) is no crossing and is not reported.
#pragma once

#include "collision/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>

namespace tandem::geometry {

struct CoplanarCubic {
  std::array<double, 4> c{};  // f(t) = c0 + c1 t + c2 t² + c3 t³
  double scale = 0.0;         // |B||C||P| largest along the motion: what "zero" is measured against

  double operator()(double t) const { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }
};

inline CoplanarCubic coplanarCubic(const Vec3& B, const Vec3& dB, const Vec3& C, const Vec3& dC, const Vec3& P,
                                   const Vec3& dP) {
  const Vec3 bc = B.cross(C), mixed = dB.cross(C) + B.cross(dC), dbdc = dB.cross(dC);
  CoplanarCubic f;
  f.c = {bc.dot(P), mixed.dot(P) + bc.dot(dP), dbdc.dot(P) + mixed.dot(dP), dbdc.dot(dP)};
  f.scale = std::max(B.norm(), (B + dB).norm()) * std::max(C.norm(), (C + dC).norm()) *
            std::max(P.norm(), (P + dP).norm());
  return f;
}

// The roots of f in [0, 1], ascending; at most three.
inline int coplanarTimes(const CoplanarCubic& f, std::array<double, 3>& roots) {
  const double zero = 1e-14 * f.scale;
  if (std::abs(f.c[0]) <= zero && std::abs(f.c[1]) <= zero && std::abs(f.c[2]) <= zero && std::abs(f.c[3]) <= zero)
    return 0;  // moving in one plane
  // Ends of the monotone pieces: 0, the roots of f' = c1 + 2 c2 t + 3 c3 t² inside (0, 1), 1.
  std::array<double, 4> ends{0.0, 1.0, 1.0, 1.0};
  int endCount = 1;
  const double qa = 3 * f.c[3], qb = 2 * f.c[2], qc = f.c[1];
  auto addEnd = [&](double t) {
    if (t > 0 && t < 1) ends[endCount++] = t;
  };
  if (std::abs(qa) > 1e-300) {
    const double discriminant = qb * qb - 4 * qa * qc;
    if (discriminant >= 0) {
      const double root = std::sqrt(discriminant);
      const double q = -0.5 * (qb + std::copysign(root, qb));  // stable quadratic roots
      double t0 = q / qa, t1 = q != 0 ? qc / q : t0;
      if (t0 > t1) std::swap(t0, t1);
      addEnd(t0);
      addEnd(t1);
    }
  } else if (std::abs(qb) > 1e-300) {
    addEnd(-qc / qb);
  }
  ends[endCount++] = 1.0;
  int count = 0;
  auto addRoot = [&](double t) {
    if (count == 0 || t > roots[count - 1] + 1e-12) roots[count++] = t;
  };
  for (int piece = 0; piece + 1 < endCount; ++piece) {
    double low = ends[piece], high = ends[piece + 1];
    double fLow = f(low), fHigh = f(high);
    if (std::abs(fLow) <= zero) {
      addRoot(low);
      continue;
    }
    if (std::abs(fHigh) <= zero) {
      if (piece + 2 == endCount) addRoot(high);  // else the next piece starts there
      continue;
    }
    if ((fLow < 0) == (fHigh < 0)) continue;
    for (int bisection = 0; bisection < 60 && high - low > 1e-13; ++bisection) {
      const double middle = 0.5 * (low + high);
      const double fMiddle = f(middle);
      if ((fMiddle < 0) == (fLow < 0)) {
        low = middle;
        fLow = fMiddle;
      } else {
        high = middle;
      }
    }
    addRoot(0.5 * (low + high));
    if (count == 3) break;
  }
  return count;
}

// The first root of f at which the features, `distanceAt(t)` apart, touch.
template <class DistanceAt>
std::optional<double> firstTouch(const CoplanarCubic& f, double tolerance, DistanceAt&& distanceAt) {
  std::array<double, 3> roots{};
  const int count = coplanarTimes(f, roots);
  for (int r = 0; r < count; ++r)
    if (distanceAt(roots[r]) <= tolerance) return roots[r];
  return std::nullopt;
}

// How finely the features' coordinates resolve: a touch closer than a few units in the last place
// of the largest coordinate cannot be told from a near miss, so `tolerance` is at least that (it
// matters only far from the origin: 1.9 µm at 2^31 m, 0.1 nm at 100 m).
inline double resolvedTolerance(double tolerance, std::initializer_list<const Vec3*> points) {
  double largest = 0.0;
  for (const Vec3* point : points) largest = std::max(largest, point->cwiseAbs().maxCoeff());
  return std::max(tolerance, 4.0 * std::numeric_limits<double>::epsilon() * largest);
}

// The first time in [0, 1] at which node p passes through (or touches) triangle abc, each
// point moving from x to x + d.
//
// Everything is measured relative to a (moving with it): the differences of nearby points far
// from the origin are exact, so the distance at the coplanar time is as accurate at 2^31 m as at
// the origin. (Positions there were rounded to 0.48 µm before subtracting them from each other:
// ten times the 50 nm touch tolerance of 5 cm features; crossings were missed.)
inline std::optional<double> nodeFaceImpact(const Vec3& p, const Vec3& dp, const Vec3& a, const Vec3& da,
                                            const Vec3& b, const Vec3& db, const Vec3& c, const Vec3& dc,
                                            double tolerance) {
  const Vec3 pa = p - a, ba = b - a, ca = c - a, dpa = dp - da, dba = db - da, dca = dc - da;
  const Vec3 pEnd = p + dp, aEnd = a + da, bEnd = b + db, cEnd = c + dc;
  tolerance = resolvedTolerance(tolerance, {&p, &a, &b, &c, &pEnd, &aEnd, &bEnd, &cEnd});
  return firstTouch(coplanarCubic(ba, dba, ca, dca, pa, dpa), tolerance, [&](double t) {
    const Vec3 pt = pa + t * dpa, bt = ba + t * dba, ct = ca + t * dca;
    const std::array<double, 3> w = closestOnTriangle(pt, Vec3::Zero(), bt, ct);
    return (pt - (w[1] * bt + w[2] * ct)).norm();
  });
}

// The first time in [0, 1] at which edge p0p1 passes through (or touches) edge q0q1; relative to
// p0, as above.
inline std::optional<double> edgeEdgeImpact(const Vec3& p0, const Vec3& dp0, const Vec3& p1, const Vec3& dp1,
                                            const Vec3& q0, const Vec3& dq0, const Vec3& q1, const Vec3& dq1,
                                            double tolerance) {
  const Vec3 p1p = p1 - p0, q0p = q0 - p0, q1p = q1 - p0, dp1p = dp1 - dp0, dq0p = dq0 - dp0, dq1p = dq1 - dp0;
  const Vec3 p0End = p0 + dp0, p1End = p1 + dp1, q0End = q0 + dq0, q1End = q1 + dq1;
  tolerance = resolvedTolerance(tolerance, {&p0, &p1, &q0, &q1, &p0End, &p1End, &q0End, &q1End});
  return firstTouch(coplanarCubic(p1p, dp1p, q1 - q0, dq1 - dq0, q0p, dq0p), tolerance, [&](double t) {
    const Vec3 a1 = p1p + t * dp1p, b0 = q0p + t * dq0p, b1 = q1p + t * dq1p;
    const auto [s, u] = closestOnSegments(Vec3::Zero(), a1, b0, b1);
    return (s * a1 - (b0 + u * (b1 - b0))).norm();
  });
}

}  // namespace tandem::geometry
