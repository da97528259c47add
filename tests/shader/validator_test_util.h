// Helpers of the validator tests (tests/shader/validate_*_test.cpp): shaders are
// written as assembly text; bytecode can carry things the assembler refuses to write
// (co-issue bits in a vertex shader, a reserved opcode, an _x2 shift in ps_2_0 …), so
// those cases go through a small reader that builds the Shader struct from the text
// as written. Tests match on messages (what the rule says) and, in
// validator_codes_test.cpp, on codes.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"
#include "refx/shader/validator.h"
#include "refx/shader/version_rules.h"

namespace refx::shader::validator_test {

// ---- a small assembly reader for the tests ---------------------------------------

inline std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
inline std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

inline uint8_t componentIndex(char c) {
  switch (c) {
    case 'x': case 'r': return 0;
    case 'y': case 'g': return 1;
    case 'z': case 'b': return 2;
    case 'w': case 'a': return 3;
  }
  throw std::runtime_error(std::string("bad component ") + c);
}

struct Reader {
  Version version;

  void reg(std::string s, RegType& type, uint16_t& index, bool& relative, RelativeAddress& rel) {
    relative = false;
    if (auto lb = s.find('['); lb != std::string::npos) {
      // c[a0.x + n] / c[aL + n]
      std::string inside = s.substr(lb + 1, s.find(']') - lb - 1);
      inside.erase(std::remove(inside.begin(), inside.end(), ' '), inside.end());
      std::string base = s.substr(0, lb);
      relative = true;
      int n = 0;
      std::string addr = inside;
      if (auto plus = inside.find('+'); plus != std::string::npos) {
        addr = inside.substr(0, plus);
        n = std::stoi(inside.substr(plus + 1));
      }
      if (addr == "al") rel = {RegType::Loop, 0};
      else rel = {RegType::Addr, componentIndex(addr.size() > 3 ? addr[3] : 'x')};
      RegType t;
      uint16_t i;
      bool r;
      RelativeAddress ra;
      reg(base + "0", t, i, r, ra);
      type = t;
      index = uint16_t(n);
      return;
    }
    static const std::pair<const char*, std::pair<RegType, int>> fixed[] = {
        {"opos", {RegType::RastOut, 0}}, {"ofog", {RegType::RastOut, 1}}, {"opts", {RegType::RastOut, 2}},
        {"odepth", {RegType::DepthOut, 0}}, {"al", {RegType::Loop, 0}}, {"vpos", {RegType::MiscType, 0}},
        {"vface", {RegType::MiscType, 1}}, {"a0", {RegType::Addr, 0}}, {"p0", {RegType::Predicate, 0}},
    };
    for (auto& [n, tv] : fixed)
      if (s == n) {
        type = tv.first;
        index = uint16_t(tv.second);
        return;
      }
    static const std::pair<const char*, RegType> prefixes[] = {
        {"od", RegType::AttrOut}, {"ot", RegType::TexCrdOut}, {"oc", RegType::ColorOut},
        {"o", RegType::Output}, {"r", RegType::Temp}, {"v", RegType::Input}, {"c", RegType::Const},
        {"t", RegType::Texture}, {"i", RegType::ConstInt}, {"b", RegType::ConstBool},
        {"s", RegType::Sampler}, {"l", RegType::Label},
    };
    for (auto& [p, t] : prefixes) {
      size_t n = std::strlen(p);
      if (s.compare(0, n, p) == 0 && s.size() > n && std::isdigit(static_cast<unsigned char>(s[n]))) {
        type = t;
        index = uint16_t(std::stoi(s.substr(n)));
        return;
      }
    }
    throw std::runtime_error("bad register " + s);
  }

  DstParam dst(std::string s) {
    DstParam d;
    if (auto dot = s.find('.'); dot != std::string::npos) {
      d.writeMask = 0;
      for (char c : s.substr(dot + 1)) d.writeMask |= uint8_t(1 << componentIndex(c));
      s = s.substr(0, dot);
    }
    reg(s, d.type, d.index, d.relative, d.rel);
    return d;
  }

