// Checks a decoded shader against the rules of its version (version_rules.h):
// opcodes and operands, modifiers, register files, ps_1_x ordering and texture
// sequences, ps_1_4 phases, dcl rules, flow control and instruction slots.
#include "refx/shader/validator.h"

#include <algorithm>
#include <cctype>
#include <functional>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include <fmt/format.h>

#include "refx/core/diagnostics.h"
#include "refx/shader/version_rules.h"

namespace refx::shader {
namespace {

using O = Opcode;
using R = RegType;

// ---- names for messages ----------------------------------------------------------

struct OpName {
  Opcode op;
  const char* name;
};
constexpr OpName kOpNames[] = {
    {O::Nop, "nop"}, {O::Mov, "mov"}, {O::Add, "add"}, {O::Sub, "sub"}, {O::Mad, "mad"},
    {O::Mul, "mul"}, {O::Rcp, "rcp"}, {O::Rsq, "rsq"}, {O::Dp3, "dp3"}, {O::Dp4, "dp4"},
    {O::Min, "min"}, {O::Max, "max"}, {O::Slt, "slt"}, {O::Sge, "sge"}, {O::Exp, "exp"},
    {O::Log, "log"}, {O::Lit, "lit"}, {O::Dst, "dst"}, {O::Lrp, "lrp"}, {O::Frc, "frc"},
    {O::M4x4, "m4x4"}, {O::M4x3, "m4x3"}, {O::M3x4, "m3x4"}, {O::M3x3, "m3x3"},
    {O::M3x2, "m3x2"}, {O::Call, "call"}, {O::CallNZ, "callnz"}, {O::Loop, "loop"},
    {O::Ret, "ret"}, {O::EndLoop, "endloop"}, {O::Label, "label"}, {O::Dcl, "dcl"},
    {O::Pow, "pow"}, {O::Crs, "crs"}, {O::Sgn, "sgn"}, {O::Abs, "abs"}, {O::Nrm, "nrm"},
    {O::SinCos, "sincos"}, {O::Rep, "rep"}, {O::EndRep, "endrep"}, {O::If, "if"},
    {O::IfC, "if_comp"}, {O::Else, "else"}, {O::EndIf, "endif"}, {O::Break, "break"},
    {O::BreakC, "break_comp"}, {O::MovA, "mova"}, {O::DefB, "defb"}, {O::DefI, "defi"},
    {O::TexCoord, "texcoord"}, {O::TexKill, "texkill"}, {O::Tex, "tex"}, {O::TexBem, "texbem"},
    {O::TexBemL, "texbeml"}, {O::TexReg2AR, "texreg2ar"}, {O::TexReg2GB, "texreg2gb"},
    {O::TexM3x2Pad, "texm3x2pad"}, {O::TexM3x2Tex, "texm3x2tex"}, {O::TexM3x3Pad, "texm3x3pad"},
    {O::TexM3x3Tex, "texm3x3tex"}, {O::TexM3x3Diff, "texm3x3diff"},
    {O::TexM3x3Spec, "texm3x3spec"}, {O::TexM3x3VSpec, "texm3x3vspec"}, {O::ExpP, "expp"},
    {O::LogP, "logp"}, {O::Cnd, "cnd"}, {O::Def, "def"}, {O::TexReg2RGB, "texreg2rgb"},
    {O::TexDP3Tex, "texdp3tex"}, {O::TexM3x2Depth, "texm3x2depth"}, {O::TexDP3, "texdp3"},
    {O::TexM3x3, "texm3x3"}, {O::TexDepth, "texdepth"}, {O::Cmp, "cmp"}, {O::Bem, "bem"},
    {O::Dp2Add, "dp2add"}, {O::Dsx, "dsx"}, {O::Dsy, "dsy"}, {O::TexLdd, "texldd"},
    {O::SetP, "setp"}, {O::TexLdl, "texldl"}, {O::BreakP, "breakp"}, {O::Phase, "phase"},
    {O::Comment, "comment"},
};

std::string opName(const Instruction& in, Version v) {
  if (in.opcode == O::Tex && (v.atLeast(1, 4))) {
    if (v.major >= 2 && (in.control & 1)) return "texldp";
    if (v.major >= 2 && (in.control & 2)) return "texldb";
    return "texld";
  }
  if (in.opcode == O::TexCoord && v.atLeast(1, 4)) return "texcrd";
  for (const OpName& n : kOpNames)
    if (n.op == in.opcode) return n.name;
  return fmt::format("opcode {}", unsigned(in.opcode));
}

std::string regName(RegType t, unsigned index, Version v) {
  switch (t) {
    case R::Temp: return fmt::format("r{}", index);
    case R::Input: return fmt::format("v{}", index);
    case R::Const: return fmt::format("c{}", index);
    case R::Addr: return v.isPixel() ? fmt::format("t{}", index) : fmt::format("a{}", index);
    case R::RastOut: return index == 0 ? "oPos" : index == 1 ? "oFog" : index == 2 ? "oPts" : fmt::format("oRast{}", index);
    case R::AttrOut: return fmt::format("oD{}", index);
    case R::TexCrdOut: return v.major >= 3 ? fmt::format("o{}", index) : fmt::format("oT{}", index);
    case R::ConstInt: return fmt::format("i{}", index);
    case R::ColorOut: return fmt::format("oC{}", index);
    case R::DepthOut: return "oDepth";
    case R::Sampler: return fmt::format("s{}", index);
    case R::ConstBool: return fmt::format("b{}", index);
    case R::Loop: return "aL";
    case R::MiscType: return index == 0 ? "vPos" : index == 1 ? "vFace" : fmt::format("misc{}", index);
    case R::Label: return fmt::format("l{}", index);
    case R::Predicate: return fmt::format("p{}", index);
    default: return fmt::format("register type {} #{}", unsigned(t), index);
  }
}

const char* blockName(Opcode op) {
  return op == O::Rep ? "rep" : op == O::Loop ? "loop" : op == O::IfC ? "if_comp" : "if";
}

// The register file as written in asm ("c", "oT", "oPos").
std::string fileName(RegType t, Version v) {
  std::string n = regName(t, 0, v);
  if (t == R::RastOut || t == R::DepthOut || t == R::Loop || t == R::MiscType) return n;
  while (!n.empty() && std::isdigit(static_cast<unsigned char>(n.back()))) n.pop_back();
  return n;
}

std::string maskName(uint8_t mask) {
  std::string s = ".";
  for (int c = 0; c < 4; ++c)
    if (mask & (1 << c)) s += "xyzw"[c];
  return s;
}

const char* srcModName(SrcMod m) {
  static const char* kNames[] = {"(none)", "-", "_bias", "-_bias", "_bx2", "-_bx2", "1-",
                                 "_x2", "-_x2", "_dz", "_dw", "_abs", "-_abs", "!"};
  unsigned i = unsigned(m);
  return i < std::size(kNames) ? kNames[i] : "(reserved)";
}

int swz(uint8_t swizzle, int c) { return (swizzle >> (2 * c)) & 3; }
bool isReplicate(uint8_t s) { return s == 0x00 || s == 0x55 || s == 0xAA || s == 0xFF; }
constexpr uint8_t kIdentity = 0xE4;

uint32_t key(RegType t, unsigned index) { return (uint32_t(t) << 16) | (index & 0xFFFF); }

bool isMatrixTex(Opcode op) {
  switch (op) {
    case O::TexM3x2Pad: case O::TexM3x2Tex: case O::TexM3x2Depth: case O::TexM3x3Pad:
    case O::TexM3x3Tex: case O::TexM3x3Spec: case O::TexM3x3VSpec: case O::TexM3x3:
      return true;
    default:
      return false;
  }
}
bool isTextureOp(const OpcodeRule& r) { return r.textureSlots > 0; }
bool isFlowOp(Opcode op) {
  switch (op) {
    case O::Call: case O::CallNZ: case O::Loop: case O::Ret: case O::EndLoop: case O::Label:
    case O::Rep: case O::EndRep: case O::If: case O::IfC: case O::Else: case O::EndIf:
    case O::Break: case O::BreakC: case O::BreakP:
      return true;
    default:
      return false;
  }
}
bool isFreeOp(Opcode op) {
  return op == O::Def || op == O::DefI || op == O::DefB || op == O::Dcl || op == O::Comment ||
         op == O::Phase || op == O::Label;
}
// Scalar instructions whose source needs a replicate swizzle in SM2+ (all sources).
bool isScalarOp(Opcode op) {
  return op == O::Rcp || op == O::Rsq || op == O::Exp || op == O::Log || op == O::ExpP ||
         op == O::LogP || op == O::Pow;
}
int matrixRows(Opcode op) {
  switch (op) {
    case O::M4x4: case O::M3x4: return 4;
    case O::M4x3: case O::M3x3: return 3;
    case O::M3x2: return 2;
    default: return 0;
  }
}
uint8_t matrixRowMask(Opcode op) { return (op == O::M4x4 || op == O::M4x3) ? 0xF : 0x7; }

// ---- instruction costs -----------------------------------------------------------

struct Cost {
  int texture = 0, arithmetic = 0, flow = 0;
};

Cost instructionCost(const VersionRules& rules, const Instruction& in,
                     const std::unordered_map<unsigned, TextureType>& samplers) {
  Cost c;
  if (isFreeOp(in.opcode)) return c;
  const OpcodeRule* r = findOpcodeRule(rules, in.opcode);
  if (!r) {
    c.arithmetic = 1;
    return c;
  }
  c = {r->textureSlots, r->arithmeticSlots, r->flowSlots};
  if (rules.ps30TextureCosts) {
    const auto& k = kPs30TextureCost;
    auto cube = [&](int srcIdx) {
      if (srcIdx >= in.srcCount) return false;
      auto it = samplers.find(in.src[srcIdx].index);
      return it != samplers.end() && it->second == TextureType::Cube;
    };
    if (in.opcode == O::Tex) {
      bool cu = cube(1);
      c.texture = (in.control & 1) ? (cu ? k.texldpCube : k.texldp)
                  : (in.control & 2) ? k.texldb
                                     : (cu ? k.texldCube : k.texld);
    } else if (in.opcode == O::TexLdl) {
      c.texture = cube(1) ? k.texldlCube : k.texldl;
    } else if (in.opcode == O::TexLdd) {
      c.texture = k.texldd;
    } else if (in.opcode == O::TexKill) {
      c.texture = k.texkill;
    }
  }
  // A co-issued pair takes one arithmetic slot.
  if (in.coissue && rules.coissue) c.arithmetic = 0;
  // Predication costs one more slot (not for the ops whose p0 is a plain operand).
  if (in.predicated) {
    if (c.texture) ++c.texture;
    else if (c.flow) ++c.flow;
    else ++c.arithmetic;
  }
  return c;
}

std::unordered_map<unsigned, TextureType> samplerTypes(const Shader& s) {
  std::unordered_map<unsigned, TextureType> m;
  for (const Instruction& in : s.instructions)
    if (in.opcode == O::Dcl && in.hasDst && in.dst.type == R::Sampler) m[in.dst.index] = in.textureType;
  return m;
}

std::string versionName(Version v) {
  if (const VersionRules* r = findVersionRules(v)) return std::string(r->name);
  std::string minor = v.minor == 1 && v.major == 2 ? "x" : v.minor == 0xFF ? "sw" : std::to_string(v.minor);
  return fmt::format("{}_{}_{}", v.isPixel() ? "ps" : "vs", v.major, minor);
}

// ---- the validator ---------------------------------------------------------------

struct Block {
  Opcode opcode;   // If, IfC, Rep, Loop
  bool dynamic;    // if_comp / if p0
  bool hasElse = false;
  SourcePos pos;
};

class Validator {
 public:
  Validator(const Shader& s, const VersionRules& r, const ValidationCaps& caps)
      : sh_(s), R_(r), caps_(caps), v_(s.version), name_(r.name) {}

