// core/parallel_errors.hpp: an exception thrown inside an OpenMP parallel region comes out of
// it, after the region, as the same exception (not std::terminate), whatever the thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <string>

#include "packlab/core/error.hpp"
#include "packlab/core/parallel_errors.hpp"

using packlab::InputError;
using packlab::ParallelErrors;

TEST(ParallelErrors, AnExceptionInsideAParallelLoopIsRethrownAfterIt) {
  for (int threads : {1, 2, 4}) {
    ParallelErrors errors;
    std::atomic<long> ran{0};
#pragma omp parallel for num_threads(threads) schedule(static)
    for (long i = 0; i < 1000; ++i)
      errors.run(i, [&] {
        ++ran;
        if (i == 637) packlab::fail_input("particle 637: bad");
      });
    EXPECT_TRUE(errors.failed());
    EXPECT_GT(ran.load(), 0);
    try {
      errors.rethrow();
      FAIL() << "nothing rethrown";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "particle 637: bad");
    }
  }
}

TEST(ParallelErrors, AnAllocationFailureStaysABadAllocAndTheLowestIndexIsKept) {
  ParallelErrors errors;
#pragma omp parallel num_threads(3)
  {
#pragma omp for schedule(static)
    for (long i = 0; i < 3; ++i)
      errors.run(i, [&] {
        if (i == 1) throw std::bad_alloc();
        if (i == 2) packlab::fail_input("later");
      });
  }
  // Index 1 is kept whichever thread threw first (with one thread, index 2 is not even run).
  EXPECT_THROW(errors.rethrow(), std::bad_alloc);
  ParallelErrors none;
#pragma omp parallel for num_threads(2)
  for (long i = 0; i < 10; ++i) none.run(i, [] {});
  EXPECT_FALSE(none.failed());
  EXPECT_NO_THROW(none.rethrow());
}
