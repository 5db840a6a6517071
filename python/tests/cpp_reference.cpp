// The library's own answers for the Python tests (test_same_answers.py): reads one request as
// JSON on stdin, answers with the C++ calls a C++ user would make, writes JSON on stdout.
//   {"query": "batch" | "scalar", "dtype": "float32" | "float64", "radii": [3], "exponents": [2],
//    "pose": 4 × 4 rows, "method": "exact" | "paper" | "radial", "vectorize": bool,
//    "points": file of N × 3 raw values, "out": file for distance N, nearest N × 3, normal N × 3}
//   {"query": "jacobians", the same fields}: pointDistanceDerivatives with kJacobians (default
//     options) per point, "out" holding per point distance, nearest (3), normal (3),
//     d_pose (6), d_shape (5), then ∂N/∂Q, ∂N/∂ξ, ∂N/∂θ, ∂n/∂Q, ∂n/∂ξ, ∂n/∂θ, each row-major
//   {"query": "pair", "radii", "exponents", "pose", "other": {"kind": ..., ...}, "other_pose"}
//     → {"distance", "point1", "point2", "contacts": [{"position", "normal", "depth"}],
//        "jacobians": pairDistanceDerivatives' fields with kJacobians, matrices row-major}
// Doubles are written with enough digits to round-trip, so the comparison is bitwise.
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl_superellipsoid/batch_distance.h>
#include <fcl_superellipsoid/fcl_integration.h>
#include <fcl_superellipsoid/pair_derivatives.h>
#include <fcl_superellipsoid/point_derivatives.h>
#include <fcl_superellipsoid/point_distance.h>

#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

namespace fse = fcl_superellipsoid;
using nlohmann::json;

namespace {

template <typename S>
fcl::Transform3<S> poseOf(const json& rows) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) X.matrix()(i, j) = static_cast<S>(rows[i][j].get<double>());
  }
  return X;
}

fse::DistanceMethod methodOf(const std::string& name) {
  if (name == "paper") return fse::DistanceMethod::kPaper;
  if (name == "radial") return fse::DistanceMethod::kRadial;
  return fse::DistanceMethod::kExact;
}

template <typename S>
void pointQueries(const json& request) {
  const fse::Superellipsoid<S> shape(
      Eigen::Vector3d(request["radii"][0], request["radii"][1], request["radii"][2]).cast<S>(),
      static_cast<S>(request["exponents"][0].get<double>()),
      static_cast<S>(request["exponents"][1].get<double>()));
  const fcl::Transform3<S> X_WS = poseOf<S>(request["pose"]);
  fse::BatchOptions<S> options;
  options.distance = fse::DistanceOptions<S>::of(methodOf(request["method"]));
  options.vectorize = request["vectorize"];
  std::ifstream in(request["points"].get<std::string>(), std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  const Eigen::Index n = static_cast<Eigen::Index>(bytes.size() / (3 * sizeof(S)));
  fse::Matrix3X<S> p_WV(3, n);
  std::memcpy(p_WV.data(), bytes.data(), static_cast<std::size_t>(n) * 3 * sizeof(S));
  fse::BatchDistanceResult<S> result;
  if (request["query"] == "batch") {
    fse::batchDistance(shape, X_WS, p_WV, result, options);
  } else if (request["query"] == "scalar") {
    result.distance.resize(n);
    result.nearest_point.resize(3, n);
    result.normal.resize(3, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto r =
          fse::pointDistance(shape, X_WS, fse::Vector3<S>(p_WV.col(i)), options.distance);
      result.distance(i) = r.distance;
      result.nearest_point.col(i) = r.nearest_point;
      result.normal.col(i) = r.normal;
    }
  }
  std::ofstream out(request["out"].get<std::string>(), std::ios::binary);
  const auto bytes_of = [&](const S* data, Eigen::Index count) {
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(count * sizeof(S)));
  };
  if (request["query"] == "jacobians") {
    const auto row_major = [&](const auto& m) {
      for (Eigen::Index r = 0; r < m.rows(); ++r) {
        for (Eigen::Index c = 0; c < m.cols(); ++c) bytes_of(&m(r, c), 1);
      }
    };
    for (Eigen::Index i = 0; i < n; ++i) {
      const fse::PointDistanceDerivatives<S> r = fse::pointDistanceDerivatives(
          shape, X_WS, fse::Vector3<S>(p_WV.col(i)), fse::DerivativeOrder::kJacobians);
      bytes_of(&r.value.distance, 1);
      bytes_of(r.value.nearest_point.data(), 3);
      bytes_of(r.value.normal.data(), 3);
      bytes_of(r.d_pose.data(), 6);
      bytes_of(r.d_shape.data(), 5);
      row_major(r.nearest_point_d_query);
      row_major(r.nearest_point_d_pose);
      row_major(r.nearest_point_d_shape);
      row_major(r.normal_d_query);
      row_major(r.normal_d_pose);
      row_major(r.normal_d_shape);
    }
    return;
  }
  bytes_of(result.distance.data(), n);
  bytes_of(result.nearest_point.data(), 3 * n);
  bytes_of(result.normal.data(), 3 * n);
}