  std::vector<Diagnostic> run();

 private:
  template <typename... Args>
  void error(const Instruction& in, fmt::format_string<Args...> f, Args&&... args) {
    out_.push_back({in.pos, fmt::format(f, std::forward<Args>(args)...)});
  }
  template <typename... Args>
  void errorAt(SourcePos pos, fmt::format_string<Args...> f, Args&&... args) {
    out_.push_back({pos, fmt::format(f, std::forward<Args>(args)...)});
  }

  std::string op(const Instruction& in) const { return opName(in, v_); }
  std::string reg(RegType t, unsigned i) const { return regName(t, i, v_); }

  int registerCount(const RegisterRule& r) const;
  uint8_t readMask(const Instruction& in, int s) const;
  uint8_t writtenMask(const Instruction& in) const;

  void prepass();
  void checkInstruction(const Instruction& in, size_t index);
  bool checkOpcode(const Instruction& in, const OpcodeRule*& rule);
  void checkRegisters(const Instruction& in);
  void checkModifiers(const Instruction& in, const OpcodeRule& rule);
  void checkReadPorts(const Instruction& in);
  void checkReads(const Instruction& in);
  void recordWrites(const Instruction& in);
  void checkPs11(const Instruction& in, const OpcodeRule& rule);
  void checkPs14(const Instruction& in, const OpcodeRule& rule);
  void checkCoissue(const Instruction& in, const OpcodeRule& rule);
  void checkSm2(const Instruction& in, const OpcodeRule& rule);
  void checkDcl(const Instruction& in);
  void checkDef(const Instruction& in);
  void checkFlow(const Instruction& in);
  void checkOutputs(const Instruction& in);
  void countSlots(const Instruction& in, const OpcodeRule& rule);
  void finish();

  const Shader& sh_;
  const VersionRules& R_;
  ValidationCaps caps_;
  Version v_;
  std::string_view name_;
  std::vector<Diagnostic> out_;

  std::unordered_map<unsigned, TextureType> samplers_;
  std::unordered_map<uint32_t, uint8_t> written_;     // component masks written so far
  std::unordered_map<uint32_t, uint8_t> declared_;    // dcl masks
  bool anyInputDcl_ = false;
  std::unordered_map<uint32_t, uint8_t> subWritten_;  // temps written inside subroutines
  std::unordered_map<uint32_t, int> opCount_;         // per-opcode count (maxPerShader)

  // Order and phase state.
  bool seenNonDef_ = false;       // an instruction other than def/comment was seen
  bool seenNonDecl_ = false;      // SM2+: an instruction other than def/dcl/comment
  bool seenArithmetic_ = false;   // ps_1_x: in the current phase
  int phase_ = 2;                 // ps_1_4: 1 before `phase` when the shader has one
  bool hasPhase_ = false;
  int phaseTexture_ = 0, phaseArithmetic_ = 0;
  bool reportedPhaseTex_ = false, reportedPhaseArith_ = false;
  std::unordered_map<unsigned, uint8_t> writtenInPhase1_;  // ps_1_4 r# masks at `phase`
  std::set<unsigned> texDstThisPhase_;                     // ps_1_4 texld/texcrd destinations
  std::map<unsigned, int> texcoordSelector_;               // ps_1_4: 0 = .xyz, 1 = .xyw
  int dzCount_ = 0;

  // ps_1_1 – ps_1_3 texture registers.
  int lastTexDst_ = -1;
  std::set<unsigned> texDefined_;     // written by a texture instruction
  std::set<unsigned> texUnreadable_;  // pad destinations, texm3x2depth destination
  std::set<unsigned> texBemRead_;     // read by texbem/texbeml
  struct Pending {
    Opcode expect1 = O::Nop;   // the next instruction must be one of these …
    Opcode expect2 = O::Nop, expect3 = O::Nop, expect4 = O::Nop;
    unsigned dst = 0, src = 0; // … writing t(dst) from t(src)
    std::string what;          // for the message
    SourcePos pos;
    bool active = false;
  } pending_;

  // Co-issue.
  const Instruction* prevArith_ = nullptr;  // the instruction a `+` pairs with
  bool prevWasCoissued_ = false;

  // Slots.
  int texture_ = 0, arithmetic_ = 0, total_ = 0;
  bool reportedTex_ = false, reportedArith_ = false, reportedTotal_ = false;

  // Flow control.
  std::vector<Block> blocks_;
  int staticFlowCount_ = 0;
  bool inSubroutine_ = false;
  bool mainEnded_ = false;
  bool lastWasRet_ = false;
  int currentLabel_ = -1;
  std::map<int, SourcePos> labels_;
  std::vector<std::pair<int, std::pair<int, SourcePos>>> calls_;  // (caller label or -1, (callee, pos))

  // Dependent reads (ps_2_0 / ps_2_x).
  std::unordered_map<uint32_t, int> texLevel_;

