// Decoded shader bytecode → exec IR (register conventions in lower.h). Semantics
// follow reference/instructions.md; the ps_1_x texture-address instructions are
// expanded into plain IR (dot products, bump matrix, sampling) here.
#include "refx/exec/lower.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>

#include "refx/core/diagnostics.h"
#include "refx/exec/abi.h"
#include "refx/shader/opcode_table.h"
#include "refx/shader/version_rules.h"

namespace refx::exec {

namespace {

namespace sh = refx::shader;
using sh::Opcode;
using sh::RegType;

// ps_1_x hardware precision: the register combiners of the DX8 parts (GeForce3/4)
// kept 9-bit signed values, 8 fractional bits over [-1, 1]; the ps_1_4 parts
// (Radeon 8500) widened the range to [-8, 8] at a similar step. Both are modelled
// as 8 fractional bits; 1/256 steps make a power built by repeated multiplies band
// (x^16 near 1 moves in steps of about 1/16) as it did on those cards.
constexpr int kHardwareFractionBits = 8;

constexpr uint8_t kMaskXYZ = 0x7;

uint8_t selectorOf(uint8_t swz, int c) { return (swz >> (2 * c)) & 3; }
// Swizzle that repeats component c of `swz` in all four positions.
uint8_t replicate(uint8_t swz, int c) { return uint8_t(selectorOf(swz, c) * 0x55); }
// Components not in `used` repeat the first used one, so readers of the program
// (the pipeline's interpolator) see only what the instruction really reads.
uint8_t trimSwizzle(uint8_t swz, uint8_t used) {
  if (!used || used == 0xF) return swz;
  int first = 0;
  while (!(used >> first & 1)) ++first;
  uint8_t r = 0;
  for (int c = 0; c < 4; ++c)
    r |= uint8_t(selectorOf(swz, used >> c & 1 ? c : first) << (2 * c));
  return r;
}
// `outer` applied after `inner`.
uint8_t compose(uint8_t inner, uint8_t outer) {
  uint8_t r = 0;
  for (int c = 0; c < 4; ++c) r |= uint8_t(selectorOf(inner, selectorOf(outer, c)) << (2 * c));
  return r;
}

float bitsToFloat(uint32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}

SrcMod modOf(sh::SrcMod m) {
  switch (m) {
    case sh::SrcMod::Neg: return SrcMod::Neg;
    case sh::SrcMod::Bias: return SrcMod::Bias;
    case sh::SrcMod::BiasNeg: return SrcMod::BiasNeg;
    case sh::SrcMod::Sign: return SrcMod::Sign;
    case sh::SrcMod::SignNeg: return SrcMod::SignNeg;
    case sh::SrcMod::Comp: return SrcMod::Comp;
    case sh::SrcMod::X2: return SrcMod::X2;
    case sh::SrcMod::X2Neg: return SrcMod::X2Neg;
    case sh::SrcMod::Abs: return SrcMod::Abs;
    case sh::SrcMod::AbsNeg: return SrcMod::AbsNeg;
    default: return SrcMod::None;  // Dz/Dw are handled by texld/texcrd; Not by flow control
  }
}

// Which components of each source an instruction reads.
enum class Reads : uint8_t {
  PerComponent,  // the written components
  Scalar,        // component 0 of the swizzle, replicated (rcp, exp, …)
  Dot2, Dot3, Dot4, All,
};

// Instructions that map onto one IR op.
struct Simple {
  Opcode opcode;
  Op op;
  Reads reads[3];
};
constexpr Reads PC = Reads::PerComponent, SC = Reads::Scalar;
constexpr Simple kSimple[] = {
    {Opcode::Mov, Op::Mov, {PC}},
    {Opcode::Add, Op::Add, {PC, PC}},
    {Opcode::Sub, Op::Sub, {PC, PC}},
    {Opcode::Mul, Op::Mul, {PC, PC}},
    {Opcode::Mad, Op::Mad, {PC, PC, PC}},
    {Opcode::Min, Op::Min, {PC, PC}},
    {Opcode::Max, Op::Max, {PC, PC}},
    {Opcode::Slt, Op::Slt, {PC, PC}},
    {Opcode::Sge, Op::Sge, {PC, PC}},
    {Opcode::Lrp, Op::Lrp, {PC, PC, PC}},
    {Opcode::Cmp, Op::Cmp, {PC, PC, PC}},
    {Opcode::Cnd, Op::Cnd, {PC, PC, PC}},
    {Opcode::Frc, Op::Frc, {PC}},
    {Opcode::Abs, Op::Abs, {PC}},
    {Opcode::Sgn, Op::Sgn, {PC}},
    {Opcode::Dsx, Op::Dsx, {PC}},
    {Opcode::Dsy, Op::Dsy, {PC}},
    {Opcode::Dp3, Op::Dp3, {Reads::Dot3, Reads::Dot3}},
    {Opcode::Dp4, Op::Dp4, {Reads::Dot4, Reads::Dot4}},
    {Opcode::Dp2Add, Op::Dp2Add, {Reads::Dot2, Reads::Dot2, SC}},
    // The opcode table's scalar instructions read component 0 of each source.
    {Opcode::Rcp, Op::Rcp, {}},
    {Opcode::Rsq, Op::Rsq, {}},
    {Opcode::Exp, Op::Exp2, {}},
    {Opcode::Log, Op::Log2, {}},
    {Opcode::LogP, Op::Log2, {}},  // D3D9 logp is the scalar log2 of |x| in every version
    {Opcode::Pow, Op::Pow, {}},
    {Opcode::SinCos, Op::SinCos, {}},
    {Opcode::Crs, Op::Crs, {Reads::Dot3, Reads::Dot3}},
    {Opcode::Nrm, Op::Nrm, {Reads::All}},
    {Opcode::Lit, Op::Lit, {Reads::All}},
    {Opcode::Dst, Op::Dist, {Reads::All, Reads::All}},
};
const Simple* simpleFor(Opcode op) {
  for (const Simple& s : kSimple)
    if (s.opcode == op) return &s;
  return nullptr;
}

// Sources of a scalar instruction (opcode table): component 0, replicated.
std::array<Reads, 3> scalarReads() { return {Reads::Scalar, Reads::Scalar, Reads::Scalar}; }

// vs_2_sw, ps_3_sw … follow the rules of the hardware version they extend.
const sh::VersionRules& rulesFor(sh::Version v) {
  if (const sh::VersionRules* r = sh::findVersionRules(v)) return *r;
  sh::Version hardware = v;
  hardware.minor = v.major == 2 ? 1 : 0;
  if (const sh::VersionRules* r = sh::findVersionRules(hardware)) return *r;
  fail("{} has no register rules to lower it with", v.name());
}

uint8_t usedComponents(Reads r, uint8_t mask) {
  switch (r) {
    case Reads::PerComponent: return mask;
    case Reads::Scalar: return 0x1;
    case Reads::Dot2: return 0x3;
    case Reads::Dot3: return 0x7;
    default: return 0xF;
  }
}

struct Block {
  Opcode opcode;  // If/IfC (also if-pred), Rep, Loop
  int at;         // IR index of the opening instruction
  int elseAt = -1;
};

class Lowerer {
 public:
  Lowerer(const sh::Shader& s, const ShaderLoweringOptions& o)
      : shader_(s), opt_(o), ver_(s.version), rules_(rulesFor(s.version)) {
    ps1x_ = ver_.ps1x();
    ps14_ = ps1x_ && ver_.minor >= 4;
    ps13_ = ps1x_ && !ps14_;
    // The device's PixelShader1xMaxValue, at least the version's own range (ps_1_4: 8).
    maxValue_ = std::max(opt_.pixelShader1xMaxValue, rules_.minRegisterRange);
    quantize_ = ps1x_ && opt_.precision == Precision::Hardware ? kHardwareFractionBits : 0;
  }

