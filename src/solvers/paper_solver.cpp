// The reference paper's iterative method (Serrano, "Strategies to Accelerate Deformable and
// Rigid Bodies Simulations", section "Contact Detection Algorithm"), implemented as written.
//
// A guess is a surface point N with four fields: N itself, the contact normal n_μ (unit, from
// N towards Q, oriented so that Q = N + d·n_μ with d signed), the surface normal n_SE(N), and
// the signed distance d. Its error is Eq. 7, ‖N + d·n_SE(N) − Q‖.
//
// Where the paper leaves a choice open, this file chooses (and says so):
//  - λ halves on a divergent guess and grows by 25 % (capped at 1) on an improving guess
//    that came from the standard computation and is "close" to the previous best;
//  - "close" means surface normals within cos > 0.99 and points within 10 % of the current
//    distance (or of the tolerance, if larger) of each other;
//  - the first guess is the starting best (the radial guess only seeds it);
//  - iterations count the guesses after the first one; the cap bounds that count.

#include <cmath>

#include "solvers/solvers.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

template <typename S>
Vector3<S> normalizedOr(const Vector3<S>& v, const Vector3<S>& fallback) {
  const S n = v.norm();
  return n > S(0) ? Vector3<S>(v / n) : fallback;
}

template <typename S>
struct Guess {
  Vector3<S> point;  // N, on the surface
  Vector3<S> n_mu;   // contact normal
  Vector3<S> n_se;   // surface normal at N
  S distance;        // d, signed
  S error;           // Eq. 7
};

template <typename S>
class PaperSolver {
 public:
  PaperSolver(const Query<S>& q, bool inside) : q_(q), sign_(inside ? S(-1) : S(1)) {}

  /// A guess from a surface point: the normal and distance corrected as in the paper
  /// ("the normal is just the vector from p to x, and the distance its norm").
  Guess<S> guessAt(const Vector3<S>& point) const {
    Guess<S> g;
    g.point = point;
    g.n_se = q_.shape.normal(point);
    g.distance = sign_ * (q_.x - point).norm();
    g.n_mu = g.distance != S(0) ? Vector3<S>((q_.x - point) / g.distance) : g.n_se;
    g.error = (point + g.distance * g.n_se - q_.x).norm();
    return g;
  }

  /// Eq. 10 then Eq. 8 then Eq. 9: adjust the distance to the new direction, step back from
  /// Q along it, and project the result radially onto the surface.
  Guess<S> step(const Guess<S>& from, const Vector3<S>& direction) const {
    const S adjusted = from.distance * from.n_mu.dot(direction);  // Eq. 10
    const Vector3<S> point = q_.x - adjusted * direction;         // Eq. 8
    return guessAt(q_.shape.radialProjection(point));             // Eq. 9
  }

  PointDistanceResult<S> solve() {
    // The radial guess: N on the ray through Q, n_μ the ray's direction, d the radial distance.
    Guess<S> radial;
    radial.point = q_.shape.radialProjection(q_.x);
    radial.n_mu = q_.x.normalized();
    radial.n_se = q_.shape.normal(radial.point);
    radial.distance = q_.shape.radialDistance(q_.x);

    // First guess: mirror the surface normal; if the normal at the new point turned by more
    // than acos(0.97), use the 80 % radial / 20 % normal average instead.
    Guess<S> best = step(radial, radial.n_se);
    if (best.n_se.dot(radial.n_se) <= S(0.97)) {
      const Vector3<S> average =
          normalizedOr<S>(S(0.8) * radial.n_mu + S(0.2) * radial.n_se, radial.n_se);
      best = step(radial, average);
    }

    S lambda = S(0.5);
    Guess<S> last = best;
    bool last_divergent = false;
    int iterations = 0;
    while (best.error > q_.tolerance && iterations < q_.max_iterations) {
      ++iterations;
      Vector3<S> direction;
      const bool standard = !last_divergent;
      if (standard) {  // Eq. 5
        direction = normalizedOr<S>((1 - lambda) * best.n_mu + lambda * best.n_se, best.n_se);
      } else {  // Eq. 6, 7 (the averaged normals) and 14
        const Vector3<S> n_mu_avg = normalizedOr<S>(best.n_mu + last.n_mu, best.n_mu);
        const Vector3<S> n_se_avg = normalizedOr<S>(best.n_se + last.n_se, best.n_se);
        direction = normalizedOr<S>((1 - lambda) * n_mu_avg + lambda * n_se_avg, best.n_se);
      }
      const Guess<S> guess = step(best, direction);
      if (guess.error < best.error) {
        const S near = S(0.1) * std::max(std::abs(best.distance), q_.tolerance);
        const bool close =
            guess.n_se.dot(best.n_se) > S(0.99) && (guess.point - best.point).norm() <= near;
        if (standard && close) lambda = std::min(S(1), lambda * S(1.25));
        best = guess;
        last_divergent = false;
      } else {
        lambda *= S(0.5);
        last = guess;
        last_divergent = true;
      }
    }

    PointDistanceResult<S> r;
    r.nearest_point = best.point;
    r.normal = best.n_se;
    r.distance = best.distance;
    r.error = best.error;
    r.iterations = iterations;
    r.converged = best.error <= q_.tolerance;
    return r;
  }

 private:
  const Query<S>& q_;
  S sign_;
};

}  // namespace

template <typename S>
PointDistanceResult<S> solvePaper(const Query<S>& q) {
  const S g = q.shape.gauge(q.x);
  if (g == S(1)) return resultAt(q, q.x, false, 0);  // on the surface
  return PaperSolver<S>(q, g < S(1)).solve();
}

template PointDistanceResult<float> solvePaper(const Query<float>&);
template PointDistanceResult<double> solvePaper(const Query<double>&);

}  // namespace detail
}  // namespace fcl_superellipsoid
