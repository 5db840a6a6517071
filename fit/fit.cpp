#include "fit.h"

#include <ceres/ceres.h>
#include <fcl_superellipsoid/point_derivatives.h>
#include <fcl_superellipsoid/point_distance.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

namespace fse_fit {

namespace fse = fcl_superellipsoid;

namespace {

using Vector5 = Eigen::Matrix<double, 5, 1>;

// The parameter blocks: the rotation as Eigen's quaternion (x, y, z, w; Ceres's
// EigenQuaternionManifold), the centre, and θ = (a1, a2, a3, ε1, ε2).
constexpr int kRotation = 4, kCentre = 3, kShape = 5;
constexpr double kMinExponent = 0.05, kMaxExponent = 1.95;
constexpr double kMinRadiusFraction = 1e-3;
// Each initial guess gets this many iterations; the best then goes on to convergence.
constexpr int kStartIterations = 25;
// With a robust loss, the initial guesses are fitted with the loss at this multiple of the
// requested scale, then the best at the requested one.
constexpr double kWideScale = 3;
// With a robust loss, this many of the best initial guesses go on to the requested scale.
constexpr std::size_t kRobustFinalists = 3;
// With a robust loss, the initial guesses' extents leave out this fraction of the points at
// each end of each axis (outliers widen the cloud's extent).
constexpr double kRobustTrim = 0.05;
// With a robust loss, passes over the explained points (fitSuperquadric): a point within this
// multiple of the requested scale of the fitted surface is explained; at most this many passes,
// each while the cost fell by more than this fraction in the one before.
constexpr double kInlierBand = 3;
constexpr int kExplainedPasses = 4;
constexpr double kPassProgress = 1e-6;

// A forward-difference step for a parameter x of the scale `scale` (SciPy's '2-point' rule,
// √ε·max(|x|, scale), which the superquadric-recovery literature's fits use).
double forwardStep(double x, double scale) {
  return std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(std::abs(x), scale);
}

// The shapes of the current evaluation point, built once per point for every residual: the
// shape of θ and, for the radial residual's derivatives, the shapes of θ + h_i·e_i.
class CurrentShapes final : public ceres::EvaluationCallback {
 public:
  CurrentShapes(const double* theta, double size, bool perturbed)
      : theta_(theta), size_(size), perturbed_(perturbed) {}

  void PrepareForEvaluation(bool evaluate_jacobians, bool /*new_evaluation_point*/) override {
    std::memcpy(built_for_.data(), theta_, sizeof(built_for_));
    base_ = build(built_for_);
    for (auto& s : shifted_) s.reset();
    if (!perturbed_ || !evaluate_jacobians) return;
    for (int i = 0; i < kShape; ++i) {
      std::array<double, kShape> theta = built_for_;
      steps_[i] = forwardStep(theta[i], i < 3 ? size_ : 1.0);
      theta[i] += steps_[i];
      shifted_[i] = build(theta);
    }
  }

  /// The shape of θ: the one built for these values, else one built into `own`; nullptr for
  /// values out of the shape's range.
  const fse::Superellipsoidd* shapeFor(const double* theta,
                                       std::optional<fse::Superellipsoidd>* own) const {
    if (base_ && std::memcmp(theta, built_for_.data(), sizeof(built_for_)) == 0) return &*base_;
    *own = build({theta[0], theta[1], theta[2], theta[3], theta[4]});
    return *own ? &**own : nullptr;
  }
  /// The shape of θ + h_i·e_i and h_i, if built.
  const fse::Superellipsoidd* shifted(int i, double* step) const {
    *step = steps_[i];
    return shifted_[i] ? &*shifted_[i] : nullptr;
  }
  double size() const { return size_; }

  static std::optional<fse::Superellipsoidd> build(const std::array<double, kShape>& theta) {
    try {
      return fse::Superellipsoidd(Eigen::Vector3d(theta[0], theta[1], theta[2]), theta[3],
                                  theta[4]);
    } catch (const std::invalid_argument&) {
      return std::nullopt;
    }
  }