  LoweredShader run() {
    out_.version = ver_;
    scan();
    layout();
    prologue();
    const auto& ins = shader_.instructions;
    for (size_t i = 0; i < ins.size(); ++i) {
      nextScratch_ = 0;
      if (ps1x_ && i + 1 < ins.size() && ins[i + 1].coissue && !ins[i].coissue) {
        lowerPair(ins[i], ins[i + 1]);
        ++i;
        continue;
      }
      lower(ins[i]);
    }
    if (!blocks_.empty()) failIn(shader_.instructions.back(), "a flow-control block is not closed");
    if (!mainEnded_) endMain();
    for (auto [at, label] : calls_) {
      auto it = labels_.find(label);
      if (it == labels_.end()) fail("call to label l{}, which is not defined", label);
      p_.code[size_t(at)].target = it->second;
    }
    clampColorInputs();
    finish();
    return std::move(out_);
  }

 private:
  const sh::Shader& shader_;
  ShaderLoweringOptions opt_;
  sh::Version ver_;
  const sh::VersionRules& rules_;
  LoweredShader out_;
  Program& p_ = out_.program;
  bool ps1x_ = false, ps13_ = false, ps14_ = false;
  float maxValue_ = 1;
  int quantize_ = 0;

  // Register layout in the Temp file.
  int rBase_ = 0, rCount_ = 0, tBase_ = -1, a0_ = -1, p0_ = -1, oBase_ = -1, vBase_ = -1, mat_ = -1;
  std::vector<int> scratchPool_;
  int nextScratch_ = 0;
  std::optional<int> redirect_;  // co-issue: the first half writes this temp instead

  // Local constants: register → immediate index.
  std::map<int, int> defF_, defI_, defB_;
  // vs_3_0 outputs: o# component → IR output (-1 none). ps_3_0 inputs: (v#, mask, input).
  std::vector<std::array<int16_t, 4>> outMap_;
  struct InputDcl {
    int reg;
    uint8_t mask;
    int input;
  };
  std::vector<InputDcl> inputDcls_;

  int maxConstRead_ = -1;
  bool relativeConst_ = false;
  std::vector<Block> blocks_;
  std::vector<std::pair<int, int>> calls_;  // IR index of the call, label number
  std::map<int, int> labels_;               // label number → IR index
  bool mainEnded_ = false;
  int padRow_ = 0;  // texm3x2pad / texm3x3pad rows done

  // ------------------------------------------------------------------ diagnostics

  // Registers of `type` the version has (for counts from the caps, the most any device has).
  int count(RegType type) const { return sh::registerCapacity(rules_, type); }

  [[noreturn]] void failIn(const sh::Instruction& in, const std::string& what) const {
    const sh::OpcodeInfo* info = sh::findOpcode(in.opcode);
    const std::string name = info ? std::string(info->name) : fmt::format("opcode {}", int(in.opcode));
    failAt(SourceLocation{"", in.pos.line, in.pos.column}, "{}: {}", name, what);
  }

  // ------------------------------------------------------------------ scanning and layout

  void scan() {
    int maxTemp = -1;
    if (ver_.isVertex() && ver_.major >= 3) outMap_.assign(size_t(count(RegType::Output)), {-1, -1, -1, -1});
    for (const sh::Instruction& in : shader_.instructions) {
      auto seeTemp = [&](RegType t, int index) {
        if (t == RegType::Temp) maxTemp = std::max(maxTemp, index);
      };
      if (in.hasDst) seeTemp(in.dst.type, in.dst.index);
      for (int i = 0; i < in.srcCount; ++i) seeTemp(in.src[i].type, in.src[i].index);
      switch (in.opcode) {
        case Opcode::Def: {
          const Vec4 v(bitsToFloat(in.literal[0]), bitsToFloat(in.literal[1]),
                       bitsToFloat(in.literal[2]), bitsToFloat(in.literal[3]));
          defF_[in.dst.index] = immIndex(v);
          break;
        }
        case Opcode::DefI:
          defI_[in.dst.index] = immIndex(Vec4(float(int32_t(in.literal[0])), float(int32_t(in.literal[1])),
                                              float(int32_t(in.literal[2])), float(int32_t(in.literal[3]))));
          break;
        case Opcode::DefB: {
          const float b = in.literal[0] ? 1.0f : 0.0f;
          defB_[in.dst.index] = immIndex(Vec4(b, b, b, b));
          break;
        }
        case Opcode::Dcl: scanDcl(in); break;
        default: break;
      }
    }
    rCount_ = maxTemp + 1;
    if (rCount_ > count(RegType::Temp))
      fail("temporary register r{} is out of range (at most r{})", maxTemp, count(RegType::Temp) - 1);
  }

  int immIndex(Vec4 v) { return p_.imm(v).index; }

  void scanDcl(const sh::Instruction& in) {
    const sh::DstParam& d = in.dst;
    if (d.type == RegType::Sampler) {
      if (d.index < kSamplerCount) out_.samplerTypes[d.index] = in.textureType;
      return;
    }
    if (ver_.isVertex() && d.type == RegType::Input) {
      out_.vertexInputs.push_back({uint8_t(d.index), in.usage, in.usageIndex});
      return;
    }
    if (ver_.isVertex() && ver_.major >= 3 && d.type == RegType::Output) {
      if (d.index >= count(RegType::Output)) failIn(in, fmt::format("output register o{} is out of range", d.index));
      const int target = varyingFor(in.usage, in.usageIndex, true);
      if (target < 0)
        failIn(in, fmt::format("output semantic {}{} has no varying; refx passes POSITION0, COLOR0-1, "
                               "TEXCOORD0-7, FOG and PSIZE",
                               usageName(in.usage), in.usageIndex));
      for (int c = 0; c < 4; ++c)
        if (d.writeMask >> c & 1) outMap_[d.index][c] = int16_t(target);
      return;
    }
    if (ver_.isPixel() && ver_.major >= 3 && d.type == RegType::Input) {
      if (d.index >= count(RegType::Input)) failIn(in, fmt::format("input register v{} is out of range", d.index));
      const int input = varyingFor(in.usage, in.usageIndex, false);
      if (input < 0)
        failIn(in, fmt::format("input semantic {}{} has no varying; refx passes COLOR0-1, TEXCOORD0-7 "
                               "and FOG",
                               usageName(in.usage), in.usageIndex));
      inputDcls_.push_back({d.index, d.writeMask, input});
    }
  }

  static const char* usageName(sh::DeclUsage u) {
    static const char* names[] = {"POSITION", "BLENDWEIGHT", "BLENDINDICES", "NORMAL", "PSIZE",
                                  "TEXCOORD", "TANGENT", "BINORMAL", "TESSFACTOR", "POSITIONT",
                                  "COLOR", "FOG", "DEPTH", "SAMPLE"};
    return size_t(u) < std::size(names) ? names[size_t(u)] : "?";
  }

