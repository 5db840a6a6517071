#include "narrowphase/region_bodies.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "shape/nested_norm.h"
#include "shape/octant.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

template <typename S>
constexpr S kEps = std::numeric_limits<S>::epsilon();

/// A body posed by X: lines and directions taken into its frame.
template <typename S>
class PosedBody : public RegionBody<S> {
 public:
  explicit PosedBody(const fcl::Transform3<S>& X) : X_(X) {}

 protected:
  Vector3<S> toLocal(const Vector3<S>& y) const {
    return X_.linear().transpose() * (y - X_.translation());
  }
  Vector3<S> directionToLocal(const Vector3<S>& v) const { return X_.linear().transpose() * v; }
  Vector3<S> toWorld(const Vector3<S>& p) const { return X_ * p; }
  fcl::Transform3<S> X_;
};

template <typename S>
class SuperellipsoidBody final : public PosedBody<S> {
 public:
  SuperellipsoidBody(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X)
      : PosedBody<S>(X),
        shape_(shape),
        norm_(NestedNorm<S>::gauge(shape)),
        bound_(shape.radii().norm() * S(1.001)) {}
  Vector3<S> support(const Vector3<S>& v) const override {
    return this->toWorld(shape_.supportPoint(this->directionToLocal(v)));
  }
  bool gauge(const Vector3<S>& x, S& value, Vector3<S>& gradient,
             Matrix3<S>& hessian) const override {
    const Vector3<S> q = this->toLocal(x);
    const NestedNormEval<S> e = norm_.evaluate(q.cwiseAbs(), true);
    Matrix3<S> h = e.hessian;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if ((q[i] < S(0)) != (q[j] < S(0))) h(i, j) = -h(i, j);
      }
    }
    const Matrix3<S>& R = this->X_.linear();
    value = e.value;
    gradient = R * intoOctantOf(q, e.gradient);
    hessian = R * h * R.transpose();
    return true;
  }
  S size() const override { return shape_.size(); }
  /// Newton on G(p + s·m) = 1 from s beyond the bounding sphere: G is convex along the line,
  /// so from the right of its largest root the iterates fall to it without overshooting; a
  /// slope ≤ 0 there means the line's lowest G is above 1 (it misses). A line or an iterate
  /// that is not finite (rounding on bodies far apart in scale) misses too.
  std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const override {
    const Vector3<S> p = this->toLocal(y), mm = this->directionToLocal(m);
    S s = -p.dot(mm) + bound_;
    for (int it = 0; it < 200; ++it) {
      const Vector3<S> q = p + s * mm;
      if (!q.allFinite()) return std::nullopt;
      const S g = shape_.gauge(q) - S(1);
      if (g <= S(4) * kEps<S>) return s;
      const S slope = shape_.gaugeGradient(q).dot(mm);
      if (!(slope > S(0))) return std::nullopt;
      const S step = g / slope;
      s -= step;
      if (step <= S(4) * kEps<S> * bound_) return s;
    }
    return s;
  }

 private:
  const Superellipsoid<S>& shape_;
  NestedNorm<S> norm_;
  S bound_;
};

/// An ellipsoid (a sphere: equal radii). A zero radius is taken as a tiny one.
template <typename S>
class EllipsoidBody final : public PosedBody<S> {
 public:
  EllipsoidBody(const Vector3<S>& radii, const fcl::Transform3<S>& X)
      : PosedBody<S>(X), radii_(radii.cwiseMax(Vector3<S>::Constant(kEps<S> * radii.maxCoeff()))) {}
  Vector3<S> support(const Vector3<S>& v) const override {
    const Vector3<S> dw = radii_.cwiseProduct(this->directionToLocal(v));
    return this->toWorld(Vector3<S>(radii_.cwiseProduct(dw) / dw.norm()));
  }
  /// G = ‖D⁻¹q‖, ∇G = D⁻²q/G, ∇²G = (D⁻² − ∇G·∇Gᵀ)/G in the ellipsoid's frame.
  bool gauge(const Vector3<S>& x, S& value, Vector3<S>& gradient,
             Matrix3<S>& hessian) const override {
    const Vector3<S> q = this->toLocal(x);
    const Vector3<S> inv2 = radii_.cwiseProduct(radii_).cwiseInverse();
    value = q.cwiseQuotient(radii_).norm();
    if (!(value > S(0))) return false;
    const Vector3<S> g = inv2.cwiseProduct(q) / value;
    const Matrix3<S> h = (Matrix3<S>(inv2.asDiagonal()) - g * g.transpose()) / value;
    const Matrix3<S>& R = this->X_.linear();
    gradient = R * g;
    hessian = R * h * R.transpose();
    return true;
  }
  S size() const override { return radii_.maxCoeff(); }
  std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const override {
    const Vector3<S> p = this->toLocal(y).cwiseQuotient(radii_);
    const Vector3<S> mm = this->directionToLocal(m).cwiseQuotient(radii_);
    const S a = mm.squaredNorm(), b = p.dot(mm), c = p.squaredNorm() - S(1);
    const S disc = b * b - a * c;
    if (disc < S(0)) return std::nullopt;
    return (-b + std::sqrt(disc)) / a;
  }

