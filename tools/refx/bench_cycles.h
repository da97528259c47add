// CPU cycles spent by this process and the core's peak FP32 throughput, for the
// cycles-per-pixel columns of `refx bench`.
#pragma once
#include <cstdint>
#include <string>

namespace refx::cli {

// User-mode cycles of every thread of the process, from perf_event_open
// (PERF_COUNT_HW_CPU_CYCLES, inherited by the threads created after start()). Where the
// kernel or the machine offers no cycle counter (a VM without a PMU, a high
// perf_event_paranoid), process CPU time × a clock measured once by a dependent add
// chain; source() says which.
class CycleCounter {
 public:
  // Opens the counter; call before the threads to be counted are created.
  void start();
  ~CycleCounter();
  // Cycles so far (a running total: measure with differences).
  double read() const;
  bool hardware() const { return fd_ >= 0; }
  // "perf_event_open cycles:u, all threads" or "process CPU time x measured clock 3.40 GHz: …".
  std::string source() const;

 private:
  int fd_ = -1;
  double hz_ = 0;  // the measured clock of the fallback
};

// FP32 FLOPs one core can issue per cycle: 16-lane FMA (2 FLOPs) on 2 ports = 64 with
// AVX-512, 8-lane = 32 with AVX2 + FMA, 4-lane mul + add ports = 8 otherwise.
struct PeakFlops {
  int perCycle;
  const char* isa;
};
PeakFlops peakFlopsPerCycle();

}  // namespace refx::cli