 private:
  const double* theta_;
  double size_;
  bool perturbed_;
  std::array<double, kShape> built_for_{};
  std::optional<fse::Superellipsoidd> base_;
  std::array<std::optional<fse::Superellipsoidd>, kShape> shifted_;
  std::array<double, kShape> steps_{};
};

// ∂r/∂x for the quaternion's four ambient coordinates from ∂r/∂δ in the manifold's tangent
// (δ: the half-angle rotation vector applied on the left, x ← exp(δ)·x). The manifold's Plus
// Jacobian P (4 × 3) has orthonormal columns at a unit x, so gᵀPᵀ is an ambient gradient
// whose product with P, what Ceres forms, is g.
void ambientRotationJacobian(const double* q, const Eigen::Vector3d& tangent, double* out) {
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> plus;
  ceres::EigenQuaternionManifold().PlusJacobian(q, plus.data());
  Eigen::Map<Eigen::Matrix<double, 1, 4>> ambient(out);
  ambient = tangent.transpose() * plus.transpose();
}

// A cloud point p_W in the frame of the shape at rotation q and centre t: Rᵀ(p − t).
Eigen::Vector3d inShape(const Eigen::Vector3d& p_W, const double* q, const double* t) {
  return Eigen::Map<const Eigen::Quaterniond>(q).normalized().conjugate() *
         (p_W - Eigen::Map<const Eigen::Vector3d>(t));
}

// A point's residual, for Ceres: a refusal by the library (a point or shape out of its range)
// is a failed evaluation, which Ceres answers with a shorter step.
class PointResidual : public ceres::SizedCostFunction<1, kRotation, kCentre, kShape> {
 public:
  PointResidual(const Eigen::Vector3d& p_W, const CurrentShapes& shapes)
      : p_W_(p_W), shapes_(shapes) {}

  bool Evaluate(double const* const* x, double* residual, double** jacobians) const final {
    try {
      return evaluate(x, residual, jacobians);
    } catch (const std::invalid_argument&) {
      return false;
    }
  }

 protected:
  virtual bool evaluate(double const* const* x, double* residual, double** jacobians) const = 0;

  Eigen::Vector3d p_W_;
  const CurrentShapes& shapes_;
};

// The exact signed distance of one point, with its analytic Jacobian (exactResidualGradient);
// the manifold's δ is half of the rotation vector ω, so ∂d/∂δ = 2·∂d/∂ω.
class ExactDistance final : public PointResidual {
 public:
  using PointResidual::PointResidual;

 private:
  bool evaluate(double const* const* x, double* residual, double** jacobians) const override {
    std::optional<fse::Superellipsoidd> own;
    const fse::Superellipsoidd* shape = shapes_.shapeFor(x[2], &own);
    if (shape == nullptr) return false;
    const Eigen::Quaterniond q = Eigen::Map<const Eigen::Quaterniond>(x[0]).normalized();
    const Eigen::Vector3d t = Eigen::Map<const Eigen::Vector3d>(x[1]);
    if (jacobians == nullptr) {
      residual[0] = fse::pointDistance(*shape, q.conjugate() * (p_W_ - t)).distance;
      return std::isfinite(residual[0]);
    }
    const ResidualGradient g = exactResidualGradient(*shape, q, t, p_W_);
    residual[0] = g.value;
    if (jacobians[0] != nullptr) ambientRotationJacobian(x[0], 2 * g.d_rotation, jacobians[0]);
    if (jacobians[1] != nullptr)
      std::copy(g.d_centre.data(), g.d_centre.data() + kCentre, jacobians[1]);
    if (jacobians[2] != nullptr)
      std::copy(g.d_shape.data(), g.d_shape.data() + kShape, jacobians[2]);
    return std::isfinite(residual[0]);
  }
};

// The radial distance of one point, with forward differences in the twelve tangent directions
// (three of the rotation, three of the centre, five of θ): one value and twelve more per point.
class RadialDistance final : public PointResidual {
 public:
  using PointResidual::PointResidual;

