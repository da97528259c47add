#include "bench_cycles.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <immintrin.h>
#include <ctime>

#include <fmt/format.h>
#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace refx::cli {

namespace {

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

// A chain of dependent integer adds retires one add per cycle on every x86 core of
// the last decade, so adds / seconds is the clock the core runs at under load. The
// seconds are the thread's CPU time: time other processes take the core is not counted.
double measureClockHz() {
  constexpr uint64_t kAdds = 24'000'000;  // ~7 ms: little in a profile of a short run
  uint64_t x = 1;
  const double t0 = threadCpuSeconds();
  for (uint64_t i = 0; i < kAdds / 8; ++i) {
    // Eight adds per iteration keep the loop overhead off the chain's critical path.
    asm volatile(
        "add %0, %0\n\tadd %0, %0\n\tadd %0, %0\n\tadd %0, %0\n\t"
        "add %0, %0\n\tadd %0, %0\n\tadd %0, %0\n\tadd %0, %0"
        : "+r"(x));
  }
  return double(kAdds) / (threadCpuSeconds() - t0);
}

}  // namespace

void CycleCounter::start() {
  perf_event_attr attr;
  std::memset(&attr, 0, sizeof attr);
  attr.size = sizeof attr;
  attr.type = PERF_TYPE_HARDWARE;
  attr.config = PERF_COUNT_HW_CPU_CYCLES;
  attr.exclude_kernel = 1;
  attr.exclude_hv = 1;
  attr.inherit = 1;  // the device's worker threads, created later, count into this one
  fd_ = int(syscall(SYS_perf_event_open, &attr, 0, -1, -1, 0));
  if (fd_ >= 0) {
    uint64_t probe = 0;
    // Some hypervisors accept the event but never count: treat that as unavailable.
    if (::read(fd_, &probe, sizeof probe) != sizeof probe) {
      close(fd_);
      fd_ = -1;
    }
  }
  if (fd_ < 0) hz_ = measureClockHz();
}

CycleCounter::~CycleCounter() {
  if (fd_ >= 0) close(fd_);
}

double CycleCounter::read() const {
  if (fd_ >= 0) {
    uint64_t v = 0;
    if (::read(fd_, &v, sizeof v) == sizeof v) return double(v);
    return 0;
  }
  return processCpuSeconds() * hz_;
}

std::string CycleCounter::source() const {
  if (fd_ >= 0) return "perf_event_open cycles:u, all threads";
  return fmt::format("process CPU time x measured clock {:.2f} GHz: no cycle counter", hz_ * 1e-9);
}

namespace {

// Twelve independent FMA chains: more than latency (4-5 cycles) x ports (2) needs, so
// the loop runs at the FMA units' throughput. FLOPs per second of thread time. The
// loop is spelled once per ISA: code for one target cannot inline another's intrinsics.
constexpr int kChains = 12;
constexpr uint64_t kFmaIterations = 400'000;  // ~2-4 ms

double flopRate(double seconds, int lanes) {
  return double(kFmaIterations) * kChains * lanes * 2 / seconds;
}

__attribute__((target("avx512f"))) double avx512Rate() {
  __m512 acc[kChains];
  for (auto& a : acc) a = _mm512_set1_ps(1.0f);
  const __m512 mul = _mm512_set1_ps(0.999f), add = _mm512_set1_ps(0.001f);
  const double t0 = threadCpuSeconds();
  for (uint64_t i = 0; i < kFmaIterations; ++i)
    for (auto& a : acc) {
      a = _mm512_fmadd_ps(a, mul, add);
      asm volatile("" : "+v"(a));  // keeps every chain and iteration
    }
  return flopRate(threadCpuSeconds() - t0, 16);
}

__attribute__((target("avx2,fma"))) double avx2Rate() {
  __m256 acc[kChains];
  for (auto& a : acc) a = _mm256_set1_ps(1.0f);
  const __m256 mul = _mm256_set1_ps(0.999f), add = _mm256_set1_ps(0.001f);
  const double t0 = threadCpuSeconds();
  for (uint64_t i = 0; i < kFmaIterations; ++i)
    for (auto& a : acc) {
      a = _mm256_fmadd_ps(a, mul, add);
      asm volatile("" : "+v"(a));
    }
  return flopRate(threadCpuSeconds() - t0, 8);
}

}  // namespace

PeakFlops peakFlopsPerCycle() {
  __builtin_cpu_init();
  const double hz = measureClockHz();
  auto best = [&](double (*rate)()) {  // the best of three: neighbours only slow a run down
    double r = 0;
    for (int i = 0; i < 3; ++i) r = std::max(r, rate());
    return std::round(r / hz * 10) / 10;
  };
  if (__builtin_cpu_supports("avx512f")) return {best(avx512Rate), "AVX-512"};
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return {best(avx2Rate), "AVX2+FMA"};
  return {8, "SSE (not measured: 4-lane mul and add)"};
}

}  // namespace refx::cli