std::shared_ptr<fcl::CollisionGeometry<double>> otherOf(const json& o) {
  const std::string kind = o["kind"];
  const std::vector<double> v = o["values"];
  if (kind == "box") return std::make_shared<fcl::Box<double>>(v[0], v[1], v[2]);
  if (kind == "sphere") return std::make_shared<fcl::Sphere<double>>(v[0]);
  if (kind == "ellipsoid") return std::make_shared<fcl::Ellipsoid<double>>(v[0], v[1], v[2]);
  if (kind == "capsule") return std::make_shared<fcl::Capsule<double>>(v[0], v[1]);
  if (kind == "cylinder") return std::make_shared<fcl::Cylinder<double>>(v[0], v[1]);
  if (kind == "cone") return std::make_shared<fcl::Cone<double>>(v[0], v[1]);
  if (kind == "halfspace") return std::make_shared<fcl::Halfspace<double>>(v[0], v[1], v[2], v[3]);
  if (kind == "plane") return std::make_shared<fcl::Plane<double>>(v[0], v[1], v[2], v[3]);
  if (kind == "superellipsoid") {
    return std::make_shared<fse::Superellipsoid<double>>(v[0], v[1], v[2], v[3], v[4]);
  }
  throw std::invalid_argument("cpp_reference: unknown kind " + kind);
}

json vector3(const Eigen::Vector3d& v) { return json::array({v(0), v(1), v(2)}); }

/// A matrix's entries, row after row.
template <typename Matrix>
json rowMajor(const Matrix& m) {
  json out = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) out.push_back(m(r, c));
  }
  return out;
}

void pairQuery(const json& request) {
  const auto shape = std::make_shared<fse::Superellipsoid<double>>(
      request["radii"][0], request["radii"][1], request["radii"][2], request["exponents"][0],
      request["exponents"][1]);
  const auto other = otherOf(request["other"]);
  const fcl::Transform3<double> X1 = poseOf<double>(request["pose"]);
  const fcl::Transform3<double> X2 = poseOf<double>(request["other_pose"]);
  fcl::DistanceRequest<double> distance_request(true);
  distance_request.enable_signed_distance = true;
  fcl::DistanceResult<double> distance_result;
  fse::distance(shape.get(), X1, other.get(), X2, distance_request, distance_result);
  fcl::CollisionRequest<double> collision_request(1, true);
  fcl::CollisionResult<double> collision_result;
  fse::collide(shape.get(), X1, other.get(), X2, collision_request, collision_result);
  json answer = {{"distance", distance_result.min_distance},
                 {"point1", vector3(distance_result.nearest_points[0])},
                 {"point2", vector3(distance_result.nearest_points[1])},
                 {"contacts", json::array()}};
  for (std::size_t i = 0; i < collision_result.numContacts(); ++i) {
    const auto& c = collision_result.getContact(i);
    answer["contacts"].push_back({{"position", vector3(c.pos)},
                                  {"normal", vector3(c.normal)},
                                  {"depth", c.penetration_depth}});
  }
  const fse::PairDistanceDerivatives<double> j =
      fse::pairDistanceDerivatives(*shape, X1, *other, X2, fse::DerivativeOrder::kJacobians);
  answer["jacobians"] = {{"distance", j.distance},
                         {"normal", vector3(j.normal)},
                         {"d_pose", rowMajor(j.d_pose)},
                         {"d_other_pose", rowMajor(j.d_other_pose)},
                         {"d_shape", rowMajor(j.d_shape)},
                         {"on_shape_d_pose", rowMajor(j.on_shape_d_pose)},
                         {"on_shape_d_other_pose", rowMajor(j.on_shape_d_other_pose)},
                         {"on_other_d_pose", rowMajor(j.on_other_d_pose)},
                         {"on_other_d_other_pose", rowMajor(j.on_other_d_other_pose)},
                         {"normal_d_pose", rowMajor(j.normal_d_pose)},
                         {"normal_d_other_pose", rowMajor(j.normal_d_other_pose)},
                         {"differentiable", j.differentiable}};
  std::cout << answer.dump() << "\n";
}

}  // namespace

int main() {
  const json request = json::parse(std::cin);
  if (request["query"] == "pair") {
    pairQuery(request);
  } else if (request["dtype"] == "float32") {
    pointQueries<float>(request);
  } else {
    pointQueries<double>(request);
  }
  return 0;
}