 private:
  Vector3<S> radii_;
};

/// A convex polytope: its vertices, and its faces' planes n·x ≤ offset (all in its frame).
template <typename S>
class PolytopeBody final : public PosedBody<S> {
 public:
  struct Face {
    Vector3<S> n;
    S offset;
  };
  PolytopeBody(std::vector<Vector3<S>> vertices, std::vector<Face> faces,
               const fcl::Transform3<S>& X)
      : PosedBody<S>(X), vertices_(std::move(vertices)), faces_(std::move(faces)) {
    S size = S(0);
    for (const Vector3<S>& v : vertices_) size = std::max(size, v.cwiseAbs().maxCoeff());
    size_ = size;
    slack_ = S(1e3) * kEps<S> * std::max(size, S(1e-30));
  }
  S size() const override { return size_; }
  Vector3<S> support(const Vector3<S>& v) const override {
    const Vector3<S> w = this->directionToLocal(v);
    std::size_t best = 0;
    for (std::size_t i = 1; i < vertices_.size(); ++i) {
      if (vertices_[i].dot(w) > vertices_[best].dot(w)) best = i;
    }
    return this->toWorld(vertices_[best]);
  }
  /// The largest s with every face's n·(p + s·m) ≤ offset, if some s holds them all.
  std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const override {
    const Vector3<S> p = this->toLocal(y), mm = this->directionToLocal(m);
    S lo = -std::numeric_limits<S>::infinity(), hi = std::numeric_limits<S>::infinity();
    for (const Face& f : faces_) {
      const S along = f.n.dot(mm), room = f.offset - f.n.dot(p);
      // A face within a millionth of a radian of the line's direction (a side face the line
      // runs along: the region's rim) bounds no s; the line must be inside it.
      if (std::abs(along) <= S(1e-6)) {
        if (room < -slack_) return std::nullopt;
      } else if (along > S(0)) {
        hi = std::min(hi, room / along);
      } else {
        lo = std::max(lo, room / along);
      }
    }
    if (!(hi >= lo - slack_) || !std::isfinite(hi)) return std::nullopt;
    return hi;
  }

 private:
  std::vector<Vector3<S>> vertices_;
  std::vector<Face> faces_;
  S size_;
  S slack_;
};

/// A triangle: its support among its corners; the extent where the line crosses its plane
/// inside it.
template <typename S>
class TriangleBody final : public RegionBody<S> {
 public:
  TriangleBody(const Vector3<S>& a, const Vector3<S>& b, const Vector3<S>& c) : v_{a, b, c} {
    normal_ = (b - a).cross(c - a);
  }
  S size() const override {
    return std::max({(v_[1] - v_[0]).norm(), (v_[2] - v_[1]).norm(), (v_[0] - v_[2]).norm()});
  }
  Vector3<S> support(const Vector3<S>& v) const override {
    const S d0 = v.dot(v_[0]), d1 = v.dot(v_[1]), d2 = v.dot(v_[2]);
    return d0 >= d1 && d0 >= d2 ? v_[0] : (d1 >= d2 ? v_[1] : v_[2]);
  }
  std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const override {
    const S along = normal_.dot(m);
    if (std::abs(along) <= kEps<S> * normal_.norm()) return std::nullopt;  // edge-on
    const S s = normal_.dot(v_[0] - y) / along;
    const Vector3<S> q = y + s * m;
    const S slack = -S(1e3) * kEps<S> * normal_.squaredNorm();
    for (int i = 0; i < 3; ++i) {
      const Vector3<S>& a = v_[i];
      const Vector3<S>& b = v_[(i + 1) % 3];
      if ((b - a).cross(q - a).dot(normal_) < slack) return std::nullopt;
    }
    return s;
  }
  bool corners(std::vector<Vector3<S>>& out) const override {
    out.assign({v_[0], v_[1], v_[2]});
    return true;
  }