  SrcParam src(std::string s) {
    SrcParam p;
    bool neg = false, invert = false, notOp = false;
    if (s[0] == '-') neg = true, s = trim(s.substr(1));
    if (s[0] == '!') notOp = true, s = s.substr(1);
    if (s.compare(0, 2, "1-") == 0) invert = true, s = trim(s.substr(2));
    std::string swz;
    if (auto dot = s.rfind('.'); dot != std::string::npos && s.find(']', dot) == std::string::npos) {
      swz = s.substr(dot + 1);
      s = s.substr(0, dot);
    }
    std::string mod;
    if (auto us = s.find('_'); us != std::string::npos) {
      mod = s.substr(us + 1);
      s = s.substr(0, us);
    }
    reg(s, p.type, p.index, p.relative, p.rel);
    if (!swz.empty()) {
      p.swizzle = 0;
      for (int c = 0; c < 4; ++c)
        p.swizzle |= uint8_t(componentIndex(swz[std::min<size_t>(c, swz.size() - 1)]) << (2 * c));
    }
    if (invert) p.mod = SrcMod::Comp;
    else if (notOp) p.mod = SrcMod::Not;
    else if (mod == "bias") p.mod = neg ? SrcMod::BiasNeg : SrcMod::Bias;
    else if (mod == "bx2") p.mod = neg ? SrcMod::SignNeg : SrcMod::Sign;
    else if (mod == "x2") p.mod = neg ? SrcMod::X2Neg : SrcMod::X2;
    else if (mod == "dz" || mod == "db") p.mod = SrcMod::Dz;
    else if (mod == "dw" || mod == "da") p.mod = SrcMod::Dw;
    else if (mod == "abs") p.mod = neg ? SrcMod::AbsNeg : SrcMod::Abs;
    else if (!mod.empty()) throw std::runtime_error("bad source modifier " + mod);
    else if (neg) p.mod = SrcMod::Neg;
    return p;
  }

  static std::vector<std::string> splitOperands(const std::string& s) {
    std::vector<std::string> out;
    std::string cur;
    int depth = 0;
    for (char c : s) {
      if (c == '[') ++depth;
      if (c == ']') --depth;
      if (c == ',' && depth == 0) {
        out.push_back(trim(cur));
        cur.clear();
      } else {
        cur += c;
      }
    }
    if (!trim(cur).empty()) out.push_back(trim(cur));
    return out;
  }

  Shader read(const std::string& text) {
    Shader sh;
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    bool haveVersion = false;
    while (std::getline(in, line)) {
      ++lineNo;
      for (const char* c : {";", "//"})
        if (auto p = line.find(c); p != std::string::npos) line = line.substr(0, p);
      std::string t = lower(trim(line));
      if (t.empty()) continue;
      if (!haveVersion) {
        std::replace(t.begin(), t.end(), '.', '_');
        version.type = t[0] == 'p' ? ShaderType::Pixel : ShaderType::Vertex;
        version.major = uint8_t(t[3] - '0');
        version.minor = t[5] == 'x' ? 1 : uint8_t(t[5] - '0');
        sh.version = version;
        haveVersion = true;
        continue;
      }
      sh.instructions.push_back(instruction(t, lineNo));
    }
    return sh;
  }