  // vs_3_0 output / ps_3_0 input semantic → register of the fixed conventions.
  static int varyingFor(sh::DeclUsage u, int index, bool vertexOutput) {
    switch (u) {
      case sh::DeclUsage::Position: return vertexOutput && index == 0 ? kVertexOutPosition : -1;
      case sh::DeclUsage::Color:
        if (index > kVertexOutSpecular - kVertexOutDiffuse) return -1;
        return vertexOutput ? kVertexOutDiffuse + index : kPixelInDiffuse + index;
      case sh::DeclUsage::TexCoord:
        if (index >= kTextureCoordinateSets) return -1;
        return vertexOutput ? kVertexOutTex0 + index : kPixelInTex0 + index;
      case sh::DeclUsage::Fog: return index == 0 ? (vertexOutput ? kVertexOutFog : kPixelInFog) : -1;
      case sh::DeclUsage::PSize: return vertexOutput && index == 0 ? kVertexOutPSize : -1;
      default: return -1;
    }
  }

  void layout() {
    rBase_ = 0;
    p_.tempCount = rCount_;
    if (ps13_) {
      tBase_ = p_.tempCount;
      p_.tempCount += count(RegType::Texture);
    }
    if (ver_.isVertex()) a0_ = p_.tempCount++;
    if (ver_.sm2plus()) p0_ = p_.tempCount++;
    if (ver_.isVertex() && ver_.major >= 3) {
      oBase_ = p_.tempCount;
      p_.tempCount += count(RegType::Output);
    }
    if (ver_.isPixel() && ver_.major >= 3) {
      vBase_ = p_.tempCount;
      p_.tempCount += count(RegType::Input);
    }
    if (ver_.isVertex()) {
      p_.inputCount = count(RegType::Input);
      p_.outputCount = kVertexOutputCount;
    } else {
      p_.inputCount = kPixelInputRegisters;
      p_.outputCount = kPixelOutputRegisters;
    }
    p_.name = ver_.isVertex() ? "vertex shader" : "pixel shader";
  }

  int scratch() {
    if (nextScratch_ == int(scratchPool_.size())) scratchPool_.push_back(p_.newTemp());
    return scratchPool_[size_t(nextScratch_++)];
  }

  int matrixTemp() {
    if (mat_ < 0) mat_ = p_.newTemp();
    return mat_;
  }

  // ps_3_0: declared inputs are copied into temps (one v# may gather several
  // semantics with disjoint masks, and v[aL + n] indexes them).
  void prologue() {
    for (const InputDcl& d : inputDcls_) {
      Instr& in = p_.emit(Op::Mov, dst(RegFile::Temp, vBase_ + d.reg, d.mask),
                          reg(RegFile::Input, d.input, trimSwizzle(kSwzXYZW, d.mask)));
      (void)in;
    }
  }

  // Color inputs v0/v1 of ps_1_x–2_x are saturated (and on the era's 8-bit grid in
  // hardware precision); done in place on the components the program reads.
  void clampColorInputs() {
    if (!rules_.colorInputsSaturated) return;
    if (opt_.colorInputsInRange && !quantize_) return;
    uint8_t used[2] = {0, 0};
    for (const Instr& in : p_.code)
      for (int i = 0; i < sourceCount(in.op); ++i) {
        const Src& s = in.src[i];
        if (s.file != RegFile::Input || s.index > 1) continue;
        for (int c = 0; c < 4; ++c) used[s.index] |= uint8_t(1u << selectorOf(s.swizzle, c));
      }
    std::vector<Instr> pre;
    for (int v = 0; v < 2; ++v) {
      if (!used[v]) continue;
      Instr in;
      in.op = Op::Mov;
      in.dst = dst(RegFile::Input, v, used[v]);
      in.src[0] = reg(RegFile::Input, v, trimSwizzle(kSwzXYZW, used[v]));
      in.saturate = true;
      in.quantize = uint8_t(quantize_);
      pre.push_back(in);
    }
    if (pre.empty()) return;
    for (Instr& in : p_.code)
      if (in.target >= 0) in.target += int(pre.size());
    p_.code.insert(p_.code.begin(), pre.begin(), pre.end());
  }

  void finish() {
    // Without calls, the first Ret is the end of the main program; drop it and the
    // unreachable subroutines so straight-line shaders keep the prepared fast path.
    if (std::none_of(p_.code.begin(), p_.code.end(), [](const Instr& i) { return i.op == Op::Call; })) {
      auto ret = std::find_if(p_.code.begin(), p_.code.end(), [](const Instr& i) { return i.op == Op::Ret; });
      p_.code.erase(ret, p_.code.end());
    }
    for (const Instr& in : p_.code)
      if (in.op >= Op::If && in.op <= Op::Ret) p_.flowControl = true;
    if (!defF_.empty()) {
      p_.localConstants.assign(size_t(defF_.rbegin()->first + 1), -1);
      for (auto [c, imm] : defF_) p_.localConstants[size_t(c)] = imm;
    }
    out_.floatConstantsRead = relativeConst_ ? count(RegType::Const) : maxConstRead_ + 1;
  }

  // ------------------------------------------------------------------ operands

