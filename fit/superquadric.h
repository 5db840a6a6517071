#ifndef FSE_FIT_SUPERQUADRIC_H
#define FSE_FIT_SUPERQUADRIC_H

// A superquadric placed in the world: the library's shape (radii a1, a2, a3 and exponents ε1, ε2,
// the library's convention: ε1 shapes the xy-plane, ε2 the z direction) and its pose, as the fit
// estimates them. docs/fitting.md → "The model".

#include <fcl_superellipsoid/superellipsoid.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace fse_fit {

struct Superquadric {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // R_WS, unit
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();         // p_WS, the centre
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();
  double eps1 = 1;
  double eps2 = 1;

  /// The library's shape. @throws std::invalid_argument for radii or exponents out of range.
  fcl_superellipsoid::Superellipsoidd shape() const;
  /// X_WS.
  fcl::Transform3d pose() const;
  /// The largest radius.
  double size() const { return radii.maxCoeff(); }
};

/// The exact signed distance (the library's Exact method) of each world point from the surface:
/// > 0 outside, < 0 inside.
std::vector<double> signedDistances(const Superquadric& sq,
                                    const std::vector<Eigen::Vector3d>& p_W);

/// The same superquadric described another way: the descriptions of one solid differ by a half
/// turn about a shape axis, and by a quarter turn about z that swaps a1 and a2 (x and y enter F
/// alike). Of these eight, the one whose rotation is nearest `reference`'s, so that two fits can
/// be compared parameter by parameter.
Superquadric equivalentNearest(const Superquadric& sq, const Superquadric& reference);

/// How far a fitted superquadric's parameters are from the truth, after equivalentNearest: the
/// centre and the radii relative to the truth's size, the exponents absolute, the rotation as an
/// angle (radians). `largest` is the largest of them.
struct ParameterError {
  double centre = 0, radii = 0, exponents = 0, rotation = 0, largest = 0;
};
ParameterError parameterError(const Superquadric& fitted, const Superquadric& truth);

}  // namespace fse_fit

#endif  // FSE_FIT_SUPERQUADRIC_H
