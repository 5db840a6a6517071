#include "fcl_glue/pairs/smooth_pair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "shape/symmetric2.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// Newton iterations per start, and how many of the start directions are refined when the
/// first run does not find the shapes separated.
constexpr int kMaxIterations = 200;
constexpr int kRefinedStarts = 4;
/// Fibonacci-sphere directions added to the starts when the shapes overlap.
constexpr int kSphereStarts = 32;

template <typename S>
struct Probe {
  S f;                             // F(v)
  Vector3<S> v;                    // unit
  Vector3<S> a, b;                 // the witnesses
  Eigen::Matrix<S, 3, 3> hessian;  // ∇²F(v)
};

template <typename S>
Probe<S> probe(const SupportMap<S>& A, const SupportMap<S>& B, const Vector3<S>& v) {
  const SupportEval<S> ea = A.evaluate(v), eb = B.evaluate(-v);
  return {ea.value + eb.value, v, ea.point, eb.point, ea.hessian + eb.hessian};
}

/// Two unit vectors that complete v to an orthonormal frame.
template <typename S>
std::array<Vector3<S>, 2> tangents(const Vector3<S>& v) {
  const Vector3<S> helper = std::abs(v[0]) < S(0.6) ? Vector3<S>::UnitX() : Vector3<S>::UnitY();
  const Vector3<S> t1 = v.cross(helper).normalized();
  return {t1, v.cross(t1)};
}

/// Newton's method for F on the unit sphere from v0, with a backtracking line search and the
/// Riemannian Hessian shifted to positive definite where F is not locally convex.
template <typename S>
Probe<S> localMinimum(const SupportMap<S>& A, const SupportMap<S>& B, const Vector3<S>& v0) {
  Probe<S> p = probe(A, B, Vector3<S>(v0.normalized()));
  const S eps = std::numeric_limits<S>::epsilon();
  for (int it = 0; it < kMaxIterations; ++it) {
    const auto [t1, t2] = tangents(p.v);
    // Riemannian gradient and Hessian: P·∇F and P·∇²F·P − (v·∇F)·P, with v·∇F = F (F is
    // 1-homogeneous).
    const Vector3<S> g = p.a - p.b;
    const S g1 = t1.dot(g), g2 = t2.dot(g);
    S h11 = t1.dot(p.hessian * t1) - p.f, h22 = t2.dot(p.hessian * t2) - p.f;
    const S h12 = t1.dot(p.hessian * t2);
    const S scale = std::abs(h11) + std::abs(h22) + std::abs(p.f) + std::numeric_limits<S>::min();
    const S lowest = S(0.5) * (h11 + h22) - hypot2(S(0.5) * (h11 - h22), h12);
    const S floor = S(1e-8) * scale;
    if (!(lowest > floor)) {
      const S shift = floor - (std::isfinite(lowest) ? lowest : -scale);
      h11 += shift;
      h22 += shift;
    }
    const S det = h11 * h22 - h12 * h12;
    S x1 = -(h22 * g1 - h12 * g2) / det, x2 = -(h11 * g2 - h12 * g1) / det;
    if (!std::isfinite(x1) || !std::isfinite(x2)) break;
    // A step of more than a quarter turn is not Newton's any more.
    const S length = hypot2(x1, x2);
    if (length > S(0.5)) {
      x1 *= S(0.5) / length;
      x2 *= S(0.5) / length;
    }
    const S slope = g1 * x1 + g2 * x2;  // ≤ 0: the Hessian is positive definite
    // F's rounding: support values are sums of terms as large as |a|, |b|.
    const S noise = S(16) * eps * (p.a.norm() + p.b.norm() + std::abs(p.f));
    bool moved = false;
    for (S alpha = S(1); alpha > S(1e-12); alpha *= S(0.5)) {
      const Vector3<S> v = (p.v + alpha * (x1 * t1 + x2 * t2)).normalized();
      const Probe<S> q = probe(A, B, v);
      if (q.f <= p.f + S(1e-4) * alpha * slope || (q.f <= p.f + noise && alpha == S(1))) {
        moved = (q.v - p.v).norm() > S(0);
        p = q;
        break;
      }
    }
    if (!moved || length < S(64) * eps) break;
  }
  return p;
}

/// Directions spread evenly over the sphere (a Fibonacci lattice).
template <typename S>
Vector3<S> sphereDirection(int i, int n) {
  const double golden = 2.39996322972865332;  // π(3 − √5)
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vector3<S>(S(r * std::cos(golden * i)), S(r * std::sin(golden * i)), S(z));
}

}  // namespace

template <typename S>
SmoothPairAnswer<S> solveSmoothPair(const SupportMap<S>& A, const SupportMap<S>& B) {
  const Vector3<S> centres = B.centre() - A.centre();
  const Vector3<S> first = centres.squaredNorm() > S(0) ? centres : Vector3<S>::UnitZ();
  Probe<S> best = localMinimum(A, B, first);
  if (!(best.f < S(0))) {
    // Not found separated: overlapping (or touching), where F may have several local minima.
    // Newton from the lowest of: both frames' axes, a lattice over the sphere, the first answer.
    std::vector<Probe<S>> starts;
    auto add = [&](const Vector3<S>& v) { starts.push_back(probe(A, B, v)); };
    for (int i = 0; i < 3; ++i) {
      for (S sign : {S(1), S(-1)}) {
        add(sign * A.pose().linear().col(i));
        add(sign * B.pose().linear().col(i));
      }
    }
    for (int i = 0; i < kSphereStarts; ++i) add(sphereDirection<S>(i, kSphereStarts));
    const int refined = std::min<int>(kRefinedStarts, static_cast<int>(starts.size()));
    std::partial_sort(starts.begin(), starts.begin() + refined, starts.end(),
                      [](const Probe<S>& x, const Probe<S>& y) { return x.f < y.f; });
    for (int k = 0; k < refined; ++k) {
      const Probe<S> p = localMinimum(A, B, starts[k].v);
      if (p.f < best.f) best = p;
    }
  }
  SmoothPairAnswer<S> out;
  out.distance = -best.f;
  out.on_a = best.a;
  out.on_b = best.b;
  out.normal = best.v;
  return out;
}

template <typename S>
std::optional<PairHit<S>> smoothHit(const Pair<S>& pair) {
  const SupportMap<S> shape(*pair.shape, *pair.X_WS);
  SmoothPairAnswer<S> r;
  if (const auto* other = otherAs<Superellipsoid<S>>(pair, fcl::BV_UNKNOWN)) {
    r = solveSmoothPair(shape, SupportMap<S>(*other, *pair.X_WO));
  } else if (const auto* other = otherAs<fcl::Ellipsoid<S>>(pair, fcl::GEOM_ELLIPSOID)) {
    r = solveSmoothPair(shape, SupportMap<S>(*other, *pair.X_WO));
  } else {
    return std::nullopt;
  }
  return PairHit<S>{r.distance, r.on_b, r.on_a, r.normal, -1};
}

#define FSE_INSTANTIATE_SMOOTH_HIT(S)                                                       \
  template SmoothPairAnswer<S> solveSmoothPair(const SupportMap<S>&, const SupportMap<S>&); \
  template std::optional<PairHit<S>> smoothHit(const Pair<S>&);
FSE_INSTANTIATE_SMOOTH_HIT(float)
FSE_INSTANTIATE_SMOOTH_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
