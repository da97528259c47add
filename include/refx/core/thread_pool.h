// A fixed pool of worker threads running index ranges. The calling thread works
// too, so a pool of N threads uses N-1 workers.
#pragma once
#include <condition_variable>
#include <cstddef>
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
  void parallelFor(size_t count, const std::function<void(size_t, int)>& fn);

 private:
  void workerLoop(int threadIndex);
  void runItems(int threadIndex);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(size_t, int)>* job_ = nullptr;
  size_t count_ = 0;
  std::atomic<size_t> next_{0};
  int busy_ = 0;
  uint64_t generation_ = 0;
  bool stop_ = false;
};

}  // namespace refx
