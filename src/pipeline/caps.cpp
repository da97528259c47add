// Caps profiles: data/caps/<name>.caps files of `Field = value` lines, fields named
// after D3DCAPS9, flag values written with the D3D flag names (prefix optional).
#include "refx/pipeline/caps.h"

#include <span>

#include "caps_flags.h"
#include "refx/core/text.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/d3d9types.h"

namespace refx {

namespace {

// ---------------------------------------------------------------------------
// Flag sets: D3D flag names (without prefix) and their bits.

struct Flag {
  std::string name;
  uint32_t bit;
};

struct FlagSet {
  std::string_view prefix;  // "D3DTEXOPCAPS_", accepted but not required
  std::vector<Flag> flags;
  bool countInLowBits = false;  // FVFCaps: the low 16 bits are a number
};

// A field whose names and bits are in caps_flags.h (shared with ValidateDevice).
FlagSet flagSet(std::string_view prefix, std::span<const caps_flags::FlagBit> table) {
  FlagSet s{prefix, {}};
  for (const caps_flags::FlagBit& f : table) s.flags.push_back({std::string(f.name), f.bit});
  return s;
}

const FlagSet kTextureCaps = flagSet("D3DPTEXTURECAPS_", caps_flags::kTextureCaps);
const FlagSet kFilterCaps = flagSet("D3DPTFILTERCAPS_", caps_flags::kFilterCaps);
const FlagSet kAddressCaps = flagSet("D3DPTADDRESSCAPS_", caps_flags::kAddressCaps);
const FlagSet kMiscCaps = flagSet("D3DPMISCCAPS_", caps_flags::kMiscCaps);
const FlagSet kTextureOpCaps = flagSet("D3DTEXOPCAPS_", caps_flags::kTextureOpCaps);
const FlagSet kBlendCaps = flagSet("D3DPBLENDCAPS_", caps_flags::kBlendCaps);
const FlagSet kRasterCaps = flagSet("D3DPRASTERCAPS_", caps_flags::kRasterCaps);

const FlagSet kDevCaps{"D3DDEVCAPS_", {
    {"EXECUTESYSTEMMEMORY", 0x10}, {"EXECUTEVIDEOMEMORY", 0x20},
    {"TLVERTEXSYSTEMMEMORY", 0x40}, {"TLVERTEXVIDEOMEMORY", 0x80},
    {"TEXTURESYSTEMMEMORY", 0x100}, {"TEXTUREVIDEOMEMORY", 0x200},
    {"DRAWPRIMTLVERTEX", 0x400}, {"CANRENDERAFTERFLIP", 0x800},
    {"TEXTURENONLOCALVIDMEM", 0x1000}, {"DRAWPRIMITIVES2", 0x2000},
    {"SEPARATETEXTUREMEMORIES", 0x4000}, {"DRAWPRIMITIVES2EX", 0x8000},
    {"HWTRANSFORMANDLIGHT", 0x10000}, {"CANBLTSYSTONONLOCAL", 0x20000},
    {"HWRASTERIZATION", 0x80000}, {"PUREDEVICE", 0x100000}, {"QUINTICRTPATCHES", 0x200000},
    {"RTPATCHES", 0x400000}, {"RTPATCHHANDLEZERO", 0x800000}, {"NPATCHES", 0x1000000}}};

// FVFCaps: low 16 bits = number of texture coordinate sets, then flags.
const FlagSet kFvfCaps{"D3DFVFCAPS_", {
    {"DONOTSTRIPELEMENTS", 0x80000}, {"PSIZE", 0x100000}}, true};

// ---------------------------------------------------------------------------
// Field table: one row per D3DCAPS9 field a profile can set.

enum class FieldKind { Text, Uint, Flags, VsVersion, PsVersion, Float };

struct Field {
  std::string_view name;  // D3DCAPS9 name
  FieldKind kind;
  std::string CapsProfile::*text = nullptr;
  uint32_t CapsProfile::*uint = nullptr;
  float CapsProfile::*real = nullptr;
  const FlagSet* (*flags)() = nullptr;
  uint32_t minValue = 0, maxValue = 0;  // for Uint
};

const FlagSet* textureOpCapsPtr() { return &kTextureOpCaps; }
const FlagSet* blendCapsPtr() { return &kBlendCaps; }
const FlagSet* textureCapsPtr() { return &kTextureCaps; }
const FlagSet* filterCapsPtr() { return &kFilterCaps; }
const FlagSet* addressCapsPtr() { return &kAddressCaps; }
const FlagSet* miscCapsPtr() { return &kMiscCaps; }
const FlagSet* rasterCapsPtr() { return &kRasterCaps; }
const FlagSet* devCapsPtr() { return &kDevCaps; }
const FlagSet* fvfCapsPtr() { return &kFvfCaps; }

Field textField(std::string_view n, std::string CapsProfile::*m) {
  Field f{n, FieldKind::Text};
  f.text = m;
  return f;
}
Field uintField(std::string_view n, uint32_t CapsProfile::*m, uint32_t lo, uint32_t hi) {
  Field f{n, FieldKind::Uint};
  f.uint = m;
  f.minValue = lo;
  f.maxValue = hi;
  return f;
}
Field flagsField(std::string_view n, uint32_t CapsProfile::*m, const FlagSet* (*set)()) {
  Field f{n, FieldKind::Flags};
  f.uint = m;
  f.flags = set;
  return f;
}
Field versionField(std::string_view n, FieldKind k, uint32_t CapsProfile::*m) {
  Field f{n, k};
  f.uint = m;
  return f;
}
Field floatField(std::string_view n, float CapsProfile::*m) {
  Field f{n, FieldKind::Float};
  f.real = m;
  return f;
}

// Printing order of describeCapsProfile; the .caps files follow it too.
const std::vector<Field>& fields() {
  using C = CapsProfile;
  static const std::vector<Field> table = {
      textField("Description", &C::description),
      uintField("MaxTextureBlendStages", &C::maxTextureBlendStages, 1, d3d::kMaxTextureStages),
      uintField("MaxSimultaneousTextures", &C::maxSimultaneousTextures, 1, d3d::kMaxTextureStages),
      flagsField("TextureOpCaps", &C::textureOpCaps, textureOpCapsPtr),
      versionField("VertexShaderVersion", FieldKind::VsVersion, &C::vertexShaderVersion),
      versionField("PixelShaderVersion", FieldKind::PsVersion, &C::pixelShaderVersion),
      floatField("MaxPixelShaderValue", &C::pixelShader1xMaxValue),
      uintField("MaxVertexShaderConst", &C::maxVertexShaderConst, 0, 8192),
      flagsField("DevCaps", &C::devCaps, devCapsPtr),
      uintField("MaxActiveLights", &C::maxActiveLights, 0, 8),
      uintField("MaxStreams", &C::maxStreams, 0, 16),
      flagsField("FVFCaps", &C::fvfCaps, fvfCapsPtr),
      flagsField("TextureCaps", &C::textureCaps, textureCapsPtr),
      uintField("MaxTextureWidth", &C::maxTextureWidth, 1, 1u << 16),
      uintField("MaxTextureHeight", &C::maxTextureHeight, 1, 1u << 16),
      uintField("MaxVolumeExtent", &C::maxVolumeExtent, 0, 1u << 16),
      uintField("MaxTextureRepeat", &C::maxTextureRepeat, 0, 1u << 24),
      uintField("MaxAnisotropy", &C::maxAnisotropy, 1, 16),
      flagsField("TextureFilterCaps", &C::textureFilterCaps, filterCapsPtr),
      flagsField("CubeTextureFilterCaps", &C::cubeTextureFilterCaps, filterCapsPtr),
      flagsField("VolumeTextureFilterCaps", &C::volumeTextureFilterCaps, filterCapsPtr),
      flagsField("VertexTextureFilterCaps", &C::vertexTextureFilterCaps, filterCapsPtr),
      flagsField("TextureAddressCaps", &C::textureAddressCaps, addressCapsPtr),
      flagsField("SrcBlendCaps", &C::srcBlendCaps, blendCapsPtr),
      flagsField("DestBlendCaps", &C::destBlendCaps, blendCapsPtr),
      flagsField("PrimitiveMiscCaps", &C::primitiveMiscCaps, miscCapsPtr),
      flagsField("RasterCaps", &C::rasterCaps, rasterCapsPtr),
      uintField("NumSimultaneousRTs", &C::maxSimultaneousRenderTargets, 1, 4),
      floatField("MaxPointSize", &C::maxPointSize),
      uintField("MaxVertexBlendMatrices", &C::maxVertexBlendMatrices, 0, 4),
      uintField("MaxVertexBlendMatrixIndex", &C::maxVertexBlendMatrixIndex, 0, 255),
      uintField("MaxUserClipPlanes", &C::maxUserClipPlanes, 0, 6),
  };
  return table;
}

// D3D9 calls MaxPixelShaderValue PixelShader1xMaxValue; both names are accepted.
std::string_view canonicalFieldName(std::string_view key) {
  const auto eq = equalsNoCase;
  if (eq(key, "PixelShader1xMaxValue")) return "MaxPixelShaderValue";
  if (eq(key, "MaxSimultaneousRenderTargets")) return "NumSimultaneousRTs";
  for (const auto& f : fields())
    if (eq(key, f.name)) return f.name;
  return {};
}

// ---------------------------------------------------------------------------
// Text helpers

std::string upper(std::string_view s) { return toUpper(s); }

std::optional<uint32_t> parseUint(std::string_view s) {
  const auto v = parseUnsigned(trim(s));
  if (!v || *v > UINT32_MAX) return std::nullopt;
  return uint32_t(*v);
}

std::string flagNames(const FlagSet& set) {
  std::string out;
  for (const auto& f : set.flags) out += (out.empty() ? "" : ", ") + f.name;
  return out;
}

// A value that may continue over several lines; each piece keeps its line.
struct Piece {
  std::string_view text;
  int line;
};

uint32_t parseFlags(const std::vector<Piece>& pieces, const Field& field, const std::string& file) {
  const FlagSet& set = *field.flags();
  uint32_t value = 0;
  for (const Piece& piece : pieces) {
    std::string_view rest = piece.text;
    while (true) {
      size_t bar = rest.find('|');
      std::string_view token = trim(rest.substr(0, bar));
      SourceLocation where{file, piece.line, 0};
      if (token.empty()) {
        // A trailing '|' continues the value on the next line; anything else is a gap.
        bool continues = bar == std::string_view::npos && &piece != &pieces.back();
        if (!continues)
          failAt(where, "{} has an empty flag between '|' separators", field.name);
      } else if (auto n = parseUint(token)) {
        value |= *n;
      } else {
        std::string name = upper(token);
        if (name.size() > set.prefix.size() && name.starts_with(set.prefix))
          name.erase(0, set.prefix.size());
        const Flag* found = nullptr;
        for (const auto& f : set.flags)
          if (f.name == name) found = &f;
        if (!found)
          failAt(where, "unknown {}* flag '{}' in {} (known: {})", set.prefix, token, field.name,
                 flagNames(set));
        value |= found->bit;
      }
      if (bar == std::string_view::npos) break;
      rest.remove_prefix(bar + 1);
    }
  }
  return value;
}

uint32_t parseVersion(std::string_view text, const Field& field, const SourceLocation& where) {
  bool vs = field.kind == FieldKind::VsVersion;
  uint32_t tag = vs ? 0xFFFE0000u : 0xFFFF0000u;
  std::string u = upper(trim(text));
  if (u == "NONE" || u == "0" || u == "0.0") return tag;
  int major = -1, minor = -1;
  // "1.4" or "ps_1_4" / "vs_1_1".
  std::string_view prefix = vs ? "VS_" : "PS_";
  if (u.size() == 6 && u.starts_with(prefix) && u[4] == '_') {
    major = u[3] - '0';
    minor = u[5] - '0';
  } else if (u.size() == 3 && u[1] == '.') {
    major = u[0] - '0';
    minor = u[2] - '0';
  }
  static const std::pair<int, int> kVs[] = {{1, 1}, {2, 0}, {3, 0}};
  static const std::pair<int, int> kPs[] = {{1, 1}, {1, 2}, {1, 3}, {1, 4}, {2, 0}, {3, 0}};
  auto known = [&](auto& list) {
    for (auto [ma, mi] : list)
      if (ma == major && mi == minor) return true;
    return false;
  };
  if (vs ? known(kVs) : known(kPs)) return tag | uint32_t(major) << 8 | uint32_t(minor);
  failAt(where, "{} '{}' is not a {} shader version (expected none, {})", field.name, trim(text),
         vs ? "vertex" : "pixel", vs ? "1.1, 2.0 or 3.0" : "1.1, 1.2, 1.3, 1.4, 2.0 or 3.0");
}

float parseFloatValue(std::string_view text, const Field& field, const SourceLocation& where) {
  std::string s(trim(text));
  if (upper(s) == "FLT_MAX") return std::numeric_limits<float>::max();
  float v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v) || v < 0)
    failAt(where, "{} '{}' is not a non-negative number or FLT_MAX", field.name, s);
  return v;
}

