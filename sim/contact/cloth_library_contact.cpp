// The `exact` and `paper` contact models: the library's batched, culled vertex queries
// (verticesWithinMargin), the way a user's simulator calls them: one reused contact vector,
// warm starts from the previous step's nearest points, the library's threads.

#include <fcl_superellipsoid/batch_distance.h>

#include <cmath>
#include <limits>

#include "contact/cloth_contact.h"

namespace fse_sim {

namespace fse = fcl_superellipsoid;

namespace {

class LibraryContact final : public ContactDetector {
 public:
  LibraryContact(const ShapeSpec& spec, int index, int vertex_count,
                 const SimulationOptions& options)
      : shape_(makeShape(spec)), index_(index), X_WS_(shapeTransform(spec)) {
    if (options.model == ContactModel::kPaper) {
      // The paper's case-study settings: tolerance 1e-3 (absolute, as in the paper; the
      // library's tolerances are relative to the shape's size) and 10 iterations.
      options_.distance.method = fse::DistanceMethod::kPaper;
      options_.distance.tolerance = 1e-3 / shape_.size();
      options_.distance.max_iterations = 10;
    }
    options_.threads = options.threads;
    warm_start_.setConstant(3, vertex_count, std::numeric_limits<double>::quiet_NaN());
    options_.warm_start_W = &warm_start_;
  }

  void detect(const Eigen::Matrix3Xd& x, double margin,
              std::vector<ContactCandidate>& out) override {
    fse::verticesWithinMargin(shape_, X_WS_, x, margin, contacts_, options_);
    for (const fse::VertexContact<double>& c : contacts_) {
      const int v = int(c.index);
      out.push_back({v, index_, c.distance, c.nearest_point, c.normal});
      warm_start_.col(v) = c.nearest_point;
    }
  }

 private:
  fse::Superellipsoidd shape_;
  int index_;
  fcl::Transform3d X_WS_;
  fse::BatchOptions<double> options_;
  Eigen::Matrix3Xd warm_start_;
  std::vector<fse::VertexContact<double>> contacts_;  // reused: no allocation once grown
};

}  // namespace

std::unique_ptr<ContactDetector> makeLibraryContact(const ShapeSpec& spec, int index,
                                                    int vertex_count,
                                                    const SimulationOptions& options) {
  return std::make_unique<LibraryContact>(spec, index, vertex_count, options);
}

}  // namespace fse_sim