 private:
  Vector3<S> v_[3];
  Vector3<S> normal_;
};

/// The s-interval [lo, hi] of the line p + s·m within the body; lo > hi: empty.
template <typename S>
struct Interval {
  S lo, hi;
  static Interval all() {
    return {-std::numeric_limits<S>::infinity(), std::numeric_limits<S>::infinity()};
  }
  static Interval none() { return {S(1), S(0)}; }
  Interval meet(const Interval& o) const { return {std::max(lo, o.lo), std::min(hi, o.hi)}; }
  bool empty() const { return !(lo <= hi); }
};

/// Where |q + s·m| ≤ r for the vectors' components `axes` (2: within r of the z axis; 3: of the
/// origin).
template <typename S>
Interval<S> withinRadius(const Vector3<S>& q, const Vector3<S>& m, S r, int axes) {
  const S a = m.head(axes).squaredNorm(), b = q.head(axes).dot(m.head(axes));
  const S c = q.head(axes).squaredNorm() - r * r;
  // A line within a millionth of a radian of the axis (one along a cylinder's side: the
  // region's rim) is within r everywhere or nowhere; rounding's share of r² counts as within.
  if (a <= S(1e-12)) {
    return c <= S(1e3) * kEps<S> * r * r ? Interval<S>::all() : Interval<S>::none();
  }
  const S disc = b * b - a * c;
  if (disc < S(0)) return Interval<S>::none();
  const S root = std::sqrt(disc);
  return {(-b - root) / a, (-b + root) / a};
}

/// Where |q_z + s·m_z| ≤ h. A line within a millionth of a radian of the slab's planes (one
/// across an end disc's plane: the region's rim) is within it everywhere or nowhere, rounding's
/// share of h counting as within: else a line on an end's plane would leave the slab wherever
/// the rounding of q_z over the tiny m_z puts it.
template <typename S>
Interval<S> withinSlab(S qz, S mz, S h, S size) {
  if (std::abs(mz) <= S(1e-6)) {
    return std::abs(qz) <= h + S(1e3) * kEps<S> * size ? Interval<S>::all() : Interval<S>::none();
  }
  const S t1 = (-h - qz) / mz, t2 = (h - qz) / mz;
  return {std::min(t1, t2), std::max(t1, t2)};
}

/// A cylinder (radius r, half-height h about its z axis) or a capsule (its segment of
/// half-length h, swept by the ball of radius r).
template <typename S>
class RoundBody final : public PosedBody<S> {
 public:
  RoundBody(S r, S h, bool capsule, const fcl::Transform3<S>& X)
      : PosedBody<S>(X), r_(r), h_(h), capsule_(capsule) {}
  /// Where the direction is within rounding of a tie (square to the axis: the side's segment
  /// supports it; along the axis: a cylinder's disc), the tie goes the same way whatever the
  /// rounding: to the +z end, to the disc's centre.
  Vector3<S> support(const Vector3<S>& v) const override {
    const Vector3<S> w = this->directionToLocal(v);
    const S tie = S(64) * kEps<S> * w.norm();
    const S end = w.z() >= -tie ? h_ : -h_;
    if (capsule_) return this->toWorld(Vector3<S>(Vector3<S>(0, 0, end) + r_ * w.normalized()));
    const S side = std::hypot(w.x(), w.y());
    const Vector3<S> rim =
        side > tie ? Vector3<S>(r_ * w.x() / side, r_ * w.y() / side, end) : Vector3<S>(0, 0, end);
    return this->toWorld(rim);
  }
  /// The largest s of the line in the body: for a cylinder, within r of the axis and within
  /// the slab; for a capsule, the largest of that and of the two end balls'.
  std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const override {
    const Vector3<S> q = this->toLocal(y), mm = this->directionToLocal(m);
    Interval<S> best = withinRadius(q, mm, r_, 2).meet(withinSlab(q.z(), mm.z(), h_, size()));
    if (capsule_) {
      for (S end : {-h_, h_}) {
        const Interval<S> ball = withinRadius(Vector3<S>(q - Vector3<S>(0, 0, end)), mm, r_, 3);
        if (!ball.empty() && (best.empty() || ball.hi > best.hi)) best = ball;
      }
    }
    if (best.empty() || !std::isfinite(best.hi)) return std::nullopt;
    return best.hi;
  }
  S size() const override { return std::max(r_, h_ + (capsule_ ? r_ : S(0))); }

