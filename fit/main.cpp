// fse_fit: fits superquadrics to point clouds with the library's exact distance
// (docs/fitting.md).
//   fse_fit study --out DIR [--seed N] [--points N] [--quick]
//       the study: synthetic clouds of known shapes, fitted with the exact and the radial
//       residual; writes DIR/study.csv (fit/fit_report.py turns it into a table and a plot)
//   fse_fit cloud FILE --out DIR [--residual exact|radial] [--loss none|huber|cauchy]
//                    [--loss-scale F]
//       fits one cloud (XYZ or PLY); writes DIR/fit.json and DIR/fit.obj
// Exit status: 0 done, 2 bad input (a message naming it; nothing written), 1 anything else.

#include <fcl_superellipsoid/tessellation.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "fit.h"
#include "point_cloud_file.h"
#include "study.h"

namespace {

using fse_fit::Superquadric;

nlohmann::json toJson(const Superquadric& sq) {
  const Eigen::Quaterniond q = sq.rotation.normalized();
  const Eigen::Matrix3d R = q.toRotationMatrix();
  return {
      {"radii", {sq.radii[0], sq.radii[1], sq.radii[2]}},
      {"exponents", {sq.eps1, sq.eps2}},
      {"translation", {sq.translation[0], sq.translation[1], sq.translation[2]}},
      {"rotation_wxyz", {q.w(), q.x(), q.y(), q.z()}},
      {"rotation_matrix",
       {{R(0, 0), R(0, 1), R(0, 2)}, {R(1, 0), R(1, 1), R(1, 2)}, {R(2, 0), R(2, 1), R(2, 2)}}}};
}

void writeObjInWorld(const Superquadric& sq, const std::string& path) {
  auto mesh = fcl_superellipsoid::tessellate(sq.shape(), 2000);
  const fcl::Transform3d X_WS = sq.pose();
  for (auto& v : mesh.vertices) v = X_WS * v;
  fcl_superellipsoid::writeObj(mesh, path);
}

int runCloud(const std::string& file, const std::string& out, fse_fit::FitOptions options) {
  const std::vector<Eigen::Vector3d> cloud = fse_fit::readPointCloud(file);
  const fse_fit::FitResult fit = fse_fit::fitSuperquadric(cloud, options);
  const double rms = fse_fit::surfaceRms(fit.fitted, cloud);
  nlohmann::json json = toJson(fit.fitted);
  json["cloud"] = {{"file", file}, {"points", cloud.size()}};
  json["fit"] = {{"residual", fse_fit::toString(options.residual)},
                 {"loss", fse_fit::toString(options.loss)},
                 {"loss_scale", options.loss_scale},
                 {"surface_rms", rms},
                 {"iterations", fit.iterations},
                 {"converged", fit.converged},
                 {"seconds", fit.seconds}};
  std::filesystem::create_directories(out);
  std::ofstream(out + "/fit.json") << json.dump(2) << '\n';
  writeObjInWorld(fit.fitted, out + "/fit.obj");
  std::cout << json.dump(2) << "\nwritten: " << out << "/fit.json, " << out << "/fit.obj\n";
  return 0;
}

int runStudy(const std::string& out, std::uint64_t seed, int points, bool quick) {
  const auto cases = fse_fit::studyCases(seed, points, quick);
  std::cout << cases.size() << " cases, each fitted with both residuals\n";
  const auto rows = fse_fit::runStudy(cases);
  std::filesystem::create_directories(out);
  std::ofstream csv(out + "/study.csv");
  csv << "# fse_fit study --seed " << seed << " --points " << points << (quick ? " --quick" : "")
      << '\n';
  fse_fit::writeCsv(rows, csv);
  std::cout << "written: " << out << "/study.csv\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Fits superquadrics to point clouds with the exact distance (docs/fitting.md)"};
  app.require_subcommand(1);
  std::string out;

  CLI::App* study = app.add_subcommand("study", "synthetic clouds of known shapes, both residuals");
  std::uint64_t seed = 1;
  int points = 1000;
  bool quick = false;
  study->add_option("--out", out, "output folder")->required();
  study->add_option("--seed", seed, "draws the shapes, poses and clouds");
  study->add_option("--points", points, "points per cloud")->check(CLI::Range(20, 1000000));
  study->add_flag("--quick", quick, "two families, full views, noise 0 and 1 %");

  CLI::App* cloud = app.add_subcommand("cloud", "fit one cloud file (XYZ or PLY)");
  std::string file;
  fse_fit::FitOptions options;
  const std::map<std::string, fse_fit::Residual> residuals = {
      {"exact", fse_fit::Residual::kExact}, {"radial", fse_fit::Residual::kRadial}};
  const std::map<std::string, fse_fit::Loss> losses = {{"none", fse_fit::Loss::kNone},
                                                       {"huber", fse_fit::Loss::kHuber},
                                                       {"cauchy", fse_fit::Loss::kCauchy}};
  cloud->add_option("file", file, "the point cloud (.xyz, .txt or .ply)")->required();
  cloud->add_option("--out", out, "output folder")->required();
  cloud->add_option("--residual", options.residual, "exact or radial")
      ->transform(CLI::CheckedTransformer(residuals, CLI::ignore_case));
  cloud->add_option("--loss", options.loss, "none, huber or cauchy")
      ->transform(CLI::CheckedTransformer(losses, CLI::ignore_case));
  cloud->add_option("--loss-scale", options.loss_scale, "the loss's scale, × the cloud's size")
      ->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (*study) return runStudy(out, seed, points, quick);
    return runCloud(file, out, options);
  } catch (const fse_fit::CloudFileError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
}
