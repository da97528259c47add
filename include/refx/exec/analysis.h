// Facts about IR programs that let a caller run them by a shorter route with the same
// results.
#pragma once
#include <optional>

#include "refx/exec/ir.h"

namespace refx::exec {

// A program whose only effect is output 0 = the texture sample of `sampler` at input
// register `input` (Op::Tex, λ from quad derivatives, coordinates .xyzw unchanged),
// with at most a clamp or saturate that keeps [0, 1] as it is, and nothing else: no
// other output, no kill, no quantization, no flow control. Such a program writes
// exactly the sampled value whenever the sample lies in [0, 1] (8-bit unorm texels).
struct SamplePassthrough {
  int sampler = 0;
  int input = 0;
};
std::optional<SamplePassthrough> findSamplePassthrough(const Program& program);

}  // namespace refx::exec
