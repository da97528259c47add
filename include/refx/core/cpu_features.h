// The vector instruction sets the hot loops can use, chosen at run time: a build
// targets the x86-64-v3 baseline (AVX2, FMA) and the sampling kernels also exist as
// AVX-512 variants, used when the CPU (and the operating system) supports them.
#pragma once

namespace refx {

enum class CpuIsa : int {
  Avx2 = 0,    // x86-64-v3: AVX2, FMA, BMI2 (what every build requires)
  Avx512 = 1,  // AVX-512 F, BW, DQ and VL: 16 float lanes in one register
};

// The highest level this CPU supports (detected once).
CpuIsa detectedIsa();

// The level the kernels use: detectedIsa(), or lower when the environment variable
// REFX_ISA says so (REFX_ISA=avx2 runs the AVX2 variants on an AVX-512 machine).
CpuIsa activeIsa();

// Makes `isa` (limited to detectedIsa()) the active level for work prepared from now
// on, and returns the previous one; lets tests run both variants in one process.
CpuIsa setActiveIsa(CpuIsa isa);

// "avx2", "avx512".
const char* isaName(CpuIsa isa);

}  // namespace refx