  Src srcOf(const sh::Instruction& in, const sh::SrcParam& s, uint8_t used = 0xF) {
    Src r;
    r.swizzle = trimSwizzle(s.swizzle, used);
    r.mod = modOf(s.mod);
    const int n = s.index;
    switch (s.type) {
      case RegType::Temp:
        if (ps1x_ && n == 0) {
          r.file = RegFile::Output, r.index = 0;  // r0 is the pixel color
        } else {
          r.file = RegFile::Temp, r.index = uint16_t(rBase_ + n);
        }
        break;
      case RegType::Input:
        if (ver_.isVertex()) {
          if (n >= count(RegType::Input)) failIn(in, fmt::format("input register v{} is out of range", n));
          r.file = RegFile::Input, r.index = uint16_t(n);
          if (s.relative) r.relLo = 0, r.relHi = uint16_t(count(RegType::Input));
        } else if (ver_.major >= 3) {
          if (n >= count(RegType::Input)) failIn(in, fmt::format("input register v{} is out of range", n));
          r.file = RegFile::Temp, r.index = uint16_t(vBase_ + n);
          r.relLo = uint16_t(vBase_), r.relHi = uint16_t(vBase_ + count(RegType::Input));
        } else {
          if (n >= count(RegType::Input)) failIn(in, fmt::format("color input v{} is out of range (v0, v1)", n));
          r.file = RegFile::Input, r.index = uint16_t(kPixelInDiffuse + n);
        }
        break;
      case RegType::Const:
        if (s.relative) {
          relativeConst_ = true;
          r.file = RegFile::Const, r.index = uint16_t(n);
        } else if (auto it = defF_.find(n); it != defF_.end()) {
          Vec4 v = p_.immediates[size_t(it->second)];
          if (ps1x_)  // ps_1_x constants read clamped to the version's range, def and API alike
            for (int c = 0; c < 4; ++c) v[c] = std::clamp(v[c], rules_.defMin, rules_.defMax);
          r.file = RegFile::Imm, r.index = uint16_t(immIndex(v));
        } else {
          maxConstRead_ = std::max(maxConstRead_, n);
          r.file = RegFile::Const, r.index = uint16_t(n);
          if (ps1x_) r.flags |= kSrcClampUnit;
        }
        break;
      case RegType::Texture:  // a0 in vertex shaders
        if (ver_.isVertex()) {
          r.file = RegFile::Temp, r.index = uint16_t(a0_);
        } else if (ps13_) {
          if (n >= count(RegType::Texture)) failIn(in, fmt::format("texture register t{} is out of range", n));
          r.file = RegFile::Temp, r.index = uint16_t(tBase_ + n);
        } else {
          if (n >= count(RegType::Texture)) failIn(in, fmt::format("texture register t{} is out of range", n));
          r.file = RegFile::Input, r.index = uint16_t(kPixelInTex0 + n);
        }
        break;
      case RegType::ConstInt:
        if (auto it = defI_.find(n); it != defI_.end()) r.file = RegFile::Imm, r.index = uint16_t(it->second);
        else r.file = RegFile::ConstInt, r.index = uint16_t(n);
        break;
      case RegType::ConstBool:
        if (auto it = defB_.find(n); it != defB_.end()) r.file = RegFile::Imm, r.index = uint16_t(it->second);
        else r.file = RegFile::ConstBool, r.index = uint16_t(n);
        break;
      case RegType::MiscType:
        if (n > 1) failIn(in, fmt::format("misc register {} is not vPos or vFace", n));
        r.file = RegFile::Input, r.index = uint16_t(n == 0 ? kPixelInPosition : kPixelInFace);
        break;
      case RegType::Predicate:
        if (p0_ < 0) failIn(in, "p0 is not available in this version");
        r.file = RegFile::Temp, r.index = uint16_t(p0_);
        break;
      case RegType::Loop: failIn(in, "aL can only index registers");
      default:
        failIn(in, fmt::format("{} cannot be read", sh::registerName(s.type, s.index, ver_)));
    }
    if (s.relative) {
      if (s.rel.type == RegType::Loop) {
        r.rel = RelMode::Loop;
      } else {
        if (a0_ < 0) failIn(in, "relative addressing needs a0 (vertex shaders only)");
        r.rel = RelMode::Temp;
        r.relReg = uint16_t(a0_);
        r.relComp = s.rel.component;
      }
    }
    return r;
  }

  // The destination as the IR sees it; scalar registers get mask .x.
  Dst dstOf(const sh::Instruction& in) {
    const sh::DstParam& d = in.dst;
    Dst r;
    r.mask = d.writeMask;
    const int n = d.index;
    switch (d.type) {
      case RegType::Temp:
        if (ps1x_ && n == 0) r.file = RegFile::Output, r.index = 0;
        else r.file = RegFile::Temp, r.index = uint16_t(rBase_ + n);
        break;
      case RegType::Texture:
        if (ver_.isVertex()) {
          r.file = RegFile::Temp, r.index = uint16_t(a0_);
        } else if (ps13_) {
          if (n >= count(RegType::Texture)) failIn(in, fmt::format("texture register t{} is out of range", n));
          r.file = RegFile::Temp, r.index = uint16_t(tBase_ + n);
        } else {
          failIn(in, fmt::format("t{} is read-only in {}", n, ver_.name()));
        }
        break;
      case RegType::RastOut:
        if (n >= count(RegType::RastOut)) failIn(in, fmt::format("rasterizer output {} is out of range", n));
        r.file = RegFile::Output;
        r.index = uint16_t(n == 0 ? kVertexOutPosition : n == 1 ? kVertexOutFog : kVertexOutPSize);
        if (n > 0) r.mask = 0x1;
        break;
      case RegType::AttrOut:
        if (n >= count(RegType::AttrOut)) failIn(in, fmt::format("color output oD{} is out of range", n));
        r.file = RegFile::Output, r.index = uint16_t(kVertexOutDiffuse + n);
        break;
      case RegType::Output:  // oT# (vs < 3), o# (vs_3_0)
        if (ver_.major >= 3) {
          if (n >= count(RegType::Output)) failIn(in, fmt::format("output register o{} is out of range", n));
          r.file = RegFile::Temp, r.index = uint16_t(oBase_ + n);
          if (d.relative)
            r.rel = RelMode::Loop, r.relLo = uint16_t(oBase_), r.relHi = uint16_t(oBase_ + count(RegType::Output));
        } else {
          if (n >= count(RegType::TexCrdOut))
            failIn(in, fmt::format("texture coordinate output oT{} is out of range", n));
          r.file = RegFile::Output, r.index = uint16_t(kVertexOutTex0 + n);
        }
        break;
      case RegType::ColorOut:
        if (n >= count(RegType::ColorOut)) failIn(in, fmt::format("color output oC{} is out of range", n));
        r.file = RegFile::Output, r.index = uint16_t(kPixelOutColor + n);
        break;
      case RegType::DepthOut:
        r.file = RegFile::Output, r.index = uint16_t(kPixelOutDepth), r.mask = 0x1;
        out_.writesDepth = true;
        break;
      case RegType::Predicate:
        if (p0_ < 0) failIn(in, "p0 is not available in this version");
        r.file = RegFile::Temp, r.index = uint16_t(p0_);
        break;
      default:
        failIn(in, fmt::format("{} cannot be written", sh::registerName(d.type, d.index, ver_)));
    }
    return r;
  }

  static Src asSrc(const Dst& d, uint8_t swizzle = kSwzXYZW) {
    Src s = reg(d.file, d.index, swizzle);
    if (d.rel == RelMode::Loop) s.rel = RelMode::Loop, s.relLo = d.relLo, s.relHi = d.relHi;
    return s;
  }
  static bool sameRegister(const Dst& d, const Src& s) {
    return d.file == s.file && (d.index == s.index || d.rel != RelMode::None || s.rel != RelMode::None);
  }

  // Result modifiers of the version: _sat; ps_1_x shift, range clamp and precision.
  Instr& modifiers(Instr& i, const sh::Instruction& in) {
    i.saturate = (in.dst.resultMod & sh::ResultSaturate) != 0;
    if (ps1x_) {
      i.shift = in.dst.shift;
      registerRange(i);
    }
    return i;
  }
  // ps_1_x register range and precision for values written to r#/t#.
  Instr& registerRange(Instr& i) {
    if (ps1x_) {
      i.clamp = true;
      i.clampLo = -maxValue_, i.clampHi = maxValue_;
      i.quantize = uint8_t(quantize_);
    }
    return i;
  }

  // ------------------------------------------------------------------ instructions

  // Writes go to `target`; a predicated instruction writes a scratch temp first and
  // then selects per component: p0 true (or false with !) takes the new value.
  struct Target {
    Dst final;
    Dst work;
  };
  Target targetOf(const sh::Instruction& in) {
    Dst d = dstOf(in);
    if (redirect_) {
      Dst w = dst(RegFile::Temp, *redirect_, d.mask);
      return {w, w};
    }
    if (!in.predicated) return {d, d};
    return {d, dst(RegFile::Temp, scratch(), d.mask)};
  }
  void commit(const sh::Instruction& in, const Target& t) {
    if (!in.predicated || redirect_) return;
    const Src pred = reg(RegFile::Temp, p0_, in.predicateSwizzle);
    const Src fresh = reg(RegFile::Temp, t.work.index), old = asSrc(t.final);
    // cnd: p > 0.5 (true is 1.0, false 0.0).
    p_.emit(Op::Cnd, t.final, pred, in.predicateNot ? old : fresh, in.predicateNot ? fresh : old);
  }