 private:
  bool evaluate(double const* const* x, double* residual, double** jacobians) const override {
    std::optional<fse::Superellipsoidd> own;
    const fse::Superellipsoidd* shape = shapes_.shapeFor(x[2], &own);
    if (shape == nullptr) return false;
    const bool shared = !own.has_value();  // the callback's: its perturbed shapes apply
    const double r0 = radial(*shape, x[0], x[1]);
    residual[0] = r0;
    if (!std::isfinite(r0)) return false;
    if (jacobians == nullptr) return true;
    if (jacobians[0] != nullptr) {
      const ceres::EigenQuaternionManifold manifold;
      Eigen::Vector3d tangent;
      for (int k = 0; k < 3; ++k) {
        const double h = forwardStep(0, 1);
        double delta[3] = {0, 0, 0}, q[4];
        delta[k] = h;
        manifold.Plus(x[0], delta, q);
        tangent[k] = (radial(*shape, q, x[1]) - r0) / h;
      }
      ambientRotationJacobian(x[0], tangent, jacobians[0]);
    }
    if (jacobians[1] != nullptr) {
      for (int k = 0; k < 3; ++k) {
        double t[3] = {x[1][0], x[1][1], x[1][2]};
        const double h = forwardStep(t[k], shapes_.size());
        t[k] += h;
        jacobians[1][k] = (radial(*shape, x[0], t) - r0) / h;
      }
    }
    if (jacobians[2] != nullptr) {
      for (int i = 0; i < kShape; ++i) {
        double h = 0;
        const fse::Superellipsoidd* shifted = shared ? shapes_.shifted(i, &h) : nullptr;
        std::optional<fse::Superellipsoidd> own_shifted;
        if (shifted == nullptr) {
          std::array<double, kShape> theta = {x[2][0], x[2][1], x[2][2], x[2][3], x[2][4]};
          h = forwardStep(theta[i], i < 3 ? shapes_.size() : 1.0);
          theta[i] += h;
          own_shifted = CurrentShapes::build(theta);
          if (!own_shifted) return false;
          shifted = &*own_shifted;
        }
        jacobians[2][i] = (radial(*shifted, x[0], x[1]) - r0) / h;
      }
    }
    return true;
  }

