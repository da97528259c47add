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

// FP32 FLOPs one core issues per cycle, measured: independent FMA chains in the
// widest vectors the CPU has (16 lanes with AVX-512, 8 with AVX2 + FMA), timed against
// the clock of a dependent add chain. Measured rather than taken from the ISA because
// cores differ: some run AVX-512 on two 512-bit FMA ports (64 FLOPs/cycle), others
// split it over 256-bit units (32).
struct PeakFlops {
  double perCycle;
  const char* isa;
};
PeakFlops peakFlopsPerCycle();

}  // namespace refx::cli
