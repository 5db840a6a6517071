#include "physics/rigid_contact_solver.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace fse_sim {
namespace {

/// The other side of a contact: a body, or the fixed bowl (nullptr).
RigidBody* otherBody(std::vector<RigidBody>& bodies, const RigidContact& c) {
  return c.b >= 0 ? &bodies[std::size_t(c.b)] : nullptr;
}

Eigen::Vector3d pointOnB(const std::vector<RigidBody>& bodies, const RigidContact& c) {
  return c.b >= 0 ? bodies[std::size_t(c.b)].toWorld(c.r_b) : c.r_b;
}

Eigen::Vector3d relativeVelocity(const std::vector<RigidBody>& bodies, const RigidContact& c) {
  const RigidBody& a = bodies[std::size_t(c.a)];
  Eigen::Vector3d v = a.velocityAt(a.q * c.r_a);
  if (c.b >= 0) {
    const RigidBody& b = bodies[std::size_t(c.b)];
    v -= b.velocityAt(b.q * c.r_b);
  }
  return v;
}

/// Applies impulse p to a at world point p_a and −p to b (if a body) at p_b, as positional
/// (positions = true) or velocity impulses.
void applyPair(RigidBody& a, RigidBody* b, const Eigen::Vector3d& p, const Eigen::Vector3d& p_a,
               const Eigen::Vector3d& p_b, bool positions) {
  if (positions) {
    a.applyPositionImpulse(p, p_a - a.x);
    if (b != nullptr) b->applyPositionImpulse(-p, p_b - b->x);
  } else {
    a.applyVelocityImpulse(p, p_a - a.x);
    if (b != nullptr) b->applyVelocityImpulse(-p, p_b - b->x);
  }
}

/// The unordered pair of a contact's two sides (−1: the bowl).
long pairKey(const RigidContact& c) {
  const long lo = std::min(c.a, c.b), hi = std::max(c.a, c.b);
  return (lo + 1) * 1000003L + (hi + 1);
}

double pairInverseMass(const RigidBody& a, const RigidBody* b, const Eigen::Vector3d& p_a,
                       const Eigen::Vector3d& p_b, const Eigen::Vector3d& direction) {
  double w = a.inverseMassAt(p_a - a.x, direction);
  if (b != nullptr) w += b->inverseMassAt(p_b - b->x, direction);
  return w;
}

}  // namespace

RigidContactSolver::RigidContactSolver(const Scene& scene) {
  if (scene.friction) {
    friction_ = true;
    mu_static_ = scene.friction->static_;
    mu_dynamic_ = scene.friction->dynamic;
  }
  if (scene.restitution) restitution_ = scene.restitution->coefficient;
  if (scene.gravity) gravity_ = scene.gravity->acceleration.norm();
  skin_ = kRigidSkinPerTolerance * scene.rigid_contact->tolerance;
}

void RigidContactSolver::begin(const std::vector<RigidBody>& bodies,
                               const std::vector<RigidContact>& contacts) {
  vn_before_.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    vn_before_[k] = contacts[k].n.dot(relativeVelocity(bodies, contacts[k]));
  }
  groupContacts(contacts);
}

void RigidContactSolver::groupContacts(const std::vector<RigidContact>& contacts) {
  // A pair's contacts come out of detection one after another; a group is a run of them whose
  // normals (turned to the group's orientation) lie within kGroupAngle of its first's.
  groups_.clear();
  const double cos_limit = std::cos(kGroupAngle);
  std::size_t pair_start = 0;  // the first group of the current pair
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const RigidContact& c = contacts[k];
    if (k > 0 && pairKey(c) != pairKey(contacts[k - 1])) pair_start = groups_.size();
    int found = -1;
    for (std::size_t g = pair_start; g < groups_.size() && found < 0; ++g) {
      const RigidContact& first = contacts[std::size_t(groups_[g].members.front())];
      const double sign = first.a == c.a ? 1.0 : -1.0;
      if (sign * first.n.dot(c.n) >= cos_limit) found = int(g);
    }
    if (found < 0) {
      found = int(groups_.size());
      groups_.emplace_back();
    }
    groups_[std::size_t(found)].members.push_back(int(k));
  }
}
RigidContactSolver::Patch RigidContactSolver::patchOf(const std::vector<RigidBody>& bodies,
                                                      const std::vector<RigidContact>& contacts,
                                                      const Group& group) const {
  Patch patch;
  const RigidContact& first = contacts[std::size_t(group.members.front())];
  patch.a = first.a;
  patch.b = first.b;
  Eigen::Vector3d on_a = Eigen::Vector3d::Zero(), on_b = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (const int k : group.members) {
    const double lambda = lambda_n_[std::size_t(k)];
    if (!(lambda > 0)) continue;
    const RigidContact& c = contacts[std::size_t(k)];
    const bool same = c.a == patch.a;
    const Eigen::Vector3d p_a = bodies[std::size_t(c.a)].toWorld(c.r_a);
    const Eigen::Vector3d p_b = pointOnB(bodies, c);
    on_a += lambda * (same ? p_a : p_b);
    on_b += lambda * (same ? p_b : p_a);
    n += lambda * (same ? c.n : Eigen::Vector3d(-c.n));
    patch.lambda += lambda;
  }
  if (patch.lambda > 0 && n.norm() > 0) {
    patch.on_a = on_a / patch.lambda;
    patch.on_b = on_b / patch.lambda;
    patch.n = n.normalized();
  } else {
    patch.lambda = 0;
  }
  return patch;
}

