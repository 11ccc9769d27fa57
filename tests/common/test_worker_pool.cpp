// The worker pool runs every index once, in blocks over its threads, and hands an exception
// back to the caller.
#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "common/worker_pool.h"

namespace aerobox {
namespace {

TEST_CASE("every index is run once, whatever the threads and the size") {
  for (int threads : {1, 2, 3, 8}) {
    WorkerPool pool(threads);
    CHECK(pool.threads() == threads);
    for (int n : {0, 1, 2, 5, 64, 1001}) {
      std::vector<std::atomic<int>> runs(static_cast<size_t>(n));
      for (int repeat = 0; repeat < 3; ++repeat) {
        pool.For(n, [&](int begin, int end) {
          for (int i = begin; i < end; ++i) ++runs[static_cast<size_t>(i)];
        });
      }
      for (const auto& r : runs) CHECK(r == 3);
    }
  }
}

TEST_CASE("an exception in a block reaches the caller, and the pool goes on") {
  WorkerPool pool(2);
  CHECK_THROWS_WITH_AS(pool.For(10,
                                [](int begin, int) {
                                  if (begin >= 5) throw std::runtime_error("block 2 failed");
                                }),
                       "block 2 failed", std::runtime_error);
  std::atomic<int> sum{0};
  pool.For(10, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) sum += i;
  });
  CHECK(sum == 45);
}

}  // namespace
}  // namespace aerobox
