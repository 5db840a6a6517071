#ifndef FCL_SUPERELLIPSOID_SRC_COMMON_TASKS_H
#define FCL_SUPERELLIPSOID_SRC_COMMON_TASKS_H

// Internal: the library's own parallel work on TBB's threads, and its stand-in in the
// ThreadSanitizer build. TSan cannot see TBB's synchronisation (Debian's libtbb is not
// instrumented), so in that build (scripts/test.sh --tsan) a task runs on a std::thread, joined
// visibly, and a sort runs on the calling thread: TSan's reports are then about this library's
// shared state, not TBB's scheduler.

#include <algorithm>
#include <exception>
#include <utility>

#if defined(__SANITIZE_THREAD__)
#include <mutex>
#include <thread>
#include <vector>
#else
#include <tbb/parallel_sort.h>
#include <tbb/task_group.h>
#endif

namespace fcl_superellipsoid {
namespace detail {

/// Tasks run beside the calling thread until wait(), which rethrows the first exception a task
/// threw. The destructor waits too (dropping exceptions), so no task outlives what it uses.
class TaskGroup {
 public:
  TaskGroup() = default;
  TaskGroup(const TaskGroup&) = delete;
  TaskGroup& operator=(const TaskGroup&) = delete;
  ~TaskGroup() {
    try {
      wait();
    } catch (...) {
    }
  }

  template <typename F>
  void run(F&& f) {
#if defined(__SANITIZE_THREAD__)
    threads_.emplace_back([this, f = std::forward<F>(f)]() mutable {
      try {
        f();
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = std::current_exception();
      }
    });
#else
    group_.run(std::forward<F>(f));
#endif
  }

  void wait() {
#if defined(__SANITIZE_THREAD__)
    for (std::thread& t : threads_) t.join();
    threads_.clear();
    std::exception_ptr error;
    std::swap(error, error_);
    if (error) std::rethrow_exception(error);
#else
    group_.wait();
#endif
  }

 private:
#if defined(__SANITIZE_THREAD__)
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::exception_ptr error_;
#else
  tbb::task_group group_;
#endif
};

/// Sorts [first, last) by less, on TBB's threads. less must be a strict total order on the
/// elements (no two compare equal), so that the result does not depend on the algorithm.
template <typename It, typename Less>
void parallelSort(It first, It last, const Less& less) {
#if defined(__SANITIZE_THREAD__)
  std::sort(first, last, less);
#else
  tbb::parallel_sort(first, last, less);
#endif
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_COMMON_TASKS_H