std::string stemOf(const std::string& file) {
  std::filesystem::path p(file);
  return p.stem().string();
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: error: cannot read caps profile", path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---------------------------------------------------------------------------
// Printing

std::string formatFlags(uint32_t value, const FlagSet& set, size_t firstIndent) {
  std::vector<std::string> parts;
  if (set.countInLowBits) {
    parts.push_back(std::to_string(value & 0xffff));
    value &= ~0xffffu;
  }
  for (const auto& f : set.flags)
    if (value & f.bit) {
      parts.push_back(f.name);
      value &= ~f.bit;
    }
  if (value) parts.push_back(fmt::format("0x{:x}", value));
  if (parts.empty()) return "0";
  // Wrap long lists; a trailing '|' continues the value, so the output parses back.
  std::string out, line;
  size_t indent = firstIndent;
  for (size_t i = 0; i < parts.size(); ++i) {
    std::string piece = parts[i] + (i + 1 < parts.size() ? " |" : "");
    if (!line.empty() && indent + line.size() + 1 + piece.size() > 96) {
      out += line + "\n    ";
      line.clear();
      indent = 4;
    }
    line += (line.empty() ? "" : " ") + piece;
  }
  return out + line;
}

std::string formatVersion(uint32_t v) {
  int major = (v >> 8) & 0xff, minor = v & 0xff;
  if (major == 0 && minor == 0) return "none";
  return fmt::format("{}.{}", major, minor);
}

std::string formatFloat(float v) {
  if (v == std::numeric_limits<float>::max()) return "FLT_MAX";
  if (v == std::floor(v) && v < 1e9f) return fmt::format("{:.1f}", v);
  return fmt::format("{}", v);
}

}  // namespace