  Instruction instruction(std::string t, int lineNo) {
    Instruction in;
    in.pos = {lineNo, 1};
    if (t[0] == '+') in.coissue = true, t = trim(t.substr(1));
    if (t[0] == '(') {
      std::string pred = t.substr(1, t.find(')') - 1);
      in.predicated = true;
      if (pred[0] == '!') in.predicateNot = true, pred = pred.substr(1);
      if (auto dot = pred.find('.'); dot != std::string::npos) {
        std::string s = pred.substr(dot + 1);
        in.predicateSwizzle = 0;
        for (int c = 0; c < 4; ++c)
          in.predicateSwizzle |= uint8_t(componentIndex(s[std::min<size_t>(c, s.size() - 1)]) << (2 * c));
      }
      t = trim(t.substr(t.find(')') + 1));
    }
    std::string mnem = t.substr(0, t.find_first_of(" \t"));
    std::string rest = t.size() > mnem.size() ? trim(t.substr(mnem.size())) : "";
    std::vector<std::string> ops = splitOperands(rest);

    // Mnemonic and its suffixes.
    static const std::map<std::string, Opcode> names = {
        {"nop", Opcode::Nop}, {"mov", Opcode::Mov}, {"add", Opcode::Add}, {"sub", Opcode::Sub},
        {"mad", Opcode::Mad}, {"mul", Opcode::Mul}, {"rcp", Opcode::Rcp}, {"rsq", Opcode::Rsq},
        {"dp3", Opcode::Dp3}, {"dp4", Opcode::Dp4}, {"min", Opcode::Min}, {"max", Opcode::Max},
        {"slt", Opcode::Slt}, {"sge", Opcode::Sge}, {"exp", Opcode::Exp}, {"log", Opcode::Log},
        {"lit", Opcode::Lit}, {"dst", Opcode::Dst}, {"lrp", Opcode::Lrp}, {"frc", Opcode::Frc},
        {"m4x4", Opcode::M4x4}, {"m4x3", Opcode::M4x3}, {"m3x4", Opcode::M3x4}, {"m3x3", Opcode::M3x3},
        {"m3x2", Opcode::M3x2}, {"call", Opcode::Call}, {"callnz", Opcode::CallNZ},
        {"loop", Opcode::Loop}, {"ret", Opcode::Ret}, {"endloop", Opcode::EndLoop},
        {"label", Opcode::Label}, {"dcl", Opcode::Dcl}, {"pow", Opcode::Pow}, {"crs", Opcode::Crs},
        {"sgn", Opcode::Sgn}, {"abs", Opcode::Abs}, {"nrm", Opcode::Nrm}, {"sincos", Opcode::SinCos},
        {"rep", Opcode::Rep}, {"endrep", Opcode::EndRep}, {"if", Opcode::If}, {"else", Opcode::Else},
        {"endif", Opcode::EndIf}, {"break", Opcode::Break}, {"mova", Opcode::MovA},
        {"defb", Opcode::DefB}, {"defi", Opcode::DefI}, {"texcoord", Opcode::TexCoord},
        {"texcrd", Opcode::TexCoord}, {"texkill", Opcode::TexKill}, {"tex", Opcode::Tex},
        {"texld", Opcode::Tex}, {"texldp", Opcode::Tex}, {"texldb", Opcode::Tex},
        {"texbem", Opcode::TexBem}, {"texbeml", Opcode::TexBemL}, {"texreg2ar", Opcode::TexReg2AR},
        {"texreg2gb", Opcode::TexReg2GB}, {"texm3x2pad", Opcode::TexM3x2Pad},
        {"texm3x2tex", Opcode::TexM3x2Tex}, {"texm3x3pad", Opcode::TexM3x3Pad},
        {"texm3x3tex", Opcode::TexM3x3Tex}, {"texm3x3spec", Opcode::TexM3x3Spec},
        {"texm3x3vspec", Opcode::TexM3x3VSpec}, {"texm3x3diff", Opcode::TexM3x3Diff}, {"expp", Opcode::ExpP}, {"logp", Opcode::LogP},
        {"cnd", Opcode::Cnd}, {"def", Opcode::Def}, {"texreg2rgb", Opcode::TexReg2RGB},
        {"texdp3tex", Opcode::TexDP3Tex}, {"texm3x2depth", Opcode::TexM3x2Depth},
        {"texdp3", Opcode::TexDP3}, {"texm3x3", Opcode::TexM3x3}, {"texdepth", Opcode::TexDepth},
        {"cmp", Opcode::Cmp}, {"bem", Opcode::Bem}, {"dp2add", Opcode::Dp2Add}, {"dsx", Opcode::Dsx},
        {"dsy", Opcode::Dsy}, {"texldd", Opcode::TexLdd}, {"setp", Opcode::SetP},
        {"texldl", Opcode::TexLdl}, {"breakp", Opcode::BreakP}, {"phase", Opcode::Phase},
    };
    static const std::map<std::string, int> comparisons = {{"gt", 1}, {"eq", 2}, {"ge", 3},
                                                           {"lt", 4}, {"ne", 5}, {"le", 6}};
    std::vector<std::string> parts;
    {
      std::string cur;
      for (char c : mnem) {
        if (c == '_') parts.push_back(cur), cur.clear();
        else cur += c;
      }
      parts.push_back(cur);
    }
    std::string base = parts[0];
    if (base == "if" && parts.size() > 1 && comparisons.count(parts[1])) in.opcode = Opcode::IfC;
    else if (base == "break" && parts.size() > 1 && comparisons.count(parts[1])) in.opcode = Opcode::BreakC;
    else if (!names.count(base)) throw std::runtime_error("unknown instruction " + base);
    else in.opcode = names.at(base);
    if (base == "texldp") in.control = 1;
    if (base == "texldb") in.control = 2;

    if (in.opcode == Opcode::Dcl) {
      std::string kind;
      in.hasDst = true;
      in.dst = dst(ops.at(0));
      for (size_t i = 1; i < parts.size(); ++i)
        if (parts[i] == "centroid") in.dst.resultMod |= ResultCentroid;
        else if (parts[i] == "pp") in.dst.resultMod |= ResultPartialPrecision;
        else kind = parts[i];
      if (kind == "2d") in.textureType = TextureType::Tex2D;
      else if (kind == "cube") in.textureType = TextureType::Cube;
      else if (kind == "volume") in.textureType = TextureType::Volume;
      else if (!kind.empty()) {
        static const std::pair<const char*, DeclUsage> usages[] = {
            {"position", DeclUsage::Position}, {"blendweight", DeclUsage::BlendWeight},
            {"blendindices", DeclUsage::BlendIndices}, {"normal", DeclUsage::Normal},
            {"psize", DeclUsage::PSize}, {"texcoord", DeclUsage::TexCoord}, {"tangent", DeclUsage::Tangent},
            {"binormal", DeclUsage::Binormal}, {"color", DeclUsage::Color}, {"fog", DeclUsage::Fog},
            {"depth", DeclUsage::Depth}};
        for (auto& [n, u] : usages)
          if (kind.compare(0, std::strlen(n), n) == 0) {
            in.usage = u;
            std::string idx = kind.substr(std::strlen(n));
            in.usageIndex = idx.empty() ? 0 : uint8_t(std::stoi(idx));
          }
      }
      return in;
    }
    for (size_t i = 1; i < parts.size(); ++i) {
      const std::string& m = parts[i];
      if (comparisons.count(m)) in.control = uint8_t(comparisons.at(m));
      else if (m == "sat") in.dst.resultMod |= ResultSaturate;
      else if (m == "pp") in.dst.resultMod |= ResultPartialPrecision;
      else if (m == "x2") in.dst.shift = 1;
      else if (m == "x4") in.dst.shift = 2;
      else if (m == "x8") in.dst.shift = 3;
      else if (m == "d2") in.dst.shift = -1;
      else if (m == "d4") in.dst.shift = -2;
      else if (m == "d8") in.dst.shift = -3;
      else throw std::runtime_error("bad instruction modifier " + m);
    }
    if (in.opcode == Opcode::Def || in.opcode == Opcode::DefI || in.opcode == Opcode::DefB) {
      in.hasDst = true;
      in.dst = dst(ops.at(0));
      for (size_t i = 1; i < ops.size() && i <= 4; ++i) {
        if (in.opcode == Opcode::Def) {
          float f = std::stof(ops[i]);
          std::memcpy(&in.literal[i - 1], &f, 4);
        } else if (in.opcode == Opcode::DefB) {
          in.literal[0] = ops[i] == "true" ? 1 : 0;
        } else {
          in.literal[i - 1] = uint32_t(std::stoi(ops[i]));
        }
      }
      return in;
    }
    static const Opcode noDst[] = {Opcode::Call, Opcode::CallNZ, Opcode::Loop, Opcode::Ret,
                                   Opcode::EndLoop, Opcode::Label, Opcode::Rep, Opcode::EndRep,
                                   Opcode::If, Opcode::IfC, Opcode::Else, Opcode::EndIf,
                                   Opcode::Break, Opcode::BreakC, Opcode::BreakP, Opcode::Nop,
                                   Opcode::Phase};
    size_t first = 0;
    if (std::find(std::begin(noDst), std::end(noDst), in.opcode) == std::end(noDst) && !ops.empty()) {
      in.hasDst = true;
      uint8_t rm = in.dst.resultMod;
      int8_t sh = in.dst.shift;
      in.dst = dst(ops[0]);
      in.dst.resultMod = rm;
      in.dst.shift = sh;
      first = 1;
    }
    for (size_t i = first; i < ops.size(); ++i) in.src[in.srcCount++] = src(ops[i]);
    return in;
  }
};

inline Shader read(const std::string& text) { return assemble(text, "test.psh"); }
// For shaders only hand-made bytecode can hold.
inline Shader readRaw(const std::string& text) { return Reader{}.read(text); }

inline std::vector<std::string> messages(const Shader& shader, const ValidationCaps& caps = {}) {
  std::vector<std::string> out;
  for (const Diagnostic& d : validate(shader, caps)) out.push_back(d.message);
  return out;
}
inline std::vector<std::string> messages(const std::string& text, const ValidationCaps& caps = {}) {
  return messages(read(text), caps);
}

inline std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& m : v) s += "  " + m + "\n";
  return s;
}

