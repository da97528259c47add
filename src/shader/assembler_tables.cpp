#include "shader/assembler_tables.h"

#include <algorithm>
#include <array>
#include <vector>

#include <fmt/format.h>

namespace refx::shader::asmtables {
namespace {

using K = MnemonicKind;
using F = FormRule;
using O = Opcode;

// Every mnemonic of vs_1_1 … ps_3_0 (D3D9 and DirectX 8 spellings).
const MnemonicInfo kMnemonics[] = {
    {"nop", O::Nop, 0, K::Plain, O::Nop, F::Any},
    {"mov", O::Mov, 0, K::Plain, O::Mov, F::Any},
    {"add", O::Add, 0, K::Plain, O::Add, F::Any},
    {"sub", O::Sub, 0, K::Plain, O::Sub, F::Any},
    {"mad", O::Mad, 0, K::Plain, O::Mad, F::Any},
    {"mul", O::Mul, 0, K::Plain, O::Mul, F::Any},
    {"rcp", O::Rcp, 0, K::Plain, O::Rcp, F::Any},
    {"rsq", O::Rsq, 0, K::Plain, O::Rsq, F::Any},
    {"dp3", O::Dp3, 0, K::Plain, O::Dp3, F::Any},
    {"dp4", O::Dp4, 0, K::Plain, O::Dp4, F::Any},
    {"min", O::Min, 0, K::Plain, O::Min, F::Any},
    {"max", O::Max, 0, K::Plain, O::Max, F::Any},
    {"slt", O::Slt, 0, K::Plain, O::Slt, F::Any},
    {"sge", O::Sge, 0, K::Plain, O::Sge, F::Any},
    {"exp", O::Exp, 0, K::Plain, O::Exp, F::Any},
    {"log", O::Log, 0, K::Plain, O::Log, F::Any},
    {"lit", O::Lit, 0, K::Plain, O::Lit, F::Any},
    {"dst", O::Dst, 0, K::Plain, O::Dst, F::Any},
    {"lrp", O::Lrp, 0, K::Plain, O::Lrp, F::Any},
    {"frc", O::Frc, 0, K::Plain, O::Frc, F::Any},
    {"m4x4", O::M4x4, 0, K::Plain, O::M4x4, F::Any},
    {"m4x3", O::M4x3, 0, K::Plain, O::M4x3, F::Any},
    {"m3x4", O::M3x4, 0, K::Plain, O::M3x4, F::Any},
    {"m3x3", O::M3x3, 0, K::Plain, O::M3x3, F::Any},
    {"m3x2", O::M3x2, 0, K::Plain, O::M3x2, F::Any},
    {"call", O::Call, 0, K::Plain, O::Call, F::Any},
    {"callnz", O::CallNZ, 0, K::Plain, O::CallNZ, F::Any},
    {"loop", O::Loop, 0, K::Plain, O::Loop, F::Any},
    {"ret", O::Ret, 0, K::Plain, O::Ret, F::Any},
    {"endloop", O::EndLoop, 0, K::Plain, O::EndLoop, F::Any},
    {"label", O::Label, 0, K::Plain, O::Label, F::Any},
    {"dcl", O::Dcl, 0, K::Dcl, O::Dcl, F::Any},
    {"pow", O::Pow, 0, K::Plain, O::Pow, F::Any},
    {"crs", O::Crs, 0, K::Plain, O::Crs, F::Any},
    {"sgn", O::Sgn, 0, K::Plain, O::Sgn, F::Any},
    {"abs", O::Abs, 0, K::Plain, O::Abs, F::Any},
    {"nrm", O::Nrm, 0, K::Plain, O::Nrm, F::Any},
    {"sincos", O::SinCos, 0, K::Plain, O::SinCos, F::Any},
    {"rep", O::Rep, 0, K::Plain, O::Rep, F::Any},
    {"endrep", O::EndRep, 0, K::Plain, O::EndRep, F::Any},
    {"if", O::If, 0, K::Compare, O::IfC, F::Any},
    {"ifc", O::IfC, 0, K::Compare, O::IfC, F::Any},
    {"else", O::Else, 0, K::Plain, O::Else, F::Any},
    {"endif", O::EndIf, 0, K::Plain, O::EndIf, F::Any},
    {"break", O::Break, 0, K::Compare, O::BreakC, F::Any},
    {"breakc", O::BreakC, 0, K::Compare, O::BreakC, F::Any},
    {"mova", O::MovA, 0, K::Plain, O::MovA, F::Any},
    {"defb", O::DefB, 0, K::Def, O::DefB, F::Any},
    {"defi", O::DefI, 0, K::Def, O::DefI, F::Any},
    {"texcoord", O::TexCoord, 0, K::Plain, O::TexCoord, F::Ps1Tex},
    {"texcrd", O::TexCoord, 0, K::Plain, O::TexCoord, F::Ps14Only},
    {"texkill", O::TexKill, 0, K::Plain, O::TexKill, F::Any},
    {"tex", O::Tex, 0, K::Plain, O::Tex, F::Ps1Tex},
    {"texld", O::Tex, 0, K::Plain, O::Tex, F::Ps14Up},
    {"texldp", O::Tex, 1, K::Plain, O::Tex, F::Sm2Up},  // D3DSI_TEXLD_PROJECT
    {"texldb", O::Tex, 2, K::Plain, O::Tex, F::Sm2Up},  // D3DSI_TEXLD_BIAS
    {"texbem", O::TexBem, 0, K::Plain, O::TexBem, F::Any},
    {"texbeml", O::TexBemL, 0, K::Plain, O::TexBemL, F::Any},
    {"texreg2ar", O::TexReg2AR, 0, K::Plain, O::TexReg2AR, F::Any},
    {"texreg2gb", O::TexReg2GB, 0, K::Plain, O::TexReg2GB, F::Any},
    {"texm3x2pad", O::TexM3x2Pad, 0, K::Plain, O::TexM3x2Pad, F::Any},
    {"texm3x2tex", O::TexM3x2Tex, 0, K::Plain, O::TexM3x2Tex, F::Any},
    {"texm3x3pad", O::TexM3x3Pad, 0, K::Plain, O::TexM3x3Pad, F::Any},
    {"texm3x3tex", O::TexM3x3Tex, 0, K::Plain, O::TexM3x3Tex, F::Any},
    {"texm3x3diff", O::TexM3x3Diff, 0, K::Plain, O::TexM3x3Diff, F::Reserved},
    {"texm3x3spec", O::TexM3x3Spec, 0, K::Plain, O::TexM3x3Spec, F::Any},
    {"texm3x3vspec", O::TexM3x3VSpec, 0, K::Plain, O::TexM3x3VSpec, F::Any},
    {"expp", O::ExpP, 0, K::Plain, O::ExpP, F::Any},
    {"logp", O::LogP, 0, K::Plain, O::LogP, F::Any},
    {"cnd", O::Cnd, 0, K::Plain, O::Cnd, F::Any},
    {"def", O::Def, 0, K::Def, O::Def, F::Any},
    {"texreg2rgb", O::TexReg2RGB, 0, K::Plain, O::TexReg2RGB, F::Any},
    {"texdp3tex", O::TexDP3Tex, 0, K::Plain, O::TexDP3Tex, F::Any},
    {"texm3x2depth", O::TexM3x2Depth, 0, K::Plain, O::TexM3x2Depth, F::Any},
    {"texdp3", O::TexDP3, 0, K::Plain, O::TexDP3, F::Any},
    {"texm3x3", O::TexM3x3, 0, K::Plain, O::TexM3x3, F::Any},
    {"texdepth", O::TexDepth, 0, K::Plain, O::TexDepth, F::Any},
    {"cmp", O::Cmp, 0, K::Plain, O::Cmp, F::Any},
    {"bem", O::Bem, 0, K::Plain, O::Bem, F::Any},
    {"dp2add", O::Dp2Add, 0, K::Plain, O::Dp2Add, F::Any},
    {"dsx", O::Dsx, 0, K::Plain, O::Dsx, F::Any},
    {"dsy", O::Dsy, 0, K::Plain, O::Dsy, F::Any},
    {"texldd", O::TexLdd, 0, K::Plain, O::TexLdd, F::Any},
    {"setp", O::SetP, 0, K::Compare, O::SetP, F::Any},
    {"texldl", O::TexLdl, 0, K::Plain, O::TexLdl, F::Any},
    {"breakp", O::BreakP, 0, K::Plain, O::BreakP, F::Any},
    {"phase", O::Phase, 0, K::Plain, O::Phase, F::Any},
};

constexpr uint32_t kMax = 2047;  // 11-bit register number
const RegisterName kVertexRegisters[] = {
    {"r", RegType::Temp, true, 0, kMax},        {"v", RegType::Input, true, 0, kMax},
    {"c", RegType::Const, true, 0, 8191},       {"a", RegType::Addr, true, 0, 0},
    {"al", RegType::Loop, false, 0, 0},         {"i", RegType::ConstInt, true, 0, kMax},
    {"b", RegType::ConstBool, true, 0, kMax},   {"s", RegType::Sampler, true, 0, kMax},
    {"l", RegType::Label, true, 0, kMax},       {"p", RegType::Predicate, true, 0, 0},
};
const RegisterName kVertexOutputsSm1Sm2[] = {
    {"opos", RegType::RastOut, false, 0, 0},    {"ofog", RegType::RastOut, false, 1, 1},
    {"opts", RegType::RastOut, false, 2, 2},    {"od", RegType::AttrOut, true, 0, kMax},
    {"ot", RegType::TexCrdOut, true, 0, kMax},
};
const RegisterName kVertexOutputsSm3[] = {
    {"o", RegType::Output, true, 0, kMax},
};
const RegisterName kPixelRegisters[] = {
    {"r", RegType::Temp, true, 0, kMax},          {"v", RegType::Input, true, 0, kMax},
    {"c", RegType::Const, true, 0, 8191},         {"s", RegType::Sampler, true, 0, kMax},
    {"i", RegType::ConstInt, true, 0, kMax},      {"b", RegType::ConstBool, true, 0, kMax},
    {"l", RegType::Label, true, 0, kMax},         {"p", RegType::Predicate, true, 0, 0},
    {"al", RegType::Loop, false, 0, 0},           {"oc", RegType::ColorOut, true, 0, kMax},
    {"odepth", RegType::DepthOut, false, 0, 0},   {"vpos", RegType::MiscType, false, 0, 0},
    {"vface", RegType::MiscType, false, 1, 1},
};
const RegisterName kPixelTexture[] = {
    {"t", RegType::Texture, true, 0, kMax},
};

template <size_t N>
const RegisterName* findIn(const RegisterName (&table)[N], std::string_view letters) {
  for (const RegisterName& r : table)
    if (letters == r.letters) return &r;
  return nullptr;
}

int editDistance(std::string_view a, std::string_view b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = int(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diag = row[0];
    row[0] = int(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      int up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

const MnemonicInfo* findMnemonic(std::string_view name) {
  for (const MnemonicInfo& m : kMnemonics)
    if (name == m.name) return &m;
  return nullptr;
}

std::string nearestMnemonic(std::string_view name) {
  if (name.size() > 32) return {};
  int best = 3;
  const char* found = nullptr;
  for (const MnemonicInfo& m : kMnemonics) {
    int d = editDistance(name, m.name);
    if (d < best) best = d, found = m.name;
  }
  return found ? found : "";
}

std::string opcodeMnemonic(Opcode op) {
  for (const MnemonicInfo& m : kMnemonics)
    if (m.opcode == op) return m.name;
  return "?";
}

std::optional<Version> parseVersionName(std::string_view text) {
  std::vector<std::string_view> parts;
  size_t a = 0;
  for (;;) {
    size_t b = text.find_first_of("._", a);
    parts.push_back(text.substr(a, b == std::string_view::npos ? std::string_view::npos : b - a));
    if (b == std::string_view::npos) break;
    a = b + 1;
  }
  if (parts.size() != 3) return std::nullopt;
  Version v;
  if (parts[0] == "vs")
    v.type = ShaderType::Vertex;
  else if (parts[0] == "ps")
    v.type = ShaderType::Pixel;
  else
    return std::nullopt;
  const std::string_view ma = parts[1], mi = parts[2];
  if (ma.size() != 1 || ma[0] < '1' || ma[0] > '3') return std::nullopt;
  v.major = uint8_t(ma[0] - '0');
  if (mi == "sw") {
    if (v.major < 2) return std::nullopt;
    v.minor = 0xFF;
    return v;
  }
  if (mi == "x" || mi == "a" || (mi == "b" && v.isPixel())) {  // 2_x; ps_2_a/ps_2_b/vs_2_a emit 2_x
    if (v.major != 2) return std::nullopt;
    v.minor = 1;
    return v;
  }
  if (mi.size() != 1 || mi[0] < '0' || mi[0] > '9') return std::nullopt;
  v.minor = uint8_t(mi[0] - '0');
  if (v.major == 1) {
    if (v.minor > (v.isPixel() ? 4 : 1)) return std::nullopt;  // vs_1_0/1_1, ps_1_0…1_4
  } else if (v.minor != 0) {
    return std::nullopt;
  }
  return v;
}

Comparison findComparison(std::string_view s) {
  static constexpr std::array<std::string_view, 7> names = {"", "gt", "eq", "ge", "lt", "ne", "le"};
  for (size_t i = 1; i < names.size(); ++i)
    if (s == names[i]) return Comparison(i);
  return Comparison::None;
}

std::optional<int8_t> findShift(std::string_view s) {
  struct E {
    std::string_view name;
    int8_t shift;
  };
  static constexpr E table[] = {{"x2", 1}, {"x4", 2}, {"x8", 3}, {"d2", -1}, {"d4", -2}, {"d8", -3}};
  for (const E& e : table)
    if (s == e.name) return e.shift;
  return std::nullopt;
}

std::optional<uint8_t> findResultModifier(std::string_view s) {
  if (s == "sat") return ResultSaturate;
  if (s == "pp") return ResultPartialPrecision;
  if (s == "centroid") return ResultCentroid;
  return std::nullopt;
}

std::optional<TextureType> findTextureType(std::string_view s) {
  if (s == "2d") return TextureType::Tex2D;
  if (s == "cube") return TextureType::Cube;
  if (s == "volume") return TextureType::Volume;
  return std::nullopt;
}

const char* textureTypeName(TextureType t) {
  switch (t) {
    case TextureType::Tex2D: return "2d";
    case TextureType::Cube: return "cube";
    case TextureType::Volume: return "volume";
    case TextureType::Tex1D: return "1d";
    default: return "unknown";
  }
}

std::optional<DeclUsage> findUsage(std::string_view s) {
  static constexpr std::array<std::string_view, 14> names = {
      "position", "blendweight", "blendindices", "normal", "psize", "texcoord", "tangent",
      "binormal", "tessfactor",  "positiont",    "color",  "fog",   "depth",    "sample"};
  for (size_t i = 0; i < names.size(); ++i)
    if (s == names[i]) return DeclUsage(i);
  return std::nullopt;
}

OperandForm operandForm(Opcode op, Version v) {
  // The encoder's table, so that what is parsed is exactly what gets encoded.
  const OperandCounts c = operandCounts(op, v);
  return {c.dst, c.src};
}

const RegisterName* findRegisterName(std::string_view letters, Version v) {
  if (v.isVertex()) {
    if (auto* r = findIn(kVertexRegisters, letters)) return r;
    return v.major >= 3 ? findIn(kVertexOutputsSm3, letters) : findIn(kVertexOutputsSm1Sm2, letters);
  }
  if (auto* r = findIn(kPixelRegisters, letters)) return r;
  return v.major < 3 ? findIn(kPixelTexture, letters) : nullptr;
}

std::string registerHelp(Version v) {
  std::string s = fmt::format("registers of {}: ", v.name());
  if (v.isVertex())
    s += v.major >= 3 ? "r#, v#, c#, a0, aL, b#, i#, p0, s#, o#" : "r#, v#, c#, a0, aL, b#, i#, p0, oPos, oFog, oPts, oD#, oT#";
  else
    s += v.major >= 3 ? "r#, v#, c#, s#, b#, i#, p0, aL, vPos, vFace, oC#, oDepth"
                      : "r#, v#, c#, t#, s#, b#, i#, p0, oC#, oDepth";
  return s;
}

std::string registerDisplayName(RegType type, uint32_t index, Version v) {
  struct D {
    RegType type;
    const char* name;
    bool indexed;
  };
  static constexpr D vs[] = {{RegType::Temp, "r", true},       {RegType::Input, "v", true},
                             {RegType::Const, "c", true},      {RegType::Addr, "a", true},
                             {RegType::AttrOut, "oD", true},   {RegType::TexCrdOut, "oT", true},
                             {RegType::ConstInt, "i", true},   {RegType::ConstBool, "b", true},
                             {RegType::Sampler, "s", true},    {RegType::Loop, "aL", false},
                             {RegType::Label, "l", true},      {RegType::Predicate, "p", true}};
  static constexpr D ps[] = {{RegType::Temp, "r", true},       {RegType::Input, "v", true},
                             {RegType::Const, "c", true},      {RegType::Texture, "t", true},
                             {RegType::ColorOut, "oC", true},  {RegType::DepthOut, "oDepth", false},
                             {RegType::ConstInt, "i", true},   {RegType::ConstBool, "b", true},
                             {RegType::Sampler, "s", true},    {RegType::Loop, "aL", false},
                             {RegType::Label, "l", true},      {RegType::Predicate, "p", true}};
  if (v.isVertex() && type == RegType::RastOut) return index == 0 ? "oPos" : index == 1 ? "oFog" : "oPts";
  if (v.isVertex() && v.major >= 3 && type == RegType::Output) return fmt::format("o{}", index);
  if (v.isPixel() && type == RegType::MiscType) return index == 0 ? "vPos" : "vFace";
  const D* begin = v.isVertex() ? std::begin(vs) : std::begin(ps);
  const D* end = v.isVertex() ? std::end(vs) : std::end(ps);
  for (const D* d = begin; d != end; ++d)
    if (d->type == type) return d->indexed ? fmt::format("{}{}", d->name, index) : std::string(d->name);
  return fmt::format("register type {}", int(type));
}

}  // namespace refx::shader::asmtables