  // Outputs.
  std::set<unsigned> colorOutWritten_;
  bool depthWritten_ = false;
  uint8_t oPosMask_ = 0;
  bool r0Written_ = false;
};

int Validator::registerCount(const RegisterRule& r) const {
  switch (r.fromCaps) {
    case CountFromCaps::VertexShaderConst:
      return caps_.maxVertexShaderConst > 0 ? caps_.maxVertexShaderConst : r.count;
    case CountFromCaps::Vs2xTemps: return std::clamp(caps_.vs2xTemps, 12, 32);
    case CountFromCaps::Ps2xTemps: return std::clamp(caps_.ps2xTemps, 12, 32);
    default: return r.count;
  }
}

// Components of source `s`'s register that the instruction reads.
uint8_t Validator::readMask(const Instruction& in, int s) const {
  const SrcParam& p = in.src[s];
  uint8_t dstMask = in.hasDst ? in.dst.writeMask : 0xF;
  uint8_t used = dstMask;  // per-component operations by default
  switch (in.opcode) {
    case O::Dp3: case O::Crs: used = 0x7; break;
    case O::Dp4: used = 0xF; break;
    case O::Rcp: case O::Rsq: case O::Exp: case O::Log: case O::ExpP: case O::LogP: case O::Pow:
    case O::IfC: case O::BreakC: case O::If: case O::CallNZ: case O::BreakP:
      used = 0x1;
      break;
    case O::SinCos: used = s == 0 ? 0x1 : 0xF; break;
    case O::Dp2Add: used = s == 2 ? 0x1 : 0x3; break;
    case O::Lit: used = 0xB; break;
    case O::Dst: used = s == 0 ? 0x6 : 0xA; break;
    case O::M4x4: case O::M4x3: used = 0xF; break;
    case O::M3x4: case O::M3x3: case O::M3x2: used = 0x7; break;
    case O::Nrm: used = 0x7 | (dstMask & 0x8); break;
    case O::Bem: used = 0x3; break;
    case O::Sgn: used = s == 0 ? dstMask : 0; break;
    case O::Tex: case O::TexLdl: case O::TexLdd:
      if (v_.major < 2) {
        used = 0x7;  // ps_1_4 texld r, r(k)[.xyz|.xyw]
      } else if (s == 0) {
        TextureType t = TextureType::Tex2D;
        if (in.srcCount > 1) {
          auto it = samplers_.find(in.src[1].index);
          if (it != samplers_.end()) t = it->second;
        }
        used = (t == TextureType::Cube || t == TextureType::Volume) ? 0x7 : 0x3;
        if (in.opcode == O::TexLdl || (in.control & 3)) used = 0xF;
      } else if (s == 1) {
        used = 0;
      } else {
        used = 0x7;  // texldd gradients
      }
      break;
    case O::TexCoord: used = 0x7; break;  // ps_1_4 texcrd
    default: break;
  }
  uint8_t m = 0;
  for (int c = 0; c < 4; ++c)
    if (used & (1 << c)) m |= uint8_t(1 << swz(p.swizzle, c));
  return m;
}

// Components an instruction writes into its destination register.
uint8_t Validator::writtenMask(const Instruction& in) const {
  if (!in.hasDst) return 0;
  if (v_.ps1x() && !v_.atLeast(1, 4)) {
    const OpcodeRule* r = findOpcodeRule(R_, in.opcode);
    if (r && isTextureOp(*r)) {
      if (in.opcode == O::TexKill || in.opcode == O::TexM3x2Pad || in.opcode == O::TexM3x3Pad ||
          in.opcode == O::TexM3x2Depth)
        return 0;
      return 0xF;
    }
  }
  if (in.opcode == O::TexKill) return 0;
  if (in.opcode == O::Tex && v_.ps1x()) return 0xF;  // ps_1_4 texld
  switch (in.opcode) {
    case O::M4x3: case O::M3x3: return in.dst.writeMask & 0x7;
    case O::M3x2: return in.dst.writeMask & 0x3;
    default: return in.dst.writeMask;
  }
}

void Validator::prepass() {
  samplers_ = samplerTypes(sh_);
  bool afterMain = false, inSub = false;
  for (const Instruction& in : sh_.instructions) {
    if (in.opcode == O::Dcl && in.hasDst && in.dst.type == R::Input) anyInputDcl_ = true;
    if (in.opcode == O::Phase) hasPhase_ = true;
    if (in.opcode == O::Label) inSub = true, afterMain = true;
    if (inSub && in.hasDst && in.opcode != O::Dcl && in.opcode != O::Def)
      subWritten_[key(in.dst.type, in.dst.index)] |= writtenMask(in);
    if (in.opcode == O::Ret && inSub) inSub = false;
    (void)afterMain;
  }
  if (hasPhase_) phase_ = 1;
}

std::vector<Diagnostic> Validator::run() {
  prepass();
  for (size_t i = 0; i < sh_.instructions.size(); ++i) checkInstruction(sh_.instructions[i], i);
  finish();
  return std::move(out_);
}

bool Validator::checkOpcode(const Instruction& in, const OpcodeRule*& rule) {
  rule = findOpcodeRule(R_, in.opcode);
  if (in.opcode == O::TexM3x3Diff) {
    error(in, "texm3x3diff is a reserved opcode and not valid in any shader");
    return false;
  }
  if (!rule) {
    error(in, "{} is not a {} instruction", op(in), name_);
    return false;
  }
  // Specific-control bits 23:16 hold the comparison of ifc/breakc/setp and, from SM2
  // on, texld's project (texldp) or bias (texldb) bit; they are reserved (0) elsewhere.
  const bool compares = in.opcode == O::IfC || in.opcode == O::BreakC || in.opcode == O::SetP;
  const bool controlOk = compares                         ? in.control >= 1 && in.control <= 6
                         : in.opcode == O::Tex && v_.major >= 2 ? in.control <= 2
                                                                : in.control == 0;
  if (!controlOk) {
    error(in, "{} has specific-control bits 0x{:02x}, which {} does not define for it", op(in),
          in.control, name_);
    return false;
  }
  // Result modifier bits 23:20 of a destination: _sat, _pp and _centroid; bit 23 is
  // undefined.
  if (in.hasDst && (in.dst.resultMod & ~(ResultSaturate | ResultPartialPrecision | ResultCentroid))) {
    error(in, "{} has result modifier bits 0x{:x}; only _sat, _pp and _centroid exist", op(in),
          in.dst.resultMod);
    return false;
  }
  if (rule->flags & OpNeedsCap) {
    bool ok = v_.isPixel() ? caps_.ps2xFlowControl : caps_.vs2xFlowControl;
    if (!ok) {
      error(in, "{} in {} needs a device that reports it (flow-control/predication caps)", op(in), name_);
      return false;
    }
  }
  if (in.srcCount > 4) {
    error(in, "{} has {} sources; instructions have at most 4", op(in), in.srcCount);
    return false;
  }
  return true;
}

void Validator::checkInstruction(const Instruction& in, size_t index) {
  if (in.opcode == O::Comment) return;
  const OpcodeRule* rule = nullptr;
  if (!checkOpcode(in, rule)) {
    lastWasRet_ = false;
    return;
  }

  // Version-wide instruction properties.
  if (in.coissue && !R_.coissue) error(in, "co-issue (+) exists only in ps_1_1 - ps_1_4, not in {}", name_);
  if (in.predicated) {
    bool ok = R_.predication && (v_.major >= 3 || (v_.isPixel() ? caps_.ps2xFlowControl : caps_.vs2xFlowControl));
    if (!ok) error(in, "predication ({}p0) is not available in {}", in.predicateNot ? "!" : "", name_);
    else {
      if (!(written_[key(R::Predicate, 0)]))
        error(in, "p0 is read before it is written (setp)");
    }
  }

  if (in.opcode == O::Def || in.opcode == O::DefI || in.opcode == O::DefB) {
    checkDef(in);
  } else if (in.opcode == O::Dcl) {
    checkDcl(in);
  } else if (in.opcode == O::Phase) {
    // ps_1_4: the phase marker.
    if (phase_ == 2 && hasPhase_) error(in, "ps_1_4 allows one phase instruction");
    for (auto& [k, mask] : written_)
      if ((k >> 16) == uint32_t(R::Temp)) writtenInPhase1_[k & 0xFFFF] = mask;
    // The alpha of every temp is lost at the phase marker.
    for (auto& [k, mask] : written_)
      if ((k >> 16) == uint32_t(R::Temp)) mask &= 0x7;
    phase_ = 2;
    seenArithmetic_ = false;
    phaseTexture_ = phaseArithmetic_ = 0;
    reportedPhaseTex_ = reportedPhaseArith_ = false;
    texDstThisPhase_.clear();
    prevArith_ = nullptr;
  } else {
    checkRegisters(in);
    checkModifiers(in, *rule);
    checkReadPorts(in);
    if (v_.ps1x() && !v_.atLeast(1, 4)) checkPs11(in, *rule);
    if (v_.ps1x() && v_.atLeast(1, 4)) checkPs14(in, *rule);
    if (v_.ps1x()) checkCoissue(in, *rule);
    if (v_.major >= 2) checkSm2(in, *rule);
    if (R_.flow.labels || isFlowOp(in.opcode)) checkFlow(in);
    checkReads(in);
    checkOutputs(in);
    recordWrites(in);
  }

  // Order: def before everything in ps_1_x; dcl before instructions in SM2+.
  if (in.opcode != O::Def) seenNonDef_ = true;
  if (!isFreeOp(in.opcode)) seenNonDecl_ = true;
  lastWasRet_ = in.opcode == O::Ret;

  // Per-shader instruction counts (ps_1_2 cmp ≤ 3, dp4 ≤ 4; ps_1_4 bem once).
  if (rule->maxPerShader) {
    int n = ++opCount_[uint32_t(in.opcode)];
    if (n == rule->maxPerShader + 1)
      error(in, "{} allows {} {} instruction{} per shader, this shader has more", name_,
            rule->maxPerShader, op(in), rule->maxPerShader == 1 ? "" : "s");
  }
  countSlots(in, *rule);
}

// ---- registers -------------------------------------------------------------------

void Validator::checkRegisters(const Instruction& in) {
  auto checkIndex = [&](RegType t, unsigned index, bool isDst, bool relative) -> const RegisterRule* {
    const RegisterRule* r = findRegisterRule(R_, t);
    if (!r) {
      error(in, "{} is not a {} register", reg(t, index), name_);
      return nullptr;
    }
    int count = registerCount(*r);
    if (!relative && int(index) >= count) {
      if (count == 1)
        error(in, "{} is out of range: {} has only {}", reg(t, index), name_, reg(t, 0));
      else
        error(in, "{} is out of range: {} has {} {} registers ({}..{})", reg(t, index), name_, count,
              r->meaning, reg(t, 0), reg(t, count - 1));
    }
    if (isDst && !(r->access & RegWrite)) {
      error(in, "{} is read-only in {}", reg(t, index), name_);
      return nullptr;
    }
    if (!isDst && !(r->access & RegRead)) {
      error(in, "{} cannot be read in {}", reg(t, index), name_);
      return nullptr;
    }
    return r;
  };
  auto checkRelative = [&](const RegisterRule* r, RegType t, const RelativeAddress& rel) {
    if (!r) return;
    if (!r->indexable || !R_.indexRegisters) {
      error(in, "{}[…] relative addressing is not available for {} registers in {}",
            fileName(t, v_), r->meaning, name_);
      return;
    }
    if (rel.type == R::Loop) {
      if (!(R_.indexRegisters & IndexLoop)) {
        error(in, "{} cannot index with aL", name_);
      } else {
        bool inLoop = std::any_of(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.opcode == O::Loop; });
        if (!inLoop && !inSubroutine_) error(in, "aL is used outside a loop … endloop block");
      }
    } else if (rel.type == R::Addr) {
      if (!(R_.indexRegisters & (IndexA0X | IndexA0Any))) {
        error(in, "{} cannot index with a0", name_);
      } else if (!(R_.indexRegisters & IndexA0Any) && rel.component != 0) {
        error(in, "{} indexes constants only with a0.x", name_);
      } else if (!(written_[key(R::Addr, 0)] & (1 << (rel.component & 3)))) {
        error(in, "a0.{} is used as an index before it is written", "xyzw"[rel.component & 3]);
      }
      if (v_.major >= 3 && v_.isVertex() && t == R::Output)
        error(in, "o[…] outputs can be indexed only with aL");
    } else {
      error(in, "relative addressing uses a0 or aL, not {}", reg(rel.type, 0));
    }
  };

  if (in.hasDst) {
    // texkill's operand is encoded as a destination but only read.
    const bool written = in.opcode != O::TexKill;
    const RegisterRule* r = checkIndex(in.dst.type, in.dst.index, written, in.dst.relative);
    if (in.dst.relative) checkRelative(r, in.dst.type, in.dst.rel);
  }
  for (int s = 0; s < in.srcCount; ++s) {
    const SrcParam& p = in.src[s];
    const RegisterRule* r = checkIndex(p.type, p.index, false, p.relative);
    if (p.relative) checkRelative(r, p.type, p.rel);
  }

  // vs_1_1 with dcl (D3D9 style) declares every input it reads; without any dcl the
  // D3D8 vertex declaration maps the inputs.
  if (v_.isVertex() && v_.major == 1 && anyInputDcl_)
    for (int s = 0; s < in.srcCount; ++s)
      if (in.src[s].type == R::Input && !declared_.count(key(R::Input, in.src[s].index)))
        error(in, "{} is read but not declared (dcl)", reg(R::Input, in.src[s].index));

  // Matrix macros read consecutive registers of src1.
  if (int rows = matrixRows(in.opcode); rows && in.srcCount >= 2) {
    const SrcParam& m = in.src[1];
    if (const RegisterRule* r = findRegisterRule(R_, m.type); r && !m.relative) {
      int count = registerCount(*r);
      if (int(m.index) + rows > count && int(m.index) < count)
        error(in, "{} reads {}..{} but {} has {} {} registers", op(in), reg(m.type, m.index),
              reg(m.type, m.index + rows - 1), name_, count, r->meaning);
    }
  }

