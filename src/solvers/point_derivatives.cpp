// The derivatives of the point distance (docs/math.md → "Derivatives of the distance"): the
// Exact solver's answer N, n, d, then first order from the gauge's derivatives at N
// (shape/gauge_derivatives.h), second order from the optimality conditions
//   N − Q + λ∇G(N) = 0,   G(N) = 1,   λ = d/‖∇G(N)‖,
// differentiated (the implicit function theorem) and solved in N's tangent plane:
//   δN = P·a + n·β,   β = −(∂G/∂θ·δθ)/‖∇G‖,
//   (I + λ·PᵀHP)·a = Pᵀ(δQ − λ·(∂∇G/∂θ)·δθ + λ·H·n·(∂G/∂θ·δθ)/‖∇G‖),
// with P an orthonormal basis of N's tangent plane; solved as the bordered system in (δN, δλ),
// equilibrated, with δN_i = 0 across a crease (the curvature is unbounded there).

#include "fcl_superellipsoid/point_derivatives.h"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>

#include "common/coordinate_range.h"
#include "common/invalid_argument.h"
#include "common/tangent_basis.h"
#include "shape/gauge_derivatives.h"
#include "solvers/exact_rules.h"
#include "solvers/point_gradient.h"
#include "solvers/solvers.h"

