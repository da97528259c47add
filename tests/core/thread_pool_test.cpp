// ThreadPool::parallelFor: every index once whatever the split, a thread's own part
// first, and the others' indices taken when one part is slow.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "refx/core/thread_pool.h"

namespace refx {
namespace {

TEST(ThreadPool, EveryIndexRunsOnceForCountsAroundThePartSizes) {
  for (int threads : {2, 3, 4}) {
    ThreadPool pool(threads);
    for (size_t count : {2u, 3u, 5u, 7u, 64u, 192u, 1001u}) {
      std::vector<std::atomic<int>> hits(count);
      pool.parallelFor(count, [&](size_t i, int) { hits[i].fetch_add(1); });
      for (size_t i = 0; i < count; ++i) EXPECT_EQ(hits[i].load(), 1) << threads << " threads, index " << i;
    }
  }
}

// With the thread that takes index 0 stalled on it until index 1 has run, the other
// thread runs its own part and then part 0's remaining indices from its end.
TEST(ThreadPool, IdleThreadTakesTheIndicesOfABusyOne) {
  ThreadPool pool(2);
  constexpr size_t kCount = 64;
  std::vector<int> ranOn(kCount, -1);
  std::vector<size_t> thread1Order;  // written by thread 1 alone
  std::atomic<bool> release{false};
  pool.parallelFor(kCount, [&](size_t i, int t) {
    ranOn[i] = t;
    if (t == 1) thread1Order.push_back(i);
    if (i == 0) {  // part 0 is [0, 32): its owner, thread 0, starts here
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (!release.load() && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
    }
    if (i == 1) release = true;  // reached only by the other thread stealing part 0
  });
  EXPECT_TRUE(release.load());
  // Thread 0 runs index 0 at most: thread 1 runs its part [32, 64), then part 0 from
  // its end down to index 1 (and index 0 too where thread 0 had not started yet).
  for (size_t i = 1; i < kCount; ++i) EXPECT_EQ(ranOn[i], 1) << i;
  std::vector<size_t> expected;
  for (size_t i = 32; i < kCount; ++i) expected.push_back(i);
  for (size_t i = 31; i >= 1; --i) expected.push_back(i);
  if (ranOn[0] == 1) expected.push_back(0);
  EXPECT_EQ(thread1Order, expected);
}

}  // namespace
}  // namespace refx