  // Operand kinds that only certain instructions take.
  for (int s = 0; s < in.srcCount; ++s) {
    RegType t = in.src[s].type;
    bool ok = true;
    const char* what = "";
    switch (t) {
      case R::Sampler:
        ok = (in.opcode == O::Tex || in.opcode == O::TexLdl || in.opcode == O::TexLdd) && s == 1;
        what = "only as the sampler operand of texld/texldl/texldd";
        break;
      case R::Label:
        ok = (in.opcode == O::Call || in.opcode == O::CallNZ || in.opcode == O::Label) && s == 0;
        what = "only by call, callnz and label";
        break;
      case R::ConstInt:
        ok = (in.opcode == O::Rep && s == 0) || (in.opcode == O::Loop && s == 1);
        what = "only by rep and loop";
        break;
      case R::ConstBool:
        ok = (in.opcode == O::If && s == 0) || (in.opcode == O::CallNZ && s == 1);
        what = "only by if and callnz";
        break;
      case R::Loop:
        ok = in.opcode == O::Loop && s == 0;
        what = "only as the loop operand and as an index (c[aL + n])";
        break;
      case R::Predicate:
        ok = ((in.opcode == O::If || in.opcode == O::BreakP) && s == 0) || (in.opcode == O::CallNZ && s == 1);
        what = "only by if, callnz, breakp and as an instruction predicate";
        break;
      case R::MiscType:
        if (in.src[s].index == 1) {
          ok = in.opcode == O::SetP || in.opcode == O::IfC || in.opcode == O::BreakC;
          what = "only in comparisons (setp, if_comp, break_comp)";
        }
        break;
      default:
        break;
    }
    if (!ok && findRegisterRule(R_, t)) error(in, "{} can be read {}", reg(t, in.src[s].index), what);
  }
  if (in.hasDst && in.dst.type == R::Predicate && in.opcode != O::SetP)
    error(in, "p0 is written only by setp");
  if (in.opcode == O::SetP && in.hasDst && in.dst.type != R::Predicate) error(in, "setp writes p0");
}

// ---- modifiers, swizzles and masks -----------------------------------------------

void Validator::checkModifiers(const Instruction& in, const OpcodeRule& rule) {
  const bool ps11 = v_.ps1x() && !v_.atLeast(1, 4);
  const bool ps14 = v_.ps1x() && v_.atLeast(1, 4);
  const bool texOp = isTextureOp(rule);

  // Result modifiers and shift.
  if (in.hasDst) {
    uint8_t rm = in.dst.resultMod;
    if (rm & ~R_.resultModifiers & (ResultSaturate | ResultPartialPrecision)) {
      std::string which = (rm & ~R_.resultModifiers & ResultSaturate) ? "_sat" : "_pp";
      error(in, "{} is not available in {}", which, name_);
    }
    if (rm & ResultCentroid) error(in, "_centroid applies only to dcl");
    if (in.dst.shift) {
      static const char* kShift[] = {"_d8", "_d4", "_d2", "", "_x2", "_x4", "_x8"};
      int sh = in.dst.shift;
      std::string n = (sh >= -3 && sh <= 3) ? kShift[sh + 3] : fmt::format("shift {}", sh);
      if (sh < R_.minShift || sh > R_.maxShift) error(in, "{} is not available in {}", n, name_);
      else if (texOp) error(in, "{} cannot take the instruction modifier {}", op(in), n);
    }
    if ((rm & ResultSaturate) && (R_.resultModifiers & ResultSaturate)) {
      bool noSat = in.opcode == O::Frc || in.opcode == O::SinCos || (texOp && v_.major >= 2);
      if (v_.ps1x() && texOp) noSat = true;
      if (noSat) error(in, "{} cannot take _sat", op(in));
    }

    // Write masks.
    uint8_t mask = in.dst.writeMask;
    if (mask == 0) error(in, "empty write mask");
    if (in.opcode == O::Frc && v_.isVertex() && v_.major == 1 && mask != 0x2 && mask != 0x3)
      error(in, "frc in {} writes .y or .xy", name_);
    if (ps11) {
      if (texOp && mask != 0xF) error(in, "{} takes no write mask", op(in));
      else if (!texOp && mask != 0xF && mask != 0x7 && mask != 0x8)
        error(in, "{} write masks are .rgba, .rgb and .a; {} is not allowed", name_, maskName(mask));
      else if (in.opcode == O::Dp3 && mask == 0x8)
        error(in, "dp3 in {} writes .rgb or .rgba (it runs in the color pipe)", name_);
    }
  }

  // Sources.
  for (int s = 0; s < in.srcCount; ++s) {
    const SrcParam& p = in.src[s];
    unsigned m = unsigned(p.mod);
    if (m > 13 || !(R_.srcModifiers & (1u << m))) {
      error(in, "source modifier {} is not available in {}", srcModName(p.mod), name_);
      continue;
    }
    if (p.mod == SrcMod::Not && p.type != R::ConstBool && p.type != R::Predicate)
      error(in, "! applies only to b# and p0 operands");
    if ((p.mod == SrcMod::Abs || p.mod == SrcMod::AbsNeg) && !isFreeOp(in.opcode) && v_.major < 3)
      error(in, "_abs is not available in {}", name_);

    bool flowOperand = p.type == R::Sampler || p.type == R::Label || p.type == R::ConstInt ||
                       p.type == R::ConstBool || p.type == R::Loop || p.type == R::Predicate;
    if (flowOperand) continue;

    // ps_1_x texture-instruction sources have their own rules (checkPs11/checkPs14).
    if (v_.ps1x() && texOp) continue;

    if (p.mod == SrcMod::Dz || p.mod == SrcMod::Dw) {
      error(in, "_dz/_dw apply only to texld and texcrd sources");
      continue;
    }
    if (ps14 && p.type == R::Const && p.mod != SrcMod::None)
      error(in, "source modifiers on constants are not allowed in ps_1_4 ({})", reg(p.type, p.index));

    // Swizzles.
    uint8_t sw = p.swizzle;
    switch (R_.swizzles) {
      case SwizzleRule::Ps11: {
        bool alphaOnly = in.hasDst && in.dst.writeMask == 0x8;
        if (sw == kIdentity || sw == 0xFF) break;
        if (sw == 0xAA) {
          if (!alphaOnly) error(in, "the .b selector is allowed in {} only on instructions that write .a", name_);
          break;
        }
        error(in, "{} source selectors are .a and .b (replicate); this swizzle is not allowed", name_);
        break;
      }
      case SwizzleRule::Ps14:
        if (sw != kIdentity && !isReplicate(sw))
          error(in, "ps_1_4 source selectors are .r, .g, .b and .a (replicate); this swizzle is not allowed");
        break;
      case SwizzleRule::Ps20: {
        bool arbitrary = v_.major == 2 && v_.minor == 1 && caps_.ps2xArbitrarySwizzle;
        if (!arbitrary && sw != kIdentity && !isReplicate(sw) && sw != 0xC9 && sw != 0xD2 && sw != 0x1B)
          error(in, "{} allows the swizzles .xyzw, replicate, .yzxw, .zxyw and .wzyx only", name_);
        break;
      }
      case SwizzleRule::Arbitrary:
        break;
    }
  }
}

void Validator::checkReadPorts(const Instruction& in) {
  std::map<RegType, std::set<unsigned>> used;
  for (int s = 0; s < in.srcCount; ++s) used[in.src[s].type].insert(in.src[s].index);
  for (auto& [t, set] : used) {
    const RegisterRule* r = findRegisterRule(R_, t);
    if (!r || !r->readPorts || int(set.size()) <= r->readPorts) continue;
    std::string list;
    for (unsigned i : set) list += (list.empty() ? "" : ", ") + reg(t, i);
    error(in, "{} reads at most {} different {} registers in one instruction, {} reads {} ({})",
          name_, r->readPorts, r->meaning, op(in), set.size(), list);
  }
}

// ---- initialised reads -----------------------------------------------------------

void Validator::checkReads(const Instruction& in) {
  const bool ps11 = v_.ps1x() && !v_.atLeast(1, 4);
  const OpcodeRule* rule = findOpcodeRule(R_, in.opcode);
  if (ps11 && rule && isTextureOp(*rule)) return;  // checked by the texture rules
  auto check = [&](RegType t, unsigned index, uint8_t need) {
    bool tracked = t == R::Temp || (ps11 && t == R::Texture);
    if (!tracked || !need) return;
    uint8_t have = 0;
    auto it = written_.find(key(t, index));
    if (it != written_.end()) have = it->second;
    // vs_1_1 shaders (D3D8 era) read unwritten components of partially written temps
    // routinely (m3x3 then .zxyw cross products); only whole unwritten temps fail there.
    if (v_.isVertex() && v_.major == 1) {
      if (!have) error(in, "{} is read before it is written", reg(t, index));
      return;
    }
    uint8_t missing = need & ~have;
    if (!missing) return;
    if (!have) {
      if (ps11 && t == R::Texture)
        error(in, "{} is read before it is written (no texture instruction writes it)", reg(t, index));
      else
        error(in, "{} is read before it is written", reg(t, index));
    } else if (v_.ps1x() && v_.atLeast(1, 4) && phase_ == 2 && hasPhase_ && missing == 0x8 &&
               (writtenInPhase1_[index] & 0x8)) {
      error(in, "{}.a is read in phase 2 but the alpha of temporaries is lost at the phase marker",
            reg(t, index));
    } else {
      error(in, "{}{} is read before it is written", reg(t, index), maskName(missing));
    }
  };
  bool ps14TexOp = v_.ps1x() && v_.atLeast(1, 4) && rule && isTextureOp(*rule);
  for (int s = 0; s < in.srcCount; ++s) {
    const SrcParam& p = in.src[s];
    if (ps14TexOp) continue;  // texld r(k) sources are checked against phase 1 (checkPs14)
    check(p.type, p.index, readMask(in, s));
    if (int rows = matrixRows(in.opcode); rows && s == 1)
      for (int k = 1; k < rows; ++k) check(p.type, p.index + k, matrixRowMask(in.opcode));
  }
  // texkill reads its (destination-encoded) operand in ps_1_4 and SM2+.
  if (in.opcode == O::TexKill && !ps11 && in.hasDst) check(in.dst.type, in.dst.index, v_.major >= 2 ? in.dst.writeMask : 0x7);
}

void Validator::recordWrites(const Instruction& in) {
  if (!in.hasDst) return;
  uint8_t m = writtenMask(in);
  if (!m) return;
  written_[key(in.dst.type, in.dst.index)] |= m;
  if (in.dst.type == R::Temp && in.dst.index == 0) r0Written_ = true;
}

// ---- def and dcl -----------------------------------------------------------------

void Validator::checkDef(const Instruction& in) {
  if (v_.ps1x() && seenNonDef_)
    error(in, "def must come before all other instructions in {}", name_);
  RegType want = in.opcode == O::Def ? R::Const : in.opcode == O::DefI ? R::ConstInt : R::ConstBool;
  if (!in.hasDst || in.dst.type != want) {
    error(in, "{} defines {} registers", op(in), fileName(want, v_));
    return;
  }
  if (in.dst.shift || in.dst.resultMod) {
    error(in, "{} takes no instruction modifier", op(in));
    return;
  }
  const RegisterRule* r = findRegisterRule(R_, want);
  if (!r) {
    error(in, "{} is not a {} register", reg(want, in.dst.index), name_);
    return;
  }
  int count = registerCount(*r);
  if (int(in.dst.index) >= count)
    error(in, "{} is out of range: {} has {} {} registers ({}..{})", reg(want, in.dst.index), name_,
          count, r->meaning, reg(want, 0), reg(want, count - 1));
  // A BOOL constant is TRUE (1) or FALSE (0), the values the assembler writes.
  if (in.opcode == O::DefB && in.literal[0] > 1)
    error(in, "defb {}: value 0x{:x} is neither FALSE (0) nor TRUE (1)", reg(want, in.dst.index),
          in.literal[0]);
  if (in.opcode == O::Def) {
    for (int i = 0; i < 4; ++i) {
      float f;
      std::memcpy(&f, &in.literal[i], 4);
      if (!(f >= R_.defMin && f <= R_.defMax)) {
        if (std::isnan(f) || R_.defMin < -3.0e38f)
          error(in, "def {}: value {} is not a finite number", reg(want, in.dst.index), i);
        else
          error(in, "def {}: {} is outside [{}, {}], the range of {} constants", reg(want, in.dst.index),
                f, R_.defMin, R_.defMax, name_);
        break;
      }
    }
  } else if (in.opcode == O::DefI) {
    // loop/rep counts and steps: count 0..255, start 0..255, step -128..127.
    auto val = [&](int i) { return int32_t(in.literal[i]); };
    if (val(0) < 0 || val(0) > 255 || val(1) < 0 || val(1) > 255 || val(2) < -128 || val(2) > 127)
      error(in, "defi {}: iteration count and start must be in 0..255 and the step in -128..127",
            reg(want, in.dst.index));
  }
}

void Validator::checkDcl(const Instruction& in) {
  if (!in.hasDst) return;
  const DstParam& d = in.dst;
  if (seenNonDecl_)
    error(in, "dcl must come before the first arithmetic, texture or flow-control instruction");
  bool vs = v_.isVertex();
  bool ok = false;
  switch (d.type) {
    case R::Input: ok = true; break;
    case R::Output: ok = vs && v_.major >= 3; break;
    case R::Sampler: ok = (vs && v_.major >= 3) || (!vs && v_.major >= 2); break;
    case R::Texture: ok = !vs && v_.major == 2; break;
    case R::MiscType: ok = !vs && v_.major >= 3; break;
    default: break;
  }
  if (!ok) {
    error(in, "dcl cannot declare {} in {}", reg(d.type, d.index), name_);
    return;
  }
  // A declaration computes nothing: its destination token carries no shift.
  if (d.shift) error(in, "dcl takes no shift (_x2, _d2 ...)");
  if ((d.writeMask & 0xF) == 0) error(in, "dcl of {} declares no component (empty write mask)", reg(d.type, d.index));
  // The texture type field (bits 30:27 of the usage token) belongs to sampler dcls.
  if (d.type != R::Sampler && in.textureType != TextureType::Unknown)
    error(in, "dcl of {} has a texture type; only samplers (s#) have one", reg(d.type, d.index));
  const RegisterRule* r = findRegisterRule(R_, d.type);
  if (!r) return;
  if (int(d.index) >= registerCount(*r)) {
    error(in, "{} is out of range: {} has {} {} registers", reg(d.type, d.index), name_,
          registerCount(*r), r->meaning);
    return;
  }
  if (d.resultMod & ResultCentroid && (vs || (d.type != R::Input && d.type != R::Texture)))
    error(in, "_centroid applies only to pixel shader input and texture coordinate declarations");
  if (d.resultMod & ResultSaturate) error(in, "dcl takes no _sat");
  if (d.type == R::Sampler) {
    if (in.textureType != TextureType::Tex2D && in.textureType != TextureType::Cube &&
        in.textureType != TextureType::Volume)
      error(in, "dcl of {} needs a texture type (dcl_2d, dcl_cube or dcl_volume)", reg(d.type, d.index));
    if (declared_.count(key(d.type, d.index))) error(in, "{} is declared twice", reg(d.type, d.index));
    declared_[key(d.type, d.index)] = 0xF;
    return;
  }
  if (uint8_t(in.usage) > uint8_t(DeclUsage::Sample))
    error(in, "dcl of {} has usage {}; D3DDECLUSAGE ends at 13 (sample)", reg(d.type, d.index),
          int(in.usage));
  uint8_t& m = declared_[key(d.type, d.index)];
  if (m & d.writeMask) {
    // vs_3_0 outputs may share one o# with disjoint masks; anything else once.
    error(in, "{} is declared twice", reg(d.type, d.index));
  }
  m |= d.writeMask;
  if (vs && d.type == R::Input) written_[key(d.type, d.index)] = 0xF;
}

// ---- ps_1_1 – ps_1_3 -------------------------------------------------------------

void Validator::checkPs11(const Instruction& in, const OpcodeRule& rule) {
  const bool texOp = isTextureOp(rule);

  // A texm3x2pad/texm3x3pad sequence must continue with the expected instruction.
  bool secondPad = false;
  if (pending_.active) {
    bool match = in.opcode == pending_.expect1 || in.opcode == pending_.expect2 ||
                 in.opcode == pending_.expect3 || in.opcode == pending_.expect4;
    match = match && in.hasDst && in.dst.type == R::Texture && in.dst.index == pending_.dst &&
            in.srcCount >= 1 && in.src[0].type == R::Texture && in.src[0].index == pending_.src;
    if (!match) error(in, "{}", pending_.what);
    secondPad = match && in.opcode == O::TexM3x3Pad;
    pending_.active = false;
  } else if (in.opcode == O::TexM3x2Tex || in.opcode == O::TexM3x2Depth) {
    error(in, "{} must follow texm3x2pad (a 3x2 matrix is a texm3x2pad, {} pair)", op(in), op(in));
  } else if (in.opcode == O::TexM3x3Tex || in.opcode == O::TexM3x3Spec ||
             in.opcode == O::TexM3x3VSpec || in.opcode == O::TexM3x3) {
    error(in, "{} must follow two texm3x3pad instructions", op(in));
  }

  if (!texOp) {
    seenArithmetic_ = true;
    // Arithmetic reads of texture registers.
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      if (p.type != R::Texture) continue;
      if (texUnreadable_.count(p.index))
        error(in, "{} holds no data after texm3x2pad/texm3x3pad/texm3x2depth and cannot be read", reg(p.type, p.index));
      else if (texBemRead_.count(p.index))
        error(in, "{} was read by texbem/texbeml and can afterwards be read only by texbem/texbeml", reg(p.type, p.index));
    }
    if (in.opcode == O::Cnd && in.srcCount >= 1) {
      const SrcParam& c = in.src[0];
      if (c.type != R::Temp || c.index != 0 || c.swizzle != 0xFF || c.mod != SrcMod::None)
        error(in, "cnd in {} takes r0.a as its first source", name_);
    }
    if (in.opcode == O::Cmp && in.hasDst)
      for (int s = 0; s < in.srcCount; ++s)
        if (in.src[s].type == in.dst.type && in.src[s].index == in.dst.index)
          error(in, "cmp in {} cannot write a register it reads ({})", name_, reg(in.dst.type, in.dst.index));
    return;
  }

