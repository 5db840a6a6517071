// The Exact method: Newton on the optimality (KKT) conditions of
//
//     min ‖N − Q‖  subject to N on the surface,
//
// in the first octant (the shape is symmetric in each coordinate plane: solve for |Q| and
// reflect back), in one of two equivalent formulations:
//
//  primal  unknowns N, μ:   Q − N = μ·∇G(N),  G(N) = 1;
//          Newton matrix [I + μ∇²G, ∇G; ∇Gᵀ, 0]. ∇²G is bounded where ε ≤ 1 and grows like
//          t^(2/ε − 2) near a coordinate plane where ε > 1 (the surface has a curvature
//          singularity there: the "crease" where the paper's method also loses convergence).
//  dual    unknowns n (unit outward normal), d:   Q = ∇h(n) + d·n,  ‖n‖ = 1,
//          with h the support function and ∇h(n) the surface point of normal n;
//          Newton matrix [∇²h + d·I, n; nᵀ, 0]. h is the gauge of the dual superellipsoid
//          (radii 1/a, exponents 2 − ε), so ∇²h is bounded exactly where ε ≥ 1.
//
// The solver starts in the formulation that is smooth for the shape's exponents and, if
// Newton stalls there (mixed shapes such as (0.1, 1.9) are singular in both), continues in
// the other from the best point so far. Every iterate is kept on the surface (primal: radial
// re-projection N ← N/G(N); dual: N = ∇h(n) lies on it by construction) and inside the first
// octant (a component that would turn negative shrinks tenfold instead). A step that does not
// reduce the error is halved, up to four times.
//
// Starts: outside, the radial projection (the problem is convex: one minimum; a caller's warm
// start, Query::hint, goes first and saves the rest when it converges; far from a box-like
// shape the support point of Q's direction goes first if its error is smaller), then, if that
// stalls, the surface points whose normals point at Q and along the contact direction found
// (∇h(n), the support point), and the radial projection of Q clamped into the bounding box; if
// Newton still stalls, the bracketed nested projection of outside_projection.h settles it. Inside,
// the problem is not convex (points on the medial axis have several nearest points; a box-like
// shape has a local minimum on each face), so Newton also runs from the three axis
// projections (closed form: move one coordinate until G = 1), and the nearest converged
// answer wins; deep inside an elongated shape, also from the diagonals of the cross-sections.
// Below G = 0.9 the direction cover's guess (solvers/direction_cover.h) competes with the radial
// start for first place. The search stops at the first answer a certificate proves global
// (rolling ball, Hessian ball, direction cover at any depth: searchInside). Each start has its own
// share of one iteration budget. On a surface of revolution about z the whole search runs in Q's
// meridian half-plane (the constructor), where the nearest points are.
//
// Convergence is judged by the paper's error (Eq. 7) so all methods share one yardstick.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "common/tangent_basis.h"
#include "shape/nested_norm.h"
#include "shape/shape_caches.h"
#include "solvers/ball_certificate.h"
#include "solvers/exact_rules.h"
#include "solvers/outside_projection.h"
#include "solvers/solvers.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

namespace rules = exact_rules;

/// A candidate answer in the first octant.
template <typename S>
struct Candidate {
  Vector3<S> point;                // on the surface
  Vector3<S> normal;               // unit outward normal at point
  Vector3<S> gradient;             // ∇G at point
  Eigen::Matrix<S, 3, 3> hessian;  // ∇²G at point (NaN: a converged dual answer, newtonDual)
  S error = std::numeric_limits<S>::infinity();
  int iterations = 0;
};

template <typename S>
class ExactSolver {
 public:
  ExactSolver(const Query<S>& q)
      : q_(q),
        y_(q.x.cwiseAbs()),
        primal_(NestedNorm<S>::gauge(q.shape)),
        dual_(NestedNorm<S>::support(q.shape)),
        primal_first_(primalIsSmoother(q.shape)),
        revolution_(q.shape.eps1() == S(1) && q.shape.radii()[0] == q.shape.radii()[1]) {
    if (revolution_) {
      // A surface of revolution about z: Q's nearest points lie in its meridian half-plane
      // (rotating a surface point into it about z brings it no farther from Q), so the solver
      // works there, with Q rotated about z onto the half-plane y = 0, x ≥ 0; finish() turns
      // the answer back. Every iterate stays on that plane (G's and h's derivatives across it
      // vanish there exactly), and the ring of nearest points that Q near the axis has on a
      // round cross-section becomes a single point.
      const S rho = std::hypot(y_[0], y_[1]);
      if (rho >= std::numeric_limits<S>::min()) {
        cos_ = y_[0] / rho;
        sin_ = y_[1] / rho;
      } else if (rho > S(0)) {
        // Subnormal: rho keeps too few bits for the quotients to be a unit vector. Scaled by
        // 2^digits (exact), the coordinates are normal.
        const S scale = std::ldexp(S(1), std::numeric_limits<S>::digits);
        const S x = y_[0] * scale, y = y_[1] * scale, r = std::hypot(x, y);
        cos_ = x / r;
        sin_ = y / r;
      }
      y_ = Vector3<S>(rho, S(0), y_[2]);
    }
  }

  PointDistanceResult<S> solve() {
    // One evaluation at Q gives both G(Q), which says the side, and the radial start.
    const NestedNormEval<S> at_y = primal_.evaluate(y_, true);
    const S g_y = at_y.value;
    if (g_y == S(1)) return finish(candidateFrom(y_, at_y), false);
    inside_ = g_y < S(1);
    sign_ = inside_ ? S(-1) : S(1);
    if (g_y == S(0)) {
      Candidate<S> centre = solveAtCentre();
      centre.iterations = iterations_;
      return finish(centre, true);
    }

    const Candidate<S> radial = candidateFrom(y_, at_y);
    const bool warm = !inside_ && q_.hint != nullptr && !q_.hint->isZero(S(0));
    Candidate<S> best = refine(firstStart(radial, warm, g_y));
    noteConverged(best);
    if (inside_) {
      searchInside(g_y, &best);
    } else {
      searchOutside(radial, warm, &best);
    }
    best.iterations = iterations_;  // all starts share one budget
    return finish(best, inside_);
  }

