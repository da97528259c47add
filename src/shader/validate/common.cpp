// Names for messages, opcode facts and instruction costs shared by the checks, and
// the Context's helpers.
#include <algorithm>
#include <cctype>

#include "refx/shader/opcode_table.h"
#include "shader/validate/check.h"

namespace refx::shader::checks {

using O = Opcode;
using R = RegType;

// ---- names for messages ----------------------------------------------------------

// Instruction names as the version writes them (tex / texld / texldp, texcoord /
// texcrd) come from the opcode table; the comparison forms keep the names the docs use
// in prose (if_comp, break_comp), and texcoord stays texcrd from ps_1_4 on, as the
// validator's messages have always named them.
std::string opName(const Instruction& in, Version v) {
  if (in.opcode == O::IfC) return "if_comp";
  if (in.opcode == O::BreakC) return "break_comp";
  if (in.opcode == O::TexCoord && v.atLeast(1, 4)) return "texcrd";
  std::string_view name = mnemonicIn(in.opcode, in.control, v);
  if (name.empty()) return fmt::format("opcode {}", unsigned(in.opcode));
  return std::string(name);
}

// The register namer of the version rules (one spelling per register file).
std::string regName(RegType t, unsigned index, Version v) { return registerName(t, index, v); }

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

// Opcode facts from the opcode table (opcode_table.h).
namespace {
uint16_t properties(Opcode op) {
  const OpcodeInfo* info = findOpcode(op);
  return info ? info->properties : 0;
}
}  // namespace

bool isReservedOpcode(Opcode op) {
  for (const OpcodeInfo& info : allOpcodes())
    if (info.opcode == op) return info.has(OpReserved);
  return false;
}
bool isMatrixTex(Opcode op) { return properties(op) & OpTextureMatrix; }
bool isFlowOp(Opcode op) { return properties(op) & OpFlowControl; }
bool isFreeOp(Opcode op) { return op == O::Comment || (properties(op) & OpNoSlot); }
bool isScalarOp(Opcode op) { return properties(op) & OpReplicateSwizzle; }
int matrixRows(Opcode op) {
  const OpcodeInfo* info = findOpcode(op);
  return info ? info->matrixRows : 0;
}
uint8_t matrixRowMask(Opcode op) {
  const OpcodeInfo* info = findOpcode(op);
  return info && info->matrixColumns == 4 ? 0xF : 0x7;
}

// ---- instruction costs -----------------------------------------------------------

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


bool isDefOp(Opcode op) { return op == O::Def || op == O::DefI || op == O::DefB; }

// ---- the context ------------------------------------------------------------------

Context::Context(const Shader& s, const VersionRules& r, const ValidationCaps& c, DiagnosticSink& out,
                 std::string f)
    : shader(s), rules(r), caps(c), v(s.version), name(r.name), sink(out), file(std::move(f)) {
  for (const Instruction& in : s.instructions)
    if (in.pos.line) end = in.pos;
  samplers = samplerTypes(s);
  bool inSub = false;
  for (const Instruction& in : s.instructions) {
    if (in.opcode == O::Dcl && in.hasDst && in.dst.type == R::Input) anyInputDcl = true;
    if (in.opcode == O::Phase) hasPhase = true;
    if (in.opcode == O::Label) inSub = true;
    if (inSub && in.hasDst && in.opcode != O::Dcl && in.opcode != O::Def)
      subWritten[registerKey(in.dst.type, in.dst.index)] |= writtenMask(in);
    if (in.opcode == O::Ret && inSub) inSub = false;
  }
  if (hasPhase) phase = 1;
}

std::string Context::op(const Instruction& in) const { return opName(in, v); }
std::string Context::reg(RegType t, unsigned i) const { return regName(t, i, v); }

int Context::registerCount(const RegisterRule& r) const {
  switch (r.fromCaps) {
    case CountFromCaps::VertexShaderConst:
      return caps.maxVertexShaderConst > 0 ? caps.maxVertexShaderConst : r.count;
    case CountFromCaps::Vs2xTemps: return std::clamp(caps.vs2xTemps, 12, 32);
    case CountFromCaps::Ps2xTemps: return std::clamp(caps.ps2xTemps, 12, 32);
    default: return r.count;
  }
}

bool Context::inLoop() const {
  return std::any_of(blocks.begin(), blocks.end(),
                     [](const Block& b) { return b.opcode == O::Rep || b.opcode == O::Loop; });
}
bool Context::inDynamicFlow() const {
  return std::any_of(blocks.begin(), blocks.end(), [](const Block& b) { return b.dynamic; });
}

// Components of source `s`'s register that the instruction reads.
uint8_t Context::readMask(const Instruction& in, int s) const {
  const SrcParam& p = in.src[s];
  uint8_t dstMask = in.hasDst ? in.dst.writeMask : 0xF;
  uint8_t used = dstMask;  // per-component operations by default
  // Scalar operations read one component; matrix macros one row's columns.
  if (isScalarOp(in.opcode)) return uint8_t(1 << swizzleComponent(p.swizzle, 0));
  if (matrixRows(in.opcode)) used = matrixRowMask(in.opcode);
  switch (in.opcode) {
    case O::Dp3: case O::Crs: used = 0x7; break;
    case O::Dp4: used = 0xF; break;
    case O::IfC: case O::BreakC: case O::If: case O::CallNZ: case O::BreakP:
      used = 0x1;
      break;
    case O::SinCos: used = s == 0 ? 0x1 : 0xF; break;
    case O::Dp2Add: used = s == 2 ? 0x1 : 0x3; break;
    case O::Lit: used = 0xB; break;
    case O::Dst: used = s == 0 ? 0x6 : 0xA; break;
    case O::Nrm: used = 0x7 | (dstMask & 0x8); break;
    case O::Bem: used = 0x3; break;
    case O::Sgn: used = s == 0 ? dstMask : 0; break;
    case O::Tex: case O::TexLdl: case O::TexLdd:
      if (v.major < 2) {
        used = 0x7;  // ps_1_4 texld r, r(k)[.xyz|.xyw]
      } else if (s == 0) {
        TextureType t = TextureType::Tex2D;
        if (in.srcCount > 1) {
          auto it = samplers.find(in.src[1].index);
          if (it != samplers.end()) t = it->second;
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
    if (used & (1 << c)) m |= uint8_t(1 << swizzleComponent(p.swizzle, c));
  return m;
}

// Components an instruction writes into its destination register.
uint8_t Context::writtenMask(const Instruction& in) const {
  if (!in.hasDst) return 0;
  if (v.ps1x() && !v.atLeast(1, 4)) {
    const OpcodeRule* r = findOpcodeRule(rules, in.opcode);
    if (r && r->textureSlots > 0) {
      if (in.opcode == O::TexKill || in.opcode == O::TexM3x2Pad || in.opcode == O::TexM3x3Pad ||
          in.opcode == O::TexM3x2Depth)
        return 0;
      return 0xF;
    }
  }
  if (in.opcode == O::TexKill) return 0;
  if (in.opcode == O::Tex && v.ps1x()) return 0xF;  // ps_1_4 texld
  switch (in.opcode) {
    case O::M4x3: case O::M3x3: return in.dst.writeMask & 0x7;
    case O::M3x2: return in.dst.writeMask & 0x3;
    default: return in.dst.writeMask;
  }
}

}  // namespace refx::shader::checks
