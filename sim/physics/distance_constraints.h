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

  /// One projection of every constraint, in order, for a substep of length h.
  void project(Eigen::Matrix3Xd& x, const Eigen::VectorXd& inverse_mass, double h) const;

  /// max |C / L| over the constraints (strain of the edges).
  double maxStrain(const Eigen::Matrix3Xd& x) const;
  /// Σ C² / (2α) (elastic energy, J); 0 for hard constraints.
  double energy(const Eigen::Matrix3Xd& x) const;

 private:
  std::vector<std::array<int, 2>> pairs_;
  std::vector<double> rest_length_;
  double compliance_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_DISTANCE_CONSTRAINTS_H