 private:
  /// The first start: the warm start (outside, a hint); else the radial projection, unless
  /// another start is nearer the answer: far outside a box-like shape the support point of Q's
  /// direction, deeper inside the direction cover's guess (then the radial projection becomes
  /// the second start, second_start_).
  Candidate<S> firstStart(const Candidate<S>& radial, bool warm, S g_y) {
    // Outside the problem is convex: a warm start that converges is the answer.
    Candidate<S> first = warm ? candidateOnRay(toMeridian(q_.hint->cwiseAbs())) : radial;
    if (!inside_ && !warm && primal_first_ &&
        radial.error > S(rules::kSupportStartError) * q_.shape.size()) {
      // Far from a box-like shape the radial start lands near a corner whose normal points
      // well away from Q. The surface point whose normal is Q's direction (∇h is
      // 0-homogeneous: h's gradient at Q itself) is within about size/‖Q‖ of the answer's
      // normal; the start with the smaller error goes first.
      const Candidate<S> support = candidateOnRay(dual_.gradient(y_));
      if (support.error < radial.error) first = support;
    }
    if (inside_ && g_y < S(rules::kCoverGauge)) {
      // Deeper inside, the first start is the nearer to Q of the radial projection and the
      // direction cover's guess of the nearest point's normal (solvers/direction_cover.h), often
      // the second (the radial projection heads for a box-like shape's corners). The other is
      // the second start (searchInside).
      const Vector3<S> guess = directionCover(q_.shape).startNear(y_);
      second_start_ = guess;
      if ((guess - y_).squaredNorm() < (radial.point - y_).squaredNorm()) {
        second_start_ = radial.point;
        first = candidateOnRay(guess);
      }
    }
    return first;
  }

  /// Outside, the problem is convex, so any converged start is the answer; the starts after
  /// the first are for where Newton did not converge: the radial start after a warm one, the
  /// support points of Q's direction and of the answer's contact direction, Q clamped into the
  /// bounding box, the bracketed projection, and at a crease the contact direction.
  void searchOutside(const Candidate<S>& radial, bool warm, Candidate<S>* best) {
    if (warm && best->error > q_.tolerance) tryStart(radial, best);
    if (best->error <= q_.tolerance) return;
    // On elongated shapes the radial start can be far off. The surface points whose normal
    // points at Q, and along the best answer's contact direction, are better starts.
    // (The shape's mirror symmetry: h(n) = h(|n|), and a component of Q − N can be negative.)
    for (const Vector3<S>& direction : {Vector3<S>(y_), Vector3<S>(y_ - best->point)}) {
      const Vector3<S> n = direction.cwiseAbs().normalized();
      if (n.allFinite()) tryStart(dual_.evaluate(n, false).gradient, best);
    }
    // Q clamped into the bounding box, then projected radially: on a cigar-like shape this
    // lands beside Q along the long axis, away from the sharp tips where Newton stalls.
    const Vector3<S> clamped = y_.cwiseMin(q_.shape.radii());
    if (best->error > q_.tolerance && clamped.squaredNorm() > S(0)) tryStart(clamped, best);
    if (best->error > q_.tolerance) {
      // Newton stalled (mixed exponents on an elongated shape). The bracketed projection is
      // exact; every surface point is at least the distance away, so the nearer point wins
      // even if its Eq. 7 error, which needs the normal, stays above the tolerance at a crease.
      const Candidate<S> projected = candidateOnRay(projectOutside(q_.shape, y_));
      if ((y_ - projected.point).squaredNorm() <= (y_ - best->point).squaredNorm()) {
        *best = projected;
      }
    }
    // At a crease the surface formula's normal is one element of the normal cone, and Eq. 7
    // with it stays large though the point is right: the contact direction may be another.
    if (best->error > q_.tolerance) tryContactDirection(best);
  }