  void lower(const sh::Instruction& in) {
    switch (in.opcode) {
      case Opcode::Nop: case Opcode::Comment: case Opcode::Phase: case Opcode::Dcl:
      case Opcode::Def: case Opcode::DefI: case Opcode::DefB: case Opcode::End:
        return;
      default: break;
    }
    if (lowerFlow(in)) return;
    if (mainEnded_ && labels_.empty()) failIn(in, "instruction after the end of the main program");
    if (in.predicated && p0_ < 0) failIn(in, "predication needs p0 (shader model 2_x or later)");
    if (lowerTexture(in)) return;
    if (const Simple* s = simpleFor(in.opcode)) {
      lowerSimple(in, *s);
      return;
    }
    if (const sh::OpcodeInfo* info = sh::findOpcode(in.opcode); info && info->matrixRows) {
      lowerMatrix(in, *info);
      return;
    }
    switch (in.opcode) {
      case Opcode::MovA: lowerAddress(in, Op::Round); return;
      case Opcode::ExpP:
        if (ver_.major < 2) lowerOne(in, Op::ExpP, scalarReads());
        else lowerOne(in, Op::Exp2, scalarReads());
        return;
      case Opcode::SetP: {
        Target t = targetOf(in);
        Instr& i = p_.emit(Op::SetP, t.work, srcOf(in, in.src[0], t.work.mask), srcOf(in, in.src[1], t.work.mask));
        i.cmp = uint8_t(in.comparison());
        commit(in, t);
        return;
      }
      case Opcode::Bem: lowerBem(in); return;
      default: break;
    }
    const sh::OpcodeInfo* info = sh::findOpcode(in.opcode);
    failIn(in, info ? fmt::format("not supported in {}", ver_.name()) : "unknown opcode");
  }

  void lowerSimple(const sh::Instruction& in, const Simple& s) {
    if (in.opcode == Opcode::Mov && in.dst.type == RegType::Addr && ver_.isVertex()) {
      // vs_1_1 loads a0.x with floor (the address-register load of that era).
      lowerAddress(in, ver_.major < 2 ? Op::Floor : Op::Round);
      return;
    }
    const sh::OpcodeInfo* info = sh::findOpcode(in.opcode);
    lowerOne(in, s.op, info && info->has(sh::OpScalarSource) ? scalarReads()
                                                              : std::array<Reads, 3>{s.reads[0], s.reads[1], s.reads[2]});
  }

  void lowerOne(const sh::Instruction& in, Op op, std::array<Reads, 3> reads) {
    Target t = targetOf(in);
    const int n = std::min(sourceCount(op), int(in.srcCount));
    Src src[3];
    for (int k = 0; k < n; ++k) {
      const uint8_t used = usedComponents(reads[size_t(k)], t.work.mask);
      src[k] = srcOf(in, in.src[size_t(k)], used);
      if (reads[size_t(k)] == Reads::Scalar) src[k].swizzle = replicate(src[k].swizzle, 0);
    }
    modifiers(p_.emit(op, t.work, src[0], src[1], src[2]), in);
    commit(in, t);
  }

  void lowerAddress(const sh::Instruction& in, Op op) {
    Target t = targetOf(in);
    modifiers(p_.emit(op, t.work, srcOf(in, in.src[0], t.work.mask)), in);
    commit(in, t);
  }

  // m4x4 …: one dot product of the table's column count per row.
  void lowerMatrix(const sh::Instruction& in, const sh::OpcodeInfo& m) {
    Target t = targetOf(in);
    const Op dot = m.matrixColumns == 4 ? Op::Dp4 : Op::Dp3;
    const uint8_t used = dot == Op::Dp4 ? 0xF : kMaskXYZ;
    Src v = srcOf(in, in.src[0], used);
    // Row k is register (matrix + k) of the same file, each resolved on its own
    // (a row may be a local def).
    std::vector<Src> rows;
    bool overlap = sameRegister(t.work, v);
    for (int k = 0; k < m.matrixRows; ++k) {
      sh::SrcParam row = in.src[1];
      row.index = uint16_t(row.index + k);
      rows.push_back(srcOf(in, row, used));
      overlap |= sameRegister(t.work, rows.back());
    }
    Dst d = overlap ? dst(RegFile::Temp, scratch(), t.work.mask) : t.work;
    for (int k = 0; k < m.matrixRows; ++k) {
      if (!(t.work.mask >> k & 1)) continue;
      Dst row = d;
      row.mask = uint8_t(1u << k);
      modifiers(p_.emit(dot, row, v, rows[size_t(k)]), in);
    }
    if (overlap) p_.emit(Op::Mov, t.work, reg(RegFile::Temp, d.index));
    commit(in, t);
  }

  // bem r(d).rg, s0, s1: d.r = s0.r + M00*s1.r + M10*s1.g; d.g = s0.g + M01*s1.r + M11*s1.g
  // with the bump matrix of stage d.
  void lowerBem(const sh::Instruction& in) {
    Target t = targetOf(in);
    const int stage = in.dst.index;
    const Src m = bumpMatrix(stage);
    Src s0 = srcOf(in, in.src[0], 0x3), s1 = srcOf(in, in.src[1], 0x3);
    Src s1x = s1, s1y = s1;
    s1x.swizzle = replicate(s1.swizzle, 0);
    s1y.swizzle = replicate(s1.swizzle, 1);
    const int tmp = scratch();
    p_.emit(Op::Mad, dst(RegFile::Temp, tmp, 0x3), s1x, withSwizzle(m, swz(0, 1, 1, 1)), s0);
    modifiers(p_.emit(Op::Mad, dst(t.work.file, t.work.index, t.work.mask & 0x3), s1y,
                      withSwizzle(m, swz(2, 3, 3, 3)), reg(RegFile::Temp, tmp)),
              in);
    commit(in, t);
  }

  static Src withSwizzle(Src s, uint8_t swizzle) {
    s.swizzle = swizzle;
    return s;
  }

  Src bumpMatrix(int stage) {
    if (stage < 0 || stage >= kBumpEnvStages) fail("bump environment of stage {} is out of range", stage);
    out_.bumpEnvStages |= uint8_t(1u << stage);
    return reg(RegFile::Const, kConstBumpEnv + 2 * stage);
  }

  // ------------------------------------------------------------------ texture instructions

  Instr& sampleInto(Op op, Dst d, Src coord, int sampler) {
    if (sampler < 0 || sampler >= kSamplerCount) fail("sampler s{} is out of range", sampler);
    out_.samplersUsed |= 1u << sampler;
    Instr& i = p_.emit(op, d, coord);
    i.sampler = uint8_t(sampler);
    return i;
  }

  Src texCoord(int stage, uint8_t swizzle = kSwzXYZW) {
    if (stage < 0 || stage >= kTextureCoordinateSets) fail("texture coordinate set {} is out of range", stage);
    return reg(RegFile::Input, kPixelInTex0 + stage, swizzle);
  }