inline ::testing::AssertionResult isValid(const std::string& text, const ValidationCaps& caps = {}) {
  auto m = messages(text, caps);
  if (m.empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected valid, got:\n" << joined(m);
}

inline ::testing::AssertionResult hasError(const Shader& shader, const std::string& expected,
                                    const ValidationCaps& caps = {}) {
  auto m = messages(shader, caps);
  for (const auto& s : m)
    if (s.find(expected) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected \"" << expected << "\", got:\n" << joined(m);
}

inline ::testing::AssertionResult hasError(const std::string& text, const std::string& expected,
                                    const ValidationCaps& caps = {}) {
  return hasError(read(text), expected, caps);
}

inline std::vector<std::string> codes(const Shader& shader, const ValidationCaps& caps = {}) {
  std::vector<std::string> out;
  for (const Diagnostic& d : validate(shader, caps)) out.push_back(d.code);
  return out;
}

// The shader breaks the rule whose code is `code` (and reports it with that code).
inline ::testing::AssertionResult hasCode(const Shader& shader, const std::string& code,
                                          const ValidationCaps& caps = {}) {
  std::string all;
  for (const Diagnostic& d : validate(shader, caps)) {
    if (d.code == code) return ::testing::AssertionSuccess();
    all += "  " + d.code + ": " + d.message + "\n";
  }
  return ::testing::AssertionFailure() << "expected " << code << ", got:\n" << all;
}
inline ::testing::AssertionResult hasCode(const std::string& text, const std::string& code,
                                          const ValidationCaps& caps = {}) {
  return hasCode(read(text), code, caps);
}

// vs_2_0 with its static flow-control constants declared and oPos written.
inline const char* const kVs20Head = "vs_2_0\ndefi i0, 3, 0, 1, 0\ndefb b0, true\ndcl_position v0\nmov oPos, v0\n";

// The validator's first message for `tokens`; "(valid)" when it has none.
inline std::string firstProblem(const std::vector<uint32_t>& tokens) {
  const auto d = refx::shader::validate(refx::shader::decode(tokens));
  return d.empty() ? "(valid)" : d[0].message;
}

// vs_2_0: one dcl of v0 with the given usage and register tokens; m4x4 oPos, v0, c0.
inline std::vector<uint32_t> vs20WithDcl(uint32_t usageToken, uint32_t registerToken) {
  return {0xFFFE0200, 0x0200001F, usageToken, registerToken, 0x03000014,
          0xC00F0000, 0x90E40000, 0xA0E40000, 0x0000FFFF};
}

}  // namespace refx::shader::validator_test
