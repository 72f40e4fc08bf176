// Exceptions thrown inside an OpenMP parallel region.
//
// An exception may not leave a parallel region: the runtime calls std::terminate and the
// program aborts (exit 134) instead of printing one line and exiting with code 2 — e.g. a
// std::bad_alloc while a neighbour list grows, or an InputError from a law. A ParallelErrors
// object, declared before the region, catches every exception inside it, keeps one, and
// rethrows it after the region, on the thread that started it, where the command line's
// handlers (cli/main.cpp) and pybind11 see it as if the code had run serially:
//
//   ParallelErrors errors;
//   #pragma omp parallel for
//   for (long i = 0; i < n; ++i)
//     errors.run(i, [&] { ... });  // may throw
//   errors.rethrow();
//
// Of several, the one of the lowest index is kept, the one a serial run would have thrown, so
// the message does not depend on the thread count: once one was caught, work of a higher index
// is skipped (a region that fails does not run to its end), work of a lower one still runs.
#pragma once

#include <atomic>
#include <exception>
#include <limits>
#include <mutex>

namespace packlab {

class ParallelErrors {
 public:
  // Runs `work`, catching whatever it throws under the label `index` (an iteration number,
  // or a thread number for whole-region work). Does nothing when an error of a lower index
  // was caught.
  template <class Work>
  void run(long index, Work&& work) noexcept {
    if (index > index_.load(std::memory_order_relaxed)) return;
    try {
      work();
    } catch (...) {
      capture(index, std::current_exception());
    }
  }
  bool failed() const noexcept { return index_.load(std::memory_order_relaxed) != no_error; }
  // Rethrows the kept exception (call after the region), or returns when there was none.
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  static constexpr long no_error = std::numeric_limits<long>::max();

  void capture(long index, std::exception_ptr error) noexcept {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (index < index_.load(std::memory_order_relaxed)) {
      error_ = std::move(error);
      index_.store(index, std::memory_order_relaxed);
    }
  }

  std::mutex mutex_;
  std::atomic<long> index_{no_error};  // of the kept exception
  std::exception_ptr error_;
};

}  // namespace packlab