  bool lowerTexture(const sh::Instruction& in) {
    if (ps13_) return lowerTexture1x(in);
    switch (in.opcode) {
      case Opcode::Tex:
        if (ps14_) lowerTexld14(in, true);
        else lowerTexld(in);
        return true;
      case Opcode::TexCoord:
        if (!ps14_) failIn(in, "texcrd needs ps_1_4");
        lowerTexld14(in, false);
        return true;
      case Opcode::TexLdl:
      case Opcode::TexLdd:
        lowerTexld(in);
        return true;
      case Opcode::TexKill: {
        // ps_1_4 tests x, y, z; ps_2_0+ the components of the operand's mask (w too).
        sh::SrcParam operand;
        operand.type = in.dst.type, operand.index = in.dst.index;
        Src s = srcOf(in, operand);
        Instr& i = p_.emit(Op::Kill, dst(RegFile::Temp, 0, ps14_ ? kMaskXYZ : in.dst.writeMask), s);
        (void)i;
        out_.kills = true;
        return true;
      }
      case Opcode::TexDepth: {
        // depth = r5.r / r5.g (1.0 where g is 0)
        sh::SrcParam r5Param;
        r5Param.type = RegType::Temp, r5Param.index = in.dst.index;
        Src r5 = srcOf(in, r5Param);
        p_.emit(Op::Quot, dst(RegFile::Output, kPixelOutDepth, 0x1), withSwizzle(r5, kSwzXXXX),
                withSwizzle(r5, kSwzYYYY));
        out_.writesDepth = true;
        return true;
      }
      default:
        return false;
    }
  }

  // ps_2_0+ texld/texldp/texldb, texldl, texldd; vs_3_0 texldl.
  void lowerTexld(const sh::Instruction& in) {
    if (in.srcCount < 2 || in.src[1].type != RegType::Sampler) failIn(in, "expected a sampler operand");
    Op op = Op::Tex;
    if (in.opcode == Opcode::TexLdl) op = Op::TexLod;
    else if (in.opcode == Opcode::TexLdd) op = Op::TexGrad;
    else if (in.control & 1) op = Op::TexProj;
    else if (in.control & 2) op = Op::TexBias;
    Target t = targetOf(in);
    const int sampler = in.src[1].index;
    const uint8_t resultSwizzle = in.src[1].swizzle;
    const bool swizzled = resultSwizzle != kSwzXYZW;
    Dst d = swizzled ? dst(RegFile::Temp, scratch()) : t.work;
    Instr& i = sampleInto(op, d, srcOf(in, in.src[0]), sampler);
    if (op == Op::TexGrad) {
      if (in.srcCount < 4) failIn(in, "expected gradient operands");
      i.src[1] = srcOf(in, in.src[2]);
      i.src[2] = srcOf(in, in.src[3]);
    }
    if (swizzled) {
      modifiers(p_.emit(Op::Mov, t.work, reg(RegFile::Temp, d.index, resultSwizzle)), in);
    } else {
      modifiers(i, in);
    }
    commit(in, t);
  }

  // ps_1_4 texld r(d), src (sample stage d) and texcrd r(d).mask, src.
  void lowerTexld14(const sh::Instruction& in, bool sample) {
    if (in.srcCount < 1) failIn(in, "expected a coordinate operand");
    const sh::SrcParam& sp = in.src[0];
    Src coord = srcOf(in, sp);
    coord.mod = SrcMod::None;
    Dst d = dstOf(in);
    if (sp.mod == sh::SrcMod::Dz || sp.mod == sh::SrcMod::Dw) {
      // x/z, y/z (x/w, y/w): the divisor is the third (fourth) selected component;
      // a zero divisor gives 1.0.
      const int tmp = scratch();
      const int k = sp.mod == sh::SrcMod::Dz ? 2 : 3;
      p_.emit(Op::Mov, dst(RegFile::Temp, tmp), coord);
      p_.emit(Op::Quot, dst(RegFile::Temp, tmp, 0x3), reg(RegFile::Temp, tmp),
              reg(RegFile::Temp, tmp, uint8_t(k * 0x55)));
      coord = reg(RegFile::Temp, tmp);
    }
    if (sample) {
      sampleInto(Op::Tex, d, coord, in.dst.index);
    } else {
      Instr& i = p_.emit(Op::Mov, d, coord);
      registerRange(i);
      i.quantize = 0;  // coordinates keep their precision
    }
  }