namespace fcl_superellipsoid {
namespace {

// N's tangent plane.
template <typename S>
using Reduced = Eigen::Matrix<S, 2, 2>;
template <typename S>
using TangentBasis = Eigen::Matrix<S, 3, 2>;

/// An orthonormal basis of the plane ⊥ the unit n, as a 3 × 2 matrix's columns.
template <typename S>
TangentBasis<S> tangentPlane(const Vector3<S>& n) {
  const std::array<Vector3<S>, 2> basis = detail::tangentBasis(n);
  TangentBasis<S> out;
  out << basis[0], basis[1];
  return out;
}

template <typename S>
Eigen::Matrix<S, 3, 3> cross(const Vector3<S>& v) {
  Eigen::Matrix<S, 3, 3> m;
  m << S(0), -v[2], v[1], v[2], S(0), -v[0], -v[1], v[0], S(0);
  return m;
}

/// A·X = B by Gaussian elimination with full pivoting, as Eigen's FullPivLU solves it (a pivot at
/// most N·ε_machine times the first, largest one counts as 0, and the unknowns past the rank are
/// 0), in straight loops, without FullPivLU's general (dynamic-size) kernels. NaN where A is not
/// finite.
template <typename S, int N, int R>
Eigen::Matrix<S, N, R> solveFullPivot(const Eigen::Matrix<S, N, N>& a_in,
                                      const Eigen::Matrix<S, N, R>& b_in) {
  if (!a_in.allFinite()) {
    return Eigen::Matrix<S, N, R>::Constant(std::numeric_limits<S>::quiet_NaN());
  }
  // Row-major: the eliminations and the back substitution are whole-row operations. Entries left
  // of the diagonal are not kept up to date (never read again).
  Eigen::Matrix<S, N, N, Eigen::RowMajor> a = a_in;
  Eigen::Matrix<S, N, R, Eigen::RowMajor> b = b_in;
  std::array<int, N> column;
  for (int i = 0; i < N; ++i) column[i] = i;
  const S threshold = std::numeric_limits<S>::epsilon() * S(N);
  S first = S(0);
  int rank = 0;
  for (int k = 0; k < N; ++k) {
    int row = k, col = k;
    S largest = S(0);
    for (int i = k; i < N; ++i) {
      for (int j = k; j < N; ++j) {
        if (std::abs(a(i, j)) > largest) {
          largest = std::abs(a(i, j));
          row = i;
          col = j;
        }
      }
    }
    if (k == 0) first = largest;
    if (!(largest > threshold * first)) break;  // also a first pivot of 0
    a.row(k).swap(a.row(row));
    b.row(k).swap(b.row(row));
    a.col(k).swap(a.col(col));
    std::swap(column[k], column[col]);
    const S inverse = S(1) / a(k, k);
    for (int i = k + 1; i < N; ++i) {
      const S f = a(i, k) * inverse;
      a.row(i) -= f * a.row(k);
      b.row(i) -= f * b.row(k);
    }
    rank = k + 1;
  }
  Eigen::Matrix<S, N, R, Eigen::RowMajor> y = Eigen::Matrix<S, N, R, Eigen::RowMajor>::Zero();
  for (int i = rank - 1; i >= 0; --i) {
    Eigen::Matrix<S, 1, R> v = b.row(i);
    for (int j = i + 1; j < rank; ++j) v -= a(i, j) * y.row(j);
    y.row(i) = v / a(i, i);
  }
  Eigen::Matrix<S, N, R> x;
  for (int i = 0; i < N; ++i) x.row(column[i]) = y.row(i);
  return x;
}

/// The pose columns (ω, v) of a point's and a normal's Jacobians from their Q Jacobians, all in
/// one frame (point_derivatives.h): moving the shape by ξ moves N by ω × N + v and Q, seen from
/// the shape, by −(ω × Q + v).
template <typename S>
void poseJacobians(const Vector3<S>& q, PointDistanceDerivatives<S>* out) {
  const Eigen::Matrix<S, 3, 3> qx = cross(q);
  const Vector3<S>& point = out->value.nearest_point;
  const Vector3<S>& normal = out->value.normal;
  out->nearest_point_d_pose << -cross(point) + out->nearest_point_d_query * qx,
      Eigen::Matrix<S, 3, 3>::Identity() - out->nearest_point_d_query;
  out->normal_d_pose << -cross(normal) + out->normal_d_query * qx, -out->normal_d_query;
}

/// The second order (the Jacobians and their `differentiable` test) of the query q's answer in
/// *out, which holds the first order: a function of its own, so that the gradient alone does not
/// set up its frame.
template <typename S>
EIGEN_DONT_INLINE void addJacobians(const Superellipsoid<S>& shape, const Vector3<S>& q,
                                    PointDistanceDerivatives<S>* out_pointer) {
  PointDistanceDerivatives<S>& out = *out_pointer;
  const Vector3<S>& point = out.value.nearest_point;
  const Vector3<S>& n = out.value.normal;
  const S d = out.value.distance;
  const detail::GaugeDerivatives<S> gauge = detail::gaugeDerivatives(shape, point, true);
  const S g = gauge.gradient.norm();
  const S lambda = d / g;
  const S floor = std::sqrt(std::numeric_limits<S>::epsilon());
  // Inside, Q at a centre of curvature of N: an eigenvalue 1 + λ·(curvature) of the system in
  // N's tangent plane, K = I + λ·PᵀHP, vanishes (outside, λ > 0 and K ≥ I): the distance is
  // differentiable there, N is not. Floored, so the Jacobians stay finite (and large) there.
  Reduced<S> k;
  TangentBasis<S> tangent;
  if (lambda < S(0)) {
    tangent = tangentPlane(n);
    k = Reduced<S>::Identity() + lambda * tangent.transpose() * gauge.hessian * tangent;
    // K's eigenvalues, mean ± radius.
    const S mean = (k(0, 0) + k(1, 1)) / S(2);
    const S radius = std::hypot((k(0, 0) - k(1, 1)) / S(2), k(0, 1));
    if (mean - radius <= floor * std::max(S(1), mean + radius)) out.differentiable = false;
  }
  out.has_jacobians = true;

  // The differentiated optimality conditions, unknowns (δN, δλ), right-hand sides for δQ (3) and
  // δθ (5). A crease's direction has δN_i = 0 (its row and column become the identity's). Rows
  // and columns are scaled to unit diagonal (H is unbounded near a crease, and the small
  // curvatures beside a large one would be lost in a solve of the raw system).
  Eigen::Matrix<S, 4, 4> system = Eigen::Matrix<S, 4, 4>::Zero();
  system.template topLeftCorner<3, 3>() =
      Eigen::Matrix<S, 3, 3>::Identity() + lambda * gauge.hessian;
  system.template topRightCorner<3, 1>() = gauge.gradient;
  system.template bottomLeftCorner<1, 3>() = gauge.gradient.transpose();
  Eigen::Matrix<S, 4, 8> rhs = Eigen::Matrix<S, 4, 8>::Zero();
  rhs.template topLeftCorner<3, 3>().setIdentity();
  rhs.template topRightCorner<3, 5>() = -lambda * gauge.gradient_d_parameters;
  rhs.template bottomRightCorner<1, 5>() = -gauge.d_parameters;
  bool crease = false;
  for (int i = 0; i < 3; ++i) {
    if (!gauge.crease[i]) continue;
    crease = true;
    system.row(i).setZero();
    system.col(i).setZero();
    system(i, i) = S(1);
    rhs.row(i).setZero();
  }
  Eigen::Matrix<S, 4, 1> scale;
  for (int i = 0; i < 3; ++i) scale[i] = S(1) / std::sqrt(std::max(std::abs(system(i, i)), S(1)));
  scale[3] =
      S(1) / std::max(scale.template head<3>().cwiseProduct(gauge.gradient).cwiseAbs().maxCoeff(),
                      std::numeric_limits<S>::min());
  const Eigen::Matrix<S, 4, 4> scaled = scale.asDiagonal() * system * scale.asDiagonal();
  Eigen::Matrix<S, 4, 8> solution =
      scale.asDiagonal() * solveFullPivot<S, 4, 8>(scaled, scale.asDiagonal() * rhs);
  if (!solution.allFinite() && lambda < S(0)) {
    // Singular (Q at a centre of curvature): the floored tangent-plane inverse instead.
    Eigen::SelfAdjointEigenSolver<Reduced<S>> eigen;
    eigen.computeDirect(k);
    const Reduced<S> k_inverse = eigen.eigenvectors() *
                                 eigen.eigenvalues().cwiseMax(floor).cwiseInverse().asDiagonal() *
                                 eigen.eigenvectors().transpose();
    const Eigen::Matrix<S, 3, 3> projector = tangent * k_inverse * tangent.transpose();
    const Eigen::Matrix<S, 1, 5> beta = -gauge.d_parameters / g;  // n·δN per δθ
    solution.template topLeftCorner<3, 3>() = projector;
    solution.template topRightCorner<3, 5>() =
        projector * (-lambda * gauge.gradient_d_parameters - lambda * gauge.hessian * n * beta) +
        n * beta;
  }
  out.nearest_point_d_query = solution.template topLeftCorner<3, 3>();
  out.nearest_point_d_shape = solution.template topRightCorner<3, 5>();

  // The normal: from n = (Q − N)/d where the curvature term dominates (|λ|·‖H‖ ≥ 1, also across
  // a crease), else from n = ∇G/‖∇G‖ (near the surface, where dividing by d would magnify N's
  // rounding).
  const Eigen::Matrix<S, 3, 3> across = Eigen::Matrix<S, 3, 3>::Identity() - n * n.transpose();
  if (d != S(0) && (crease || std::abs(lambda) * gauge.hessian.cwiseAbs().maxCoeff() >= S(1))) {
    out.normal_d_query = (across - out.nearest_point_d_query) / d;
    out.normal_d_shape = -(out.nearest_point_d_shape + n * out.d_shape.transpose()) / d;
  } else {
    out.normal_d_query = across * gauge.hessian * out.nearest_point_d_query / g;
    out.normal_d_shape =
        across * (gauge.hessian * out.nearest_point_d_shape + gauge.gradient_d_parameters) / g;
    if (crease) out.differentiable = false;  // on the surface at a crease: a normal cone
  }
  poseJacobians(q, &out);
}

template <typename S>
PointDistanceDerivatives<S> derivativesInShapeFrame(const Superellipsoid<S>& shape,
                                                    const Vector3<S>& q, DerivativeOrder order,
                                                    const DistanceOptions<S>& options) {
  detail::validateQuery("pointDistanceDerivatives", q, options);
  if (options.method != DistanceMethod::kExact) {
    detail::throwInvalidArgument("pointDistanceDerivatives",
                                 "options.method must be DistanceMethod::kExact",
                                 std::string(toString(options.method)));
  }
  if (order != DerivativeOrder::kGradient && order != DerivativeOrder::kJacobians) {
    detail::throwInvalidArgument("pointDistanceDerivatives", "order must be a DerivativeOrder",
                                 static_cast<int>(order));
  }
  PointDistanceDerivatives<S> out;
  S runner_up = std::numeric_limits<S>::infinity();
  out.value = detail::solve<S>(shape, q, nullptr, options, &runner_up);
  const Vector3<S>& point = out.value.nearest_point;
  const Vector3<S>& n = out.value.normal;
  const S d = out.value.distance;
  out.d_query = n;
  out.d_pose = detail::poseGradient(n, point);
  out.d_shape = detail::shapeGradient(shape, point, n);
  out.differentiable =
      !detail::hasSeveralNearestPoints(shape.size(), q, point, d, runner_up, options.tolerance);

  if (order == DerivativeOrder::kJacobians) {
    addJacobians(shape, q, &out);
  } else {
    out.nearest_point_d_query.setZero();
    out.nearest_point_d_pose.setZero();
    out.nearest_point_d_shape.setZero();
    out.normal_d_query.setZero();
    out.normal_d_pose.setZero();
    out.normal_d_shape.setZero();
  }
  return out;
}

}  // namespace

template <typename S>
PointDistanceDerivatives<S> pointDistanceDerivatives(
    const Superellipsoid<S>& shape, const detail::NonDeduced<Vector3<S>>& p_SQ,
    DerivativeOrder order, const detail::NonDeduced<DistanceOptions<S>>& options) {
  return derivativesInShapeFrame(shape, p_SQ, order, options);
}

template <typename S>
PointDistanceDerivatives<S> pointDistanceDerivatives(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const detail::NonDeduced<Vector3<S>>& p_WQ, DerivativeOrder order,
    const detail::NonDeduced<DistanceOptions<S>>& options) {
  detail::validateQuery("pointDistanceDerivatives", p_WQ, options);
  detail::checkPose("pointDistanceDerivatives", "X_WS", X_WS);
  const Vector3<S> p_SQ = X_WS.inverse(Eigen::Isometry) * p_WQ;
  PointDistanceDerivatives<S> out = derivativesInShapeFrame(shape, p_SQ, order, options);
  const Eigen::Matrix<S, 3, 3> r = X_WS.linear();
  out.value.nearest_point = X_WS * out.value.nearest_point;
  out.value.normal = r * out.value.normal;
  out.d_query = out.value.normal;
  out.d_pose = detail::poseGradient(out.value.normal, out.value.nearest_point);
  if (out.has_jacobians) {
    out.nearest_point_d_query = r * out.nearest_point_d_query * r.transpose();
    out.nearest_point_d_shape = r * out.nearest_point_d_shape;
    out.normal_d_query = r * out.normal_d_query * r.transpose();
    out.normal_d_shape = r * out.normal_d_shape;
    poseJacobians(p_WQ, &out);
  }
  return out;
}

template PointDistanceDerivatives<float> pointDistanceDerivatives(const Superellipsoid<float>&,
                                                                  const Vector3<float>&,
                                                                  DerivativeOrder,
                                                                  const DistanceOptions<float>&);
template PointDistanceDerivatives<double> pointDistanceDerivatives(const Superellipsoid<double>&,
                                                                   const Vector3<double>&,
                                                                   DerivativeOrder,
                                                                   const DistanceOptions<double>&);
template PointDistanceDerivatives<float> pointDistanceDerivatives(const Superellipsoid<float>&,
                                                                  const fcl::Transform3<float>&,
                                                                  const Vector3<float>&,
                                                                  DerivativeOrder,
                                                                  const DistanceOptions<float>&);
template PointDistanceDerivatives<double> pointDistanceDerivatives(const Superellipsoid<double>&,
                                                                   const fcl::Transform3<double>&,
                                                                   const Vector3<double>&,
                                                                   DerivativeOrder,
                                                                   const DistanceOptions<double>&);

}  // namespace fcl_superellipsoid