  double radial(const fse::Superellipsoidd& shape, const double* q, const double* t) const {
    fse::DistanceOptions<double> options;
    options.method = fse::DistanceMethod::kRadial;
    return fse::pointDistance(shape, inShape(p_W_, q, t), options).distance;
  }
};

struct StartResult {
  Superquadric fitted;
  int iterations = 0;
  double cost = std::numeric_limits<double>::infinity();
  bool converged = false;
};

// One Ceres solve from `guess` with a loss of absolute scale `scale` (options.loss), at most
// `iterations` iterations; `size` scales the finite-difference steps.
StartResult fitFrom(const std::vector<Eigen::Vector3d>& cloud, const Superquadric& guess,
                    const FitOptions& options, double scale, int iterations, double size) {
  Eigen::Quaterniond rotation = guess.rotation.normalized();
  Eigen::Vector3d centre = guess.translation;
  std::array<double, kShape> theta = {guess.radii[0], guess.radii[1], guess.radii[2], guess.eps1,
                                      guess.eps2};
  CurrentShapes shapes(theta.data(), size, options.residual == Residual::kRadial);

  std::unique_ptr<ceres::LossFunction> loss;
  if (options.loss == Loss::kHuber) loss = std::make_unique<ceres::HuberLoss>(scale);
  if (options.loss == Loss::kCauchy) loss = std::make_unique<ceres::CauchyLoss>(scale);

  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.evaluation_callback = &shapes;
  ceres::Problem problem(problem_options);
  for (const Eigen::Vector3d& p : cloud) {
    ceres::CostFunction* cost =
        options.residual == Residual::kExact
            ? static_cast<ceres::CostFunction*>(new ExactDistance(p, shapes))
            : static_cast<ceres::CostFunction*>(new RadialDistance(p, shapes));
    problem.AddResidualBlock(cost, loss.get(), rotation.coeffs().data(), centre.data(),
                             theta.data());
  }
  problem.SetManifold(rotation.coeffs().data(), new ceres::EigenQuaternionManifold);
  for (int i = 0; i < 3; ++i) {
    problem.SetParameterLowerBound(theta.data(), i, kMinRadiusFraction * size);
  }
  for (int i = 3; i < kShape; ++i) {
    problem.SetParameterLowerBound(theta.data(), i, kMinExponent);
    problem.SetParameterUpperBound(theta.data(), i, kMaxExponent);
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = iterations;
  solver.function_tolerance = 1e-14;
  solver.gradient_tolerance = 1e-16;
  solver.parameter_tolerance = 1e-14;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  StartResult out;
  out.fitted.rotation = rotation.normalized();
  out.fitted.translation = centre;
  out.fitted.radii = Eigen::Vector3d(theta[0], theta[1], theta[2]);
  out.fitted.eps1 = theta[3];
  out.fitted.eps2 = theta[4];
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.cost = summary.final_cost;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  if (!std::isfinite(out.cost)) out.cost = std::numeric_limits<double>::infinity();
  return out;
}

// The schedule from the initial guesses: every guess for a few iterations at the first scale;
// the best go on through every scale, and the lowest final cost wins. With a robust loss the
// three best go on: the wide loss's ranking need not be the narrow one's (a huge shape with a
// flat side through part of the cloud can lead at the wide scale and lose at the requested one).
StartResult fitFromGuesses(const std::vector<Eigen::Vector3d>& cloud,
                           const std::vector<Superquadric>& guesses, const FitOptions& options,
                           const std::vector<double>& scales, double size, FitResult& result) {
  std::vector<StartResult> starts;
  for (const Superquadric& guess : guesses) {
    starts.push_back(fitFrom(cloud, guess, options, scales.front(),
                             std::min(kStartIterations, options.max_iterations), size));
    result.iterations += starts.back().iterations;
    ++result.starts;
  }
  std::sort(starts.begin(), starts.end(),
            [](const StartResult& a, const StartResult& b) { return a.cost < b.cost; });
  const std::size_t finalists = options.loss == Loss::kNone ? 1 : kRobustFinalists;
  StartResult best;
  for (std::size_t k = 0; k < std::min(finalists, starts.size()); ++k) {
    StartResult r = starts[k];
    for (const double scale : scales) {
      r = fitFrom(cloud, r.fitted, options, scale, options.max_iterations, size);
      result.iterations += r.iterations;
    }
    if (r.cost < best.cost) best = r;
  }
  return best;
}

// A point's residual from the fitted superquadric, as the fit measures it.
double residualOf(const Superquadric& sq, const Eigen::Vector3d& p_W, Residual residual) {
  fse::DistanceOptions<double> options;
  if (residual == Residual::kRadial) options.method = fse::DistanceMethod::kRadial;
  const Eigen::Vector3d p_S = sq.rotation.normalized().inverse() * (p_W - sq.translation);
  return fse::pointDistance(sq.shape(), p_S, options).distance;
}

}  // namespace

ResidualGradient exactResidualGradient(const fse::Superellipsoidd& shape,
                                       const Eigen::Quaterniond& rotation,
                                       const Eigen::Vector3d& centre, const Eigen::Vector3d& p_W) {
  // s = Rᵀ(p − t). Rotating the shape by ω about the world origin (the centre kept) moves s by
  // −Rᵀ(ω × w), w = p − t, so ∂d/∂ω = n_W × w; moving the centre, ∂d/∂t = −n_W; ∂d/∂θ is the
  // library's.
  const Eigen::Matrix3d R = rotation.normalized().toRotationMatrix();
  const Eigen::Vector3d w = p_W - centre;
  const fse::PointDistanceDerivatives<double> d =
      fse::pointDistanceDerivatives(shape, Eigen::Vector3d(R.transpose() * w));
  const Eigen::Vector3d n_W = R * d.d_query;
  return {d.value.distance, n_W.cross(w), -n_W, d.d_shape};
}

ResidualGradient exactResidualGradient(const Superquadric& sq, const Eigen::Vector3d& p_W) {
  return exactResidualGradient(sq.shape(), sq.rotation, sq.translation, p_W);
}

const char* toString(Residual residual) {
  return residual == Residual::kExact ? "exact" : "radial";
}

const char* toString(Loss loss) {
  switch (loss) {
    case Loss::kNone:
      return "none";
    case Loss::kHuber:
      return "huber";
    case Loss::kCauchy:
      return "cauchy";
  }
  return "?";
}

std::vector<Superquadric> initialGuesses(const std::vector<Eigen::Vector3d>& cloud, double trim) {
  if (cloud.size() < 4) {
    throw std::invalid_argument("fit: a cloud needs at least 4 points, got " +
                                std::to_string(cloud.size()));
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud[i].allFinite()) {
      throw std::invalid_argument("fit: point " + std::to_string(i) + " is not finite");
    }
    mean += cloud[i];
  }
  mean /= static_cast<double>(cloud.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : cloud) covariance += (p - mean) * (p - mean).transpose();
  Eigen::Matrix3d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  // The extents along each axis: between the quantiles `trim` and 1 − `trim`.
  Eigen::Vector3d low, high;
  std::vector<double> along(cloud.size());
  const auto last = static_cast<std::ptrdiff_t>(cloud.size()) - 1;
  const auto first = static_cast<std::ptrdiff_t>(std::floor(trim * static_cast<double>(last)));
  for (int k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < cloud.size(); ++i) along[i] = axes.col(k).dot(cloud[i] - mean);
    std::nth_element(along.begin(), along.begin() + first, along.end());
    low[k] = along[first];
    std::nth_element(along.begin(), along.begin() + (last - first), along.end());
    high[k] = along[last - first];
  }
  const Eigen::Vector3d half = (high - low) / 2;
  const double size = half.maxCoeff();
  if (!(size > 0) || !std::isfinite(size)) {
    throw std::invalid_argument("fit: the cloud has no extent (every point the same)");
  }
  const Eigen::Vector3d centre = mean + axes * ((high + low) / 2);
  std::vector<Superquadric> guesses;
  for (int z = 0; z < 3; ++z) {  // the principal axis z taken as the shape's z; cyclic order
    const int x = (z + 1) % 3, y = (z + 2) % 3;
    Eigen::Matrix3d R;
    R << axes.col(x), axes.col(y), axes.col(z);
    Superquadric g;
    g.rotation = Eigen::Quaterniond(R).normalized();
    g.translation = centre;
    g.radii = Eigen::Vector3d(half[x], half[y], half[z]).cwiseMax(kMinRadiusFraction * size * 10);
    g.eps1 = g.eps2 = 1;
    guesses.push_back(g);
    // The same turned an eighth about z: a cross-section with pointed sides (ε1 > 1) has its
    // extent along its diagonals, where the principal axes can lie.
    g.rotation =
        (g.rotation * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ())))
            .normalized();
    guesses.push_back(g);
  }
  return guesses;
}