  // ps_1_1 – ps_1_3: the destination register number is the texture stage.
  bool lowerTexture1x(const sh::Instruction& in) {
    const int m = in.dst.index;
    auto tReg = [&](int n) { return dst(RegFile::Temp, tBase_ + n); };
    auto source = [&](uint8_t used = kMaskXYZ) { return srcOf(in, in.src[0], used); };
    auto dp3Row = [&](int row) {  // row of the texm3x2/texm3x3 matrix: TC(m) . t(n)
      p_.emit(Op::Dp3, dst(RegFile::Temp, matrixTemp(), uint8_t(1u << row)), texCoord(m, trimSwizzle(kSwzXYZW, kMaskXYZ)),
              source());
    };
    auto check = [&](int srcs) {
      if (m < 0 || m >= count(RegType::Texture)) failIn(in, fmt::format("texture register t{} is out of range", m));
      if (in.srcCount < srcs) failIn(in, "missing source operand");
    };
    switch (in.opcode) {
      case Opcode::Tex: {
        check(0);
        const bool projected = opt_.projectedTextureStages >> m & 1;
        sampleInto(projected ? Op::TexProj : Op::Tex, tReg(m), texCoord(m), m);
        return true;
      }
      case Opcode::TexCoord: {
        // t(m) = saturate(u, v, w), 1
        check(0);
        Instr& i = p_.emit(Op::Mov, dst(RegFile::Temp, tBase_ + m, kMaskXYZ), texCoord(m, swz(0, 1, 2, 2)));
        i.saturate = true;
        i.quantize = uint8_t(quantize_);
        p_.emit(Op::Mov, dst(RegFile::Temp, tBase_ + m, 0x8), p_.imm({1, 1, 1, 1}));
        return true;
      }
      case Opcode::TexKill:
        check(0);
        p_.emit(Op::Kill, dst(RegFile::Temp, 0, kMaskXYZ), texCoord(m, swz(0, 1, 2, 2)));
        out_.kills = true;
        return true;
      case Opcode::TexBem:
      case Opcode::TexBemL: {
        // u' = u + M00*du + M10*dv, v' = v + M01*du + M11*dv (matrix of stage m)
        check(1);
        const Src mat = bumpMatrix(m);
        Src du = source(0x3), dv = du;
        du.swizzle = replicate(du.swizzle, 0);
        dv.swizzle = replicate(dv.swizzle, 1);
        const int tmp = scratch();
        p_.emit(Op::Mov, dst(RegFile::Temp, tmp, 0xC), texCoord(m));
        p_.emit(Op::Mad, dst(RegFile::Temp, tmp, 0x3), du, withSwizzle(mat, swz(0, 1, 1, 1)),
                texCoord(m, swz(0, 1, 1, 1)));
        p_.emit(Op::Mad, dst(RegFile::Temp, tmp, 0x3), dv, withSwizzle(mat, swz(2, 3, 3, 3)),
                reg(RegFile::Temp, tmp));
        sampleInto(Op::Tex, tReg(m), reg(RegFile::Temp, tmp), m);
        if (in.opcode == Opcode::TexBemL) {
          // t(m) *= t(n).b * LSCALE + LOFFSET (not saturated)
          Src lum = reg(RegFile::Const, kConstBumpEnv + 2 * m + 1);
          Src b = source(0x4);
          b.swizzle = replicate(b.swizzle, 2);
          p_.emit(Op::Mad, dst(RegFile::Temp, tmp, 0x1), b, withSwizzle(lum, kSwzXXXX), withSwizzle(lum, kSwzYYYY));
          registerRange(p_.emit(Op::Mul, tReg(m), reg(RegFile::Temp, tBase_ + m), reg(RegFile::Temp, tmp, kSwzXXXX)));
        }
        return true;
      }
      case Opcode::TexReg2AR:
      case Opcode::TexReg2GB:
      case Opcode::TexReg2RGB: {
        check(1);
        // (a, r) / (g, b) / (r, g, b) of t(n) as coordinates
        const uint8_t sel = in.opcode == Opcode::TexReg2AR   ? swz(3, 0, 0, 0)
                            : in.opcode == Opcode::TexReg2GB ? swz(1, 2, 2, 2)
                                                             : swz(0, 1, 2, 2);
        Src s = srcOf(in, in.src[0]);
        s.swizzle = compose(s.swizzle, sel);
        sampleInto(Op::Tex, tReg(m), s, m);
        return true;
      }
      case Opcode::TexM3x2Pad:
      case Opcode::TexM3x3Pad:
        check(1);
        if (padRow_ > 1) failIn(in, "too many pad instructions in a row");
        dp3Row(padRow_++);
        return true;
      case Opcode::TexM3x2Tex:
        check(1);
        dp3Row(1);
        padRow_ = 0;
        sampleInto(Op::Tex, tReg(m), reg(RegFile::Temp, matrixTemp(), swz(0, 1, 1, 1)), m);
        return true;
      case Opcode::TexM3x2Depth:
        // depth = z / w (1.0 where w is 0), z from the pad row
        check(1);
        dp3Row(1);
        padRow_ = 0;
        p_.emit(Op::Quot, dst(RegFile::Output, kPixelOutDepth, 0x1), reg(RegFile::Temp, matrixTemp(), kSwzXXXX),
                reg(RegFile::Temp, matrixTemp(), kSwzYYYY));
        out_.writesDepth = true;
        return true;
      case Opcode::TexM3x3Tex:
      case Opcode::TexM3x3:
      case Opcode::TexM3x3Spec:
      case Opcode::TexM3x3VSpec: {
        check(in.opcode == Opcode::TexM3x3Spec ? 2 : 1);
        dp3Row(2);
        padRow_ = 0;
        const int mat = matrixTemp();
        const Src n = reg(RegFile::Temp, mat, swz(0, 1, 2, 2));
        if (in.opcode == Opcode::TexM3x3Tex) {
          sampleInto(Op::Tex, tReg(m), n, m);
        } else if (in.opcode == Opcode::TexM3x3) {
          // t(m) = (u', v', w', 1)
          registerRange(p_.emit(Op::Mov, dst(RegFile::Temp, tBase_ + m, kMaskXYZ), n));
          p_.emit(Op::Mov, dst(RegFile::Temp, tBase_ + m, 0x8), p_.imm({1, 1, 1, 1}));
        } else {
          // R = 2 (N.E) / (N.N) N - E; E from c# (spec) or the q of TC(m-2..m) (vspec)
          Src e;
          if (in.opcode == Opcode::TexM3x3Spec) {
            e = srcOf(in, in.src[1], kMaskXYZ);
          } else {
            if (m < 2) failIn(in, "texm3x3vspec needs two pad rows before it");
            const int eye = scratch();
            for (int k = 0; k < 3; ++k)
              p_.emit(Op::Mov, dst(RegFile::Temp, eye, uint8_t(1u << k)), texCoord(m - 2 + k, kSwzWWWW));
            e = reg(RegFile::Temp, eye, swz(0, 1, 2, 2));
          }
          const int k = scratch();
          p_.emit(Op::Dp3, dst(RegFile::Temp, k, 0x1), n, e);                        // N.E
          p_.emit(Op::Dp3, dst(RegFile::Temp, k, 0x2), n, n);                        // N.N
          p_.emit(Op::Rcp, dst(RegFile::Temp, k, 0x4), reg(RegFile::Temp, k, kSwzYYYY));
          p_.emit(Op::Mul, dst(RegFile::Temp, k, 0x8), reg(RegFile::Temp, k, kSwzXXXX),
                  reg(RegFile::Temp, k, kSwzZZZZ))
              .shift = 1;  // 2 (N.E) / (N.N)
          Src negE = e;
          negE.mod = negE.mod == SrcMod::Neg ? SrcMod::None : negE.mod == SrcMod::None ? SrcMod::Neg : negE.mod;
          if (negE.mod != SrcMod::None && negE.mod != SrcMod::Neg) {  // modified E: materialise it
            const int ev = scratch();
            p_.emit(Op::Mov, dst(RegFile::Temp, ev), e);
            negE = reg(RegFile::Temp, ev, kSwzXYZW, SrcMod::Neg);
          }
          p_.emit(Op::Mad, dst(RegFile::Temp, k, kMaskXYZ), reg(RegFile::Temp, k, kSwzWWWW), n, negE);
          sampleInto(Op::Tex, tReg(m), reg(RegFile::Temp, k, swz(0, 1, 2, 2)), m);
        }
        return true;
      }
      case Opcode::TexDP3:
      case Opcode::TexDP3Tex: {
        check(1);
        if (in.opcode == Opcode::TexDP3) {
          // t(m).rgba = TC(m) . t(n)
          registerRange(p_.emit(Op::Dp3, tReg(m), texCoord(m, swz(0, 1, 2, 2)), source()));
        } else {
          // 1D lookup at (u', 0, 0)
          const int tmp = scratch();
          p_.emit(Op::Mov, dst(RegFile::Temp, tmp, 0xE), p_.imm({0, 0, 0, 0}));
          p_.emit(Op::Dp3, dst(RegFile::Temp, tmp, 0x1), texCoord(m, swz(0, 1, 2, 2)), source());
          sampleInto(Op::Tex, tReg(m), reg(RegFile::Temp, tmp), m);
        }
        return true;
      }
      default:
        return false;
    }
  }

  // ------------------------------------------------------------------ flow control

  // Condition of if/break/call on a bool constant or a predicate component.
  void boolCondition(const sh::Instruction& in, const sh::SrcParam& s, Instr& out) {
    Src c = srcOf(in, s, 0x1);
    c.swizzle = replicate(s.swizzle, 0);
    c.mod = SrcMod::None;
    out.src[0] = c;
    out.src[1] = p_.imm({0, 0, 0, 0});
    out.cmp = uint8_t(s.mod == sh::SrcMod::Not ? sh::Comparison::Eq : sh::Comparison::Ne);
  }
  void compareCondition(const sh::Instruction& in, Instr& out) {
    if (in.srcCount < 2) failIn(in, "expected two operands");
    for (int k = 0; k < 2; ++k) {
      out.src[size_t(k)] = srcOf(in, in.src[size_t(k)], 0x1);
      out.src[size_t(k)].swizzle = replicate(out.src[size_t(k)].swizzle, 0);
    }
    out.cmp = uint8_t(in.comparison());
    if (out.cmp == 0 || out.cmp == 7) failIn(in, "invalid comparison");
  }

