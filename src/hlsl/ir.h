// The compiler's own IR: a list of vector operations on virtual registers, each
// defined once (functions inlined, loops unrolled, branches turned into selects by the
// builder). Components of one virtual register are 0..width-1.
//
// Loops marked [loop] and branches marked [branch] may stay flow control: the list
// then holds properly nested regions, Rep … EndRep and If … [Else …] EndIf. Code in a
// region runs zero or more times, so a variable it changes lives in a register that
// Assign writes more than once (before the region, and at the end of each body); such
// a register has no single definition. A value defined inside a region is read only
// inside it. Passes treat Assign targets as opaque and never move code across a marker.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hlsl/ast.h"
#include "refx/core/diagnostics.h"
#include "refx/shader/bytecode.h"

namespace refx::hlsl::detail {

enum class IrOp : uint8_t {
  Input,     // shader input register (see IrProgram::inputs)
  Uniform,   // one constant register of a uniform
  UniformRel,  // one constant register of a uniform array, relative: c[src0.x + row] (vertex shaders)
  Constant,  // literal values
  Combine,   // components gathered from other registers (parts[])
  Mov, Add, Mul, Mad, Dp2, Dp3, Dp4, Min, Max, Slt, Sge,
  Cmp,       // src0 >= 0 ? src1 : src2
  Lrp,       // src0 * src1 + (1 - src0) * src2
  Frc, Abs, Nrm, Crs,
  Rcp, Rsq, Exp2, Log2, Pow,  // scalar: per component
  SinCos,    // width 2 from the replicated src0 in [-pi, pi]: .x = cos, .y = sin
  Dsx, Dsy,
  Tex, TexProj, TexBias, TexLod, TexGrad,  // src0 coordinate, src1/2 gradients; sampler = index
  Kill,      // texkill src0: discard when any component < 0
  // Structured flow control (no dst).
  Rep,       // rep: the body runs `index` times, or i# of int uniform `uniform` times
  EndRep,
  If,        // if_comp src0 `compare` src1, or if b# of bool uniform `uniform` (index 1: if !b#)
  Else,
  EndIf,
  Break,     // break (no sources), or break_comp src0 `compare` src1
  Assign,    // dst (an existing register, written more than once) = src0
};

inline bool isFlowMarker(IrOp op) { return op >= IrOp::Rep && op <= IrOp::Break; }

struct IrSrc {
  int reg = -1;                            // virtual register
  std::array<uint8_t, 4> swizzle{0, 1, 2, 3};  // component of `reg` read for each result component
  bool negate = false, absolute = false;
};

struct IrPart {  // one component of a Combine: a literal or (reg, component)
  int reg = -1;
  uint8_t component = 0;
  float literal = 0;
};

struct IrInst {
  IrOp op = IrOp::Mov;
  int dst = -1;
  int width = 4;       // components of dst
  bool saturate = false;
  std::array<IrSrc, 3> src{};
  int srcCount = 0;
  int sampler = -1;    // Tex*: sampler index in IrProgram::samplers
  int index = 0;       // Input: input index; Uniform, UniformRel: uniform index and register row (row << 16 | uniform)
  int uniform = -1;    // Rep, If: the int / bool uniform read from an i# / b# register
  shader::Comparison compare = shader::Comparison::None;  // If, Break with sources
  std::array<float, 4> literal{};  // Constant
  std::vector<IrPart> parts;       // Combine
  SourceLocation where;
};

struct IrInput {
  shader::DeclUsage usage = shader::DeclUsage::TexCoord;
  int usageIndex = 0;
  int width = 4;
  std::string semantic;
  bool isPosition = false;  // ps_3_0 VPOS
  bool isFace = false;      // ps_3_0 VFACE
};

struct IrOutput {
  shader::DeclUsage usage = shader::DeclUsage::Color;
  int usageIndex = 0;
  std::string semantic;
  std::vector<IrPart> parts;  // components written (1..4)
  SourceLocation where;
};

// A global the shader reads, as it appears in the constant table.
struct IrUniform {
  std::string name;
  const VarDecl* decl = nullptr;
  Type type;
  int registerCount = 0;  // float registers a full allocation takes
  bool used = false;
  int firstRegister = -1;  // assigned by the back end
  std::vector<float> defaults;  // per register, 4 floats each (from the initialiser)
  // A register the preshader writes (an expression of uniforms computed on the CPU):
  // placed like a uniform, absent from the constant table.
  bool preshaderOutput = false;
  bool loopCount = false;   // a [loop] trip count: an int register i# (rep i#)
  bool branchBool = false;  // a [branch] condition: a bool register b# (if b#)
  int flowRegister = -1;    // i# / b#, assigned by the back end
};

struct IrSampler {
  std::string name;
  const VarDecl* decl = nullptr;
  SamplerDim dim = SamplerDim::Dim2D;
  int registerIndex = -1;
};

struct IrProgram {
  shader::Version version;
  std::vector<IrInst> code;
  std::vector<int> regWidth;  // width of each virtual register
  std::vector<IrInput> inputs;
  std::vector<IrOutput> outputs;
  std::vector<IrUniform> uniforms;
  std::vector<IrSampler> samplers;
  bool usesKill = false;

  int newReg(int width) {
    regWidth.push_back(width);
    return int(regWidth.size()) - 1;
  }
  // Registers Assign writes (variables of flow-control regions).
  std::vector<bool> assignedRegisters() const {
    std::vector<bool> out(regWidth.size(), false);
    for (const IrInst& in : code)
      if (in.op == IrOp::Assign) out[in.dst] = true;
    return out;
  }
};

struct BuildOptions {
  shader::Version version;
  std::string entry;
  std::string fileName;  // for diagnostics without a position in the source
  bool rowMajorDefault = false;
  bool compatibility = false;  // the white paper's pre-release dialect
  std::vector<const Expr*> entryArguments;
  bool compat() const { return compatibility; }
};

// Syntax tree → IR for one entry point: type checking, overload resolution,
// inlining, unrolling and flattening. Diagnostics go to `sink`.
IrProgram buildIr(const Program& program, const BuildOptions& options, DiagnosticSink& sink);

// One component of a component-wise operation (Mov … Pow) on literal values, as the
// shader instructions compute it (pow and log2 of |a|, rsq of |a|): constant folding
// and the preshader evaluator share it.
float evaluateComponent(IrOp op, float a, float b, float c);

// Optimisation passes over the IR (each small and named after what it does).
void foldConstants(IrProgram& ir);
void propagateCopies(IrProgram& ir);
void mergeDuplicates(IrProgram& ir);
void vectorizeScalars(IrProgram& ir);
void fuseMultiplyAdd(IrProgram& ir);
void removeDeadCode(IrProgram& ir);

// IR → shader instructions for the version: instruction selection, legalisation to
// the version's operand rules, register allocation, dcl/def, CTAB. Errors (profile
// limits) go to `sink`.
shader::Shader generateCode(IrProgram& ir, const std::string& creator, DiagnosticSink& sink,
                            const SourceLocation& entryWhere);

}  // namespace refx::hlsl::detail