 private:
  S r_, h_;
  bool capsule_;
};

/// A cone: its base the disc of radius r at z = −h, its apex at z = h (FCL's cone, h = lz/2).
template <typename S>
class ConeBody final : public PosedBody<S> {
 public:
  ConeBody(S r, S h, const fcl::Transform3<S>& X)
      : PosedBody<S>(X), r_(r), h_(h), slope_(h > S(0) ? r / (S(2) * h) : S(0)) {}
  /// The apex, or the rim point (the base's centre for a direction along −z) of the base,
  /// whichever is farther along v; a tie within rounding goes to the apex.
  Vector3<S> support(const Vector3<S>& v) const override {
    const Vector3<S> w = this->directionToLocal(v);
    const S tie = S(64) * kEps<S> * w.norm() * std::max(r_, h_);
    const S side = std::hypot(w.x(), w.y());
    if (S(2) * h_ * w.z() >= r_ * side - tie) return this->toWorld(Vector3<S>(0, 0, h_));
    const Vector3<S> rim = side > S(64) * kEps<S> * w.norm()
                               ? Vector3<S>(r_ * w.x() / side, r_ * w.y() / side, -h_)
                               : Vector3<S>(0, 0, -h_);
    return this->toWorld(rim);
  }
  /// The largest s of the line in the slab |z| ≤ h where the distance from the axis is at most
  /// slope·(h − z): the line's interval ends at a slab face or on the side, where the
  /// quadratic |xy|² = slope²·(h − z)² has a root; the largest candidate inside is the answer.
  std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const override {
    const Vector3<S> q = this->toLocal(y), mm = this->directionToLocal(m);
    const Interval<S> slab = withinSlab(q.z(), mm.z(), h_, size());
    if (slab.empty()) return std::nullopt;
    const S k2 = slope_ * slope_, up = h_ - q.z();
    const S a = mm.head(2).squaredNorm() - k2 * mm.z() * mm.z();
    const S b = q.head(2).dot(mm.head(2)) + k2 * up * mm.z();
    const S c = q.head(2).squaredNorm() - k2 * up * up;
    S candidates[4] = {slab.lo, slab.hi, std::numeric_limits<S>::quiet_NaN(),
                       std::numeric_limits<S>::quiet_NaN()};
    if (std::abs(a) > S(1e-12)) {
      const S disc = b * b - a * c;
      if (disc >= S(0)) {
        const S root = std::sqrt(disc);
        candidates[2] = (-b - root) / a;
        candidates[3] = (-b + root) / a;
      }
    } else if (b != S(0)) {  // along a generator: one root
      candidates[2] = -c / (S(2) * b);
    }
    const S slack = S(1e3) * kEps<S> * std::max(r_, h_);
    std::optional<S> best;
    for (S s : candidates) {
      if (!std::isfinite(s) || s < slab.lo - slack || s > slab.hi + slack) continue;
      const Vector3<S> p = q + s * mm;
      if (std::hypot(p.x(), p.y()) > slope_ * (h_ - p.z()) + slack) continue;
      if (!best || s > *best) best = s;
    }
    return best;
  }
  S size() const override { return std::max(r_, h_); }

 private:
  S r_, h_, slope_;
};

/// The halfspace n·x ≤ offset (unit n, world).
template <typename S>
class FlatBody final : public RegionBody<S> {
 public:
  FlatBody(const Vector3<S>& n, S offset, const Vector3<S>& on) : n_(n), offset_(offset), on_(on) {}
  Vector3<S> support(const Vector3<S>&) const override { return on_; }
  S size() const override { return S(0); }
  std::optional<S> extent(const Vector3<S>& y, const Vector3<S>& m) const override {
    const S along = n_.dot(m);
    if (!(along > kEps<S>)) return std::nullopt;
    return (offset_ - n_.dot(y)) / along;
  }
  bool unbounded() const override { return true; }

 private:
  Vector3<S> n_;
  S offset_;
  Vector3<S> on_;
};

