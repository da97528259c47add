#include "shader/assembler_tables.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <span>
#include <vector>

#include <fmt/format.h>

namespace refx::shader::asmtables {
namespace {

// The register files assembly names in each shader type, with the highest number each
// encodes (11 bits; c# reaches 8191 through CONST2..4). Their letters are the register
// namer's spelling (version_rules.h) in lower case.
struct AssembledFile {
  RegType type;
  uint32_t maxIndex;
};
constexpr uint32_t kMax = 2047;
constexpr AssembledFile kVertexFiles[] = {
    {RegType::Temp, kMax},     {RegType::Input, kMax},     {RegType::Const, 8191},  {RegType::Addr, 0},
    {RegType::Loop, 0},        {RegType::ConstInt, kMax},  {RegType::ConstBool, kMax}, {RegType::Sampler, kMax},
    {RegType::Label, kMax},    {RegType::Predicate, 0},
};
constexpr AssembledFile kVertexOutputsSm1Sm2[] = {
    {RegType::RastOut, 0}, {RegType::AttrOut, kMax}, {RegType::TexCrdOut, kMax}};
constexpr AssembledFile kVertexOutputsSm3[] = {{RegType::Output, kMax}};
constexpr AssembledFile kPixelFiles[] = {
    {RegType::Temp, kMax},     {RegType::Input, kMax},  {RegType::Const, 8191},    {RegType::Sampler, kMax},
    {RegType::ConstInt, kMax}, {RegType::ConstBool, kMax}, {RegType::Label, kMax}, {RegType::Predicate, 0},
    {RegType::Loop, 0},        {RegType::ColorOut, kMax}, {RegType::DepthOut, 0},  {RegType::MiscType, 0},
};
constexpr AssembledFile kPixelTexture[] = {{RegType::Texture, kMax}};

std::string lowerCase(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = char(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

// Numbered files by their prefix (r#, oT#); the others by each fixed name (oPos = RASTOUT 0).
std::vector<RegisterName> registerLetters(std::initializer_list<std::span<const AssembledFile>> groups, Version v) {
  std::vector<RegisterName> out;
  for (std::span<const AssembledFile> files : groups)
    for (const AssembledFile& f : files) {
      const RegisterNaming* n = findRegisterNaming(f.type, v);
      if (!n) continue;
      if (*n->prefix && !n->fixedNames[0]) {
        out.push_back({lowerCase(n->prefix), f.type, true, 0, f.maxIndex});
        continue;
      }
      for (uint32_t i = 0; i < n->fixedNames.size() && n->fixedNames[i]; ++i)
        out.push_back({lowerCase(n->fixedNames[i]), f.type, false, i, i});
    }
  return out;
}

const std::vector<RegisterName>& registerLettersOf(Version v) {
  static const std::vector<RegisterName> vs1 =
      registerLetters({kVertexFiles, kVertexOutputsSm1Sm2}, {ShaderType::Vertex, 1, 1});
  static const std::vector<RegisterName> vs3 =
      registerLetters({kVertexFiles, kVertexOutputsSm3}, {ShaderType::Vertex, 3, 0});
  static const std::vector<RegisterName> ps1 = registerLetters({kPixelFiles, kPixelTexture}, {ShaderType::Pixel, 2, 0});
  static const std::vector<RegisterName> ps3 = registerLetters({kPixelFiles}, {ShaderType::Pixel, 3, 0});
  if (v.isVertex()) return v.major >= 3 ? vs3 : vs1;
  return v.major >= 3 ? ps3 : ps1;
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

std::string nearestMnemonic(std::string_view name) {
  if (name.size() > 32) return {};
  int best = 3;
  const char* found = nullptr;
  for (const MnemonicInfo& m : allMnemonics()) {
    int d = editDistance(name, m.name);
    if (d < best) best = d, found = m.name;
  }
  return found ? found : "";
}

std::string opcodeMnemonic(Opcode op) {
  const std::string_view name = opcodeName(op);
  return name.empty() ? "?" : std::string(name);
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

// D3DSHADER_COMPARISON order: gt 1 … le 6.
constexpr std::array<std::string_view, 7> kComparisonNames = {"", "gt", "eq", "ge", "lt", "ne", "le"};

Comparison findComparison(std::string_view s) {
  for (size_t i = 1; i < kComparisonNames.size(); ++i)
    if (s == kComparisonNames[i]) return Comparison(i);
  return Comparison::None;
}

std::string_view comparisonName(Comparison c) {
  return size_t(c) < kComparisonNames.size() ? kComparisonNames[size_t(c)] : "";
}

struct ShiftSpelling {
  std::string_view name;
  int8_t shift;
};
constexpr ShiftSpelling kShifts[] = {{"x2", 1}, {"x4", 2}, {"x8", 3}, {"d2", -1}, {"d4", -2}, {"d8", -3}};

std::optional<int8_t> findShift(std::string_view s) {
  for (const ShiftSpelling& e : kShifts)
    if (s == e.name) return e.shift;
  return std::nullopt;
}

std::string_view shiftName(int8_t shift) {
  for (const ShiftSpelling& e : kShifts)
    if (e.shift == shift) return e.name;
  return "";
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

// D3DDECLUSAGE order.
constexpr std::array<std::string_view, 14> kUsageNames = {
    "position", "blendweight", "blendindices", "normal", "psize", "texcoord", "tangent",
    "binormal", "tessfactor",  "positiont",    "color",  "fog",   "depth",    "sample"};

std::optional<DeclUsage> findUsage(std::string_view s) {
  for (size_t i = 0; i < kUsageNames.size(); ++i)
    if (s == kUsageNames[i]) return DeclUsage(i);
  return std::nullopt;
}

std::string_view usageName(DeclUsage u) { return size_t(u) < kUsageNames.size() ? kUsageNames[size_t(u)] : ""; }

OperandForm operandForm(Opcode op, Version v) {
  // The encoder's table, so that what is parsed is exactly what gets encoded.
  const OperandCounts c = operandCounts(op, v);
  return {c.dst, c.src};
}

const RegisterName* findRegisterName(std::string_view letters, Version v) {
  for (const RegisterName& r : registerLettersOf(v))
    if (letters == r.letters) return &r;
  return nullptr;
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

}  // namespace refx::shader::asmtables
