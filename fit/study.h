#ifndef FSE_FIT_STUDY_H
#define FSE_FIT_STUDY_H

// The fitting study: synthetic clouds of known superquadrics, fitted with the exact residual and
// with the radial one, measured against the truth. docs/fitting.md → "The study".

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "fit.h"
#include "synthetic_cloud.h"

namespace fse_fit {

struct StudyCase {
  std::string family;  ///< round, blocky, elongated, pinched, cylinder-like, mixed
  std::string view;    ///< full, partial
  CloudSpec cloud;
  FitOptions options;  ///< the loss (Cauchy where the cloud has outliers); residual set per fit
};

/// The cases: one shape of each family drawn from `seed` (exponents, radii with aspect ratios up
/// to 10:1, a pose), each seen fully and from one side, at noise 0, 1 % and 2 % of the size, and
/// with 20 % outliers at 1 % noise (fitted with a Cauchy loss of scale 2 % of the size).
/// `quick`: two families, full views, noise 0 and 1 %.
std::vector<StudyCase> studyCases(std::uint64_t seed, int points, bool quick);

struct StudyRow {
  std::string family, view, residual;
  double noise = 0, outliers = 0;
  ParameterError parameters;
  double rms = 0;          ///< surface RMS of the inliers (exact distance), × the size
  double shape_error = 0;  ///< surfaceError(fitted, truth)
  double seconds = 0;
  int iterations = 0;
  bool converged = false;
};

/// Fits every case with both residuals.
std::vector<StudyRow> runStudy(const std::vector<StudyCase>& cases);

void writeCsv(const std::vector<StudyRow>& rows, std::ostream& out);

}  // namespace fse_fit

#endif  // FSE_FIT_STUDY_H
