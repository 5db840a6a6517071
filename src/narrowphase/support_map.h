#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SUPPORT_MAP_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SUPPORT_MAP_H

// Internal: the support function of a posed smooth convex shape, in world coordinates, with its
// gradient (the support point) and Hessian (docs/math.md → "Shape pairs").
//
//   h_W(v) = h_L(Rᵀv) + v·t,   ∇h_W(v) = R·∇h_L(Rᵀv) + t,   ∇²h_W(v) = R·∇²h_L(Rᵀv)·Rᵀ
//
// for the pose X = (R, t). h is 1-homogeneous, its gradient 0-homogeneous and its Hessian
// (−1)-homogeneous; every evaluation divides the direction by its largest component first.

#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

#include <Eigen/Core>
#include <limits>

#include "fcl_superellipsoid/superellipsoid.h"
#include "shape/nested_norm.h"
#include "shape/octant.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
struct SupportEval {
  S value;                         // h(v)
  Vector3<S> point;                // ∇h(v): the support point
  Eigen::Matrix<S, 3, 3> hessian;  // ∇²h(v)
};

/// A superellipsoid, an ellipsoid or a sphere, posed. The shape must outlive the map.
template <typename S>
class SupportMap {
 public:
  SupportMap(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X)
      : kind_(Kind::kSuperellipsoid),
        norm_(NestedNorm<S>::support(shape)),
        gauge_(NestedNorm<S>::gauge(shape)),
        X_(X) {}
  SupportMap(const fcl::Ellipsoid<S>& shape, const fcl::Transform3<S>& X)
      : kind_(Kind::kEllipsoid), radii_(shape.radii), X_(X) {}
  SupportMap(const fcl::Sphere<S>& shape, const fcl::Transform3<S>& X)
      : kind_(Kind::kEllipsoid), radii_(Vector3<S>::Constant(shape.radius)), X_(X) {}
  /// A single point p (an ellipsoid of radii 0 there): h(v) = v·p.
  static SupportMap ofPoint(const Vector3<S>& p) {
    fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
    X.translation() = p;
    return SupportMap(Kind::kEllipsoid, X);
  }
  /// A circle of radius r around `centre`, in the plane ⊥ `axis` (unit; an ellipsoid of radii
  /// (r, r, 0)): h(v) = v·centre + r·‖v − (v·axis)·axis‖, a rim of a cylinder or a cone.
  static SupportMap ofCircle(const Vector3<S>& centre, const Vector3<S>& axis, S r) {
    fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
    const Vector3<S> e1 = axis.unitOrthogonal();
    X.linear().col(0) = e1;
    X.linear().col(1) = axis.cross(e1);
    X.linear().col(2) = axis;
    X.translation() = centre;
    SupportMap map(Kind::kEllipsoid, X);
    map.radii_ = Vector3<S>(r, r, S(0));
    return map;
  }

  /// The support at the world direction v ≠ 0; without `with_hessian` the Hessian is not
  /// computed (NaN), the value and the point are the same.
  SupportEval<S> evaluate(const Vector3<S>& v, bool with_hessian = true) const {
    const Vector3<S> u = X_.linear().transpose() * v;
    const S m = u.cwiseAbs().maxCoeff();
    const Vector3<S> w = u / m;  // largest component ±1
    SupportEval<S> local;
    if (kind_ == Kind::kSuperellipsoid) {
      const NestedNormEval<S> e = norm_.evaluate(w.cwiseAbs(), with_hessian);
      local.value = e.value;
      local.point = intoOctantOf(w, e.gradient);
      if (with_hessian) {
        local.hessian = e.hessian;
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            if ((w[i] < S(0)) != (w[j] < S(0))) local.hessian(i, j) = -local.hessian(i, j);
          }
        }
      }
    } else {
      // h(w) = ‖D·w‖ with D = diag(radii): ∇h = D²w/h, ∇²h = (D² − ∇h·∇hᵀ)/h.
      const Vector3<S> dw = radii_.cwiseProduct(w);
      local.value = dw.norm();
      if (local.value > S(0)) {
        local.point = radii_.cwiseProduct(dw) / local.value;
        if (with_hessian) {
          local.hessian = (Eigen::Matrix<S, 3, 3>(radii_.cwiseProduct(radii_).asDiagonal()) -
                           local.point * local.point.transpose()) /
                          local.value;
        }
      } else {  // flat along w (a zero radius): the centre supports it
        local.point.setZero();
        local.hessian.setZero();
      }
    }
    SupportEval<S> out;
    out.value = m * local.value + v.dot(X_.translation());
    out.point = X_.linear() * local.point + X_.translation();
    if (with_hessian) {
      out.hessian = X_.linear() * local.hessian * X_.linear().transpose() / m;
    } else {
      out.hessian.setConstant(std::numeric_limits<S>::quiet_NaN());
    }
    return out;
  }

  /// The support point only.
  Vector3<S> point(const Vector3<S>& v) const { return evaluate(v, false).point; }

  /// The point x + s·d (d unit) on the surface nearest to x along the line, for x within a
  /// small fraction of the size of the surface: Newton on the gauge, G(x + s·d) = 1, from s = 0.
  /// x itself where that does not converge in a few steps, and for a point or a circle (no
  /// gauge): the smooth pair's witness beside a flat face (smooth_pair.cpp).
  Vector3<S> ontoSurfaceAlong(const Vector3<S>& x, const Vector3<S>& d) const {
    if (kind_ == Kind::kEllipsoid && !(radii_.minCoeff() > S(0))) return x;
    const Vector3<S> q0 = X_.linear().transpose() * (x - X_.translation());
    const Vector3<S> m = X_.linear().transpose() * d;
    const S eps = std::numeric_limits<S>::epsilon();
    S s = S(0);
    for (int it = 0; it < 4; ++it) {
      const Vector3<S> q = q0 + s * m;
      S value;
      Vector3<S> gradient;
      if (kind_ == Kind::kSuperellipsoid) {
        const NestedNormEval<S> e = gauge_.evaluate(q.cwiseAbs(), false);
        value = e.value;
        gradient = intoOctantOf(q, e.gradient);
      } else {
        const Vector3<S> r = q.cwiseQuotient(radii_);
        value = r.norm();
        gradient = r.cwiseQuotient(radii_) / value;
      }
      const S slope = gradient.dot(m);
      if (!std::isfinite(value) || !(slope > S(0))) return x;
      if (std::abs(value - S(1)) <= S(4) * eps) return X_ * q;
      s -= (value - S(1)) / slope;
    }
    return x;
  }
  const Vector3<S> centre() const { return X_.translation(); }
  const fcl::Transform3<S>& pose() const { return X_; }

 private:
  enum class Kind { kSuperellipsoid, kEllipsoid };
  SupportMap(Kind kind, const fcl::Transform3<S>& X) : kind_(kind), X_(X) {}
  Kind kind_;
  NestedNorm<S> norm_{};   // the support function
  NestedNorm<S> gauge_{};  // the primal gauge
  Vector3<S> radii_ = Vector3<S>::Zero();
  fcl::Transform3<S> X_;
};

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SUPPORT_MAP_H
