#include "refx/core/cpu_features.h"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace refx {

namespace {

CpuIsa detect() {
#if defined(__x86_64__) && defined(__GNUC__)
  // __builtin_cpu_supports also checks that the OS saves the registers (XCR0).
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
    return CpuIsa::Avx512;
#endif
  return CpuIsa::Avx2;
}

CpuIsa limitToCpu(CpuIsa isa) { return int(isa) < int(detectedIsa()) ? isa : detectedIsa(); }

CpuIsa fromEnvironment() {
  const char* want = std::getenv("REFX_ISA");
  if (want && std::strcmp(want, "avx2") == 0) return CpuIsa::Avx2;
  return detectedIsa();
}

std::atomic<int>& active() {
  static std::atomic<int> isa{int(fromEnvironment())};
  return isa;
}

}  // namespace

CpuIsa detectedIsa() {
  static const CpuIsa isa = detect();
  return isa;
}

CpuIsa activeIsa() { return CpuIsa(active().load(std::memory_order_relaxed)); }

CpuIsa setActiveIsa(CpuIsa isa) {
  return CpuIsa(active().exchange(int(limitToCpu(isa)), std::memory_order_relaxed));
}

const char* isaName(CpuIsa isa) { return isa == CpuIsa::Avx512 ? "avx512" : "avx2"; }

}  // namespace refx
