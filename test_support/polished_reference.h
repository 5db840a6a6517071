#ifndef FCL_SUPERELLIPSOID_TEST_POLISHED_REFERENCE_H
#define FCL_SUPERELLIPSOID_TEST_POLISHED_REFERENCE_H

// The reference nearest point to the last digits of long double, for finite differences of
// the distance, the nearest point and the normal (the derivatives' tests). Independent of src/:
// the global search of reference_distance.h finds the basin (its nearest point is good to about
// 1e-9), then Newton on the optimality conditions
//   N − Q + λ∇G(N) = 0,   G(N) = 1
// polishes it, with ∇G and ∇²G of the gauge's textbook formula
//   G = ((|x/a1|^(2/ε1) + |y/a2|^(2/ε1))^(ε1/ε2) + |z/a3|^(2/ε2))^(ε2/2)
// taken by forward-mode differentiation (a value with its gradient and Hessian, Jet below).
// A perturbed query or shape is polished from the unperturbed answer (same basin).

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "reference_distance.h"

namespace fcl_superellipsoid {
namespace test {

using Vec3L = Eigen::Matrix<long double, 3, 1>;
using Mat3L = Eigen::Matrix<long double, 3, 3>;

/// A function of three variables with its gradient and Hessian.
struct Jet {
  long double v;
  Vec3L g;
  Mat3L h;
  static Jet variable(int i, long double x) { return {x, Vec3L::Unit(i), Mat3L::Zero()}; }
};

inline Jet operator+(const Jet& a, const Jet& b) { return {a.v + b.v, a.g + b.g, a.h + b.h}; }
inline Jet operator*(long double c, const Jet& a) { return {c * a.v, c * a.g, c * a.h}; }

/// a^p for a ≥ 0 (0 where a = 0, with p > 1).
inline Jet pow(const Jet& a, long double p) {
  if (a.v == 0) return {0, Vec3L::Zero(), Mat3L::Zero()};
  const long double f = std::pow(a.v, p);
  const long double f1 = p * f / a.v, f2 = (p - 1) * f1 / a.v;
  return {f, f1 * a.g, f1 * a.h + f2 * a.g * a.g.transpose()};
}

struct ReferenceShape {
  std::array<long double, 3> a;
  long double e1, e2;
};

/// G with its gradient and Hessian at a first-octant point.
inline Jet gaugeJet(const ReferenceShape& s, const Vec3L& w) {
  const Jet x = (1 / s.a[0]) * Jet::variable(0, w[0]);
  const Jet y = (1 / s.a[1]) * Jet::variable(1, w[1]);
  const Jet z = (1 / s.a[2]) * Jet::variable(2, w[2]);
  const Jet xy = pow(x, 2 / s.e1) + pow(y, 2 / s.e1);
  return pow(pow(xy, s.e1 / s.e2) + pow(z, 2 / s.e2), s.e2 / 2);
}

struct PolishedResult {
  long double distance;  // signed
  Vec3L nearest;         // in the query's octant
  Vec3L normal;          // unit outward
  bool ok;               // Newton converged to the last digits
};

/// The pose X moved by h along component k of the twist ξ = (ω, v) (point_derivatives.h):
/// X ← exp(h·e_k)·X, a rotation about the world's axis k (k < 3) or a translation along k − 3.
inline Eigen::Transform<long double, 3, Eigen::Isometry> twisted(
    Eigen::Transform<long double, 3, Eigen::Isometry> X, int k, long double h) {
  if (k < 3) {
    X.prerotate(Eigen::AngleAxis<long double>(h, Vec3L::Unit(k)));
  } else {
    X.pretranslate(h * Vec3L::Unit(k - 3));
  }
  return X;
}

/// Newton on the optimality conditions for |q| from the first-octant point `start` (on or near
/// the surface), reflected back into q's octant. `hold_tiny`: see polish() below.
inline PolishedResult polishOnce(const ReferenceShape& s, const Vec3L& q, const Vec3L& start,
                                 bool hold_tiny) {
  const Vec3L y = q.cwiseAbs();
  Vec3L n_point = start.cwiseAbs();
  Jet gj = gaugeJet(s, n_point);
  long double lambda = (y - n_point).dot(gj.g) / gj.g.squaredNorm();
  const long double scale =
      std::max(y.norm(), static_cast<long double>(std::max({s.a[0], s.a[1], s.a[2]})));
  // On a symmetry plane that Q lies on, with the start on it too, N stays on it (0; across it
  // the curvature can be unbounded, ε > 1, and the raw system says nothing there). Else a
  // coordinate the start has at 0 (or below 1e-30 of the scale) starts at 1e-30 of the scale:
  // beside a pinched tip the nearest point is off the axis by a tiny amount (N_i ~
  // Q_i^(1/(p − 1)), p = 2/ε < 2) that Newton reaches from below without overshooting (the
  // condition is concave in N_i there); no iterate leaves the first octant (steps are cut to
  // 90 % of the way to a coordinate plane). With hold_tiny, a coordinate below 1e-15 of the
  // scale beside a crease (its level's ε > 1) is held where it starts instead: where the offset
  // is below 1e-30 of the scale (ε near 2: N_i ~ Q_i^19), Newton from above it wanders, and
  // such a coordinate is 0 to long double's precision, as is its derivative.
  const long double tiny = 1e-15L * scale;
  const bool pinched_xy = s.e2 > 1 && n_point[0] <= tiny && n_point[1] <= tiny;
  std::array<bool, 3> on_plane{};
  for (int i = 0; i < 3; ++i) {
    const bool crease = n_point[i] <= tiny && ((i < 2 ? s.e1 : s.e2) > 1 || (i < 2 && pinched_xy));
    on_plane[i] = (y[i] == 0 && n_point[i] <= tiny) || (hold_tiny && crease);
    if (y[i] == 0 && n_point[i] <= tiny) n_point[i] = 0;
    if (!on_plane[i]) n_point[i] = std::max(n_point[i], 1e-30L * scale);
  }
  bool ok = false;
  for (int it = 0; it < 400; ++it) {
    gj = gaugeJet(s, n_point);
    Eigen::Matrix<long double, 4, 1> f;
    f.head<3>() = n_point - y + lambda * gj.g;
    f[3] = gj.v - 1;
    Eigen::Matrix<long double, 4, 4> j;
    j.topLeftCorner<3, 3>() = Mat3L::Identity() + lambda * gj.h;
    j.topRightCorner<3, 1>() = gj.g;
    j.bottomLeftCorner<1, 3>() = gj.g.transpose();
    j(3, 3) = 0;
    for (int i = 0; i < 3; ++i) {
      if (!on_plane[i]) continue;
      j.row(i).setZero();
      j.col(i).setZero();
      j(i, i) = 1;
      f[i] = 0;
    }
    // Equilibrated (unit diagonal, unit border): near a crease ∇²G is huge in one direction,
    // and an unscaled solve loses the others' steps beside it.
    Eigen::Matrix<long double, 4, 1> sc;
    for (int i = 0; i < 3; ++i) sc[i] = 1 / std::sqrt(std::max(std::fabs(j(i, i)), 1.0L));
    sc[3] = 1 / sc.head<3>().cwiseProduct(gj.g).cwiseAbs().maxCoeff();
    const Eigen::Matrix<long double, 4, 1> step =
        sc.asDiagonal() *
        (sc.asDiagonal() * j * sc.asDiagonal()).fullPivLu().solve(-(sc.asDiagonal() * f));
    long double t = 1;
    for (int i = 0; i < 3; ++i) {
      if (step[i] < 0 && n_point[i] + t * step[i] < 0) t = 0.9L * n_point[i] / -step[i];
    }
    n_point += t * step.head<3>();
    lambda += t * step[3];
    if (step.head<3>().norm() <= 1e-18L * scale && f.head<3>().norm() <= 1e-17L * scale &&
        std::fabs(f[3]) <= 1e-17L) {
      ok = true;
      break;
    }
  }
  gj = gaugeJet(s, n_point);
  PolishedResult r;
  const bool inside = gaugeJet(s, y).v < 1;
  r.distance = (inside ? -1 : 1) * (y - n_point).norm();
  // The normal: (Q − N)/d away from the surface, where N determines it to the last digits
  // (∇G/‖∇G‖ does not near a crease with ε near 2, where ∂G/∂x_i ~ t^(2/ε − 1) is a slow power
  // of a coordinate that may be below the rounding of the others); ∇G/‖∇G‖ within 1e-3 of the
  // scale from it, where dividing by d would magnify N's rounding.
  r.normal = std::abs(r.distance) > 1e-3L * scale ? Vec3L((y - n_point) / r.distance)
                                                  : Vec3L(gj.g.normalized());
  r.nearest = n_point;
  for (int i = 0; i < 3; ++i) {
    if (q[i] < 0) {
      r.nearest[i] = -r.nearest[i];
      r.normal[i] = -r.normal[i];
    }
  }
  r.ok = ok && n_point.allFinite() && n_point.minCoeff() >= 0;
  return r;
}

/// polishOnce, and if Newton does not converge, again with the coordinates beside a crease that
/// are 0 to long double's precision held.
inline PolishedResult polish(const ReferenceShape& s, const Vec3L& q, const Vec3L& start) {
  const PolishedResult r = polishOnce(s, q, start, false);
  return r.ok ? r : polishOnce(s, q, start, true);
}

/// The global reference (reference_distance.h), polished; inside, also polished from the three
/// axis projections of Q (one coordinate moved until G = 1, by bisection), and the nearest
/// converged answer kept: on a flat shape (a radius 1e-2 of the largest) the global search's
/// grid can miss the basin of the near flat face.
inline PolishedResult polishedReference(const ReferenceShape& s, const Vec3L& q) {
  const ReferenceDistance reference(s.a, s.e1, s.e2);
  const ReferenceResult r = reference.query({q[0], q[1], q[2]});
  PolishedResult best = polish(s, q, Vec3L(r.nearest[0], r.nearest[1], r.nearest[2]));
  const Vec3L y = q.cwiseAbs();
  if (reference.gauge({y[0], y[1], y[2]}) >= 1) return best;
  for (int i = 0; i < 3; ++i) {
    long double lo = y[i], hi = s.a[i];
    for (int k = 0; k < 200 && lo < hi; ++k) {
      const long double mid = (lo + hi) / 2;
      std::array<long double, 3> p{y[0], y[1], y[2]};
      p[i] = mid;
      (reference.gauge(p) < 1 ? lo : hi) = mid;
    }
    Vec3L start = y;
    start[i] = hi;
    const PolishedResult c = polish(s, q, start);
    if (c.ok && (!best.ok || std::fabs(c.distance) < std::fabs(best.distance))) best = c;
  }
  return best;
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_POLISHED_REFERENCE_H
