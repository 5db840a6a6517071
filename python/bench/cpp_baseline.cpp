// The C++ side of the Python module's speed benchmark (speed.py): the calls a C++ user makes,
// timed on the same points in the same run, so speed.py reports Python against C++ as ratios.
//   fse_python_baseline POINTS a1 a2 a3 eps1 eps2 REPS
// POINTS: N × 3 float64, raw. Prints one JSON object of nanoseconds:
//   batch: batchDistance on all N points (default options: every thread), per point, best of REPS
//   batch_1_thread: the same on one thread
//   single: pointDistance(shape, X_WS, p) per call over the first min(N, 20000) points, best of
//   REPS
#include <fcl_superellipsoid/batch_distance.h>
#include <fcl_superellipsoid/point_distance.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace fse = fcl_superellipsoid;

namespace {

template <typename F>
double bestSeconds(int reps, F f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < reps; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 8) {
    std::cerr << "usage: fse_python_baseline POINTS a1 a2 a3 eps1 eps2 REPS\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  const Eigen::Index n = static_cast<Eigen::Index>(bytes.size() / (3 * sizeof(double)));
  fse::Matrix3X<double> points(3, n);
  std::memcpy(points.data(), bytes.data(), static_cast<std::size_t>(n) * 3 * sizeof(double));
  const fse::Superellipsoid<double> shape(std::stod(argv[2]), std::stod(argv[3]),
                                          std::stod(argv[4]), std::stod(argv[5]),
                                          std::stod(argv[6]));
  const int reps = std::stoi(argv[7]);
  const fcl::Transform3<double> X_WS = fcl::Transform3<double>::Identity();

  fse::BatchDistanceResult<double> result;
  fse::BatchOptions<double> one_thread;
  one_thread.threads = 1;
  const double batch = bestSeconds(reps, [&] { fse::batchDistance(shape, X_WS, points, result); });
  const double batch_1 =
      bestSeconds(reps, [&] { fse::batchDistance(shape, X_WS, points, result, one_thread); });
  const Eigen::Index singles = std::min<Eigen::Index>(n, 20000);
  double sink = 0;
  const double single = bestSeconds(reps, [&] {
    for (Eigen::Index i = 0; i < singles; ++i) {
      sink += fse::pointDistance(shape, X_WS, fse::Vector3<double>(points.col(i))).distance;
    }
  });
  std::cout << "{\"batch\": " << batch / n * 1e9 << ", \"batch_1_thread\": " << batch_1 / n * 1e9
            << ", \"single\": " << single / singles * 1e9 << ", \"sink\": " << (sink != 0) << "}\n";
  return 0;
}