void RigidContactSolver::projectPositions(std::vector<RigidBody>& bodies,
                                          const std::vector<RigidContact>& contacts, double h) {
  lambda_n_.assign(contacts.size(), 0.0);
  // How far each contact may push in this substep: what its points closed in by (their normal
  // velocity before it), plus an overlap the substep started with at no more than
  // kMaxDepenetrationSpeed.
  pushed_.assign(contacts.size(), 0.0);
  budget_.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    budget_[k] = (std::max(0.0, -vn_before_[k]) + kMaxDepenetrationSpeed) * h;
  }
  for (int iteration = 0; iteration < kPositionIterations; ++iteration) {
    for (const Group& group : groups_) {
      for (const int index : group.members) {
        const auto k = std::size_t(index);
        const RigidContact& c = contacts[k];
        RigidBody& a = bodies[std::size_t(c.a)];
        RigidBody* b = otherBody(bodies, c);
        const Eigen::Vector3d p_a = a.toWorld(c.r_a), p_b = pointOnB(bodies, c);
        const double d = std::min((p_b - p_a).dot(c.n) + c.offset + skin_, budget_[k] - pushed_[k]);
        if (d <= 0) continue;
        const double w = pairInverseMass(a, b, p_a, p_b, c.n);
        if (w <= 0) continue;
        applyPair(a, b, (d / w) * c.n, p_a, p_b, true);
        pushed_[k] += d;
        lambda_n_[k] += d / w;
      }
      if (!friction_) continue;
      // Then each contact's hold, against its own normal impulse; a persistent place's against
      // the patch's: Coulomb's bound holds for the face as a whole, however the sweeps have
      // shared its normal impulse among its places.
      const double patch_lambda = holdPatch(bodies, contacts, group);
      for (const int index : group.members) {
        const RigidContact& c = contacts[std::size_t(index)];
        const double own = lambda_n_[std::size_t(index)];
        if (own > 0) holdPlace(bodies, c, c.anchored ? patch_lambda : own);
      }
    }
  }
  active_.clear();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (lambda_n_[k] > 0) active_.push_back(int(k));
  }
}

void RigidContactSolver::holdPlace(std::vector<RigidBody>& bodies, const RigidContact& c,
                                   double lambda_n) const {
  // Static friction at one contact: its points' tangential slip over the substep (an anchored
  // place: how far its points lie apart along the contact plane), undone while the impulse that
  // takes is below μs·λn.
  if (!(lambda_n > 0)) return;
  RigidBody& a = bodies[std::size_t(c.a)];
  RigidBody* b = otherBody(bodies, c);
  const Eigen::Vector3d p_a = a.toWorld(c.r_a), p_b = pointOnB(bodies, c);
  Eigen::Vector3d slip = p_a - p_b;
  if (!c.anchored) {
    const Eigen::Vector3d prev_b = b != nullptr ? b->toWorldPrevious(c.r_b) : c.r_b;
    slip = (p_a - a.toWorldPrevious(c.r_a)) - (p_b - prev_b);
  }
  slip -= slip.dot(c.n) * c.n;
  const double length = slip.norm();
  if (!(length > 0)) return;
  const Eigen::Vector3d t = slip / length;
  const double w_t = pairInverseMass(a, b, p_a, p_b, t);
  if (!(w_t > 0)) return;
  const double lambda_t = length / w_t;
  if (lambda_t < mu_static_ * lambda_n) applyPair(a, b, -lambda_t * t, p_a, p_b, true);
}