// ---------------------------------------------------------------------------

std::vector<std::string> capsProfileNames() {
  return {"dx6-tnt2", "dx6-g400", "dx7", "dx8", "dx8-ps13", "dx81", "dx9", "dx9-sm3", "ref"};
}

CapsProfile parseCapsProfile(const std::string& text, const std::string& file) {
  CapsProfile caps;
  caps.name = stemOf(file);
  // Split into lines, dropping comments.
  std::vector<std::string_view> lines;
  std::string_view all(text);
  while (!all.empty() || lines.empty()) {
    size_t nl = all.find('\n');
    std::string_view line = all.substr(0, nl);
    if (size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    lines.push_back(trim(line));
    if (nl == std::string_view::npos) break;
    all.remove_prefix(nl + 1);
  }
  std::vector<std::string_view> seen;
  for (size_t i = 0; i < lines.size(); ++i) {
    std::string_view line = lines[i];
    if (line.empty()) continue;
    int lineNo = int(i) + 1;
    SourceLocation where{file, lineNo, 0};
    size_t eq = line.find('=');
    if (eq == std::string_view::npos)
      failAt(where, "expected 'Field = value', got '{}'", line);
    std::string_view key = trim(line.substr(0, eq));
    std::vector<Piece> pieces{{trim(line.substr(eq + 1)), lineNo}};
    // A value ending in '|' continues on the next non-empty line.
    while (pieces.back().text.ends_with('|')) {
      size_t j = i + 1;
      while (j < lines.size() && lines[j].empty()) ++j;
      if (j == lines.size()) failAt(where, "'{}' ends with '|' but no line follows", key);
      i = j;
      pieces.push_back({lines[j], int(j) + 1});
    }
    std::string_view name = canonicalFieldName(key);
    if (name.empty()) failAt(where, "unknown caps field '{}'", key);
    for (auto s : seen)
      if (s == name) failAt(where, "caps field '{}' is set twice", name);
    seen.push_back(name);
    const Field* field = nullptr;
    for (const auto& f : fields())
      if (f.name == name) field = &f;
    std::string_view value = pieces.front().text;
    if (value.empty() && field->kind != FieldKind::Text)
      failAt(where, "caps field '{}' has no value", name);
    if (field->kind != FieldKind::Flags && pieces.size() > 1)
      failAt(where, "only flag fields may continue with '|'");
    switch (field->kind) {
      case FieldKind::Text: caps.*(field->text) = std::string(value); break;
      case FieldKind::Flags: caps.*(field->uint) = parseFlags(pieces, *field, file); break;
      case FieldKind::VsVersion:
      case FieldKind::PsVersion: caps.*(field->uint) = parseVersion(value, *field, where); break;
      case FieldKind::Float: caps.*(field->real) = parseFloatValue(value, *field, where); break;
      case FieldKind::Uint: {
        auto v = parseUint(value);
        if (!v) failAt(where, "{} '{}' is not an unsigned integer", name, value);
        if (*v < field->minValue || *v > field->maxValue)
          failAt(where, "{} {} is out of range [{}, {}]", name, *v, field->minValue,
                 field->maxValue);
        caps.*(field->uint) = *v;
        break;
      }
    }
  }
  return caps;
}

CapsProfile loadCapsProfile(const std::string& nameOrPath) {
  bool isPath = nameOrPath.find('/') != std::string::npos || nameOrPath.ends_with(".caps");
  if (isPath) return parseCapsProfile(readFile(nameOrPath), nameOrPath);
  std::string path = std::string(REFX_DATA_DIR) + "/caps/" + nameOrPath + ".caps";
  std::error_code ec;
  if (nameOrPath.empty() || !std::filesystem::is_regular_file(path, ec)) {
    std::string known;
    for (const auto& n : capsProfileNames()) known += (known.empty() ? "" : ", ") + n;
    throw Error(SourceLocation{},
                fmt::format("unknown caps profile '{}' (known: {})", nameOrPath, known));
  }
  return parseCapsProfile(readFile(path), path);
}

std::string describeCapsProfile(const CapsProfile& caps) {
  std::string out = fmt::format("# caps profile {}\n", caps.name);
  for (const auto& f : fields()) {
    std::string value;
    switch (f.kind) {
      case FieldKind::Text: value = caps.*(f.text); break;
      case FieldKind::Uint: value = std::to_string(caps.*(f.uint)); break;
      case FieldKind::Flags: value = formatFlags(caps.*(f.uint), *f.flags(), f.name.size() + 3); break;
      case FieldKind::VsVersion:
      case FieldKind::PsVersion: value = formatVersion(caps.*(f.uint)); break;
      case FieldKind::Float: value = formatFloat(caps.*(f.real)); break;
    }
    out += fmt::format("{} = {}\n", f.name, value);
  }
  return out;
}

}  // namespace refx
