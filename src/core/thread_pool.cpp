#include "refx/core/thread_pool.h"

#include <algorithm>
#include <chrono>

namespace refx {

namespace {

// How long a thread polls for the next call (a worker) or for the workers to finish (the
// caller) before it sleeps on a condition variable. Waking a sleeping thread can cost
// milliseconds (an idle virtual CPU, the scheduler's wake-up preemption): more than a
// draw's shading, and a draw's calls come a few microseconds apart.
constexpr auto kSpinTime = std::chrono::microseconds(200);

// Polls `ready` for at most kSpinTime; true once it holds.
template <typename Ready>
bool spinUntil(Ready ready) {
  const auto deadline = std::chrono::steady_clock::now() + kSpinTime;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    if (std::chrono::steady_clock::now() >= deadline) return ready();
  }
}

int resolveThreads(int threads) {
  return threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}
}  // namespace

ThreadPool::ThreadPool(int threads) : parts_(size_t(resolveThreads(threads))) {
  for (int i = 1; i < int(parts_.size()); ++i) workers_.emplace_back([this, i] { workerLoop(i); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

bool ThreadPool::takeFront(int p, size_t& index) {
  std::atomic<uint64_t>& range = parts_[size_t(p)].range;
  uint64_t r = range.load(std::memory_order_relaxed);
  for (;;) {
    const uint64_t first = r & 0xffffffffu, end = r >> 32;
    if (first >= end) return false;
    if (range.compare_exchange_weak(r, r + 1, std::memory_order_relaxed)) {
      index = size_t(first);
      return true;
    }
  }
}

bool ThreadPool::takeBack(int p, size_t& index) {
  std::atomic<uint64_t>& range = parts_[size_t(p)].range;
  uint64_t r = range.load(std::memory_order_relaxed);
  for (;;) {
    const uint64_t first = r & 0xffffffffu, end = r >> 32;
    if (first >= end) return false;
    if (range.compare_exchange_weak(r, r - (uint64_t(1) << 32), std::memory_order_relaxed)) {
      index = size_t(end - 1);
      return true;
    }
  }
}

bool ThreadPool::allTaken() const {
  for (const Part& part : parts_) {
    const uint64_t r = part.range.load();
    if ((r & 0xffffffffu) < (r >> 32)) return false;
  }
  return true;
}

void ThreadPool::runItems(int threadIndex) {
  size_t i;
  while (takeFront(threadIndex, i)) (*job_)(i, threadIndex);
  const int n = threadCount();
  for (int k = 1; k < n; ++k) {
    const int other = (threadIndex + k) % n;
    while (takeBack(other, i)) (*job_)(i, threadIndex);
  }
}

void ThreadPool::workerLoop(int threadIndex) {
  uint64_t seen = 0;
  for (;;) {
    spinUntil([&] { return stop_.load() || generation_.load() != seen; });
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      ++busy_;
    }
    runItems(threadIndex);
    {
      std::lock_guard lock(mutex_);
      if (--busy_ == 0) done_.notify_all();
    }
  }
}

void ThreadPool::parallelFor(size_t count, const std::function<void(size_t, int)>& fn) {
  if (count == 0) return;
  if (workers_.empty() || count == 1) {
    for (size_t i = 0; i < count; ++i) fn(i, 0);
    return;
  }
  constexpr size_t kMaxCount = 0xffffffffu;  // indices packed in 32 bits (Part)
  if (count > kMaxCount) {
    for (size_t base = 0; base < count; base += kMaxCount)
      parallelFor(std::min(kMaxCount, count - base), [&](size_t i, int t) { fn(base + i, t); });
    return;
  }
  const size_t n = parts_.size();
  {
    std::lock_guard lock(mutex_);
    job_ = &fn;
    for (size_t p = 0; p < n; ++p)
      parts_[p].range.store(uint64_t(count * p / n) | uint64_t(count * (p + 1) / n) << 32);
    ++generation_;
  }
  wake_.notify_all();
  runItems(0);
  spinUntil([&] { return busy_.load() == 0 && allTaken(); });
  std::unique_lock lock(mutex_);
  // Workers that woke late find no items left and finish at once.
  done_.wait(lock, [&] { return busy_ == 0 && allTaken(); });
  job_ = nullptr;
}

}  // namespace refx
