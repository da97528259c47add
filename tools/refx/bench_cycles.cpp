#include "bench_cycles.h"

#include <cstring>
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

PeakFlops peakFlopsPerCycle() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return {64, "AVX-512"};
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return {32, "AVX2+FMA"};
  return {8, "SSE"};
}

}  // namespace refx::cli
