#ifndef FSE_FIT_FIT_H
#define FSE_FIT_FIT_H

// Fitting a superquadric (pose and five parameters) to a point cloud by nonlinear least squares
// (Ceres). docs/fitting.md → "The fit".

#include <Eigen/Core>
#include <string>
#include <vector>

#include "superquadric.h"

namespace fse_fit {

/// What a point's residual is.
enum class Residual {
  /// The exact signed distance from the surface (the library's Exact method), with its analytic
  /// derivatives with respect to the pose and the five parameters (pointDistanceDerivatives).
  kExact,
  /// The radial distance ‖Q‖·(1 − 1/G(Q)) along the ray from the centre (the library's Radial
  /// method): what the superquadric-recovery literature fits, with forward-difference
  /// derivatives, as it does.
  kRadial,
};

/// The robust loss applied to each point's squared residual.
enum class Loss {
  kNone,    ///< plain least squares
  kHuber,   ///< quadratic within the scale, linear beyond
  kCauchy,  ///< log(1 + (r/scale)²): far points barely count
};

const char* toString(Residual residual);

/// A point's exact residual and its gradient: the signed distance d of p_W from the surface and
/// ∂d/∂ω (the shape rotated by the rotation vector ω about the world origin, its centre kept),
/// ∂d/∂t (its centre moved), ∂d/∂(a1, a2, a3, ε1, ε2). What the fit's exact residual evaluates.
struct ResidualGradient {
  double value = 0;
  Eigen::Vector3d d_rotation, d_centre;
  Eigen::Matrix<double, 5, 1> d_shape;
};
ResidualGradient exactResidualGradient(const fcl_superellipsoid::Superellipsoidd& shape,
                                       const Eigen::Quaterniond& rotation,
                                       const Eigen::Vector3d& centre, const Eigen::Vector3d& p_W);
ResidualGradient exactResidualGradient(const Superquadric& sq, const Eigen::Vector3d& p_W);
const char* toString(Loss loss);

struct FitOptions {
  Residual residual = Residual::kExact;
  Loss loss = Loss::kNone;
  /// The loss's scale, a fraction of the initial guess's size.
  double loss_scale = 0.01;
  /// Per start.
  int max_iterations = 200;
};

struct FitResult {
  Superquadric fitted;
  int iterations = 0;      ///< the Ceres iterations of every start
  int starts = 0;          ///< the initial guesses tried
  double seconds = 0;      ///< wall time of the whole fit
  double cost = 0;         ///< the best start's final cost (½ Σ loss(r²))
  bool converged = false;  ///< Ceres's convergence test held for the best start
};

/// The initial guesses: the cloud's centre of extent in its principal axes, radii from its
/// extents (between the quantiles `trim` and 1 − `trim` along each axis), round exponents (1, 1);
/// for each choice of the principal axis taken as the shape's z (the axis ε2 shapes), one guess
/// with the other two as x and y and one turned an eighth about z.
/// @throws std::invalid_argument for fewer than 4 points, a non-finite point (naming it) or a
/// cloud with no extent.
std::vector<Superquadric> initialGuesses(const std::vector<Eigen::Vector3d>& cloud,
                                         double trim = 0);

/// Fits from each initial guess and keeps the lowest final cost; with a robust loss, then again
/// from the points the fit explains, while that lowers the cost (docs/fitting.md → "The fit").
/// Radii are kept ≥ 1e-3 × the guess's size, exponents in [0.05, 1.95].
/// @throws std::invalid_argument as initialGuesses, or for a non-finite point (naming it).
FitResult fitSuperquadric(const std::vector<Eigen::Vector3d>& cloud,
                          const FitOptions& options = {});

}  // namespace fse_fit

#endif  // FSE_FIT_FIT_H
