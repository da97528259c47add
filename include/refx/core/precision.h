// The precision model shaders run with, chosen on the device and applied when a
// shader is lowered for the executor.
#pragma once
#include <cstdint>

namespace refx {

// exact: fp32 with the versions' ranges clamped (ps_1_x registers, constants and
// color inputs). hardware: ps_1_x values are also quantised to the fixed point of
// the era's parts.
enum class Precision : uint8_t { Exact, Hardware };

}  // namespace refx