  // Texture-address instructions.
  if (seenArithmetic_)
    error(in, "{} follows an arithmetic instruction; {} needs all texture instructions first", op(in), name_);
  if (!in.hasDst || in.dst.type != R::Texture) {
    error(in, "{} writes a t register", op(in));
    return;
  }
  unsigned m = in.dst.index;
  if (in.opcode != O::TexKill) {
    if (texDefined_.count(m) || texUnreadable_.count(m))
      error(in, "t{} is already the destination of a texture instruction", m);
    else if (int(m) < lastTexDst_)
      error(in, "texture instructions must use t registers in increasing order: t{} comes after t{}", m, lastTexDst_);
    lastTexDst_ = std::max(lastTexDst_, int(m));
  }

  // Sources.
  bool ps11only = !v_.atLeast(1, 2);
  for (int s = 0; s < in.srcCount; ++s) {
    const SrcParam& p = in.src[s];
    bool constOperand = in.opcode == O::TexM3x3Spec && s == 1;
    if (constOperand) {
      if (p.type != R::Const) error(in, "texm3x3spec takes the eye vector from a c register");
      if (p.mod != SrcMod::None || p.swizzle != kIdentity) error(in, "texm3x3spec's constant takes no modifier or swizzle");
      continue;
    }
    if (p.type != R::Texture) {
      error(in, "{} reads a t register, not {}", op(in), reg(p.type, p.index));
      continue;
    }
    if (p.swizzle != kIdentity) error(in, "{} sources take no swizzle", op(in));
    if (p.mod != SrcMod::None) {
      bool bx2ok = p.mod == SrcMod::Sign &&
                   (ps11only ? isMatrixTex(in.opcode)
                             : !(in.opcode == O::TexReg2AR || in.opcode == O::TexReg2GB ||
                                 in.opcode == O::TexBem || in.opcode == O::TexBemL));
      if (!bx2ok) {
        if (p.mod == SrcMod::Sign)
          error(in, "_bx2 is not allowed on the source of {} in {}", op(in), name_);
        else
          error(in, "{} sources take no modifier other than _bx2", op(in));
      }
    }
    if (p.index >= m) {
      error(in, "{} t{}, t{}: the source must be a lower t register than the destination", op(in), m, p.index);
    } else if (texUnreadable_.count(p.index)) {
      error(in, "t{} holds no data after texm3x2pad/texm3x3pad/texm3x2depth and cannot be read", p.index);
    } else if (!texDefined_.count(p.index)) {
      error(in, "t{} is read by {} before a texture instruction writes it", p.index, op(in));
    } else if (texBemRead_.count(p.index) && in.opcode != O::TexBem && in.opcode != O::TexBemL) {
      error(in, "t{} was read by texbem/texbeml and can afterwards be read only by texbem/texbeml", p.index);
    }
    if (in.opcode == O::TexBem || in.opcode == O::TexBemL) texBemRead_.insert(p.index);
  }

  // Matrix sequences: pads on consecutive registers with one source, then the
  // instruction that completes the matrix.
  unsigned src = in.srcCount ? in.src[0].index : 0;
  auto expect = [&](std::initializer_list<Opcode> ops, std::string what) {
    pending_ = {};
    Opcode* slots[] = {&pending_.expect1, &pending_.expect2, &pending_.expect3, &pending_.expect4};
    int i = 0;
    for (Opcode o : ops) *slots[i++] = o;
    pending_.dst = m + 1;
    pending_.src = src;
    pending_.what = std::move(what);
    pending_.pos = in.pos;
    pending_.active = true;
  };
  switch (in.opcode) {
    case O::TexM3x2Pad:
      texUnreadable_.insert(m);
      expect({O::TexM3x2Tex, O::TexM3x2Depth},
             fmt::format("texm3x2pad t{0}, t{1} must be followed by texm3x2tex{2} t{3}, t{1}", m, src,
                         v_.atLeast(1, 3) ? " or texm3x2depth" : "", m + 1));
      break;
    case O::TexM3x3Pad:
      texUnreadable_.insert(m);
      if (secondPad)
        expect({O::TexM3x3Tex, O::TexM3x3Spec, O::TexM3x3VSpec, O::TexM3x3},
               fmt::format("texm3x3pad t{0}, t{1} must be followed by texm3x3tex, texm3x3spec, texm3x3vspec{2} t{3}, t{1}",
                           m, src, v_.atLeast(1, 2) ? " or texm3x3" : "", m + 1));
      else
        expect({O::TexM3x3Pad},
               fmt::format("texm3x3pad t{0}, t{1} must be followed by a second texm3x3pad t{2}, t{1}", m, src, m + 1));
      break;
    case O::TexM3x2Depth:
      texUnreadable_.insert(m);
      break;
    case O::TexKill:
      break;
    default:
      texDefined_.insert(m);
      break;
  }
}

