// A fixed pool of worker threads running index ranges. The calling thread works
// too, so a pool of N threads uses N-1 workers.
#pragma once
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>
#include <atomic>

namespace refx {

class ThreadPool {
 public:
  explicit ThreadPool(int threads);  // threads <= 0: hardware concurrency
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threadCount() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls fn(index, threadIndex) for every index in [0, count), dynamically
  // distributed; returns when all calls are done. threadIndex < threadCount().
  // Thread t starts on the t-th of threadCount() equal consecutive parts of the range
  // and, once its part is done, takes indices from the ends of the others: a thread
  // mostly gets the same indices call after call, so what it wrote for them last time
  // (a tile of the target) is still in its core's caches.
  void parallelFor(size_t count, const std::function<void(size_t, int)>& fn);

 private:
  void workerLoop(int threadIndex);
  void runItems(int threadIndex);
  // Takes the first (owner) or last (others) index left in part p; false: none left.
  bool takeFront(int p, size_t& index);
  bool takeBack(int p, size_t& index);
  bool allTaken() const;

  // The indices [first, end) of a part not yet taken, packed as first | end << 32, so
  // its owner and the others take them with one compare-exchange; a cache line each.
  struct alignas(64) Part {
    std::atomic<uint64_t> range{0};
  };

  std::vector<std::thread> workers_;
  std::vector<Part> parts_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(size_t, int)>* job_ = nullptr;
  // Changed under mutex_; atomic so that the threads can also poll them while they spin.
  std::atomic<int> busy_{0};
  std::atomic<uint64_t> generation_{0};
  std::atomic<bool> stop_{false};
};

}  // namespace refx
