#include "report/measurements.h"

#include <fcl_superellipsoid/batch_distance.h>

#include <algorithm>
#include <cmath>

namespace fse_sim {

namespace fse = fcl_superellipsoid;

Measurer::Measurer(const Scene& scene) {
  for (const ShapeSpec& spec : scene.shapes) {
    shapes_.push_back(makeShape(spec));
    poses_.push_back(shapeTransform(spec));
  }
}

double Measurer::maxPenetration(const Eigen::Matrix3Xd& x) const {
  double deepest = 0;
  for (std::size_t s = 0; s < shapes_.size(); ++s) {
    for (const auto& c : fse::verticesWithinMargin(shapes_[s], poses_[s], x, 0.0)) {
      deepest = std::max(deepest, -c.distance);
    }
  }
  return deepest;
}

StepRecord Measurer::measure(const ClothSimulation& sim) const {
  StepRecord r;
  r.time = sim.time();
  r.seconds = sim.lastStepTimes();
  r.max_edge_strain = sim.maxEdgeStrain();
  r.energy = sim.energy();
  for (Eigen::Index i = 0; i < sim.velocities().cols(); ++i) {
    r.max_speed = std::max(r.max_speed, sim.velocities().col(i).norm());
  }
  if (shapes_.empty()) return r;
  r.max_penetration = maxPenetration(sim.positions());
  if (const Contacts* contacts = sim.contacts()) {
    // True distances of the vertices the contacts hold, per shape, in one batched call each.
    double sum = 0;
    for (std::size_t s = 0; s < shapes_.size(); ++s) {
      std::vector<int> held;
      for (int k : contacts->active()) {
        if (contacts->candidates()[k].shape == int(s))
          held.push_back(contacts->candidates()[k].vertex);
      }
      if (held.empty()) continue;
      Eigen::Matrix3Xd p(3, Eigen::Index(held.size()));
      for (std::size_t k = 0; k < held.size(); ++k)
        p.col(Eigen::Index(k)) = sim.positions().col(held[k]);
      fse::BatchDistanceResult<double> result;
      fse::batchDistance(shapes_[s], poses_[s], p, result);
      for (Eigen::Index k = 0; k < result.distance.size(); ++k) {
        const double e = std::abs(result.distance[k]);
        r.contact_error_max = std::max(r.contact_error_max, e);
        sum += e;
      }
      r.contacts += int(held.size());
    }
    if (r.contacts > 0) r.contact_error_mean = sum / r.contacts;
  }
  return r;
}

}  // namespace fse_sim