  int emitFlow(Op op) {
    p_.emit(op, dst(RegFile::Temp, 0, 0));
    return int(p_.code.size()) - 1;
  }

  void endMain() {
    epilogue();
    emitFlow(Op::Ret);
    mainEnded_ = true;
  }

  // vs_3_0: o# temps to the outputs their dcl names, component positions kept.
  void epilogue() {
    if (oBase_ < 0) return;
    for (size_t o = 0; o < outMap_.size(); ++o) {
      for (int c = 0; c < 4; ++c) {
        const int target = outMap_[o][c];
        if (target < 0) continue;
        uint8_t mask = 0;
        for (int k = c; k < 4; ++k)
          if (outMap_[o][k] == target) mask |= uint8_t(1u << k);
        bool first = true;
        for (int k = 0; k < c; ++k) first &= outMap_[o][k] != target;
        if (!first) continue;
        p_.emit(Op::Mov, dst(RegFile::Output, target, target == kVertexOutFog || target == kVertexOutPSize ? 0x1 : mask),
                reg(RegFile::Temp, oBase_ + o, target == kVertexOutFog || target == kVertexOutPSize ? replicate(kSwzXYZW, c)
                                                                                            : kSwzXYZW));
      }
    }
  }

  bool lowerFlow(const sh::Instruction& in) {
    switch (in.opcode) {
      case Opcode::If: {
        if (in.srcCount < 1) failIn(in, "expected a condition");
        const int at = emitFlow(Op::If);
        boolCondition(in, in.src[0], p_.code.back());
        blocks_.push_back({Opcode::If, at});
        return true;
      }
      case Opcode::IfC: {
        const int at = emitFlow(Op::If);
        compareCondition(in, p_.code.back());
        blocks_.push_back({Opcode::If, at});
        return true;
      }
      case Opcode::Else: {
        if (blocks_.empty() || blocks_.back().opcode != Opcode::If || blocks_.back().elseAt >= 0)
          failIn(in, "else without if");
        const int at = emitFlow(Op::Else);
        blocks_.back().elseAt = at;
        p_.code[size_t(blocks_.back().at)].target = at;
        return true;
      }
      case Opcode::EndIf: {
        if (blocks_.empty() || blocks_.back().opcode != Opcode::If) failIn(in, "endif without if");
        const int at = emitFlow(Op::EndIf);
        const Block b = blocks_.back();
        blocks_.pop_back();
        if (b.elseAt >= 0) p_.code[size_t(b.elseAt)].target = at;
        else p_.code[size_t(b.at)].target = at;
        return true;
      }
      case Opcode::Rep:
      case Opcode::Loop: {
        const bool loop = in.opcode == Opcode::Loop;
        const int k = loop ? 1 : 0;  // loop aL, i#
        if (in.srcCount <= k || in.src[size_t(k)].type != RegType::ConstInt) failIn(in, "expected an integer constant i#");
        const int at = emitFlow(loop ? Op::Loop : Op::Rep);
        p_.code.back().src[0] = srcOf(in, in.src[size_t(k)]);
        blocks_.push_back({in.opcode, at});
        return true;
      }
      case Opcode::EndRep:
      case Opcode::EndLoop: {
        const Opcode open = in.opcode == Opcode::EndRep ? Opcode::Rep : Opcode::Loop;
        if (blocks_.empty() || blocks_.back().opcode != open)
          failIn(in, fmt::format("{} without {}", in.opcode == Opcode::EndRep ? "endrep" : "endloop",
                                 open == Opcode::Rep ? "rep" : "loop"));
        const int at = emitFlow(in.opcode == Opcode::EndRep ? Op::EndRep : Op::EndLoop);
        p_.code.back().target = blocks_.back().at;
        p_.code[size_t(blocks_.back().at)].target = at;
        blocks_.pop_back();
        return true;
      }
      case Opcode::Break:
      case Opcode::BreakC:
      case Opcode::BreakP: {
        if (std::none_of(blocks_.begin(), blocks_.end(),
                         [](const Block& b) { return b.opcode == Opcode::Rep || b.opcode == Opcode::Loop; }))
          failIn(in, "break outside rep/loop");
        emitFlow(Op::Break);
        if (in.opcode == Opcode::BreakC) compareCondition(in, p_.code.back());
        else if (in.opcode == Opcode::BreakP) {
          if (in.srcCount < 1) failIn(in, "expected a predicate");
          boolCondition(in, in.src[0], p_.code.back());
        }
        return true;
      }
      case Opcode::Call:
      case Opcode::CallNZ: {
        if (in.srcCount < 1 || in.src[0].type != RegType::Label) failIn(in, "expected a label l#");
        const int at = emitFlow(Op::Call);
        if (in.opcode == Opcode::CallNZ) {
          if (in.srcCount < 2) failIn(in, "expected a condition");
          boolCondition(in, in.src[1], p_.code.back());
        }
        calls_.push_back({at, in.src[0].index});
        return true;
      }
      case Opcode::Ret:
        if (!blocks_.empty()) failIn(in, "ret inside a flow-control block");
        if (!mainEnded_) endMain();
        else emitFlow(Op::Ret);
        return true;
      case Opcode::Label: {
        if (!blocks_.empty()) failIn(in, "label inside a flow-control block");
        if (in.srcCount < 1 && !in.hasDst) failIn(in, "expected a label l#");
        if (!mainEnded_) endMain();
        else if (p_.code.empty() || p_.code.back().op != Op::Ret) emitFlow(Op::Ret);  // no fall-through
        const int label = in.srcCount ? in.src[0].index : in.dst.index;
        if (labels_.count(label)) failIn(in, fmt::format("label l{} is defined twice", label));
        labels_[label] = int(p_.code.size());
        return true;
      }
      default:
        return false;
    }
  }

  // ------------------------------------------------------------------ co-issue

  // ps_1_x co-issued pair: both halves read the registers as they were before the
  // pair (DX8 combiner hardware). Ordered so that neither reads what the other
  // wrote; when each reads the other's destination, the first writes a scratch
  // register and is copied after the second.
  void lowerPair(const sh::Instruction& a, const sh::Instruction& b) {
    auto reads = [&](const sh::Instruction& reader, const sh::Instruction& writer) {
      if (!writer.hasDst) return false;
      const Dst w = dstOf(writer);
      for (int k = 0; k < reader.srcCount; ++k) {
        const sh::SrcParam& s = reader.src[size_t(k)];
        if (s.type == RegType::Const || s.type == RegType::Sampler) continue;
        if (sameRegister(w, srcOf(reader, s))) return true;
      }
      return false;
    };
    const bool bReadsA = reads(b, a), aReadsB = reads(a, b);
    if (!bReadsA) {
      lower(a);
      lower(b);
    } else if (!aReadsB) {
      lower(b);
      lower(a);
    } else {
      const int tmp = scratch();
      redirect_ = tmp;
      lower(a);
      redirect_.reset();
      lower(b);
      p_.emit(Op::Mov, dstOf(a), reg(RegFile::Temp, tmp));
    }
  }
};

}  // namespace

LoweredShader lowerShader(const shader::Shader& shader, const ShaderLoweringOptions& options) {
  return Lowerer(shader, options).run();
}

}  // namespace refx::exec