// ---- ps_1_4 ----------------------------------------------------------------------

void Validator::checkPs14(const Instruction& in, const OpcodeRule& rule) {
  const bool texOp = isTextureOp(rule);
  if (!texOp) {
    seenArithmetic_ = true;
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      if (p.type == R::Texture)
        error(in, "{} can be read only by texld and texcrd in ps_1_4", reg(p.type, p.index));
      if (p.type == R::Input && phase_ == 1)
        error(in, "{} cannot be read in phase 1 of ps_1_4 (color inputs arrive in phase 2)", reg(p.type, p.index));
    }
    if (in.opcode == O::Bem) {
      if (phase_ != 1) error(in, "bem is allowed only in phase 1 of ps_1_4 (before the phase marker)");
      if (in.hasDst && in.dst.writeMask != 0x3) error(in, "bem writes .rg only");
    }
    return;
  }
  if (seenArithmetic_)
    error(in, "{} follows an arithmetic instruction; in each ps_1_4 phase the texture instructions come first", op(in));
  if (!in.hasDst) return;
  const DstParam& d = in.dst;

  if (in.opcode == O::TexDepth) {
    if (d.type != R::Temp || d.index != 5) error(in, "texdepth works only on r5");
    if (phase_ != 2) error(in, "texdepth is available only in phase 2 (after the phase marker, or in a shader without one)");
    return;
  }
  if (in.opcode == O::TexKill) {
    if (d.type != R::Temp && d.type != R::Texture) error(in, "texkill takes an r or t register");
    return;
  }
  // texld / texcrd
  if (d.type != R::Temp) {
    error(in, "{} writes an r register in ps_1_4", op(in));
    return;
  }
  if (!texDstThisPhase_.insert(d.index).second)
    error(in, "r{} is already the destination of a texture instruction in this phase (r# names texture stage #)", d.index);
  if (in.opcode == O::TexCoord && d.writeMask != 0x7 && d.writeMask != 0x3 && d.writeMask != 0xF)
    error(in, "texcrd writes .rgb or .rg");
  if (in.opcode == O::Tex && d.writeMask != 0xF) error(in, "texld takes no write mask");
  if (d.resultMod || d.shift) error(in, "{} takes no instruction modifier", op(in));
  if (in.srcCount < 1) return;

  const SrcParam& p = in.src[0];
  uint8_t sw = p.swizzle;
  bool xyw = sw == 0xF4;
  if (sw != kIdentity && sw != 0xA4 && sw != 0xF4)
    error(in, "{} sources take the .xyz or .xyw selector only", op(in));
  if (p.mod != SrcMod::None && p.mod != SrcMod::Dz && p.mod != SrcMod::Dw)
    error(in, "{} sources take _dz/_dw only", op(in));
  if (p.type == R::Texture) {
    if (p.mod == SrcMod::Dz) error(in, "_dz applies to r registers; t registers take _dw");
    if (p.mod == SrcMod::Dw) xyw = true;
    if (p.mod == SrcMod::Dw && in.opcode == O::TexCoord && d.writeMask != 0x3)
      error(in, "texcrd with _dw writes .rg only");
    auto [it, fresh] = texcoordSelector_.emplace(p.index, xyw ? 1 : 0);
    if (!fresh && it->second != (xyw ? 1 : 0))
      error(in, "t{} is read with both .xyz and .xyw; every read of one t register uses the same selector", p.index);
  } else if (p.type == R::Temp) {
    if (in.opcode == O::TexCoord) error(in, "texcrd reads only t registers");
    else if (phase_ == 1 || !hasPhase_)
      error(in, "texld reads r{}, but r registers are texld coordinates only in phase 2 (after the phase marker)", p.index);
    else {
      uint8_t need = readMask(in, 0);
      uint8_t have = writtenInPhase1_[p.index];
      if (need & ~have)
        error(in, "r{}{} used as texld coordinates must be written in phase 1", p.index, maskName(need & ~have));
    }
    if (p.mod == SrcMod::Dw) error(in, "_dw applies to t registers; r registers take _dz");
    if (p.mod == SrcMod::Dz && ++dzCount_ == 3) error(in, "ps_1_4 allows _dz at most twice per shader");
  } else {
    error(in, "{} reads a t or r register, not {}", op(in), reg(p.type, p.index));
  }
}

// ---- co-issue --------------------------------------------------------------------

void Validator::checkCoissue(const Instruction& in, const OpcodeRule& rule) {
  bool arith = !isTextureOp(rule) && !isFreeOp(in.opcode);
  if (!in.coissue) {
    prevArith_ = arith ? &in : nullptr;
    prevWasCoissued_ = false;
    return;
  }
  const Instruction* first = prevArith_;
  prevArith_ = nullptr;
  if (!arith) {
    error(in, "{} cannot be co-issued (+); only arithmetic instructions pair", op(in));
    return;
  }
  if (!first) {
    error(in, "co-issued {} (+) must follow an arithmetic instruction it pairs with", op(in));
    return;
  }
  for (const Instruction* half : {first, &in}) {
    const OpcodeRule* r = findOpcodeRule(R_, half->opcode);
    if (r && (r->flags & OpNoCoissue)) error(in, "{} cannot be co-issued", opName(*half, v_));
  }
  uint8_t a = first->hasDst ? first->dst.writeMask : 0xF;
  uint8_t b = in.hasDst ? in.dst.writeMask : 0xF;
  bool ps14 = v_.atLeast(1, 4);
  auto isColor = [&](uint8_t m) { return ps14 ? (m && !(m & 0x8)) : m == 0x7; };
  const Instruction* colorHalf = isColor(a) && b == 0x8 ? first : isColor(b) && a == 0x8 ? &in : nullptr;
  if (!colorHalf) {
    error(in, "a co-issued pair writes {} in one instruction and .a in the other; these write {} and {}",
          ps14 ? "a subset of .rgb" : ".rgb", maskName(a), maskName(b));
    return;
  }
  const Instruction* alphaHalf = colorHalf == first ? &in : first;
  if (const OpcodeRule* r = findOpcodeRule(R_, alphaHalf->opcode); r && (r->flags & OpVectorOnly))
    error(in, "{} can be co-issued only as the color (.rgb) half", opName(*alphaHalf, v_));
}

// ---- SM2 / SM3 -------------------------------------------------------------------

void Validator::checkSm2(const Instruction& in, const OpcodeRule& rule) {
  // Scalar operations take one component: a replicate swizzle.
  auto needReplicate = [&](int s, const char* what) {
    if (s < in.srcCount && !isReplicate(in.src[s].swizzle))
      error(in, "{} needs a replicate swizzle (.x, .y, .z or .w) on its {}", op(in), what);
  };
  if (R_.scalarReplicate) {
    if (isScalarOp(in.opcode)) {
      needReplicate(0, in.srcCount > 1 ? "first source" : "source");
      if (in.opcode == O::Pow) needReplicate(1, "second source");
    }
    if (in.opcode == O::SinCos) needReplicate(0, "source");
    if (in.opcode == O::Dp2Add) needReplicate(2, "third source");
    if (in.opcode == O::IfC || in.opcode == O::BreakC) {
      needReplicate(0, "first source");
      needReplicate(1, "second source");
    }
    if ((in.opcode == O::If || in.opcode == O::BreakP) && in.srcCount && in.src[0].type == R::Predicate)
      needReplicate(0, "p0 operand");
    if (in.opcode == O::CallNZ && in.srcCount > 1 && in.src[1].type == R::Predicate)
      needReplicate(1, "p0 operand");
  }

  const DstParam& d = in.dst;
  uint8_t mask = in.hasDst ? d.writeMask : 0;
  auto srcIsDst = [&](int s) {
    return s < in.srcCount && in.hasDst && in.src[s].type == d.type && in.src[s].index == d.index;
  };

  // Matrix macros: plain matrix operand, fixed masks, no overlap.
  if (int rows = matrixRows(in.opcode); rows && in.srcCount >= 2) {
    if (in.src[1].swizzle != kIdentity || in.src[1].mod != SrcMod::None)
      error(in, "{} takes no swizzle or modifier on the matrix operand", op(in));
    if ((in.opcode == O::M4x3 || in.opcode == O::M3x3) && mask != 0x7) error(in, "{} writes .xyz", op(in));
    if (in.opcode == O::M3x2 && mask != 0x3) error(in, "m3x2 writes .xy");
    for (int s = 0; s < 2; ++s)
      if (in.hasDst && in.src[s].type == d.type && in.src[s].index <= d.index &&
          d.index < in.src[s].index + (s == 1 ? rows : 1))
        error(in, "{} cannot write a register it reads", op(in));
  }
  switch (in.opcode) {
    case O::SinCos:
      if (mask != 0x1 && mask != 0x2 && mask != 0x3) error(in, "sincos writes .x, .y or .xy");
      if (d.type != R::Temp) error(in, "sincos writes a temporary register");
      if (v_.major == 2 && in.srcCount >= 3) {
        if (in.src[1].type != R::Const || in.src[2].type != R::Const || in.src[1].index == in.src[2].index)
          error(in, "sincos in {} takes two different constant registers (D3DSINCOSCONST1/2) as its 2nd and 3rd operands", name_);
      }
      break;
    case O::Crs:
      if (!mask || (mask & 0x8)) error(in, "crs writes a subset of .xyz");
      if (d.type != R::Temp) error(in, "crs writes a temporary register");
      for (int s = 0; s < 2 && s < in.srcCount; ++s) {
        if (in.src[s].swizzle != kIdentity) error(in, "crs takes no source swizzle");
        if (srcIsDst(s)) error(in, "crs cannot write a register it reads");
      }
      break;
    case O::Nrm:
      if (d.type != R::Temp) error(in, "nrm writes a temporary register");
      if (srcIsDst(0)) error(in, "nrm cannot write the register it reads");
      break;
    case O::Pow:
      if (srcIsDst(1)) error(in, "pow cannot write the register of its exponent operand");
      break;
    case O::Sgn:
      if (v_.major == 2 && in.srcCount >= 3) {
        if (in.src[1].type != R::Temp || in.src[2].type != R::Temp || in.src[1].index == in.src[2].index)
          error(in, "sgn in {} takes two different temporary registers as scratch operands", name_);
      }
      break;
    case O::MovA:
      if (d.type != R::Addr) error(in, "mova writes a0");
      break;
    default:
      break;
  }
  if (in.hasDst && d.type == R::Addr && v_.isVertex() && in.opcode != O::MovA)
    error(in, "{} writes a0 only with mova", name_);

  // Texture sampling.
  if (in.opcode == O::Tex || in.opcode == O::TexLdl || in.opcode == O::TexLdd) {
    if (in.srcCount >= 2) {
      const SrcParam& s = in.src[1];
      if (s.type != R::Sampler) error(in, "{} samples through an s register", op(in));
      else if (!declared_.count(key(R::Sampler, s.index)))
        error(in, "{} is used before it is declared (dcl_2d, dcl_cube or dcl_volume)", reg(R::Sampler, s.index));
      if (v_.major == 2 && (s.swizzle != kIdentity || s.mod != SrcMod::None))
        error(in, "the sampler operand takes no swizzle or modifier in {}", name_);
    }
    if (in.hasDst && d.type != R::Temp) error(in, "{} writes a temporary register", op(in));
    if (v_.isPixel() && v_.major == 2 && in.opcode == O::Tex && in.srcCount >= 1) {
      const SrcParam& c = in.src[0];
      if (mask != 0xF) error(in, "{} in {} writes the full .xyzw mask", op(in), name_);
      if (c.type != R::Temp && c.type != R::Texture)
        error(in, "{} coordinates come from a t or r register in {}", op(in), name_);
      if (c.swizzle != kIdentity || c.mod != SrcMod::None)
        error(in, "{} coordinates take no swizzle or modifier in {}", op(in), name_);
      // Dependent-read chains (ps_2_0 without NODEPENDENTREADLIMIT): at most 4 levels.
      int level = 1;
      if (c.type == R::Temp) level = std::max(1, texLevel_[key(R::Temp, c.index)]) + 1;
      bool limit = R_.dependentReadLevels && !(v_.minor == 1 && caps_.ps2xNoDependentReadLimit);
      if (limit && level > R_.dependentReadLevels)
        error(in, "{} allows {} levels of dependent texture reads, this {} is level {}", name_,
              R_.dependentReadLevels, op(in), level);
      if (in.hasDst) texLevel_[key(d.type, d.index)] = level;
    }
  } else if (in.hasDst && d.type == R::Temp && v_.isPixel()) {
    int level = 0;
    for (int s = 0; s < in.srcCount; ++s)
      if (in.src[s].type == R::Temp) level = std::max(level, texLevel_[key(R::Temp, in.src[s].index)]);
    int& cur = texLevel_[key(R::Temp, d.index)];
    cur = (mask == 0xF) ? level : std::max(cur, level);
  }
  if (in.opcode == O::TexKill && in.hasDst && d.type != R::Temp && d.type != R::Texture && d.type != R::Input)
    error(in, "texkill takes an r or t register");

  // Declared inputs.
  if (R_.dclInputs) {
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      bool needsDcl = p.type == R::Input || (v_.isPixel() && (p.type == R::Texture || p.type == R::MiscType));
      if (!needsDcl || p.relative) continue;
      auto it = declared_.find(key(p.type, p.index));
      if (it == declared_.end()) {
        error(in, "{} is read but not declared (dcl)", reg(p.type, p.index));
      } else if (v_.isPixel()) {
        uint8_t need = readMask(in, s);
        if (need & ~it->second)
          error(in, "{}{} is read but only {}{} is declared", reg(p.type, p.index), maskName(need & ~it->second),
                reg(p.type, p.index), maskName(it->second));
      }
    }
    if (in.opcode == O::TexKill && in.hasDst && (d.type == R::Texture || d.type == R::Input) &&
        !declared_.count(key(d.type, d.index)))
      error(in, "{} is read but not declared (dcl)", reg(d.type, d.index));
  }
  (void)rule;
}

