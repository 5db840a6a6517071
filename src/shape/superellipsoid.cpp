#include "fcl_superellipsoid/superellipsoid.h"

#include <cmath>
#include <memory>
#include <ostream>
#include <string>

#include "common/invalid_argument.h"
#include "fcl_glue/registration.h"
#include "shape/curvature.h"
#include "shape/nested_norm.h"
#include "shape/octant.h"
#include "shape/shape_caches.h"

namespace fcl_superellipsoid {
namespace {

template <typename S>
void checkRadius(const char* name, S value) {
  if (!(std::isfinite(value) && value > S(0))) {
    detail::throwInvalidArgument("Superellipsoid", std::string(name) + " must be finite and > 0",
                                 value);
  }
  using Range = NumericRange<S>;
  if (!(value >= Range::kMinRadius && value <= Range::kMaxRadius)) {
    detail::throwInvalidArgument("Superellipsoid",
                                 std::string(name) + " must be in the supported range [" +
                                     detail::formatValue(Range::kMinRadius) + ", " +
                                     detail::formatValue(Range::kMaxRadius) + "]",
                                 value);
  }
}

template <typename S>
void checkAspectRatio(const Vector3<S>& radii) {
  const S ratio = radii.maxCoeff() / radii.minCoeff();
  if (!(ratio <= NumericRange<S>::kMaxAspectRatio)) {
    detail::throwInvalidArgument("Superellipsoid",
                                 "the largest radius may be at most " +
                                     detail::formatValue(NumericRange<S>::kMaxAspectRatio) +
                                     " x the smallest, radii",
                                 radii);
  }
}

template <typename S>
void checkExponent(const char* name, S value) {
  if (!(std::isfinite(value) && value > S(0) && value < S(2))) {
    detail::throwInvalidArgument("Superellipsoid",
                                 std::string(name) + " must be in the open interval (0, 2)", value);
  }
}

/// The evaluations' one check: a point that is not finite has no gauge, normal or projection.
template <typename S>
void checkPoint(const char* function, const Vector3<S>& p_S) {
  if (!p_S.allFinite()) {
    detail::throwInvalidArgument(std::string("Superellipsoid::") + function,
                                 "the point must be finite", p_S);
  }
}

}  // namespace

template <typename S>
Superellipsoid<S>::Superellipsoid(S a1, S a2, S a3, S eps1, S eps2)
    : Superellipsoid(Vector3<S>(a1, a2, a3), eps1, eps2) {}

template <typename S>
Superellipsoid<S>::Superellipsoid(const Vector3<S>& radii, S eps1, S eps2)
    : radii_(radii), eps1_(eps1), eps2_(eps2), caches_(std::make_shared<detail::ShapeCaches<S>>()) {
  checkRadius("radius a1", radii[0]);
  checkRadius("radius a2", radii[1]);
  checkRadius("radius a3", radii[2]);
  checkAspectRatio(radii);
  checkExponent("exponent eps1", eps1);
  checkExponent("exponent eps2", eps2);
  computeLocalAABB();
  // The one call from the shape up into the FCL layer (fcl_glue/registration.h): FCL's
  // function tables learn the shape before its first query.
  detail::registerWithFclOnce();
}

template <typename S>
S Superellipsoid<S>::minRadiusOfCurvature() const {
  return detail::ShapeCaches<S>::of(*this).minRadiusOfCurvature([this] {
    return static_cast<S>(
        detail::minRadiusOfCurvature(radii_.template cast<double>(), eps1_, eps2_));
  });
}

template <typename S>
void Superellipsoid<S>::setQueryOptions(const DistanceOptions<S>& options) {
  validateOptions(options);
  query_options_ = options;
}

template <typename S>
void Superellipsoid<S>::setMeshContacts(MeshContacts contacts) {
  if (contacts != MeshContacts::kVertices && contacts != MeshContacts::kRegions) {
    detail::throwInvalidArgument("setMeshContacts", "contacts must be kVertices or kRegions",
                                 static_cast<int>(contacts));
  }
  mesh_contacts_ = contacts;
}

template <typename S>
S Superellipsoid<S>::gauge(const Vector3<S>& p_S) const {
  checkPoint("gauge", p_S);
  return detail::NestedNorm<S>::gauge(*this).value(p_S.cwiseAbs());
}

template <typename S>
S Superellipsoid<S>::implicitFunction(const Vector3<S>& p_S) const {
  checkPoint("implicitFunction", p_S);
  return std::pow(gauge(p_S), S(2) / eps2_);
}

template <typename S>
Vector3<S> Superellipsoid<S>::gaugeGradient(const Vector3<S>& p_S) const {
  checkPoint("gaugeGradient", p_S);
  const Vector3<S> g = detail::NestedNorm<S>::gauge(*this).evaluate(p_S.cwiseAbs(), false).gradient;
  return detail::intoOctantOf(p_S, g);
}

template <typename S>
Vector3<S> Superellipsoid<S>::implicitGradient(const Vector3<S>& p_S) const {
  checkPoint("implicitGradient", p_S);
  // F = G^(2/ε2)  ⇒  ∇F = (2/ε2)·G^(2/ε2 − 1)·∇G.
  const S p2 = S(2) / eps2_;
  return p2 * std::pow(gauge(p_S), p2 - S(1)) * gaugeGradient(p_S);
}

template <typename S>
Vector3<S> Superellipsoid<S>::normal(const Vector3<S>& p_S) const {
  checkPoint("normal", p_S);
  const Vector3<S> g = gaugeGradient(p_S);
  const S n = g.norm();
  if (!(n > S(0))) return Vector3<S>::UnitZ();
  return g / n;
}

template <typename S>
S Superellipsoid<S>::radialDistance(const Vector3<S>& p_S) const {
  checkPoint("radialDistance", p_S);
  const S largest = p_S.cwiseAbs().maxCoeff();  // (scaled first: ‖p‖² may overflow)
  if (largest == S(0)) return -radii_.minCoeff();
  const S len = largest * (p_S / largest).norm();
  // ‖p‖·(1 − 1/G(p)) = ‖p‖ − 1/G(p/‖p‖): the second form stays exact as p → 0.
  return len - S(1) / gauge(Vector3<S>(p_S / len));
}

template <typename S>
Vector3<S> Superellipsoid<S>::radialProjection(const Vector3<S>& p_S) const {
  checkPoint("radialProjection", p_S);
  const S largest = p_S.cwiseAbs().maxCoeff();  // (scaled first: ‖p‖² may overflow)
  if (largest == S(0)) return Vector3<S>(S(0), S(0), radii_[2]);
  const Vector3<S> dir = (p_S / largest).normalized();
  return dir / gauge(dir);
}

template <typename S>
Vector3<S> Superellipsoid<S>::surfacePoint(S eta, S omega) const {
  if (!(std::isfinite(eta) && std::isfinite(omega))) {
    detail::throwInvalidArgument("Superellipsoid::surfacePoint", "eta and omega must be finite",
                                 Eigen::Matrix<S, 2, 1>(eta, omega));
  }
  using detail::signedPow;
  const S ce = signedPow(std::cos(eta), eps2_);
  return Vector3<S>(radii_[0] * ce * signedPow(std::cos(omega), eps1_),
                    radii_[1] * ce * signedPow(std::sin(omega), eps1_),
                    radii_[2] * signedPow(std::sin(eta), eps2_));
}

template <typename S>
bool Superellipsoid<S>::contains(const Vector3<S>& p_S) const {
  checkPoint("contains", p_S);
  return gauge(p_S) <= S(1);
}

template <typename S>
Vector3<S> Superellipsoid<S>::supportPoint(const Vector3<S>& direction) const {
  if (!direction.allFinite()) {
    detail::throwInvalidArgument("Superellipsoid::supportPoint", "direction must be finite",
                                 direction);
  }
  if (direction.isZero(S(0))) return Vector3<S>(radii_[0], S(0), S(0));
  // ∇h is 0-homogeneous: divide by the largest component so nothing overflows.
  const Vector3<S> w = direction.cwiseAbs() / direction.cwiseAbs().maxCoeff();
  const Vector3<S> p = detail::NestedNorm<S>::support(*this).gradient(w);
  return detail::intoOctantOf(direction, p);
}

template <typename S>
void Superellipsoid<S>::computeLocalAABB() {
  this->aabb_local.min_ = -radii_;
  this->aabb_local.max_ = radii_;
  this->aabb_center = Vector3<S>::Zero();
  this->aabb_radius = radii_.norm();
}

template <typename S>
S Superellipsoid<S>::computeVolume() const {
  // Evaluated in double: std::beta in float loses digits for small ε.
  const double e1 = eps1_, e2 = eps2_;
  const double v = 2.0 * double(radii_[0]) * radii_[1] * radii_[2] * e1 * e2 *
                   std::beta(e1 / 2, e1 / 2) * std::beta(e2 / 2 + 1, e2);
  return static_cast<S>(v);
}

template <typename S>
fcl::Matrix3<S> Superellipsoid<S>::computeMomentofInertia() const {
  // Unit density, about the centre (docs/math.md → "Volume and inertia"): k = ½·a1·a2·a3·ε1·ε2,
  //   Ixx = k·[a2²·B(3ε1/2, ε1/2)·B(ε2/2, 2ε2+1) + 4a3²·B(ε1/2, ε1/2+1)·B(3ε2/2, ε2+1)],
  //   Iyy = the same with a1², Izz = k·(a1² + a2²)·B(3ε1/2, ε1/2)·B(ε2/2, 2ε2+1).
  const double e1 = eps1_, e2 = eps2_;
  const double a1 = radii_[0], a2 = radii_[1], a3 = radii_[2];
  const double k = 0.5 * a1 * a2 * a3 * e1 * e2;
  const double planar = std::beta(1.5 * e1, e1 / 2) * std::beta(e2 / 2, 2 * e2 + 1);
  const double axial = 4.0 * std::beta(e1 / 2, e1 / 2 + 1) * std::beta(1.5 * e2, e2 + 1);
  fcl::Matrix3<S> inertia = fcl::Matrix3<S>::Zero();
  inertia(0, 0) = static_cast<S>(k * (a2 * a2 * planar + a3 * a3 * axial));
  inertia(1, 1) = static_cast<S>(k * (a1 * a1 * planar + a3 * a3 * axial));
  inertia(2, 2) = static_cast<S>(k * (a1 * a1 + a2 * a2) * planar);
  return inertia;
}

template <typename S>
std::vector<Vector3<S>> Superellipsoid<S>::getBoundVertices(const fcl::Transform3<S>& tf) const {
  std::vector<Vector3<S>> corners;
  corners.reserve(8);
  for (int i = 0; i < 8; ++i) {
    const Vector3<S> c((i & 1) ? radii_[0] : -radii_[0], (i & 2) ? radii_[1] : -radii_[1],
                       (i & 4) ? radii_[2] : -radii_[2]);
    corners.push_back(tf * c);
  }
  return corners;
}

template <typename S>
std::ostream& operator<<(std::ostream& out, const Superellipsoid<S>& shape) {
  return out << "Superellipsoid(a=(" << shape.radii()[0] << ", " << shape.radii()[1] << ", "
             << shape.radii()[2] << "), eps1=" << shape.eps1() << ", eps2=" << shape.eps2() << ")";
}

template class Superellipsoid<float>;
template class Superellipsoid<double>;
template std::ostream& operator<<(std::ostream&, const Superellipsoid<float>&);
template std::ostream& operator<<(std::ostream&, const Superellipsoid<double>&);

}  // namespace fcl_superellipsoid
