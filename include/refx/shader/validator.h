// Version rules of the D3D9 shader models (one table per version) checked against a
// decoded Shader: instruction slots, register files and counts, modifiers, order
// rules of ps_1_x, ps_1_4 phases, dcl rules and flow-control nesting. Every
// violation is a refx::Diagnostic with a code of docs/diagnostics.md ("Shader
// validator"), and every violation of a shader is reported, not only the first.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/bytecode.h"

namespace refx::shader {

// Device limits the rules depend on (from the caps profile); defaults = the
// minimum every device of the version guarantees.
struct ValidationCaps {
  int maxVertexShaderConst = 0;   // 0 = the version's minimum (96 for vs_1_1, 256 for vs_2_0+)
  int vs2xTemps = 12;             // vs_2_x NumTemps
  int ps2xTemps = 12;             // ps_2_x NumTemps
  int ps2xInstructionSlots = 96;  // ps_2_x NumInstructionSlots
  bool ps2xFlowControl = true;    // ps_2_x static flow control / predication / dsx
  bool vs2xFlowControl = true;    // vs_2_x dynamic flow control / predication
  int staticFlowControlDepth = 4;   // vs_2_x / ps_2_x rep (and call) nesting, 1..4
  int dynamicFlowControlDepth = 24; // vs_2_x / ps_2_x if_comp / if p0 nesting, 0 or 24
  bool ps2xArbitrarySwizzle = false;       // D3DPS20CAPS_ARBITRARYSWIZZLE
  bool ps2xNoDependentReadLimit = false;   // D3DPS20CAPS_NODEPENDENTREADLIMIT
  bool ps2xNoTexInstructionLimit = false;  // D3DPS20CAPS_NOTEXINSTRUCTIONLIMIT
};

// Instruction-slot use as the version's tables count it (macros expanded, ps_1_x
// texture vs arithmetic slots, ps_3_0 texld costs …).
struct SlotCount {
  int texture = 0, arithmetic = 0, flowControl = 0;
  int total() const { return texture + arithmetic + flowControl; }
};
SlotCount countSlots(const Shader& shader);

// All rule violations found (empty = valid), in the order of the instructions, then
// the whole-shader rules (slot totals, unclosed blocks, outputs). Locations carry the
// assembler's line and column ({0, 0} for decoded bytecode) and no file name.
std::vector<Diagnostic> validate(const Shader& shader, const ValidationCaps& caps = {});
// The same into a sink, with `fileName` in every location.
void validate(const Shader& shader, DiagnosticSink& sink, std::string_view fileName,
              const ValidationCaps& caps = {});

// One line per violation, "<prefix>: <code>: <message>" (the form ShaderObject
// reports for a decoded shader, with the version as the prefix).
std::string describeViolations(std::string_view prefix, const std::vector<Diagnostic>& violations);

// "ps_1_4 needs PixelShaderVersion 1.4, dx8 has 1.1" when the device's version token
// (D3DCAPS9 VertexShaderVersion / PixelShaderVersion) does not cover the shader's
// version; empty when it does. ps_2_x / vs_2_x need more than 2.0.
std::string checkDeviceVersion(Version shader, uint32_t deviceVersion, std::string_view deviceName);

// Throws refx::Error listing every violation, one per line, as
// "file:line:col: error V1102: message".
void requireValid(const Shader& shader, std::string_view fileName, const ValidationCaps& caps = {});

}  // namespace refx::shader
