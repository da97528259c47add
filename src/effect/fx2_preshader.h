// Compiled shaders' preshaders in fx_2_0 binaries: the HLSL compiler's preshader as
// FXLC code, embedded in the shader as fxc does (a PRES comment after the CTAB).
#pragma once
#include <cstdint>
#include <vector>

#include "fxlc.h"
#include "refx/hlsl/compiler.h"

namespace refx::effect::detail {

// The same computation as `pre.run`: inputs in `pre.inputs`' registers, each output
// register's four components written to the shader register pre.outputRegisters[i].
// Throws refx::Error for an instruction FXLC cannot express.
FxlcProgram fxlcFromPreshader(const hlsl::Preshader& pre);

// `tokens` (a shader) with a PRES comment (version 0x46580201, CTAB, PRSI, CLIT, FXLC)
// after its leading comments.
std::vector<uint32_t> withPresComment(const std::vector<uint32_t>& tokens, const FxlcProgram& program);

}  // namespace refx::effect::detail