// ---- outputs ---------------------------------------------------------------------

void Validator::checkOutputs(const Instruction& in) {
  if (!in.hasDst) return;
  const DstParam& d = in.dst;
  bool inFlow = !blocks_.empty() || inSubroutine_;
  bool dynamicFlow = std::any_of(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.dynamic; });
  if (v_.isVertex()) {
    if (v_.major == 1 && d.type == R::Addr) {
      if (in.opcode != O::Mov || d.writeMask != 0x1) error(in, "vs_1_1 writes a0 only with mov a0.x");
    }
    if (d.type == R::RastOut && d.index == 0) oPosMask_ |= d.writeMask;
    if (v_.major >= 3 && d.type == R::Output && !d.relative && !declared_.count(key(R::Output, d.index)))
      error(in, "{} is written but not declared (dcl_position, dcl_texcoord …)", reg(d.type, d.index));
    if (v_.major >= 3 && d.type == R::Output && !d.relative) {
      auto it = declared_.find(key(R::Output, d.index));
      if (it != declared_.end() && (d.writeMask & ~it->second))
        error(in, "{}{} is written but only {}{} is declared", reg(d.type, d.index),
              maskName(d.writeMask & ~it->second), reg(d.type, d.index), maskName(it->second));
    }
    return;
  }
  if (d.type != R::ColorOut && d.type != R::DepthOut) return;
  const std::string n = reg(d.type, d.index);
  if (v_.major == 2) {
    const SrcParam& s = in.src[0];
    if (in.opcode != O::Mov) error(in, "{} is written only by mov in {}", n, name_);
    // oDepth takes one component, which a replicate swizzle (.x .y .z .w) may select
    // (fxc emits mov oDepth, r0.x); other swizzles stay rejected, as for oCn.
    else if (d.type == R::DepthOut && (s.mod != SrcMod::None ||
                                       (s.swizzle != kIdentity && !isReplicate(s.swizzle))))
      error(in, "mov to {} takes no source modifier and no swizzle but .x .y .z .w in {}", n,
            name_);
    else if (d.type == R::ColorOut && (s.swizzle != kIdentity || s.mod != SrcMod::None))
      error(in, "mov to {} takes no source swizzle or modifier in {}", n, name_);
    if (d.type == R::ColorOut && d.writeMask != 0xF) error(in, "{} is written with the full mask in {}", n, name_);
    if (d.resultMod & ResultSaturate) error(in, "{} cannot be written with _sat in {}", n, name_);
    if (inFlow || in.predicated) error(in, "{} cannot be written inside flow control or predicated in {}", n, name_);
    if (d.type == R::ColorOut) {
      if (!colorOutWritten_.insert(d.index).second) error(in, "{} is written more than once", n);
    } else {
      if (depthWritten_) error(in, "oDepth is written more than once");
      depthWritten_ = true;
    }
  } else {
    if (dynamicFlow || in.predicated)
      error(in, "{} cannot be written inside dynamic flow control or predicated", n);
    // ps_3_0 writes outputs with any instruction; a mov to oDepth still selects one
    // component, so its swizzle is a replicate (or none, which reads .x).
    const uint8_t sw = in.src[0].swizzle;
    if (d.type == R::DepthOut && in.opcode == O::Mov && in.srcCount > 0 && sw != kIdentity &&
        !isReplicate(sw))
      error(in, "mov to {} takes no swizzle but .x .y .z .w in {}", n, name_);
    if (d.type == R::ColorOut) colorOutWritten_.insert(d.index);
    else depthWritten_ = true;
  }
}

// ---- flow control ----------------------------------------------------------------

void Validator::checkFlow(const Instruction& in) {
  const FlowLimits& F = R_.flow;
  const bool isX = v_.major == 2 && v_.minor == 1;
  int loopLimit = F.loopDepth, dynLimit = F.dynamicDepth;
  if (isX) {
    loopLimit = std::clamp(caps_.staticFlowControlDepth, 1, 4);
    dynLimit = std::clamp(caps_.dynamicFlowControlDepth, 0, 24);
  }
  auto depth = [&](auto pred) { return int(std::count_if(blocks_.begin(), blocks_.end(), pred)); };
  auto countStatic = [&]() {
    if (F.staticFlowCount && ++staticFlowCount_ == F.staticFlowCount + 1)
      error(in, "{} allows {} static flow-control instructions (if b#, else, rep, loop, call, callnz b#), this shader has more",
            name_, F.staticFlowCount);
  };
  auto operand = [&](int s) -> const SrcParam* { return s < in.srcCount ? &in.src[s] : nullptr; };
  const Opcode o = in.opcode;

  if (mainEnded_ && o != O::Label && !inSubroutine_) {
    error(in, "{} follows the ret that ends the main program; subroutines start with label", op(in));
  }

  switch (o) {
    case O::If: case O::IfC: {
      bool dynamic = o == O::IfC;
      if (o == O::If) {
        const SrcParam* c = operand(0);
        if (!c || (c->type != R::ConstBool && c->type != R::Predicate))
          error(in, "if takes a b# or p0 operand");
        else if (c->type == R::Predicate) {
          dynamic = true;
          if (!R_.predication) error(in, "if p0 is not available in {}", name_);
          else if (!written_[key(R::Predicate, 0)]) error(in, "p0 is read before it is written (setp)");
        }
      }
      if (!dynamic) countStatic();
      blocks_.push_back({o, dynamic, false, in.pos});
      if (dynamic) {
        int dd = depth([](const Block& b) { return b.dynamic; });
        if (dd > dynLimit)
          error(in, "{} allows dynamic flow-control nesting depth {}, this {} is at depth {}", name_, dynLimit, op(in), dd);
      } else {
        int sd = depth([](const Block& b) { return (b.opcode == O::If) && !b.dynamic; });
        if (F.staticIfDepth && sd > F.staticIfDepth)
          error(in, "{} allows if nesting depth {}, this if is at depth {}", name_, F.staticIfDepth, sd);
      }
      break;
    }
    case O::Else:
      if (blocks_.empty() || (blocks_.back().opcode != O::If && blocks_.back().opcode != O::IfC))
        error(in, "else without if");
      else if (blocks_.back().hasElse)
        error(in, "if has a second else");
      else {
        blocks_.back().hasElse = true;
        if (!blocks_.back().dynamic) countStatic();
      }
      break;
    case O::EndIf:
      if (blocks_.empty() || (blocks_.back().opcode != O::If && blocks_.back().opcode != O::IfC))
        error(in, "endif without if{}", blocks_.empty() ? "" : fmt::format(" (the open block is {})", blockName(blocks_.back().opcode)));
      else blocks_.pop_back();
      break;
    case O::Rep: case O::Loop: {
      if (o == O::Rep) {
        const SrcParam* c = operand(0);
        if (!c || c->type != R::ConstInt) error(in, "rep takes an integer constant (rep i#)");
      } else {
        const SrcParam* a = operand(0);
        const SrcParam* c = operand(1);
        if (!a || a->type != R::Loop || !c || c->type != R::ConstInt)
          error(in, "loop takes aL and an integer constant (loop aL, i#)");
      }
      countStatic();
      blocks_.push_back({o, false, false, in.pos});
      int ld = depth([](const Block& b) { return b.opcode == O::Rep || b.opcode == O::Loop; });
      if (ld > loopLimit)
        error(in, "{} allows rep/loop nesting depth {}, this {} is at depth {}", name_, loopLimit, op(in), ld);
      break;
    }
    case O::EndRep: case O::EndLoop: {
      Opcode open = o == O::EndRep ? O::Rep : O::Loop;
      if (blocks_.empty() || blocks_.back().opcode != open)
        error(in, "{} without {}{}", op(in), open == O::Rep ? "rep" : "loop",
              blocks_.empty() ? "" : fmt::format(" (the open block is {})", blockName(blocks_.back().opcode)));
      else blocks_.pop_back();
      break;
    }
    case O::Break: case O::BreakC: case O::BreakP: {
      bool inLoop = std::any_of(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.opcode == O::Rep || b.opcode == O::Loop; });
      if (!inLoop) error(in, "{} outside a rep or loop block", op(in));
      if (o == O::BreakP) {
        const SrcParam* p = operand(0);
        if (!p || p->type != R::Predicate) error(in, "breakp takes p0");
        else if (!written_[key(R::Predicate, 0)]) error(in, "p0 is read before it is written (setp)");
      }
      break;
    }
    case O::Call: case O::CallNZ: {
      const SrcParam* l = operand(0);
      if (!l || l->type != R::Label) {
        error(in, "{} takes a label (l#)", op(in));
        break;
      }
      if (o == O::Call) countStatic();
      if (o == O::CallNZ) {
        const SrcParam* c = operand(1);
        if (!c || (c->type != R::ConstBool && c->type != R::Predicate)) error(in, "callnz takes a b# or p0 condition");
        else if (c->type == R::ConstBool) countStatic();
        else if (!written_[key(R::Predicate, 0)]) error(in, "p0 is read before it is written (setp)");
      }
      calls_.push_back({inSubroutine_ ? currentLabel_ : -1, {int(l->index), in.pos}});
      // What the subroutines write counts as written after a call.
      for (auto& [k, m] : subWritten_) written_[k] |= m;
      break;
    }
    case O::Ret:
      if (!blocks_.empty())
        error(in, "ret inside an open {} block", blockName(blocks_.back().opcode));
      if (inSubroutine_) inSubroutine_ = false;
      else mainEnded_ = true;
      break;
    case O::Label: {
      const SrcParam* l = operand(0);
      if (!l || l->type != R::Label) {
        error(in, "label takes l#");
        break;
      }
      if (!lastWasRet_) error(in, "label l{} must directly follow a ret", l->index);
      if (!blocks_.empty()) error(in, "label inside an open block");
      if (!labels_.emplace(int(l->index), in.pos).second) error(in, "label l{} is defined twice", l->index);
      inSubroutine_ = true;
      mainEnded_ = true;
      currentLabel_ = int(l->index);
      break;
    }
    default:
      break;
  }
}