  /// Inside, the problem is not convex: starts beyond the radial one, until the best answer so far
  /// is certified to be the global nearest point: the ball around Q through it lies inside the
  /// shape, so nothing on the surface is nearer (exact_rules::certifiedGlobal, the rolling ball,
  /// or ball_certificate.h, the Hessian bound over that ball).
  void searchInside(S g_y, Candidate<S>* best) {
    noteSurfacePoint(best->point);
    // The rolling radius costs thousands of evaluations on a new shape (then it is kept): it is
    // asked for only where neither the Hessian ball, which needs nothing built, nor the direction
    // cover, which evaluates only the cells it reads, certifies. The certificates are tried in
    // another order then, not on other answers: the search stops where it would have.
    S rolling_radius = ShapeCaches<S>::of(q_.shape).knownMinRadiusOfCurvature();  // NaN: not yet
    Vector3<S> checked = Vector3<S>::Constant(S(-1));  // the last answer the Hessian ball refused
    auto certified = [&] {
      if (best->error > q_.tolerance) return false;
      const S distance = (y_ - best->point).norm();
      if (rules::certifiedGlobal(distance, q_.tolerance, rolling_radius)) return true;
      if (best->point == checked) return false;
      checked = best->point;
      if (ballCertified(*best, distance)) return true;
      if (!std::isnan(rolling_radius)) return coverCertified(*best, distance);
      if (coverCertified(*best, distance)) return true;
      rolling_radius = q_.shape.minRadiusOfCurvature();
      return rules::certifiedGlobal(distance, q_.tolerance, rolling_radius);
    };
    if (certified()) return;
    // Deeper inside, the second start is the one solve() did not take (the radial projection
    // or the cover's guess); nearer the surface the cover's start is not tried (the axis
    // projections below find the other basins there as often, without it).
    if (!second_start_.isZero(S(0))) {
      tryStart(second_start_, best);
      if (certified()) return;
    }
    const std::array<Vector3<S>, 3> projections = axisProjections();
    for (int i = 0; i < 3; ++i) {
      if (revolution_ && i == 1) continue;  // in the meridian plane: the x one's twin
      tryStart(projections[i], best);
      if (certified()) return;
    }
    tryRingRotations(best);  // if nothing converged: a start creeping along a ring (below)
    if (certified()) return;
    // On a coordinate plane every start above lies on it too, and the plane is a mirror
    // symmetry: Newton never leaves it, though for ε > 1 the nearest points can be off it
    // (the plane is a saddle there). Start once more from a point tilted off each such plane.
    // (One start per such plane, and one off all of them at once for a point on an axis.)
    Vector3<S> all_tilted = y_;
    int planes = 0;
    for (int i = 0; i < 3; ++i) {
      if (y_[i] > rules::nearPlaneFraction<S>() * q_.shape.radii()[i]) continue;
      Vector3<S> tilted = y_;
      tilted[i] += S(0.5) * q_.shape.radii()[i];
      all_tilted[i] = tilted[i];
      ++planes;
      tryStart(tilted, best);
    }
    if (planes > 1) tryStart(all_tilted, best);
    if (certified()) return;
    // Deep in an elongated shape the nearest point can lie off the axis directions of the
    // cross-section through Q (a diamond-like cross-section, ε > 1, is nearest on its
    // diagonal faces). When the answer so far is farther than a quarter of a cross-section's
    // smaller radius, start once more along that cross-section's diagonal.
    const Vector3<S>& a = q_.shape.radii();
    const S best_distance = (y_ - best->point).norm();
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      if (best_distance > S(rules::kDiagonalStartDepth) * std::min(a[j], a[k])) {
        Vector3<S> start = y_;
        start[j] += S(0.5) * a[j];
        start[k] += S(0.5) * a[k];
        tryStart(start, best);
        if (certified()) return;
      }
    }
    tryRingRotations(best);            // if nothing converged yet
    if (g_y < S(rules::kDeepGauge)) {  // deep inside: the centre's candidates may be nearer
      const Candidate<S> other = solveAtCentre();
      noteConverged(other);
      if (isBetter(other, *best)) *best = other;
    }
  }

  /// The Hessian-ball certificate (ball_certificate.h) of a converged inside answer c at distance
  /// d from Q; on a surface of revolution, of its meridian disc (hessianDiscCertified), which
  /// also holds below a sharp tip, where the ball's box reaches the axis.
  bool ballCertified(const Candidate<S>& c, S distance) const {
    if (!revolution_) {
      return hessianBallCertified(primal_, y_, c.point, c.gradient, distance, c.error);
    }
    const Vector3<S> in_plane(std::hypot(c.point[0], c.point[1]), S(0), c.point[2]);
    return hessianDiscCertified(primal_, y_, in_plane, c.gradient, distance, c.error);
  }

  /// The direction cover's certificate (ball_certificate.h, directionCoverCertified) for a
  /// converged inside answer c at distance d from Q, tried on at most kCoverAttempts answers.
  bool coverCertified(const Candidate<S>& c, S distance) {
    if (cover_attempts_ == rules::kCoverAttempts) return false;
    ++cover_attempts_;
    return directionCoverCertified(directionCover(q_.shape), primal_, y_, c.point, c.normal,
                                   c.gradient, distance, S(rules::kCoverCapLimit), &split_budget_);
  }

  /// Near the axis of a (nearly) round cross-section the nearest points form a (nearly)
  /// degenerate ring around that axis, a valley in which Newton's straight steps leave the
  /// valley and are halved to nothing: starts creep along the ring (docs/hardening.md,
  /// finding 12). If no start has converged, the nearest surface point found so far rotated
  /// about an axis into Q's meridian plane (its distance from the axis and its height kept)
  /// lands on the ring's lowest point for a surface of revolution and next to it for a nearly
  /// round one. (The nearest point, not the one of smallest error: a start stuck on a mirror
  /// plane's saddle can have a smaller error than one creeping along the ring, but every
  /// surface point bounds the distance from above, so the nearest one is the closer guess.)
  /// The axes go in the order of how nearly the rotated point stays on the surface. Such a
  /// start converges in a few iterations where it applies, so each gets a small share of the
  /// budget.
  void tryRingRotations(Candidate<S>* best) {
    if (best->error <= q_.tolerance) return;
    const Vector3<S> seed = nearest_point_;
    std::array<std::pair<S, Vector3<S>>, 3> rotations;
    int count = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const int j = (axis + 1) % 3, k = (axis + 2) % 3;
      const S q_radius = std::hypot(y_[j], y_[k]);
      const S n_radius = std::hypot(seed[j], seed[k]);
      if (!(q_radius > S(0))) continue;
      Vector3<S> rotated;
      rotated[axis] = seed[axis];
      rotated[j] = n_radius * (y_[j] / q_radius);
      rotated[k] = n_radius * (y_[k] / q_radius);
      // Already in Q's meridian about this axis (to √ε × size): nothing to gain.
      if ((rotated - seed).norm() <= rules::nearPlaneFraction<S>() * q_.shape.size()) {
        continue;
      }
      rotations[count++] = {std::abs(primal_.value(rotated) - S(1)), rotated};
    }
    for (int i = 1; i < count; ++i) {  // at most three: insertion order by the first member
      for (int k = i; k > 0 && rotations[k].first < rotations[k - 1].first; --k) {
        std::swap(rotations[k], rotations[k - 1]);
      }
    }
    for (int i = 0; i < count && best->error > q_.tolerance; ++i) {
      tryStart(rotations[i].second, best, rules::kRingStartIterations);
    }
  }

  /// The exact centre: every direction is radial, and the nearest point depends on ε (the end
  /// of the shortest semi-axis for a box-like shape, a face centre for an octahedron-like one).
  /// The axis tips are stationary points, so they are candidates as they are; Newton runs
  /// from the radial projections of the diagonal directions. Ties keep the first candidate,
  /// in the order +x, +y, +z tips, then the diagonals.
  Candidate<S> solveAtCentre() {
    Candidate<S> best;
    for (int i = 0; i < 3; ++i) {
      Vector3<S> tip = Vector3<S>::Zero();
      tip[i] = q_.shape.radii()[i];
      const Candidate<S> c = candidateOnRay(tip);
      if (i == 0 || (c.point.squaredNorm() < best.point.squaredNorm())) best = c;
    }
    for (const Vector3<S>& direction :
         {Vector3<S>(1, 1, 1), Vector3<S>(1, 1, 0), Vector3<S>(1, 0, 1), Vector3<S>(0, 1, 1)}) {
      const Candidate<S> c = refine(candidateOnRay(direction));
      if (c.error <= q_.tolerance && c.point.squaredNorm() < best.point.squaredNorm()) best = c;
    }
    return best;
  }

  /// Outside, the best point N with the contact direction n = (Q − N)/‖Q − N‖ as its normal, if
  /// n is in N's normal cone to the tolerance: the duality gap h(n) − n·N (h the support
  /// function) is ≥ 0, and ‖Q − N‖ exceeds the distance by at most the gap, since every point
  /// of the shape is at least n·Q − h(n) away; where that gap exceeds the tolerance, ‖Q − N‖
  /// less the lower bound of a better direction (dualLowerBound). The candidate's error is the
  /// larger of the gap and Eq. 7 with n (rounding: n is parallel to Q − N); kept if it beats
  /// best. A component of
  /// n can be negative (N a rounding beyond Q on a coordinate plane's side): the shape's mirror
  /// symmetry gives h(n) = h(|n|), and the support function is evaluated in the first octant.
  void tryContactDirection(Candidate<S>* best) const {
    const Vector3<S> n = (y_ - best->point).normalized();
    if (!n.allFinite()) return;
    Candidate<S> c = *best;
    c.normal = n;
    S gap = dual_.value(n.cwiseAbs()) - n.dot(c.point);
    if (gap > q_.tolerance) {  // the gap of a better direction (dualLowerBound)
      const S upper = (y_ - c.point).norm();
      gap = upper - dualLowerBound(n.cwiseAbs(), upper);
    }
    c.error = std::isfinite(gap) ? std::max(std::abs(gap), errorAt(c.point, n))
                                 : std::numeric_limits<S>::infinity();
    if (isBetter(c, *best)) *best = c;
  }

  /// A lower bound on the distance of an outside Q from the dual problem: the distance is the
  /// largest φ(n) = n·Q − h(n) over the unit ball, and every n gives a lower bound (each point of
  /// the shape is at least n·Q − h(n) from Q along n). φ is concave; from the first-octant unit
  /// vector n, projected gradient ascent (the gradient Q − ∇h(n), ∇h(n) the support point; the
  /// projection sets negative components to 0, since Q is in the first octant, and scales into
  /// the ball), each step halved until it raises φ, until the bound is within the tolerance of
  /// `upper` (the candidate's distance). Where the nearest point's normal has a component too
  /// small for the format (beside the tip of a pinched cross-section on a nearly flat wall:
  /// docs/hardening.md, finding 21), the contact direction's φ falls short of the distance by
  /// more than the tolerance, and the step that sets that component to 0 closes the gap.
  S dualLowerBound(Vector3<S> n, S upper) const {
    S bound = y_.dot(n) - dual_.value(n);
    for (int step = 0; step < rules::kDualAscentSteps && upper - bound > q_.tolerance; ++step) {
      const Vector3<S> ascent = y_ - dual_.evaluate(n, false).gradient;
      S t = S(1) / upper;
      bool raised = false;
      for (int k = 0; k < rules::kDualAscentHalvings && !raised; ++k, t *= S(0.5)) {
        Vector3<S> m = (n + t * ascent).cwiseMax(S(0));
        const S norm = m.norm();
        if (!(norm > S(0))) continue;
        if (norm > S(1)) m /= norm;
        const S phi = y_.dot(m) - dual_.value(m);
        if (phi > bound) {
          bound = phi;
          n = m;
          raised = true;
        }
      }
      if (!raised) break;
    }
    return bound;
  }

  /// Runs Newton from a start (the ray's surface point) and keeps the result if it beats best.
  void tryStart(const Vector3<S>& ray, Candidate<S>* best, int share = rules::kIterationsPerStart) {
    tryStart(candidateOnRay(ray), best, share);
  }
  void tryStart(const Candidate<S>& start, Candidate<S>* best,
                int share = rules::kIterationsPerStart) {
    const Candidate<S> c = refine(start, share);
    noteSurfacePoint(c.point);
    noteConverged(c);
    if (isBetter(c, *best)) *best = c;
  }

  /// Keeps the surface point nearest to Q among the starts' answers (tryRingRotations).
  void noteSurfacePoint(const Vector3<S>& point) {
    const S squared = (y_ - point).squaredNorm();
    if (squared < nearest_squared_) {
      nearest_squared_ = squared;
      nearest_point_ = point;
    }
  }

  /// Keeps a converged answer for the runner-up (Query::runner_up, finish()).
  void noteConverged(const Candidate<S>& c) {
    if (q_.runner_up == nullptr || !(c.error <= q_.tolerance)) return;
    if (converged_count_ < converged_.size()) converged_[converged_count_++] = c.point;
  }

  /// Newton in the smoother formulation first; if that stalls, in the other, warm-started where
  /// the first stopped and then from the original start.
  Candidate<S> refine(Candidate<S> c, int share = rules::kIterationsPerStart) {
    // Each start gets at most its share of the budget (exact_rules.h).
    limit_ = std::min(q_.max_iterations, iterations_ + share);
    const Candidate<S> start = c;
    c = primal_first_ ? newtonPrimal(c) : newtonDual(c);
    if (c.error > q_.tolerance && iterations_ < limit_) {
      // The other formulation, warm-started where the first stopped and, since the first may
      // have walked somewhere useless (toward a sharp tip), also from the original start.
      const Candidate<S> warm = primal_first_ ? newtonDual(c) : newtonPrimal(c);
      if (isBetter(warm, c)) c = warm;
      if (c.error > q_.tolerance && iterations_ < limit_) {
        const Candidate<S> fresh = primal_first_ ? newtonDual(start) : newtonPrimal(start);
        if (isBetter(fresh, c)) c = fresh;
      }
    }
    return c;
  }

  /// The candidate where the ray from the centre through `ray` meets the surface, with G's
  /// gradient and Hessian there, from one evaluation at `ray` itself: ∇G is 0-homogeneous and
  /// ∇²G is (−1)-homogeneous, so at N = ray/G(ray) they are ∇G(ray) and G(ray)·∇²G(ray).
  /// On a surface of revolution, a start off the meridian plane y = 0 is rotated onto it about
  /// z (G is unchanged); the Newton iterates on it pass through unchanged (y exactly 0).
  Candidate<S> candidateOnRay(const Vector3<S>& ray) const {
    if (revolution_ && ray[1] != S(0)) {
      const Vector3<S> in_plane(std::hypot(ray[0], ray[1]), S(0), ray[2]);
      return candidateFrom(in_plane, primal_.evaluate(in_plane, true));
    }
    return candidateFrom(ray, primal_.evaluate(ray, true));
  }

  /// A first-octant vector of Q's frame in the solver's (rotated onto the meridian plane on a
  /// surface of revolution, the mirror image across y = 0 taken where it turns negative),
  /// and back (toQuery; the solver's vectors have y ≥ 0).
  Vector3<S> toMeridian(const Vector3<S>& v) const {
    if (!revolution_) return v;
    return Vector3<S>(v[0] * cos_ + v[1] * sin_, std::abs(v[1] * cos_ - v[0] * sin_), v[2]);
  }
  Vector3<S> toQuery(const Vector3<S>& v) const {
    if (!revolution_) return v;
    return Vector3<S>(v[0] * cos_ - v[1] * sin_, v[0] * sin_ + v[1] * cos_, v[2]);
  }

  /// The same from G's evaluation `e` (with the Hessian) at `ray`.
  Candidate<S> candidateFrom(const Vector3<S>& ray, const NestedNormEval<S>& e) const {
    Candidate<S> c;
    c.point = ray / e.value;
    c.gradient = e.gradient;
    c.hessian = e.value * e.hessian;
    const S n = e.gradient.norm();
    c.normal = n > S(0) ? Vector3<S>(e.gradient / n) : Vector3<S>::UnitZ();
    c.error = c.point.allFinite() ? errorAt(c.point, c.normal) : std::numeric_limits<S>::infinity();
    return c;
  }

  /// Paper Eq. 7 with d = ±‖Q − N‖.
  S errorAt(const Vector3<S>& point, const Vector3<S>& normal) const {
    const S d = sign_ * (y_ - point).norm();
    const S e = (point + d * normal - y_).norm();
    return std::isfinite(e) ? e : std::numeric_limits<S>::infinity();
  }

  bool isBetter(const Candidate<S>& a, const Candidate<S>& b) const {
    const bool a_ok = a.error <= q_.tolerance, b_ok = b.error <= q_.tolerance;
    if (a_ok != b_ok) return a_ok;
    if (!a_ok) return a.error < b.error;
    return (y_ - a.point).squaredNorm() < (y_ - b.point).squaredNorm();
  }

  /// Keeps an iterate in the first octant: a component that would turn negative shrinks
  /// toward its coordinate plane instead (exact_rules::kOctantShrink).
  static Vector3<S> stayInOctant(const Vector3<S>& from, const Vector3<S>& to) {
    Vector3<S> out = to;
    for (int i = 0; i < 3; ++i) {
      if (!(out[i] >= S(0))) out[i] = S(rules::kOctantShrink) * from[i];
    }
    return out;
  }

  /// One Newton system [matrix, border; borderᵀ, 0]·[δ; δλ] = [residual; 0], the border along
  /// the iterate's normal; `scale` is the length that sets convexification's thresholds.
  struct NewtonSystem {
    Vector3<S> residual;
    Eigen::Matrix<S, 3, 3> matrix;
    S scale;
  };

  /// Primal, at a surface point N (border ∇G): residual of Q − N = μ∇G with μ its least-squares
  /// multiplier (G(N) = 1 holds: N is re-projected every step), matrix I + μ∇²G. ∇G and ∇²G at
  /// N come with the candidate (one evaluation per trial point).
  NewtonSystem primalSystem(const Candidate<S>& c) const {
    const S mu = c.gradient.dot(y_ - c.point) / c.gradient.squaredNorm();
    return {y_ - c.point - mu * c.gradient, Eigen::Matrix<S, 3, 3>::Identity() + mu * c.hessian,
            S(1)};
  }

  /// Dual, at a normal n with h's evaluation e there (border n): the surface point is ∇h(n),
  /// d = n·(Q − ∇h(n)), residual Q − ∇h(n) − d·n, matrix ∇²h + d·I.
  NewtonSystem dualSystem(const Vector3<S>& n, const NestedNormEval<S>& e) const {
    const S d = n.dot(y_ - e.gradient);
    return {y_ - e.gradient - d * n, e.hessian + d * Eigen::Matrix<S, 3, 3>::Identity(),
            std::abs(d)};
  }

  /// The Newton steps at one iterate, solved in the tangent plane of the normal n: the bordered
  /// system [A, b; bᵀ, 0]·[δ; δλ] = [r; 0] (b ∥ n) forces δ ⊥ n, so with an orthonormal tangent
  /// basis T = (t1, t2), (TᵀAT)·c = Tᵀr and δ = T·c — a 2×2 solve on the block convexification
  /// inspects anyway, in place of a 4×4 LU (the SIMD kernel does the same).
  struct TangentSteps {
    Vector3<S> plain;        // Newton's step (not finite if the block is singular)
    Vector3<S> convexified;  // with the convexified block, if `convexify`
    bool convexify;          // an eigenvalue needed replacing (below)
    bool full_step_first;    // ... and the smallest was positive: try `plain` first
    bool valley;             // positive definite, but flat one way (exact_rules::kValleyRatio)
  };

  /// The tangent block must be positive definite for the step to head for a minimum of the
  /// distance. Outside it always is (the shape is convex); inside it is not beyond a focal point
  /// (|d| > a radius of curvature), where the iterate sits near a saddle such as the tip of a
  /// creased shape (ε > 1). There (a tangent eigenvalue below 1e-4 × `scale`) that eigenvalue
  /// alone is replaced by 10 % of `scale`, along its own eigenvector: a damped step uphill on
  /// the Lagrangian's curvature in that direction, not toward the saddle, and the plain Newton
  /// step in the other direction, whose curvature is untouched (shifting both would make the
  /// iterate creep along a mirror plane whose crossing direction is strongly negative). Near a
  /// focal ring (Q close to the axis of a round cross-section) or a focal point (Q near the
  /// centre of a near-sphere) the smallest eigenvalue is small but positive and the full Newton
  /// step is the one that converges (the replaced one creeps, by about eigenvalue/(10 % of
  /// scale) per iteration), so a positive one comes back in `full_step_first`: the caller tries
  /// the plain step first.
  /// The restoring step (exact_rules::kStepTrials): the Newton step of `system` at the normal n
  /// along the tangent block's stiffer eigenvector only, back to a curved valley's floor without
  /// moving along the valley. Not finite where that eigenvalue is not positive.
  static Vector3<S> restoringStep(const NewtonSystem& system, const Vector3<S>& n) {
    const std::array<Vector3<S>, 2> basis = tangentBasis(n);
    const Vector3<S>&t1 = basis[0], &t2 = basis[1];
    const Eigen::Matrix<S, 3, 3>& a = system.matrix;
    const S b11 = t1.dot(a * t1), b22 = t2.dot(a * t2), b12 = t1.dot(a * t2);
    const Eigenvalues2<S> e = eigenvalues2(b11, b12, b22);
    if (!(e.highest > S(0))) return Vector3<S>::Constant(std::numeric_limits<S>::quiet_NaN());
    const auto [c, s] = lowerEigenvector(b11, b12, b22, e.half_gap);
    const Vector3<S> stiff = c * t2 - s * t1;  // (−s, c) in the basis
    return (stiff.dot(system.residual) / e.highest) * stiff;
  }

  static TangentSteps tangentSteps(const NewtonSystem& system, const Vector3<S>& n) {
    const std::array<Vector3<S>, 2> basis = tangentBasis(n);
    const Vector3<S>&t1 = basis[0], &t2 = basis[1];
    const Eigen::Matrix<S, 3, 3>& a = system.matrix;
    const S b11 = t1.dot(a * t1), b22 = t2.dot(a * t2), b12 = t1.dot(a * t2);
    const S c1 = t1.dot(system.residual), c2 = t2.dot(system.residual);
    // δ = T·M⁻¹·Tᵀr for a symmetric 2×2 block M.
    auto solve = [&](S m11, S m12, S m22) {
      const S det = m11 * m22 - m12 * m12;
      return Vector3<S>(((m22 * c1 - m12 * c2) / det) * t1 + ((m11 * c2 - m12 * c1) / det) * t2);
    };
    const rules::TangentBlock<S> m = rules::convexifiedTangentBlock(b11, b12, b22, system.scale);
    const Eigenvalues2<S> e = eigenvalues2(b11, b12, b22);
    const bool valley = e.lowest > S(0) && e.lowest < S(rules::kValleyRatio) * e.highest;
    TangentSteps steps{solve(b11, b12, b22), Vector3<S>::Zero(), m.modified, m.full_step_first,
                       valley};
    if (m.modified) steps.convexified = solve(m.m11, m.m12, m.m22);
    return steps;
  }

  /// Stall detection of one Newton run inside the shape (exact_rules::kStallWindow): false once
  /// a window of iterations has not cut the error by kStallFactor, so a start creeping along a
  /// flat valley hands the budget on to the next start instead of spending its whole share.
  /// (Outside, one start is usually all there is, and the nested projection backs it up.)
  class Progress {
   public:
    Progress(S error, int iteration, bool active)
        : reference_(error), checkpoint_(iteration), active_(active) {}
    bool keeps(S error, int iteration) {
      if (!active_ || iteration - checkpoint_ < rules::kStallWindow) return true;
      if (!(error <= S(rules::kStallFactor) * reference_)) return false;
      reference_ = error;
      checkpoint_ = iteration;
      return true;
    }

   private:
    S reference_;
    int checkpoint_;
    bool active_;
  };

  Candidate<S> newtonPrimal(Candidate<S> c) {
    Progress progress(c.error, iterations_, inside_);
    while (c.error > q_.tolerance && iterations_ < limit_ && progress.keeps(c.error, iterations_)) {
      ++iterations_;
      const TangentSteps steps = tangentSteps(primalSystem(c), c.normal);
      if (!steps.convexify || steps.full_step_first) {
        if (steps.plain.allFinite() && tryStep(&c, steps.plain, true, steps.valley)) continue;
        if (!steps.convexify) break;
      }
      if (!steps.convexified.allFinite() || !tryStep(&c, steps.convexified, false)) break;
    }
    return c;
  }

  /// h's evaluation at a candidate's normal n from the candidate's own primal evaluation: ∇h(n)
  /// is the candidate's point, and on the tangent plane ∇²h(n) is the inverse of the shape
  /// operator W = Tᵀ∇²G·T/‖∇G‖ (dX = ∇²h·dn, dn = W·dX; ∇²h·n = 0, h being 1-homogeneous). Saves
  /// the dual's first evaluation of each start (outside, one of the 4–6 of a dual-first shape's
  /// query); h is evaluated instead outside in float (on a flat disc the derived block sent an
  /// outside start astray: docs/math.md → "The Exact solver") and where W is not positive
  /// definite.
  NestedNormEval<S> dualAtCandidate(const Candidate<S>& c) const {
    const Vector3<S>& n = c.normal;
    if (!inside_ && !std::is_same<S, double>::value) return dual_.evaluate(n, true);
    const S g = c.gradient.norm();
    const std::array<Vector3<S>, 2> basis = tangentBasis(n);
    const Vector3<S>&t1 = basis[0], &t2 = basis[1];
    const S w11 = t1.dot(c.hessian * t1) / g, w22 = t2.dot(c.hessian * t2) / g;
    const S w12 = t1.dot(c.hessian * t2) / g;
    const S det = w11 * w22 - w12 * w12;
    if (!(w11 > S(0) && det > S(0) && std::isfinite(det) && std::isfinite(w11 + w22 + w12))) {
      return dual_.evaluate(n, true);
    }
    // W⁻¹ = [w22, −w12; −w12, w11]/det, as T·W⁻¹·Tᵀ.
    const S i11 = w22 / det, i22 = w11 / det, i12 = -w12 / det;
    NestedNormEval<S> e;
    e.value = n.dot(c.point);
    e.gradient = c.point;
    e.hessian = i11 * t1 * t1.transpose() + i22 * t2 * t2.transpose() +
                i12 * (t1 * t2.transpose() + t2 * t1.transpose());
    return e;
  }

  Candidate<S> newtonDual(Candidate<S> c) {
    // The dual iterate is the normal n; its surface point is ∇h(n), whose normal is n itself,
    // so a trial costs one evaluation of h (with the Hessian, reused by the next iteration).
    Vector3<S> n = c.normal;
    NestedNormEval<S> e = dualAtCandidate(c);
    bool moved = false;
    Progress progress(c.error, iterations_, inside_);
    while (c.error > q_.tolerance && iterations_ < limit_ && progress.keeps(c.error, iterations_)) {
      ++iterations_;
      const TangentSteps steps = tangentSteps(dualSystem(n, e), n);
      auto accept = [&](const Vector3<S>& trial_n, const NestedNormEval<S>& trial, S error) {
        c.point = trial.gradient;
        c.normal = trial_n;
        c.error = error;
        n = trial_n;
        e = trial;
        moved = true;
      };
      // The restoring steps (exact_rules::kRestoringSteps) from a refused trial at the normal m
      // (h's evaluation t there, its error `error`): accepted, and true, once below `target`.
      auto restoreDual = [&](Vector3<S> m, NestedNormEval<S> t, S error, S target) {
        for (int k = 1; k <= rules::kRestoringSteps && iterations_ + k <= limit_; ++k) {
          const Vector3<S> back = restoringStep(dualSystem(m, t), m);
          const Vector3<S> next_m = stayInOctant(m, Vector3<S>(m + back)).normalized();
          if (!next_m.allFinite()) return false;
          const NestedNormEval<S> next = dual_.evaluate(next_m, true);
          const S next_error = errorAt(next.gradient, next_m);
          if (!(next_error < error)) return false;
          if (next_error < target) {
            iterations_ += k;
            accept(next_m, next, next_error);
            return true;
          }
          m = next_m;
          t = next;
          error = next_error;
        }
        return false;
      };
      // A step with halving; true if a trial reduced the error. A full Newton step (`corrected`)
      // that fails gets its second-order correction, and in a `valley` every trial its restoring
      // steps (exact_rules::kStepTrials), before it is halved.
      auto try_dual_step = [&](Vector3<S> step, bool corrected, bool valley) {
        for (int trial_step = 0; trial_step < rules::kStepTrials; ++trial_step) {
          const Vector3<S> trial_n = stayInOctant(n, Vector3<S>(n + step)).normalized();
          const NestedNormEval<S> trial = dual_.evaluate(trial_n, true);
          const S error = errorAt(trial.gradient, trial_n);
          if (error < c.error) {
            accept(trial_n, trial, error);
            return true;
          }
          if (trial_step == 0 && corrected && iterations_ < limit_ && std::isfinite(error)) {
            const Vector3<S> step_t = tangentSteps(dualSystem(trial_n, trial), trial_n).plain;
            if (step_t.allFinite()) {
              const Vector3<S> corrected_n =
                  stayInOctant(trial_n, Vector3<S>(trial_n + step_t)).normalized();
              const NestedNormEval<S> second = dual_.evaluate(corrected_n, true);
              const S corrected_error = errorAt(second.gradient, corrected_n);
              if (corrected_error < c.error) {
                ++iterations_;
                accept(corrected_n, second, corrected_error);
                return true;
              }
            }
          }
          if (valley && std::isfinite(error) && restoreDual(trial_n, trial, error, c.error)) {
            return true;
          }
          step *= S(0.5);
        }
        return false;
      };
      if (!steps.convexify || steps.full_step_first) {
        if (steps.plain.allFinite() && try_dual_step(steps.plain, true, steps.valley)) continue;
        if (!steps.convexify) break;
      }
      if (!steps.convexified.allFinite() || !try_dual_step(steps.convexified, false, false)) break;
    }
    // Back to the primal's view of the final point (its own normal, gradient and Hessian), so
    // the error reported and any primal iterations that follow are the primal's. Converged,
    // nothing iterates from it: the point ∇h(n) and its normal n stand, with ∇G = n/h(n) there
    // (the gauge's gradient at the boundary point of normal n) and no Hessian (NaN).
    if (!moved) return c;
    if (c.error <= q_.tolerance) {
      c.gradient = c.normal / c.normal.dot(c.point);
      c.hessian.setConstant(std::numeric_limits<S>::quiet_NaN());
      return c;
    }
    Candidate<S> out = candidateOnRay(c.point);
    return out.error <= c.error ? out : Candidate<S>{c.point,     c.normal, out.gradient,
                                                     out.hessian, c.error,  0};
  }

  /// Applies a primal step (re-projected radially onto the surface) with halving; false if no
  /// trial reduced the error. A full Newton step (`corrected`) that fails gets its second-order
  /// correction, and in a `valley` every trial its restoring steps (exact_rules::kStepTrials),
  /// before it is halved.
  bool tryStep(Candidate<S>* c, Vector3<S> step, bool corrected, bool valley = false) {
    for (int trial_step = 0; trial_step < rules::kStepTrials; ++trial_step) {
      const Vector3<S> p = stayInOctant(c->point, Vector3<S>(c->point + step));
      if (p.allFinite() && p.squaredNorm() > S(0)) {
        Candidate<S> trial = candidateOnRay(p);
        if (trial.error < c->error) {
          *c = trial;
          return true;
        }
        if (trial_step == 0 && corrected && iterations_ < limit_ && std::isfinite(trial.error)) {
          const Vector3<S> step_t = tangentSteps(primalSystem(trial), trial.normal).plain;
          if (step_t.allFinite()) {
            const Vector3<S> q = stayInOctant(trial.point, Vector3<S>(trial.point + step_t));
            if (q.allFinite() && q.squaredNorm() > S(0)) {
              const Candidate<S> second = candidateOnRay(q);
              if (second.error < c->error) {
                ++iterations_;
                *c = second;
                return true;
              }
            }
          }
        }
        if (valley && std::isfinite(trial.error) && restore(trial, c)) return true;
      }
      step *= S(0.5);
    }
    return false;
  }

  /// The restoring steps (exact_rules::kRestoringSteps) from a refused primal trial: true, and
  /// *c replaced, once the point they reach has a smaller error than *c.
  bool restore(Candidate<S> trial, Candidate<S>* c) {
    for (int k = 1; k <= rules::kRestoringSteps && iterations_ + k <= limit_; ++k) {
      const Vector3<S> back = restoringStep(primalSystem(trial), trial.normal);
      const Vector3<S> p = stayInOctant(trial.point, Vector3<S>(trial.point + back));
      if (!p.allFinite() || !(p.squaredNorm() > S(0))) return false;
      const Candidate<S> next = candidateOnRay(p);
      if (!(next.error < trial.error)) return false;
      if (next.error < c->error) {
        iterations_ += k;
        *c = next;
        return true;
      }
      trial = next;
    }
    return false;
  }

  /// The three points reached by moving one coordinate of an inside Q outward until G = 1
  /// (closed form through the nested norms).
  std::array<Vector3<S>, 3> axisProjections() const {
    const NestedNorm<S>& c = primal_;
    const Vector3<S> u = y_.cwiseProduct(c.scale);
    auto complement = [](S t, S p, S inv_p) {  // s with ‖(t, s)‖_p = 1, t ≤ 1
      return std::pow(std::max(S(0), S(1) - std::pow(t, p)), inv_p);
    };
    std::array<Vector3<S>, 3> points;
    const S r = pnorm2(u[0], u[1], c.p1, c.inv_p1);
    const S r_target = complement(u[2], c.p2, c.inv_p2);  // the xy-norm the surface needs
    for (int i = 0; i < 2; ++i) {
      Vector3<S> v = u;
      const S other = u[1 - i];
      v[i] = other < r_target ? r_target * complement(other / r_target, c.p1, c.inv_p1) : u[i];
      points[i] = v.cwiseQuotient(c.scale);
    }
    Vector3<S> v = u;
    v[2] = complement(std::min(r, S(1)), c.p2, c.inv_p2);
    points[2] = v.cwiseQuotient(c.scale);
    return points;
  }

  /// Reflects the first-octant candidate back to Q's octant.
  PointDistanceResult<S> finish(const Candidate<S>& c, bool inside) const {
    PointDistanceResult<S> r = fromFirstOctant(q_.x, toQuery(c.point), toQuery(c.normal), inside);
    r.error = c.error;
    r.iterations = c.iterations;
    r.converged = c.error <= q_.tolerance;
    if (q_.runner_up != nullptr) {
      const S separation = std::sqrt(q_.tolerance * q_.shape.size());
      S runner_up = std::numeric_limits<S>::infinity();
      for (std::size_t i = 0; i < converged_count_; ++i) {
        if ((converged_[i] - c.point).norm() > separation) {
          runner_up = std::min(runner_up, (y_ - converged_[i]).norm());
        }
      }
      *q_.runner_up = runner_up;
    }
    return r;
  }

  const Query<S>& q_;
  Vector3<S> y_;
  NestedNorm<S> primal_, dual_;
  bool primal_first_;          // which formulation refine() tries first
  bool revolution_;            // a surface of revolution about z: y_ is on the meridian plane
  S cos_ = S(1), sin_ = S(0);  // ... and Q's azimuth, which toQuery turns the answer by
  int cover_attempts_ = 0;     // coverCertified's, at most exact_rules::kCoverAttempts
  int split_budget_ = DirectionCover<S>::kSplitSupportPoints;  // coverCertified's, decremented
  Vector3<S> second_start_ = Vector3<S>::Zero();  // deeper inside: the start solve() did not take
  bool inside_ = false;
  S sign_ = S(1);
  int iterations_ = 0;
  int limit_ = 0;  // iteration count at which the current start stops
  // Inside: the surface point nearest to Q among the starts' answers (noteSurfacePoint).
  Vector3<S> nearest_point_ = Vector3<S>::Zero();
  S nearest_squared_ = std::numeric_limits<S>::infinity();
  // The converged answers, if the query asks for the runner-up (noteConverged).
  std::array<Vector3<S>, 16> converged_;
  std::size_t converged_count_ = 0;
};

}  // namespace

template <typename S>
PointDistanceResult<S> solveExact(const Query<S>& q) {
  return ExactSolver<S>(q).solve();
}

template PointDistanceResult<float> solveExact(const Query<float>&);
template PointDistanceResult<double> solveExact(const Query<double>&);

}  // namespace detail
}  // namespace fcl_superellipsoid
