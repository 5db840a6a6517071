#ifndef FSE_SIM_PHYSICS_DISTANCE_CONSTRAINTS_H
#define FSE_SIM_PHYSICS_DISTANCE_CONSTRAINTS_H

// XPBD distance constraints C = |x_i − x_j| − L (Macklin, Müller, Chentanez 2016), the cloth's
// stretch (along triangle edges) and bending (across each inner edge, between the two
// vertices opposite it). One Gauss–Seidel iteration per substep ("Small steps", Macklin et al.
// 2019), λ starting at 0 each substep, so one projection is
//     Δλ = −C / (w_i + w_j + α/h²),   Δx_i = +w_i Δλ n,   Δx_j = −w_j Δλ n,   n = (x_i − x_j)/|x_i
//     − x_j|
// with w the inverse masses and α the compliance (m/N; 0: inextensible).

#include <Eigen/Core>
#include <array>
#include <vector>

namespace fse_sim {

class DistanceConstraints {
 public:
  /// One constraint per pair, its rest length taken from `rest`.
  DistanceConstraints(const std::vector<std::array<int, 2>>& pairs, const Eigen::Matrix3Xd& rest,
                      double compliance);

  /// One projection of every constraint, colour after colour, for a substep of length h. With
  /// `parallel`, a large colour is split over the current TBB arena's threads: the pairs of a
  /// colour share no vertex, so the result is bitwise the same for any number of threads.
  void project(Eigen::Matrix3Xd& x, const Eigen::VectorXd& inverse_mass, double h,
               bool parallel = false) const;

  /// max |C / L| over the constraints (strain of the edges).
  double maxStrain(const Eigen::Matrix3Xd& x) const;
  /// Σ C² / (2α) (elastic energy, J); 0 for hard constraints.
  double energy(const Eigen::Matrix3Xd& x) const;

 private:
  /// Pairs per task when a colour is split over threads.
  static constexpr std::size_t kParallelGrain = 512;

  void projectRange(std::size_t first, std::size_t last, Eigen::Matrix3Xd& x,
                    const Eigen::VectorXd& inverse_mass, double alpha_tilde) const;

  // colour_begin_ before pairs_: the constructor fills both from one call.
  std::vector<std::size_t> colour_begin_;  ///< where each colour starts; then pairs_.size()
  std::vector<std::array<int, 2>> pairs_;  ///< grouped by colour
  std::vector<double> rest_length_;
  double compliance_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_DISTANCE_CONSTRAINTS_H
