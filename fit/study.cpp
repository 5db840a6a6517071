#include "study.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <random>

namespace fse_fit {

namespace {

struct Family {
  const char* name;
  double eps1_low, eps1_high, eps2_low, eps2_high;
  double aspect_low, aspect_high;  // the largest radius over the smallest
};

constexpr Family kFamilies[] = {
    {"round", 0.8, 1.2, 0.8, 1.2, 1.3, 2.0},         {"blocky", 0.1, 0.3, 0.1, 0.3, 1.5, 3.0},
    {"elongated", 0.3, 1.0, 0.3, 1.0, 6.0, 10.0},    {"pinched", 1.5, 1.9, 1.5, 1.9, 1.3, 3.0},
    {"cylinder-like", 0.9, 1.1, 0.1, 0.3, 2.0, 4.0}, {"mixed", 0.1, 0.5, 1.2, 1.9, 1.5, 5.0},
};

Superquadric drawShape(const Family& f, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0, 1);
  auto within = [&](double low, double high) { return low + (high - low) * unit(random); };
  Superquadric sq;
  sq.eps1 = within(f.eps1_low, f.eps1_high);
  sq.eps2 = within(f.eps2_low, f.eps2_high);
  // Radii: the largest 1, the smallest 1/aspect, the middle one between them at least 15 %
  // from both (distinct radii: no description of the shape is ambiguous), in a random order.
  const double aspect = within(f.aspect_low, f.aspect_high);
  const double small = 1 / aspect;
  const double middle = std::exp(within(std::log(small * 1.15), std::log(1 / 1.15)));
  std::vector<double> radii = {1, middle, small};
  std::shuffle(radii.begin(), radii.end(), random);
  const double size = within(0.5, 2.0);
  sq.radii = size * Eigen::Vector3d(radii[0], radii[1], radii[2]);
  Eigen::Vector4d q(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
  sq.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  sq.translation = Eigen::Vector3d(within(-2, 2), within(-2, 2), within(-2, 2));
  return sq;
}

}  // namespace

std::vector<StudyCase> studyCases(std::uint64_t seed, int points, bool quick) {
  std::mt19937_64 random(seed);
  struct Condition {
    double noise, outliers;
  };
  const std::vector<Condition> conditions =
      quick ? std::vector<Condition>{{0, 0}, {0.01, 0}}
            : std::vector<Condition>{{0, 0}, {0.01, 0}, {0.02, 0}, {0.01, 0.2}};
  std::vector<StudyCase> cases;
  int families = 0;
  for (const Family& family : kFamilies) {
    if (quick && families == 2) break;
    ++families;
    const Superquadric truth = drawShape(family, random);
    std::uniform_real_distribution<double> unit(-1, 1);
    const Eigen::Vector3d view =
        Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    for (const bool partial : {false, true}) {
      if (quick && partial) continue;
      for (const Condition& c : conditions) {
        StudyCase k;
        k.family = family.name;
        k.view = partial ? "partial" : "full";
        k.cloud.truth = truth;
        k.cloud.points = points;
        k.cloud.partial = partial;
        k.cloud.view = view;
        k.cloud.noise = c.noise;
        k.cloud.outliers = c.outliers;
        k.cloud.seed = random();
        if (c.outliers > 0) {
          k.options.loss = Loss::kCauchy;
          k.options.loss_scale = 0.02;
        }
        cases.push_back(k);
      }
    }
  }
  return cases;
}

std::vector<StudyRow> runStudy(const std::vector<StudyCase>& cases) {
  std::vector<StudyRow> rows;
  for (const StudyCase& k : cases) {
    const SyntheticCloud cloud = makeCloud(k.cloud);
    for (const Residual residual : {Residual::kExact, Residual::kRadial}) {
      FitOptions options = k.options;
      options.residual = residual;
      const FitResult fit = fitSuperquadric(cloud.points, options);
      StudyRow row;
      row.family = k.family;
      row.view = k.view;
      row.residual = toString(residual);
      row.noise = k.cloud.noise;
      row.outliers = k.cloud.outliers;
      row.parameters = parameterError(fit.fitted, k.cloud.truth);
      row.rms = surfaceRms(fit.fitted, cloud.inliers) / k.cloud.truth.size();
      row.shape_error = surfaceError(fit.fitted, k.cloud.truth);
      row.seconds = fit.seconds;
      row.iterations = fit.iterations;
      row.converged = fit.converged;
      rows.push_back(row);
    }
  }
  return rows;
}

void writeCsv(const std::vector<StudyRow>& rows, std::ostream& out) {
  out << "family,view,noise,outliers,residual,parameter_error,centre_error,radii_error,"
         "exponent_error,rotation_error,rms,shape_error,seconds,iterations,converged\n";
  out << std::setprecision(6);
  for (const StudyRow& r : rows) {
    out << r.family << ',' << r.view << ',' << r.noise << ',' << r.outliers << ',' << r.residual
        << ',' << r.parameters.largest << ',' << r.parameters.centre << ',' << r.parameters.radii
        << ',' << r.parameters.exponents << ',' << r.parameters.rotation << ',' << r.rms << ','
        << r.shape_error << ',' << r.seconds << ',' << r.iterations << ',' << (r.converged ? 1 : 0)
        << '\n';
  }
}

}  // namespace fse_fit