// ---- slots -----------------------------------------------------------------------

void Validator::countSlots(const Instruction& in, const OpcodeRule& rule) {
  Cost c = instructionCost(R_, in, samplers_);
  (void)rule;
  const SlotLimits& L = R_.slots;
  if (v_.ps1x()) {
    if (L.perPhase) {
      phaseTexture_ += c.texture;
      phaseArithmetic_ += c.arithmetic;
      if (phaseTexture_ > L.texture && !reportedPhaseTex_) {
        reportedPhaseTex_ = true;
        error(in, "ps_1_4 allows {} texture instructions per phase, phase {} has {}", L.texture, phase_, phaseTexture_);
      }
      if (phaseArithmetic_ > L.arithmetic && !reportedPhaseArith_) {
        reportedPhaseArith_ = true;
        error(in, "ps_1_4 allows {} arithmetic instructions per phase, phase {} has {}", L.arithmetic, phase_,
              phaseArithmetic_);
      }
    }
    texture_ += c.texture;
    arithmetic_ += c.arithmetic;
    return;
  }
  texture_ += c.texture;
  arithmetic_ += c.arithmetic;
  total_ += c.texture + c.arithmetic + c.flow;
}

void Validator::finish() {
  SourcePos end;
  for (const Instruction& in : sh_.instructions)
    if (in.pos.line) end = in.pos;
  const SlotLimits& L = R_.slots;

  // Slot limits (the count is reported with the position of the whole shader's end).
  if (v_.ps1x() && !L.perPhase) {
    if (texture_ > L.texture)
      errorAt(end, "{} allows {} texture instructions, this shader has {}", name_, L.texture, texture_);
    if (arithmetic_ > L.arithmetic)
      errorAt(end, "{} allows {} arithmetic instructions, this shader has {}", name_, L.arithmetic, arithmetic_);
  } else if (!v_.ps1x()) {
    int totalLimit = L.totalFromCaps ? std::clamp(caps_.ps2xInstructionSlots, 96, 512) : L.total;
    if (totalLimit && total_ > totalLimit)
      errorAt(end, "{} allows {} instruction slots, this shader uses {}", name_, totalLimit, total_);
    if (L.arithmetic && arithmetic_ > L.arithmetic)
      errorAt(end, "{} allows {} arithmetic instruction slots, this shader uses {}", name_, L.arithmetic, arithmetic_);
    bool texLimit = L.texture && !(v_.minor == 1 && caps_.ps2xNoTexInstructionLimit);
    if (texLimit && texture_ > L.texture)
      errorAt(end, "{} allows {} texture instruction slots, this shader uses {}", name_, L.texture, texture_);
  }

  if (pending_.active) errorAt(pending_.pos, "{}", pending_.what);

  // Outputs.
  if (v_.ps1x() && !r0Written_)
    errorAt(end, "{} never writes r0, the pixel color", name_);
  if (v_.isPixel() && v_.major == 2) {
    if (!colorOutWritten_.count(0)) errorAt(end, "{} must write oC0", name_);
    for (unsigned i : colorOutWritten_)
      for (unsigned k = 0; k < i; ++k)
        if (!colorOutWritten_.count(k)) {
          errorAt(end, "oC{} is written but oC{} is not; render targets are written in order from oC0", i, k);
          break;
        }
  }
  if (v_.isVertex() && v_.major < 3 && oPosMask_ != 0xF)
    errorAt(end, "a {} shader must write all four components of oPos{}", name_,
            oPosMask_ ? fmt::format(" ({} is never written)", maskName(uint8_t(~oPosMask_ & 0xF))) : "");
  if (v_.isVertex() && v_.major >= 3) {
    bool position = false;
    for (const Instruction& in : sh_.instructions)
      if (in.opcode == O::Dcl && in.hasDst && in.dst.type == R::Output && in.usage == DeclUsage::Position &&
          in.usageIndex == 0)
        position = true;
    if (!position) errorAt(end, "vs_3_0 must declare a position output (dcl_position o#)");
  }

  // Flow control.
  for (const Block& b : blocks_)
    errorAt(b.pos, "{} is never closed with {}", blockName(b.opcode),
            b.opcode == O::Rep ? "endrep" : b.opcode == O::Loop ? "endloop" : "endif");
  for (auto& [caller, callee] : calls_)
    if (!labels_.count(callee.first)) errorAt(callee.second, "call to l{}: the shader has no label l{}", callee.first, callee.first);
  if (inSubroutine_) errorAt(end, "subroutine l{} does not end with ret", currentLabel_);

  // Call nesting: main's calls are depth 1.
  if (!calls_.empty()) {
    std::map<int, std::vector<int>> graph;
    for (auto& [caller, callee] : calls_) graph[caller].push_back(callee.first);
    int limit = R_.flow.callDepth;
    if (v_.major == 2 && v_.minor == 1) limit = std::clamp(caps_.staticFlowControlDepth, 1, 4);
    std::map<int, int> depthOf;  // -1 while being computed (recursion)
    bool recursive = false;
    std::function<int(int)> depthFrom = [&](int node) -> int {
      auto it = depthOf.find(node);
      if (it != depthOf.end()) {
        if (it->second < 0) recursive = true;
        return std::max(it->second, 0);
      }
      depthOf[node] = -1;
      int d = 0;
      for (int next : graph[node]) d = std::max(d, 1 + depthFrom(next));
      depthOf[node] = d;
      return d;
    };
    int worst = depthFrom(-1);
    if (recursive) errorAt(end, "subroutines call themselves (recursion is not allowed)");
    else if (worst > limit)
      errorAt(end, "{} allows call nesting depth {}, this shader nests calls {} deep", name_, limit, worst);
  }
}

}  // namespace

SlotCount countSlots(const Shader& shader) {
  SlotCount sc;
  const VersionRules* rules = findVersionRules(shader.version);
  auto samplers = samplerTypes(shader);
  for (const Instruction& in : shader.instructions) {
    if (isFreeOp(in.opcode)) continue;
    if (!rules) {
      ++sc.arithmetic;
      continue;
    }
    Cost c = instructionCost(*rules, in, samplers);
    sc.texture += c.texture;
    sc.arithmetic += c.arithmetic;
    sc.flowControl += c.flow;
  }
  return sc;
}

std::vector<Diagnostic> validate(const Shader& shader, const ValidationCaps& caps) {
  const VersionRules* rules = findVersionRules(shader.version);
  if (!rules) {
    SourcePos pos;
    return {{pos, fmt::format("{} is not a supported shader version", versionName(shader.version))}};
  }
  return Validator(shader, *rules, caps).run();
}

std::string checkDeviceVersion(Version shader, uint32_t deviceVersion, std::string_view deviceName) {
  const bool vs = shader.isVertex();
  const char* field = vs ? "VertexShaderVersion" : "PixelShaderVersion";
  int devMajor = (deviceVersion >> 8) & 0xFF, devMinor = deviceVersion & 0xFF;
  std::string has = (devMajor == 0 && devMinor == 0) ? "none" : fmt::format("{}.{}", devMajor, devMinor);
  // 2_x is minor 1; vs_1_0/ps_1_0 run wherever 1_1 does.
  int major = shader.major, minor = shader.minor == 0xFF ? 0 : shader.minor;
  if (major == 1 && minor == 0) minor = 1;
  bool covered = devMajor > major || (devMajor == major && devMinor >= minor);
  if (covered) return {};
  std::string need = (major == 2 && minor == 1) ? std::string("above 2.0") : fmt::format("{}.{}", major, minor);
  return fmt::format("{} needs {} {}, {} has {}", versionName(shader), field, need, deviceName, has);
}

void requireValid(const Shader& shader, std::string_view fileName, const ValidationCaps& caps) {
  auto diags = validate(shader, caps);
  if (diags.empty()) return;
  const Diagnostic& d = diags.front();
  throw Error(SourceLocation{std::string(fileName), d.pos.line, d.pos.column}, d.message);
}

}  // namespace refx::shader