FitResult fitSuperquadric(const std::vector<Eigen::Vector3d>& cloud, const FitOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.loss_scale > 0) || !std::isfinite(options.loss_scale)) {
    throw std::invalid_argument("fit: the loss scale must be finite and > 0, got " +
                                std::to_string(options.loss_scale));
  }
  if (options.max_iterations < 1) {
    throw std::invalid_argument("fit: max_iterations must be ≥ 1, got " +
                                std::to_string(options.max_iterations));
  }
  const std::vector<Superquadric> guesses =
      initialGuesses(cloud, options.loss == Loss::kNone ? 0 : kRobustTrim);
  const double size = guesses.front().size();  // the cloud's: every guess has its extents
  // The loss's scales, the wider first (graduated: a wide loss finds the shape among the
  // outliers, the narrow one then leaves them out).
  std::vector<double> scales = {options.loss_scale * size};
  if (options.loss != Loss::kNone) scales.insert(scales.begin(), kWideScale * scales[0]);
  FitResult result;
  StartResult best = fitFromGuesses(cloud, guesses, options, scales, size, result);
  if (options.loss != Loss::kNone) {
    // Passes over the points the fit explains, the guesses taken again from them alone: the
    // cloud's outliers skew its principal axes and extents, and so every first guess. A pass's
    // answer, polished on the whole cloud, replaces the fit where its cost there is lower, and
    // the next pass starts from the points it explains (one pass from a far larger shape can
    // land on another wrong one that explains more of the inliers).
    const double band = kInlierBand * scales.back();
    for (int pass = 0; pass < kExplainedPasses; ++pass) {
      std::vector<Eigen::Vector3d> explained;
      for (const Eigen::Vector3d& p : cloud) {
        if (std::abs(residualOf(best.fitted, p, options.residual)) <= band) explained.push_back(p);
      }
      if (explained.size() < 4 || explained.size() == cloud.size()) break;
      const StartResult again = fitFromGuesses(explained, initialGuesses(explained, kRobustTrim),
                                               options, scales, size, result);
      const StartResult polished =
          fitFrom(cloud, again.fitted, options, scales.back(), options.max_iterations, size);
      result.iterations += polished.iterations;
      if (!(polished.cost < best.cost)) break;
      const bool progressed = polished.cost < (1 - kPassProgress) * best.cost;
      best = polished;
      if (!progressed) break;
    }
  }
  result.fitted = best.fitted;
  result.cost = best.cost;
  result.converged = best.converged;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace fse_fit
