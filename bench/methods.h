#ifndef FCL_SUPERELLIPSOID_BENCH_METHODS_H
#define FCL_SUPERELLIPSOID_BENCH_METHODS_H

// Every way the benchmark answers "how far is this point from the shape?": our solvers, the
// paper's, and what an FCL or Bullet user would otherwise use. Each method is built once per
// shape (meshes are tessellated then) and queried with points in the shape's frame.

#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "workload.h"

namespace fcl_superellipsoid {
namespace bench {

struct Answer {
  double distance;          // signed (negative inside) if the method signs, else ≥ 0
  Vector3<double> nearest;  // a nearest surface point, shape frame
  int converged;            // 1 or 0; −1 where the method has no convergence test
  double estimate = NAN;    // the method's own error estimate (the paper's Eq. 7), if any
};

// Family names, as they appear in tables, CSV and JSON.
inline constexpr const char* kExact = "Exact";
inline constexpr const char* kPaper = "Paper";
inline constexpr const char* kRadial = "Radial";
inline constexpr const char* kFclMesh = "FCL mesh";
inline constexpr const char* kFclConvex = "FCL GJK convex";
inline constexpr const char* kFclEllipsoid = "FCL GJK ellipsoid";
inline constexpr const char* kBullet = "Bullet GJK";
inline constexpr const char* kFrontEnd = "Front end";

class Method {
 public:
  /// setting: the knob's value as printed ("1e-09", "272 v"); setting_value: the same as a
  /// number (tolerance, vertex count, or NaN); memory_bytes: the representation's size.
  Method(std::string family, std::string setting, double setting_value, bool is_signed,
         std::size_t memory_bytes)
      : family_(std::move(family)),
        setting_(std::move(setting)),
        setting_value_(setting_value),
        signed_(is_signed),
        memory_bytes_(memory_bytes) {}
  virtual ~Method() = default;

  /// The distance from x (shape frame). Never throws for finite x.
  virtual Answer query(const Vector3<double>& x) const = 0;

  const std::string& family() const { return family_; }
  const std::string& setting() const { return setting_; }
  std::string label() const { return setting_.empty() ? family_ : family_ + " " + setting_; }
  double settingValue() const { return setting_value_; }
  bool isSigned() const { return signed_; }
  std::size_t memoryBytes() const { return memory_bytes_; }
  /// Seconds spent building the representation (tessellation, BVH), 0 for the solvers.
  double setupSeconds() const { return setup_seconds_; }
  void setSetupSeconds(double s) { setup_seconds_ = s; }

 private:
  std::string family_, setting_;
  double setting_value_;
  bool signed_;
  std::size_t memory_bytes_;
  double setup_seconds_ = 0;
};

/// Which methods and settings to build.
struct MethodSelection {
  std::vector<double> exact_tolerances{1e-3, 1e-6, 1e-9, 1e-12};
  std::vector<double> paper_tolerances{1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6};  // cap 30, as the paper
  bool radial = true;
  std::vector<int> mesh_vertices{72, 272, 1000, 4000, 16000, 64000};
  // fcl::Convex's support function scans every vertex: beyond a few thousand it is
  // hopeless per query, and the full run would take hours.
  std::vector<int> convex_vertices{72, 272, 1000};
  bool fcl_ellipsoid = true;  // on shapes with ε1 = ε2 = 1 only
  bool bullet = true;
  bool front_end = true;
};

/// The methods of `selection` for this shape, in table order.
std::vector<std::unique_ptr<Method>> makeMethods(const BenchShape& shape,
                                                 const MethodSelection& selection);

// Per-family factories (methods.cpp, methods_fcl.cpp, methods_bullet.cpp).
std::unique_ptr<Method> makeSolverMethod(const BenchShape& shape, const char* family,
                                         double tolerance);
std::unique_ptr<Method> makeFclMeshMethod(const BenchShape& shape, int vertices);
std::unique_ptr<Method> makeFclConvexMethod(const BenchShape& shape, int vertices);
std::unique_ptr<Method> makeFclEllipsoidMethod(const BenchShape& shape);
std::unique_ptr<Method> makeFrontEndMethod(const BenchShape& shape);
std::unique_ptr<Method> makeBulletMethod(const BenchShape& shape);

/// "1e-09"-style text of a tolerance.
std::string toleranceText(double tolerance);

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_METHODS_H
