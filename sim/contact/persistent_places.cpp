#include "contact/persistent_places.h"

#include <algorithm>
#include <cmath>

namespace fse_sim {
namespace {

/// A place dies once its two points have drifted apart along the contact plane by this share of
/// the patch tolerance: the bodies slid there, and static friction's anchor moves on with them.
constexpr double kDriftPerPatchTolerance = 0.1;
/// The places keep their normal while the pair's stays within this angle of it (rad).
constexpr double kNormalAngle = 0.02;
/// A region's place is not born where a living place stands within this share of the smaller
/// body's size.
constexpr double kNearShareOfSize = 0.05;

struct Candidate {
  PersistentPlace place;
  Eigen::Vector3d on_a;  ///< world
  double separation;     ///< along the normal, now, m
};

/// Twice the area of the convex hull of points of the plane.
double hullArea(std::vector<Eigen::Vector2d> p) {
  if (p.size() < 3) return 0;
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return (u - o).x() * (v - o).y() - (u - o).y() * (v - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
    hull[k++] = p[i - 1];
  }
  double area = 0;
  for (std::size_t i = 0; i + 1 < k; ++i) {
    area += hull[i].x() * hull[i + 1].y() - hull[i + 1].x() * hull[i].y();
  }
  return std::abs(area);
}

/// The deepest candidate (least separation less offset) and, one at a time, those that add the
/// most area (with fewer than three, the farthest), until `count` are chosen.
std::vector<Candidate> reduce(const std::vector<Candidate>& all, const Eigen::Vector3d& n,
                              int count) {
  if (int(all.size()) <= count) return all;
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = n.cross(helper).normalized(), t2 = n.cross(t1);
  auto plane = [&](const Candidate& c) { return Eigen::Vector2d(t1.dot(c.on_a), t2.dot(c.on_a)); };
  auto held = [](const Candidate& c) { return c.separation - c.place.offset; };
  std::size_t deepest = 0;
  for (std::size_t k = 1; k < all.size(); ++k) {
    if (held(all[k]) < held(all[deepest])) deepest = k;
  }
  std::vector<bool> taken(all.size(), false);
  std::vector<Candidate> chosen{all[deepest]};
  std::vector<Eigen::Vector2d> points{plane(all[deepest])};
  taken[deepest] = true;
  while (int(chosen.size()) < count) {
    std::size_t best = 0;
    double best_score = -1;
    for (std::size_t k = 0; k < all.size(); ++k) {
      if (taken[k]) continue;
      std::vector<Eigen::Vector2d> trial = points;
      trial.push_back(plane(all[k]));
      const double score = trial.size() < 3 ? (trial[1] - trial[0]).squaredNorm() : hullArea(trial);
      if (score > best_score) {
        best_score = score;
        best = k;
      }
    }
    taken[best] = true;
    chosen.push_back(all[best]);
    points.push_back(plane(all[best]));
  }
  return chosen;
}

}  // namespace

void updatePlaces(const RigidBody& a, int ia, const RigidBody& b, int ib,
                  const fcl_superellipsoid::ContactManifold<double>& region,
                  const Eigen::Vector3d& normal, double tolerance, int max_places, PairPlaces& kept,
                  std::vector<RigidContact>& out) {
  std::vector<PersistentPlace>& places = kept.places;
  // The normal: the one held, while the pair's stays near it; else the pair's (`normal`, or
  // the region's where they differ), and every place is born again along it.
  Eigen::Vector3d n = -region.normal;
  if (normal.dot(n) >= std::cos(kNormalAngle)) n = normal;
  const Eigen::Vector3d held = a.q * kept.normal_a;
  if (held.squaredNorm() > 0 && held.dot(n) >= std::cos(kNormalAngle)) {
    n = held;
  } else {
    places.clear();
    kept.normal_a = a.q.inverse() * n;
  }
  std::vector<Candidate> candidates;
  for (const PersistentPlace& place : places) {
    const Eigen::Vector3d p_a = a.toWorld(place.r_a);
    const Eigen::Vector3d gap = p_a - b.toWorld(place.r_b);
    const double separation = gap.dot(n);
    if ((gap - separation * n).norm() > kDriftPerPatchTolerance * tolerance) continue;
    if (separation - place.offset - region.distance > tolerance) continue;
    candidates.push_back({place, p_a, separation});
  }
  const std::size_t living = candidates.size();
  const double near = kNearShareOfSize * std::min(a.shape->size(), b.shape->size());
  for (const auto& found : region.points) {
    bool stands_near = false;
    for (std::size_t k = 0; k < living && !stands_near; ++k) {
      const Eigen::Vector3d apart = candidates[k].on_a - found.on_shape;
      stands_near = (apart - apart.dot(n) * n).norm() < near;
    }
    if (stands_near) continue;
    // Born with b's point straight below a's along n, and the offset that holds it level with
    // the deepest place (the two caps of the region reach up to twice the tolerance).
    const double separation = (found.on_shape - found.on_other).dot(n);
    PersistentPlace place;
    place.r_a = a.q.inverse() * (found.on_shape - a.x);
    place.r_b = b.q.inverse() * (found.on_shape - separation * n - b.x);
    place.offset = std::clamp(separation - region.distance, 0.0, 2 * tolerance);
    candidates.push_back({place, found.on_shape, separation});
  }
  const std::vector<Candidate> chosen = reduce(candidates, n, max_places);
  places.clear();
  for (const Candidate& c : chosen) {
    places.push_back(c.place);
    RigidContact contact;
    contact.a = ia;
    contact.b = ib;
    contact.r_a = c.place.r_a;
    contact.r_b = c.place.r_b;
    contact.n = n;
    contact.distance = c.separation;
    contact.offset = c.place.offset;
    contact.anchored = true;
    out.push_back(contact);
  }
}

}  // namespace fse_sim
