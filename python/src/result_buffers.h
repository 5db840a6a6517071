#ifndef FSE_PYTHON_RESULT_BUFFERS_H
#define FSE_PYTHON_RESULT_BUFFERS_H
/// @file
/// The batched queries' result buffers, recycled between calls.
///
/// A C++ caller passes the same BatchDistanceResult to every call, so its memory is touched
/// once. A Python call returns arrays that own their result, and a fresh result of 1e5 points
/// (5.6 MB in double) is fresh pages from the kernel: their faults cost up to a third of the
/// query (measured: python/bench/speed.py). So a result whose arrays are all dropped comes back
/// here, and the next call of the same size reuses it; at most kKept are held per type.
#include <fcl_superellipsoid/batch_distance.h>

#include <memory>
#include <mutex>
#include <vector>

namespace fcl_superellipsoid {
namespace python {

template <typename S>
class ResultBuffers {
 public:
  static constexpr std::size_t kKept = 2;

  /// A result to fill for n points: a kept one of that size if there is one, else a new one.
  static std::unique_ptr<BatchDistanceResult<S>> take(Eigen::Index n) {
    Kept& kept = instance();
    std::lock_guard<std::mutex> lock(kept.mutex);
    for (auto it = kept.results.begin(); it != kept.results.end(); ++it) {
      if ((*it)->distance.size() == n) {
        std::unique_ptr<BatchDistanceResult<S>> result = std::move(*it);
        kept.results.erase(it);
        return result;
      }
    }
    return std::make_unique<BatchDistanceResult<S>>();
  }

  /// Takes back a result no array refers to any more (the owning capsule's destructor).
  static void give(BatchDistanceResult<S>* result) {
    std::unique_ptr<BatchDistanceResult<S>> owned(result);
    Kept& kept = instance();
    std::lock_guard<std::mutex> lock(kept.mutex);
    if (kept.results.size() == kKept) kept.results.erase(kept.results.begin());
    kept.results.push_back(std::move(owned));
  }

 private:
  struct Kept {
    std::mutex mutex;
    std::vector<std::unique_ptr<BatchDistanceResult<S>>> results;  // oldest first
  };
  /// Never destroyed: capsules may be freed while the interpreter shuts down.
  static Kept& instance() {
    static Kept* kept = new Kept;
    return *kept;
  }
};

}  // namespace python
}  // namespace fcl_superellipsoid

#endif  // FSE_PYTHON_RESULT_BUFFERS_H