/// The faces of fcl::Convex's list (count, then that many vertex indices, per face) as planes
/// facing away from the vertices' centroid (Newell's normal: any planar polygon).
template <typename S>
std::vector<typename PolytopeBody<S>::Face> convexFaces(const fcl::Convex<S>& convex) {
  const std::vector<Vector3<S>>& v = convex.getVertices();
  Vector3<S> centroid = Vector3<S>::Zero();
  for (const Vector3<S>& x : v) centroid += x;
  centroid /= S(std::max<std::size_t>(v.size(), 1));
  const std::vector<int>& list = convex.getFaces();
  std::vector<typename PolytopeBody<S>::Face> faces;
  for (std::size_t i = 0; i < list.size();) {
    const int count = list[i];
    Vector3<S> n = Vector3<S>::Zero(), mid = Vector3<S>::Zero();
    for (int k = 0; k < count; ++k) {
      const Vector3<S>& a = v[list[i + 1 + k]];
      const Vector3<S>& b = v[list[i + 1 + (k + 1) % count]];
      n += Vector3<S>((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                      (a.x() - b.x()) * (a.y() + b.y()));
      mid += a;
    }
    i += 1 + count;
    if (count < 3 || !(n.norm() > S(0))) continue;
    n.normalize();
    mid /= S(count);
    if (n.dot(mid - centroid) < S(0)) n = -n;
    faces.push_back({n, n.dot(mid)});
  }
  return faces;
}

}  // namespace

template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const Superellipsoid<S>& shape,
                                          const fcl::Transform3<S>& X) {
  return std::make_unique<SuperellipsoidBody<S>>(shape, X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Sphere<S>& sphere,
                                          const fcl::Transform3<S>& X) {
  return std::make_unique<EllipsoidBody<S>>(Vector3<S>::Constant(sphere.radius), X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Ellipsoid<S>& ellipsoid,
                                          const fcl::Transform3<S>& X) {
  return std::make_unique<EllipsoidBody<S>>(ellipsoid.radii, X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Box<S>& box, const fcl::Transform3<S>& X) {
  const Vector3<S> h = S(0.5) * box.side;
  std::vector<Vector3<S>> corners;
  for (int k = 0; k < 8; ++k) {
    corners.emplace_back(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z());
  }
  std::vector<typename PolytopeBody<S>::Face> faces;
  for (int i = 0; i < 3; ++i) {
    for (S sign : {S(1), S(-1)}) faces.push_back({sign * Vector3<S>::Unit(i), h[i]});
  }
  return std::make_unique<PolytopeBody<S>>(std::move(corners), std::move(faces), X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Convex<S>& convex,
                                          const fcl::Transform3<S>& X) {
  return std::make_unique<PolytopeBody<S>>(convex.getVertices(), convexFaces(convex), X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::TriangleP<S>& triangle,
                                          const fcl::Transform3<S>& X) {
  return std::make_unique<TriangleBody<S>>(X * triangle.a, X * triangle.b, X * triangle.c);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Capsule<S>& capsule,
                                          const fcl::Transform3<S>& X) {
  return std::make_unique<RoundBody<S>>(capsule.radius, S(0.5) * capsule.lz, true, X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Cylinder<S>& cylinder,
                                          const fcl::Transform3<S>& X) {
  return std::make_unique<RoundBody<S>>(cylinder.radius, S(0.5) * cylinder.lz, false, X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> regionBody(const fcl::Cone<S>& cone, const fcl::Transform3<S>& X) {
  return std::make_unique<ConeBody<S>>(cone.radius, S(0.5) * cone.lz, X);
}
template <typename S>
std::unique_ptr<RegionBody<S>> flatRegionBody(const PairHit<S>& hit) {
  const Vector3<S> n = -hit.normal.normalized();
  return std::make_unique<FlatBody<S>>(n, n.dot(hit.on_other), hit.on_other);
}

#define FSE_INSTANTIATE_REGION_BODIES(S)                                         \
  template std::unique_ptr<RegionBody<S>> regionBody(const Superellipsoid<S>&,   \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::Sphere<S>&,      \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::Ellipsoid<S>&,   \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::Box<S>&,         \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::Convex<S>&,      \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::TriangleP<S>&,   \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::Capsule<S>&,     \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::Cylinder<S>&,    \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> regionBody(const fcl::Cone<S>&,        \
                                                     const fcl::Transform3<S>&); \
  template std::unique_ptr<RegionBody<S>> flatRegionBody(const PairHit<S>&);
FSE_INSTANTIATE_REGION_BODIES(float)
FSE_INSTANTIATE_REGION_BODIES(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