double RigidContactSolver::holdPatch(std::vector<RigidBody>& bodies,
                                     const std::vector<RigidContact>& contacts,
                                     const Group& group) const {
  // Static friction on the patch as a whole: the tangential slip over the substep of the two
  // bodies' material points at its centre, undone while the impulse that takes is below μs
  // times the patch's normal impulse.
  const Patch patch = patchOf(bodies, contacts, group);
  if (!(patch.lambda > 0)) return 0;
  RigidBody& a = bodies[std::size_t(patch.a)];
  RigidBody* b = patch.b >= 0 ? &bodies[std::size_t(patch.b)] : nullptr;
  const Eigen::Vector3d before_a = a.toWorldPrevious(a.q.inverse() * (patch.on_a - a.x));
  const Eigen::Vector3d before_b =
      b != nullptr ? b->toWorldPrevious(b->q.inverse() * (patch.on_b - b->x)) : patch.on_b;
  Eigen::Vector3d slip = (patch.on_a - before_a) - (patch.on_b - before_b);
  slip -= slip.dot(patch.n) * patch.n;
  const double length = slip.norm();
  if (!(length > 0)) return patch.lambda;
  const Eigen::Vector3d t = slip / length;
  const double w_t = pairInverseMass(a, b, patch.on_a, patch.on_b, t);
  if (!(w_t > 0)) return patch.lambda;
  const double lambda_t = length / w_t;
  if (lambda_t < mu_static_ * patch.lambda) {
    applyPair(a, b, -lambda_t * t, patch.on_a, patch.on_b, true);
  }
  return patch.lambda;
}

void RigidContactSolver::solveVelocities(std::vector<RigidBody>& bodies,
                                         const std::vector<RigidContact>& contacts, double h) {
  // Restitution once per pair of bodies (or body and bowl): at its active contact that closed
  // in fastest, after the pair's other contacts have had their normal velocity set to 0
  // (otherwise they would cancel the bounce). Each contact of a face setting its own bounce
  // would spin the bodies up, one lever arm after another, past the energy they met with.
  std::unordered_map<long, std::size_t> fastest;  // pair → its fastest-closing active contact
  for (std::size_t i = 0; i < active_.size(); ++i) {
    const auto k = std::size_t(active_[i]);
    const auto [it, added] = fastest.emplace(pairKey(contacts[k]), k);
    if (!added && vn_before_[k] < vn_before_[it->second]) it->second = k;
  }
  friction_impulse_.assign(groups_.size(), Eigen::Vector3d::Zero());
  for (int iteration = 0; iteration < kVelocityIterations; ++iteration) {
    for (const bool bouncing : {false, true}) {
      for (const int index : active_) {
        const auto k = std::size_t(index);
        const bool primary = fastest.at(pairKey(contacts[k])) == k;
        if (primary != bouncing) continue;
        const double e = primary && std::abs(vn_before_[k]) > 2 * gravity_ * h ? restitution_ : 0.0;
        solveNormalVelocity(bodies, contacts[k], -e * vn_before_[k]);
      }
    }
    if (!friction_) continue;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      slidePatch(bodies, contacts, groups_[g], h, friction_impulse_[g]);
    }
  }
}

void RigidContactSolver::solveNormalVelocity(std::vector<RigidBody>& bodies, const RigidContact& c,
                                             double bounce) const {
  RigidBody& a = bodies[std::size_t(c.a)];
  RigidBody* b = otherBody(bodies, c);
  const Eigen::Vector3d p_a = a.toWorld(c.r_a), p_b = pointOnB(bodies, c);
  const double dvn = -c.n.dot(relativeVelocity(bodies, c)) + std::max(bounce, 0.0);
  const double w_n = pairInverseMass(a, b, p_a, p_b, c.n);
  if (dvn != 0 && w_n > 0) applyPair(a, b, (dvn / w_n) * c.n, p_a, p_b, false);
}

void RigidContactSolver::slidePatch(std::vector<RigidBody>& bodies,
                                    const std::vector<RigidContact>& contacts, const Group& group,
                                    double h, Eigen::Vector3d& applied) const {
  // Dynamic friction on the patch as a whole, at its centre: the normal force is λn/h², so the
  // friction impulse (all sweeps together: `applied`) is at most μd·|fn|·h = μd·λn/h; within
  // that, what stops the tangential motion there.
  const Patch patch = patchOf(bodies, contacts, group);
  if (!(patch.lambda > 0)) return;
  RigidBody& a = bodies[std::size_t(patch.a)];
  RigidBody* b = patch.b >= 0 ? &bodies[std::size_t(patch.b)] : nullptr;
  Eigen::Vector3d v = a.velocityAt(patch.on_a - a.x);
  if (b != nullptr) v -= b->velocityAt(patch.on_b - b->x);
  const Eigen::Vector3d vt = v - patch.n.dot(v) * patch.n;
  const double speed_t = vt.norm();
  if (!(speed_t > 0)) return;
  const Eigen::Vector3d t = vt / speed_t;
  const double w_t = pairInverseMass(a, b, patch.on_a, patch.on_b, t);
  if (!(w_t > 0)) return;
  Eigen::Vector3d total = applied - (speed_t / w_t) * t;
  const double bound = mu_dynamic_ * patch.lambda / h;
  if (total.norm() > bound) total *= bound / total.norm();
  applyPair(a, b, total - applied, patch.on_a, patch.on_b, false);
  applied = total;
}

}  // namespace fse_sim
