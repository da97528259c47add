// Validator: every version rule has a shader that keeps it and one that breaks it,
// with the message checked. Shaders are written as assembly text. Bytecode can carry
// things the assembler refuses to write (co-issue bits in a vertex shader, a reserved
// opcode, an _x2 shift in ps_2_0 …); those cases go through a small reader local to
// this test that builds the Shader struct from the text as written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"
#include "refx/shader/validator.h"
#include "refx/shader/version_rules.h"

namespace refx::shader {
namespace {

// ---- a small assembly reader for the tests ---------------------------------------

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

uint8_t componentIndex(char c) {
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

Shader read(const std::string& text) { return assemble(text, "test.psh"); }
// For shaders only hand-made bytecode can hold.
Shader readRaw(const std::string& text) { return Reader{}.read(text); }

std::vector<std::string> messages(const Shader& shader, const ValidationCaps& caps = {}) {
  std::vector<std::string> out;
  for (const Diagnostic& d : validate(shader, caps)) out.push_back(d.message);
  return out;
}
std::vector<std::string> messages(const std::string& text, const ValidationCaps& caps = {}) {
  return messages(read(text), caps);
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& m : v) s += "  " + m + "\n";
  return s;
}

::testing::AssertionResult isValid(const std::string& text, const ValidationCaps& caps = {}) {
  auto m = messages(text, caps);
  if (m.empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected valid, got:\n" << joined(m);
}

::testing::AssertionResult hasError(const Shader& shader, const std::string& expected,
                                    const ValidationCaps& caps = {}) {
  auto m = messages(shader, caps);
  for (const auto& s : m)
    if (s.find(expected) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected \"" << expected << "\", got:\n" << joined(m);
}

::testing::AssertionResult hasError(const std::string& text, const std::string& expected,
                                    const ValidationCaps& caps = {}) {
  return hasError(read(text), expected, caps);
}

// ---- the seeds' shaders (valid as written) ---------------------------------------

TEST(ValidatorSeeds, RacorXPixelShadersAreValid) {
  // RacorX6 diffDot3.psh and diffDot314.psh
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3 r1, t1_bx2, v0_bx2\nmul r0,t0, r1"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r0, t0\ntexld r1, t0\ndp3 r2, r1_bx2, v0_bx2\nmul r0, r0, r2"));
  // RacorX7 specular by four muls
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3 r0,t1_bx2,v1_bx2\nmul r1,r0,r0\nmul r0,r1,r1\n"
                      "mul r1,r0,r0\nmul r0,r1,r1\nmul r0,t0,r0"));
  // RacorX8 table lookup, both versions
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntexm3x2pad t1, t0_bx2\ntexm3x2tex t2, t0_bx2\ntex t3\nmul r0,t2,t3"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r0, t0\ntexcrd r1.rgb, t1\ndp3 r1.rg, r1, r0_bx2\nphase\n"
                      "texld r3, t0\ntexld r2, r1\nmul r0, r2, r3"));
  // RacorX9 both versions
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3 r0,t1_bx2,v1_bx2\nmul r1,r0,r0\nmul r0,r1,r1\n"
                      "mul r1,r0,r0\nmul r0,r1,r1\ndp3 r1, t1_bx2, v0_bx2\nmad r0, t0, r1, r0"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t0\ntexcrd r4.rgb, t2\ndp3 r4.rg, r4_bx2, r1_bx2\nmov r2, r1\n"
                      "phase\ntexld r0, t0\ntexld r1, r4\ndp3 r3, r2_bx2, v0_bx2\nmad r0, r0, r3, r1.a"));
  // RacorX10 point light and SpecDot3
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\nadd r0, 1-t0, -t1.a"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntexm3x2pad t2, t1_bx2\ntexm3x2tex t3, t1_bx2\n"
                      "mul r1.rgb, t3, t0\n+mul r1.a, t0.a, t3.a\nadd r0, r1.a, r1"));
  // RacorX11 diffCubeMap and specular
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntex t2\ndp3 r1, t2_bx2, t1_bx2\nmul r0, t0, r1"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntexm3x2pad t2, t1_bx2\ntexm3x2tex t3, t1_bx2\nmul r0, t0.a, t3.a"));
  // RacorX12 (ps_1_2 texdp3tex)
  EXPECT_TRUE(isValid("ps.1.2\ntex t0\ntex t1\ntex t2\ntexdp3tex t3, t1_bx2\ndp3 r0, t2_bx2, t1_bx2\n"
                      "mul r1.rgb, t0, r0\n+mul r1.a, t0.a, t3.a\nadd r0, r1, r1.a"));
  // RacorX13 and the three RacorX14 shaders
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t1\ntexld r0, t0\ntexcrd r3.rgb, t2\ndp3 r1.rgb, r1_bx2, r0_bx2\n"
                      "dp3 r4.rgb, r3, r0_bx2\nphase\ntexld r2, t0\ntexld r3, r4\ntexld r4, t4\ntexld r5, t5\n"
                      "add r5, 1-r4, -r5.a\nmul r1.a, r2.a, r3.a\n+mul r1.rgb, r1, r2\nadd r0, r1.a, r1\nmul r0, r0, r5"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t1\ntexld r0, t0\ntexcrd r3.rgb, t2\ntexld r4, t5\n"
                      "dp3 r1.rgb, r1_bx2, r0_bx2\ndp3 r5.rgb, r3, r0_bx2\nmov r0.r, r4.a\nphase\n"
                      "texld r2, t0\ntexld r3, r5\ntexld r4, t4\nadd r0, 1-r4, -r0.r\nmul r1.a, r2.a, r3.a\n"
                      "+mul r1.rgb, r1, r2\nadd r5, r1.a, r1\nmul r0, r5, r0"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t1\ntexld r0, t0\ntexld r5, t2\ntexld r4, t5\n"
                      "dp3 r1.rgb, r1_bx2, r0_bx2\ndp3 r5.rgb, r5, r0_bx2\nmov r0.r, r4.a\nphase\n"
                      "texld r2, t0\ntexld r3, r5\ntexld r4, t4\nadd r0, 1-r4, -r0.r\nmul r1.a, r2.a, r3.a\n"
                      "+mul r1.rgb, r1, r2\nadd r5, r1.a, r1\nmul r0, r5, r0"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r0, t0\ntexld r5, t2\ntexld r4, t5\ndp3 r5.rgb, r5, r0_bx2\n"
                      "mov r1.r, r4.a\nphase\ntexld r2, t0\ntexld r3, r5\ntexld r4, t4\ntexld r5, t1\n"
                      "dp3 r5.rgb, r5_bx2, r0_bx2\nadd r4, 1-r4, -r1.r\nmul r1.a, r2.a, r3.a\n"
                      "+mul r1.rgb, r5, r2\nadd r3, r1.a, r1\nmul r0, r3, r4"));
}

TEST(ValidatorSeeds, PaperShadersAreValid) {
  // Per-pixel lighting paper: diffuse, multiply-based specular, BRDF, hemisphere fragment.
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3_sat r1,t1_bx2,v0_bx2\nmul r0,t0, r1"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3_sat r0,t1_bx2,v1_bx2\nmul r1,r0,r0\nmul r0,r1,r1\n"
                      "mul r1,r0,r0\nmul r0,r1,r1\nmul r0,r0,t0"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntex t2\ntex t3\nmul r0,t0,t1\nmul r0,r0,t2\nmul r0,r0,t3\nmul r0,r0,v0"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3_d2_sat r0,v0_bx2,t0_bx2\nadd r0,r0,c5\nlrp r0,r0,c1,c2\nmul r0,r0,t1"));
  // Vertex shaders: BRDF, diffuse, emboss, hemisphere (D3D8 style, no dcl).
  EXPECT_TRUE(isValid(R"(vs.1.1
    m4x4 oPos, v0, c4
    m4x4 r4,v0,c0
    m3x3 r0,v3,c0
    m3x3 r1,v8,c0
    mul r2,-r1.zxyw,r0.yzxw
    mad r2,-r1.yzxw,r0.zxyw,-r2
    add r4.xyz,-r4.xyz,c10
    dp3 r5.x,r4.xyz,r4.xyz
    rsq r5.x,r5.x
    mul r4.xyz,r5.xxx,r4.xyz
    add r5.xyz,r4.xyz,-c16
    dp3 r6.x,r5.xyz,r5.xyz
    rsq r6.x,r6.x
    mul r5.xyz,r6.xxx,r5.xyz
    dp3 oT0.x,r4,r1
    dp3 oT0.y,r4,r2
    dp3 oT0.z,r4,r0
    dp3 oT1.x,-c16,r1
    dp3 oT1.y,-c16,r2
    dp3 oT2.z,-c16,r0
    dp3 oT2.x,r5,r1
    dp3 oT2.y,r5,r2
    dp3 oT2.z,r5,r0
    mov oT3.xy,v7.xy
    mov oD0,c9)"));
  EXPECT_TRUE(isValid(R"(vs.1.1
    m4x4 oPos, v0,c8
    m3x3 r3, v8, c0
    m3x3 r5, v3, c0
    mul r0,r3.zxyw,r5.yzxw
    mad r4,r3.yzxw,r5.zxyw,-r0
    dp3 r6.x,r3,c12
    dp3 r6.y,r4,c12
    mul r1.xy,  r6.xy, -c24.xy
    mov oT0.xy, v7.xy
    add oT1.xy, v7.xy,  r1.xy
    dp3 oD0.xyz,v3.xyz,c12.xyz)"));
  EXPECT_TRUE(isValid(R"(vs.1.1
    m4x4 oPos,v0,c8
    m3x3 r0, v3,c0
    dp3 r0,r0,c40
    mov r1,c33
    mad r0,r0,c33,r1
    mov r1,c42
    sub r1,c41,r1
    mad r0,r1,r0,c42
    sub r1,c44,v7.zzz
    mul r0,r0,r1
    mul oD0,r0,c43)"));
  // RacorX10 point light vertex shader.
  EXPECT_TRUE(isValid("vs.1.1\nm4x4 oPos, v0, c8\nm4x4 r2, v0, c0\nadd r10, r2, c12\nmul r10, r10, c33.x\n"
                      "mad r10, r10, c33.yyyy, c33.yyyy\nmov oT0.xy, r10.xy\nmov oT1.x, r10.z"));
}

// ---- ps_1_1 – ps_1_3 -------------------------------------------------------------

TEST(ValidatorPs11, ArithmeticSlots) {
  std::string eight = "ps_1_1\ntex t0\n";
  for (int i = 0; i < 8; ++i) eight += "mul r0, t0, t0\n";
  EXPECT_TRUE(isValid(eight));
  EXPECT_TRUE(hasError(eight + "mul r0, r0, t0\n", "ps_1_1 allows 8 arithmetic instructions, this shader has 9"));
  // A co-issued pair takes one slot: 7 + 1 pair = 8.
  std::string paired = "ps_1_1\ntex t0\n";
  for (int i = 0; i < 7; ++i) paired += "mul r0, t0, t0\n";
  EXPECT_TRUE(isValid(paired + "mul r0.rgb, r0, t0\n+mov r0.a, t0\n"));
}

TEST(ValidatorPs11, TextureSlots) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntex t1\ntex t2\ntex t3\nmov r0, t3"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\ntex t2\ntex t3\ntex t4\nmov r0, t3",
                       "ps_1_1 allows 4 texture instructions, this shader has 5"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t4\nmov r0, t4", "t4 is out of range: ps_1_1 has 4 texture registers (t0..t3)"));
}

TEST(ValidatorPs11, InstructionOrder) {
  EXPECT_TRUE(isValid("ps_1_1\ndef c0, 1, 0, 0, 1\ntex t0\nmul r0, t0, c0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ndef c0, 1, 0, 0, 1\nmul r0, t0, c0",
                       "def must come before all other instructions in ps_1_1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0\ntex t1\nmul r0, r0, t1",
                       "tex follows an arithmetic instruction; ps_1_1 needs all texture instructions first"));
}

TEST(ValidatorPs11, TextureRegisterOrder) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t1\ntex t0\nmul r0, t0, t1",
                       "texture instructions must use t registers in increasing order: t0 comes after t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t0\nmov r0, t0", "t0 is already the destination of a texture instruction"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntexbem t1, t0\nmov r0, t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t1\ntexbem t2, t0\nmov r0, t2", "t0 is read by texbem before a texture instruction writes it"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\ntexbem t1, t1\nmov r0, t1",
                       "texbem t1, t1: the source must be a lower t register than the destination"));
}

TEST(ValidatorPs11, MatrixSequences) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntexm3x3pad t1, t0_bx2\ntexm3x3pad t2, t0_bx2\ntexm3x3tex t3, t0_bx2\nmov r0, t3"));
  EXPECT_TRUE(isValid("ps_1_1\ndef c0, 0, 0, 1, 0\ntex t0\ntexm3x3pad t1, t0_bx2\ntexm3x3pad t2, t0_bx2\n"
                      "texm3x3spec t3, t0_bx2, c0\nmov r0, t3"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2pad t1, t0\nmov r0, t0",
                       "texm3x2pad t1, t0 must be followed by texm3x2tex t2, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2tex t1, t0\nmov r0, t1", "texm3x2tex must follow texm3x2pad"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\ntexm3x2pad t2, t0\ntexm3x2tex t3, t1\nmov r0, t3",
                       "texm3x2pad t2, t0 must be followed by texm3x2tex t3, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x3pad t1, t0\ntexm3x3tex t2, t0\nmov r0, t2",
                       "texm3x3pad t1, t0 must be followed by a second texm3x3pad t2, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\nmov r0, t0",
                       "texm3x3pad t2, t0 must be followed by texm3x3tex, texm3x3spec, texm3x3vspec t3, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x3tex t1, t0\nmov r0, t1", "texm3x3tex must follow two texm3x3pad instructions"));
  // The pad destination holds no data.
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2pad t1, t0\ntexm3x2tex t2, t0\nmul r0, t2, t1",
                       "t1 holds no data after texm3x2pad/texm3x3pad/texm3x2depth and cannot be read"));
  // texm3x2depth exists from ps_1_3 on.
  std::string depth = "tex t0\ntexm3x2pad t1, t0\ntexm3x2depth t2, t0\nmov r0, t0";
  EXPECT_TRUE(isValid("ps_1_3\n" + depth));
  EXPECT_TRUE(hasError("ps_1_2\n" + depth, "texm3x2depth is not a ps_1_2 instruction"));
}

TEST(ValidatorPs11, TexbemSourceIsReservedForTexbem) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntexbem t1, t0\ntexbem t2, t0\nadd r0, t1, t2"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexbem t1, t0\nadd r0, t1, t0",
                       "t0 was read by texbem/texbeml and can afterwards be read only by texbem/texbeml"));
}

TEST(ValidatorPs11, TextureSourceModifiers) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexbem t1, t0_bx2\nmov r0, t1", "_bx2 is not allowed on the source of texbem in ps_1_1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexreg2ar t1, t0_bx2\nmov r0, t1", "_bx2 is not allowed on the source of texreg2ar"));
  EXPECT_TRUE(isValid("ps_1_2\ntex t0\ntexdp3 t1, t0_bx2\nmov r0, t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2pad t1, t0_bias\ntexm3x2tex t2, t0\nmov r0, t2",
                       "texm3x2pad sources take no modifier other than _bx2"));
  EXPECT_TRUE(hasError("ps_1_1\ntex_sat t0\nmov r0, t0", "tex cannot take _sat"));
}

TEST(ValidatorPs11, Selectors) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmul r0, t0, t0.a"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmov r0.rgb, t0\n+mov r0.a, t0.b"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0.b", "the .b selector is allowed in ps_1_1 only on instructions that write .a"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0.g", "ps_1_1 source selectors are .a and .b (replicate)"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0, r0.g"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r0, r0.yxzw", "ps_1_4 source selectors are .r, .g, .b and .a"));
}

TEST(ValidatorPs11, WriteMasks) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmov r0.rgb, t0\nmov r0.a, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0\nmov r0.rg, t0", "ps_1_1 write masks are .rgba, .rgb and .a; .xy is not allowed"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0\ndp3 r0.a, t0, t0", "dp3 in ps_1_1 writes .rgb or .rgba"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0.rg, r0"));
}

TEST(ValidatorPs11, Coissue) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0.rgb, t0\n+mov r0.rgb, t0",
                       "a co-issued pair writes .rgb in one instruction and .a in the other; these write .xyz and .xyz"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\n+mov r0.a, t0\nmov r0.rgb, t0",
                       "co-issued mov (+) must follow an arithmetic instruction it pairs with"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\n+tex t1\nmov r0, t0", "tex cannot be co-issued (+); only arithmetic instructions pair"));
  EXPECT_TRUE(hasError("ps_1_2\ntex t0\ndp4 r0.rgb, t0, t0\n+mov r0.a, t0", "dp4 cannot be co-issued"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ndp3 r0.rgb, t0, t0\n+mov r0.a, t0"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r1.rgb, r0\n+dp3 r1.a, r0, r0\nmov r0, r1",
                       "dp3 can be co-issued only as the color (.rgb) half"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0.rg, r0\n+mov r0.a, r0"));
  EXPECT_TRUE(hasError(readRaw("vs_1_1\nmov oPos, v0\n+mov oD0, v0"), "co-issue (+) exists only in ps_1_1 - ps_1_4, not in vs_1_1"));
}

TEST(ValidatorPs11, DefRange) {
  EXPECT_TRUE(isValid("ps_1_1\ndef c0, -1.0, 0.5, 1.0, 0\nmov r0, c0"));
  EXPECT_TRUE(hasError("ps_1_1\ndef c0, 1.5, 0, 0, 0\nmov r0, c0", "def c0: 1.5 is outside [-1, 1], the range of ps_1_1 constants"));
  EXPECT_TRUE(hasError("ps_1_4\ndef c0, 0, -2, 0, 0\nmov r0, c0", "def c0: -2 is outside [-1, 1], the range of ps_1_4 constants"));
  EXPECT_TRUE(isValid("ps_2_0\ndef c0, 1.5, 0, 0, 0\nmov oC0, c0"));
}

TEST(ValidatorPs11, ReadPorts) {
  EXPECT_TRUE(isValid("ps_1_1\nmad r0, c0, c1, v0"));
  EXPECT_TRUE(hasError("ps_1_1\nmad r0, c0, c1, c2",
                       "ps_1_1 reads at most 2 different constant registers in one instruction, mad reads 3 (c0, c1, c2)"));
  std::string threeT = "tex t0\ntex t1\ntex t2\nmad r0, t0, t1, t2";
  EXPECT_TRUE(hasError("ps_1_1\n" + threeT, "ps_1_1 reads at most 2 different texture registers in one instruction, mad reads 3"));
  EXPECT_TRUE(isValid("ps_1_2\n" + threeT));
}

TEST(ValidatorPs11, InstructionAvailability) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ndp4 r0, t0, t0", "dp4 is not a ps_1_1 instruction"));
  EXPECT_TRUE(isValid("ps_1_2\ntex t0\ndp4 r0, t0, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexreg2rgb t1, t0\nmov r0, t1", "texreg2rgb is not a ps_1_1 instruction"));
  EXPECT_TRUE(hasError("ps_1_1\nrcp r0, v0", "rcp is not a ps_1_1 instruction"));
  EXPECT_TRUE(hasError(readRaw("ps_1_1\ntex t0\ntexm3x3diff t1, t0\nmov r0, t0"), "texm3x3diff is a reserved opcode"));
}

TEST(ValidatorPs11, CmpAndDp4Limits) {
  // ps_1_2: cmp 2 slots, at most 3; dp4 2 slots, at most 4.
  std::string three = "ps_1_2\ndef c0, 1, 1, 1, 1\ntex t0\ncmp r0, t0, c0, -c0\ncmp r1, r0, c0, -c0\ncmp r0, r1, c0, -c0\n";
  EXPECT_TRUE(isValid(three));
  EXPECT_TRUE(hasError(three + "cmp r1, r0, c0, -c0\nmov r0, r1", "ps_1_2 allows 3 cmp instructions per shader"));
  EXPECT_TRUE(hasError(three + "mov r1, r0\nmov r0, r1\nmov r1, r0", "ps_1_2 allows 8 arithmetic instructions, this shader has 9"));
  EXPECT_TRUE(hasError("ps_1_2\ntex t0\ncmp r0, t0, r0, t0", "cmp in ps_1_2 cannot write a register it reads (r0)"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\ncmp r0, r0, r0, r0"));
}

TEST(ValidatorPs11, UninitialisedReads) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, r1", "r1 is read before it is written"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r1.rgb, t0\nmov r0, r1", "r1.w is read before it is written"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmov r1.rgb, t0\nmov r0.rgb, r1\n+mov r0.a, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmul r0, t0, t3", "t3 is read before it is written (no texture instruction writes it)"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r1, t0", "ps_1_1 never writes r0, the pixel color"));
}

TEST(ValidatorPs11, InstructionModifiers) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmul_x4 r0, t0, t0\nmul_d2_sat r0, r0, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmul_x8 r0, t0, t0", "_x8 is not available in ps_1_1"));
  EXPECT_TRUE(hasError("ps_1_3\ntex t0\nmul_d4 r0, t0, t0", "_d4 is not available in ps_1_3"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmul_x8 r0, r0, r0\nmul_d8 r0, r0, r0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmul_pp r0, t0, t0", "_pp is not available in ps_1_1"));
}

TEST(ValidatorPs11, SourceModifiers) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmad r0, t0_bias, -t0_bx2, 1-t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0_x2", "source modifier _x2 is not available in ps_1_1"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0, r0_x2"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nadd r0, r0, -c0", "source modifiers on constants are not allowed in ps_1_4 (c0)"));
}

TEST(ValidatorPs11, Cnd) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntex t1\nmov r0, t0\ncnd r0, r0.a, t0, t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\nmov r1, t0\ncnd r0, r1.a, t0, t1", "cnd in ps_1_1 takes r0.a as its first source"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\ntexld r1, t1\ncnd r0, r1, r0, r1"));
}

// ---- ps_1_4 ----------------------------------------------------------------------

TEST(ValidatorPs14, SlotsPerPhase) {
  std::string p1 = "ps_1_4\ntexld r0, t0\n";
  for (int i = 0; i < 8; ++i) p1 += "mul r0, r0, r0\n";
  std::string p2 = "phase\ntexld r1, t1\n";
  for (int i = 0; i < 8; ++i) p2 += "mul r0, r1, r1\n";
  EXPECT_TRUE(isValid(p1 + p2));  // 16 arithmetic instructions in two phases
  EXPECT_TRUE(hasError(p1 + p2 + "mul r0, r0, r1\n", "ps_1_4 allows 8 arithmetic instructions per phase, phase 2 has 9"));
  EXPECT_TRUE(hasError(p1 + "mul r0, r0, r0\n" + p2, "ps_1_4 allows 8 arithmetic instructions per phase, phase 1 has 9"));
  std::string tex = "ps_1_4\ntexld r0, t0\ntexld r1, t1\ntexld r2, t2\ntexld r3, t3\ntexld r4, t4\ntexld r5, t5\n";
  EXPECT_TRUE(isValid(tex + "mov r0, r5"));
  EXPECT_TRUE(hasError(tex + "texkill t0\nmov r0, r5", "ps_1_4 allows 6 texture instructions per phase, phase 2 has 7"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r0, t1\nmov r0, r0",
                       "r0 is already the destination of a texture instruction in this phase"));
}

TEST(ValidatorPs14, Phases) {
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r1, r0\ntexld r2, t2\nmov r0, r2",
                       "texld follows an arithmetic instruction; in each ps_1_4 phase the texture instructions come first"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nphase\ntexld r1, t1\nphase\nmov r0, r1", "ps_1_4 allows one phase instruction"));
  // texld from r#: phase 2 only, coordinates written in phase 1.
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r1, r0\nmov r0, r1",
                       "texld reads r0, but r registers are texld coordinates only in phase 2 (after the phase marker)"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nphase\ntexld r1, r2\nmov r0, r1",
                       "r2.xyz used as texld coordinates must be written in phase 1"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r0.rgb, t0\nphase\ntexcrd r1.rgb, r0\nmov r0, r1", "texcrd reads only t registers"));
  // Color inputs arrive in phase 2.
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmul r0, r0, v0\nphase\ntexld r1, r0\nmov r0, r1",
                       "v0 cannot be read in phase 1 of ps_1_4"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0, r0\nphase\ntexld r1, r0\nmul r0, r1, v0"));
  // The alpha of temporaries is lost at the phase marker.
  EXPECT_TRUE(hasError("ps_1_4\ntexld r1, t0\nphase\nmov r0, r1.a",
                       "r1.a is read in phase 2 but the alpha of temporaries is lost at the phase marker"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r1, t0\nphase\nmov r0, r1.b"));
}

TEST(ValidatorPs14, TextureRegisters) {
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nadd r0, r0, t1", "t1 can be read only by texld and texcrd in ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov t0, r0\nmov r0, r0", "t0 is read-only in ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld t0, t0\nmov r0, r0", "texld writes an r register in ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0.xyz\ntexld r1, t0.xyw\nadd r0, r0, r1",
                       "t0 is read with both .xyz and .xyw; every read of one t register uses the same selector"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0.xyw\ntexcrd r1.rg, t0_dw.xyw\nadd r0.rg, r0, r1"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0.yxz\nmov r0, r0", "texld sources take the .xyz or .xyw selector only"));
}

TEST(ValidatorPs14, DivideModifiers) {
  std::string ok = "ps_1_4\ntexcrd r0.rgb, t0\ntexcrd r1.rgb, t1\ntexcrd r2.rgb, t2\nphase\n";
  EXPECT_TRUE(isValid(ok + "texld r3, r0_dz\ntexld r4, r1_dz.xyz\nadd r0, r3, r4"));
  EXPECT_TRUE(hasError(ok + "texld r3, r0_dz\ntexld r4, r1_dz\ntexld r5, r2_dz\nadd r0, r3, r4",
                       "ps_1_4 allows _dz at most twice per shader"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0_dz\nmov r0, r0", "_dz applies to r registers; t registers take _dw"));
  EXPECT_TRUE(hasError(ok + "texld r3, r0_dw\nmov r0, r3", "_dw applies to t registers; r registers take _dz"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r0, r0_dz", "_dz/_dw apply only to texld and texcrd sources"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r0.rgb, t0_dw.xyw\nmov r0, r0", "texcrd with _dw writes .rg only"));
}

TEST(ValidatorPs14, TexdepthAndBem) {
  EXPECT_TRUE(isValid("ps_1_4\ntexcrd r5.rgb, t0\nphase\ntexdepth r5\nmov r0, c0"));
  // texkill reads its operand (encoded as a destination): read-only t# are fine.
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\ntexkill t1\nmov r0, r0"));
  EXPECT_TRUE(isValid("ps_2_0\ndcl t1\ntexkill t1\nmov oC0, t1"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl t1\ntexkill r0\nmov oC0, t1", "r0 is read before it is written"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r4.rgb, t0\nphase\ntexdepth r4\nmov r0, c0", "texdepth works only on r5"));
  // A ps_1_4 shader without `phase` is all phase 2 (registers-and-limits.md), so
  // texdepth is allowed there; in phase 1 of a two-phase shader it is not.
  EXPECT_TRUE(isValid("ps_1_4\ntexcrd r5.rgb, t0\ntexdepth r5\nmov r0, c0"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r5.rgb, t0\ntexdepth r5\nphase\nmov r0, c0",
                       "texdepth is available only in phase 2"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r1, t1\ntexcrd r2.rgb, t2\nbem r2.rg, r2, r1\nphase\ntexld r2, r2\nmov r0, r2"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r1, t1\nbem r2.rg, r0, r1\nmov r0, r2",
                       "bem is allowed only in phase 1 of ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r1, t1\nbem r2, r0, r1\nphase\nmov r0, r2", "bem writes .rg only"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r1, t1\nbem r2.rg, r0, r1\nbem r3.rg, r0, r1\nphase\nmov r0, r2",
                       "ps_1_4 allows 1 bem instruction per shader"));
}

// ---- vertex shaders --------------------------------------------------------------

TEST(ValidatorVs, SlotLimitsAndMacroCosts) {
  std::string body = "vs_1_1\nmov oPos, v0\n";
  for (int i = 0; i < 31; ++i) body += "m4x4 r0, v0, c0\n";  // 1 + 31*4 = 125
  EXPECT_TRUE(isValid(body + "frc r1.xy, v0\n"));               // + 3 = 128
  EXPECT_TRUE(hasError(body + "frc r1.xy, v0\nmov r2, v0\n", "vs_1_1 allows 128 instruction slots, this shader uses 129"));
  std::string exps = "vs_1_1\nmov oPos, v0\n";
  for (int i = 0; i < 13; ++i) exps += "exp r0, v0.x\n";  // exp is a 10-slot macro in vs_1_1
  EXPECT_TRUE(hasError(exps, "vs_1_1 allows 128 instruction slots, this shader uses 131"));
  std::string vs20 = "vs_2_0\ndcl_position v0\nmov oPos, v0\n";
  for (int i = 0; i < 13; ++i) vs20 += "exp r0, v0.x\n";  // 1 slot in vs_2_0
  EXPECT_TRUE(isValid(vs20));
}

TEST(ValidatorVs, AddressRegister) {
  EXPECT_TRUE(isValid("vs_1_1\nmov a0.x, v1.x\nmov oPos, c[a0.x + 3]"));
  EXPECT_TRUE(hasError("vs_1_1\nmov a0.xy, v1\nmov oPos, c[a0.x + 3]", "vs_1_1 writes a0 only with mov a0.x"));
  EXPECT_TRUE(hasError("vs_1_1\nmova a0.x, v1\nmov oPos, v0", "mova is not a vs_1_1 instruction"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, c[a0.x + 3]", "a0.x is used as an index before it is written"));
  EXPECT_TRUE(hasError(readRaw("vs_1_1\nmov a0.x, v1.x\nmov oPos, c[a0.y + 3]"), "vs_1_1 indexes constants only with a0.x"));
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\nmova a0.y, v0.x\nmov oPos, c[a0.y + 3]"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov a0.x, v0.x\nmov oPos, c[a0.x]", "vs_2_0 writes a0 only with mova"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, a0", "a0 cannot be read in vs_1_1"));
  EXPECT_TRUE(hasError(readRaw("ps_2_0\ndcl t0\nmov oC0, c[a0.x + 1]"), "relative addressing is not available for constant registers in ps_2_0"));
}

TEST(ValidatorVs, RegisterCounts) {
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, c96", "c96 is out of range: vs_1_1 has 96 constant registers (c0..c95)"));
  ValidationCaps dx81;
  dx81.maxVertexShaderConst = 192;
  EXPECT_TRUE(isValid("vs_1_1\nmov oPos, c96", dx81));
  EXPECT_TRUE(hasError("vs_1_1\nmov r12, v0\nmov oPos, r12", "r12 is out of range: vs_1_1 has 12 temporary registers (r0..r11)"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, v0\nmov oT8, v0", "oT8 is out of range: vs_1_1 has 8 texture coordinate output registers"));
  ValidationCaps temps;
  temps.vs2xTemps = 32;
  EXPECT_TRUE(isValid("vs_2_x\ndcl_position v0\nmov r20, v0\nmov oPos, r20", temps));
  EXPECT_TRUE(hasError("vs_2_x\ndcl_position v0\nmov r20, v0\nmov oPos, r20", "r20 is out of range: vs_2_x has 12 temporary registers"));
  EXPECT_TRUE(hasError("vs_1_1\nmov v0, c0\nmov oPos, v0", "v0 is read-only in vs_1_1"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, oD0", "oD0 cannot be read in vs_1_1"));
  EXPECT_TRUE(hasError(readRaw("vs_1_1\nmov oPos, v0\nmov oC0, v0"), "oC0 is not a vs_1_1 register"));
}

TEST(ValidatorVs, PositionOutput) {
  EXPECT_TRUE(isValid("vs_1_1\nmov oPos.xy, v0\nmov oPos.zw, v1"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos.xyz, v0", "a vs_1_1 shader must write all four components of oPos (.w is never written)"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oD0, v0", "must write all four components of oPos"));
}

TEST(ValidatorVs, Declarations) {
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\ndcl_texcoord0 v1\nmov oPos, v0\nmov oT0, v1"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov oPos, v0\nmov oT0, v1", "v1 is read but not declared (dcl)"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov oPos, v0\ndcl_texcoord0 v1\nmov oT0, v1",
                       "dcl must come before the first arithmetic, texture or flow-control instruction"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\ndcl_normal v0\nmov oPos, v0", "v0 is declared twice"));
  EXPECT_TRUE(isValid("vs_1_1\nmov oPos, v0\nmov oT0, v7"));  // D3D8 vertex declarations: no dcl
  EXPECT_TRUE(hasError("vs_1_1\ndcl_position v0\nmov oPos, v0\nmov oT0, v7", "v7 is read but not declared (dcl)"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position oPos\nmov oPos, c0", "dcl cannot declare oPos in vs_2_0"));
  // vs_3_0 outputs are declared, one of them as the position.
  EXPECT_TRUE(isValid("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1.xy\nmov o0, v0\nmov o1.xy, v0"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\nmov o1, v0", "o1 is written but not declared"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_texcoord0 o0\nmov o0, v0", "vs_3_0 must declare a position output (dcl_position o#)"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1.xy\nmov o0, v0\nmov o1, v0",
                       "o1.zw is written but only o1.xy is declared"));
}

TEST(ValidatorVs, ReadPortsAndSwizzles) {
  EXPECT_TRUE(isValid("vs_1_1\nmad oPos, c0, c1, c2"));  // constants: no port limit in vs_1_1 (reference table)
  EXPECT_TRUE(hasError("vs_2_0\nmad oPos, c0, c1, c2",
                       "vs_2_0 reads at most 2 different constant registers in one instruction, mad reads 3"));
  EXPECT_TRUE(isValid("vs_1_1\nrcp r0, v0\nmov oPos, r0"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nrcp r0, v0\nmov oPos, r0",
                       "rcp needs a replicate swizzle (.x, .y, .z or .w) on its source"));
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\nrcp r0, v0.w\nmov oPos, r0"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\npow r0, v0.x, v0\nmov oPos, r0", "pow needs a replicate swizzle (.x, .y, .z or .w) on its second source"));
}

TEST(ValidatorVs, Saturate) {
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov_sat oPos, v0", "_sat is not available in vs_2_0"));
  EXPECT_TRUE(isValid("vs_3_0\ndcl_position v0\ndcl_position o0\nmov_sat o0, v0"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\nfrc_sat r0, v0\nmov o0, r0", "frc cannot take _sat"));
}

TEST(ValidatorVs, InstructionForms) {
  EXPECT_TRUE(hasError("vs_1_1\nfrc r0.x, v0\nmov oPos, v0", "frc in vs_1_1 writes .y or .xy"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nm4x4 oPos, v0, c0.yxzw", "m4x4 takes no swizzle or modifier on the matrix operand"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nm3x3 r0.xyzw, v0, c0\nmov oPos, r0", "m3x3 writes .xyz"));
  // Without a mask (as the DirectX 8 shaders write it) m3x3 writes the .xyz it computes.
  EXPECT_TRUE(isValid("vs_1_1\nm3x3 r0, v0, c0\nmov r0.w, v0.w\nmov oPos, r0"));
  EXPECT_TRUE(hasError("vs_1_1\nm4x4 oPos, v0, c94", "m4x4 reads c94..c97 but vs_1_1 has 96 constant registers"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nsincos r0.xy, v0.x, c0, c0\nmov oPos, v0",
                       "sincos in vs_2_0 takes two different constant registers"));
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\nsincos r0.xy, v0.x, c0, c1\nmov oPos, v0"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\nsincos r0.xyz, v0.x\nmov o0, v0", "sincos writes .x, .y or .xy"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\ncrs r0.xyzw, v0, v0\nmov oPos, v0", "crs writes a subset of .xyz"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov r0, v0\nnrm r0, r0\nmov oPos, r0", "nrm cannot write the register it reads"));
}

// ---- flow control ----------------------------------------------------------------

const char* kVs20Head = "vs_2_0\ndefi i0, 3, 0, 1, 0\ndefb b0, true\ndcl_position v0\nmov oPos, v0\n";

TEST(ValidatorFlow, Nesting) {
  std::string h = kVs20Head;
  EXPECT_TRUE(isValid(h + "rep i0\nadd r0, v0, c0\nendrep"));
  EXPECT_TRUE(hasError(h + "rep i0\nrep i0\nendrep\nendrep", "vs_2_0 allows rep/loop nesting depth 1, this rep is at depth 2"));
  std::string v3 = "vs_3_0\ndefi i0, 3, 0, 1, 0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n";
  std::string four = "rep i0\nrep i0\nrep i0\nrep i0\nendrep\nendrep\nendrep\nendrep\n";
  EXPECT_TRUE(isValid(v3 + four));
  EXPECT_TRUE(hasError(v3 + "rep i0\n" + four + "endrep\n", "vs_3_0 allows rep/loop nesting depth 4, this rep is at depth 5"));
  std::string ifs, ends;
  for (int i = 0; i < 25; ++i) ifs += "if b0\n", ends += "endif\n";
  EXPECT_TRUE(hasError("vs_3_0\ndefb b0, true\ndcl_position v0\ndcl_position o0\nmov o0, v0\n" + ifs + ends,
                       "vs_3_0 allows if nesting depth 24, this if is at depth 25"));
  std::string dyn, dynEnd;
  for (int i = 0; i < 25; ++i) dyn += "if_gt v0.x, c0.x\n", dynEnd += "endif\n";
  EXPECT_TRUE(hasError(v3 + dyn + dynEnd, "vs_3_0 allows dynamic flow-control nesting depth 24, this if_comp is at depth 25"));
  ValidationCaps shallow;
  shallow.staticFlowControlDepth = 1;
  std::string v2x = "vs_2_x\ndefi i0, 3, 0, 1, 0\ndcl_position v0\nmov oPos, v0\n";
  EXPECT_TRUE(isValid(v2x + "rep i0\nrep i0\nendrep\nendrep"));
  EXPECT_TRUE(hasError(v2x + "rep i0\nrep i0\nendrep\nendrep", "vs_2_x allows rep/loop nesting depth 1", shallow));
}

TEST(ValidatorFlow, StaticFlowCount) {
  std::string s = kVs20Head;
  for (int i = 0; i < 16; ++i) s += "if b0\nendif\n";
  EXPECT_TRUE(isValid(s));
  EXPECT_TRUE(hasError(s + "if b0\nendif\n", "vs_2_0 allows 16 static flow-control instructions"));
}

TEST(ValidatorFlow, Matching) {
  std::string h = kVs20Head;
  EXPECT_TRUE(hasError(h + "endif", "endif without if"));
  EXPECT_TRUE(hasError(h + "rep i0\nendif\nendrep", "endif without if (the open block is rep)"));
  EXPECT_TRUE(hasError(h + "if b0\nendrep", "endrep without rep (the open block is if)"));
  EXPECT_TRUE(hasError(h + "rep i0\nmov r0, v0", "rep is never closed with endrep"));
  EXPECT_TRUE(hasError(h + "if b0\nelse\nelse\nendif", "if has a second else"));
  EXPECT_TRUE(hasError(h + "else\nendif", "else without if"));
  EXPECT_TRUE(isValid(h + "if b0\nmov r0, v0\nelse\nmov r0, c0\nendif\nmov oD0, r0"));
  EXPECT_TRUE(hasError(h + "loop aL, i0\nendrep", "endrep without rep (the open block is loop)"));
}

TEST(ValidatorFlow, LoopOperandsAndBreak) {
  std::string h = kVs20Head;
  EXPECT_TRUE(isValid(h + "loop aL, i0\nadd r0, v0, c[aL + 2]\nendloop"));
  EXPECT_TRUE(hasError(h + "loop i0, i0\nendloop", "loop takes aL and an integer constant (loop aL, i#)"));
  EXPECT_TRUE(hasError(h + "rep b0\nendrep", "rep takes an integer constant (rep i#)"));
  EXPECT_TRUE(hasError(h + "add r0, v0, c[aL + 2]", "aL is used outside a loop"));
  std::string x = "vs_2_x\ndefi i0, 3, 0, 1, 0\ndcl_position v0\nmov oPos, v0\n";
  EXPECT_TRUE(isValid(x + "rep i0\nbreak\nendrep"));
  EXPECT_TRUE(hasError(x + "break", "break outside a rep or loop block"));
  EXPECT_TRUE(hasError(h + "rep i0\nbreak\nendrep", "break is not a vs_2_0 instruction"));
}

TEST(ValidatorFlow, Subroutines) {
  std::string h = kVs20Head;
  EXPECT_TRUE(isValid(h + "call l0\nmov oD0, r0\nret\nlabel l0\nmov r0, c0\nret"));
  EXPECT_TRUE(hasError(h + "call l1\nret\nlabel l0\nret", "call to l1: the shader has no label l1"));
  EXPECT_TRUE(hasError(h + "call l0\nret\nmov r0, v0\nlabel l0\nret", "label l0 must directly follow a ret"));
  EXPECT_TRUE(hasError(h + "call l0\nret\nlabel l0\ncall l1\nret\nlabel l1\nret",
                       "vs_2_0 allows call nesting depth 1, this shader nests calls 2 deep"));
  EXPECT_TRUE(isValid("vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\ncall l0\nret\nlabel l0\ncall l1\nret\nlabel l1\nret"));
  EXPECT_TRUE(hasError(h + "call l0\nret\nlabel l0\nmov r0, v0", "subroutine l0 does not end with ret"));
  EXPECT_TRUE(hasError(h + "callnz l0, i0\nret\nlabel l0\nret", "callnz takes a b# or p0 condition"));
}

TEST(ValidatorFlow, Predication) {
  std::string v3 = "vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n";
  EXPECT_TRUE(isValid(v3 + "setp_gt p0, v0, c0\n(p0) add r0, v0, c0\n(!p0.x) mov r0, c1"));
  EXPECT_TRUE(hasError(v3 + "(p0) add r0, v0, c0", "p0 is read before it is written (setp)"));
  EXPECT_TRUE(hasError(std::string(kVs20Head) + "(p0) add r0, v0, c0", "predication (p0) is not available in vs_2_0"));
  EXPECT_TRUE(hasError(v3 + "mov p0, c0", "p0 is written only by setp"));
}

// ---- ps_2_0 / ps_2_x / ps_3_0 ----------------------------------------------------

TEST(ValidatorPs20, Slots) {
  std::string s = "ps_2_0\ndcl t0\ndcl_2d s0\n";
  for (int i = 0; i < 32; ++i) s += "texld r0, t0, s0\n";
  for (int i = 0; i < 63; ++i) s += "add r1, r0, c0\n";
  s += "mov oC0, r1\n";
  EXPECT_TRUE(isValid(s));  // 32 texture + 64 arithmetic
  EXPECT_TRUE(hasError(s + "add r1, r0, c0\n", "ps_2_0 allows 64 arithmetic instruction slots, this shader uses 65"));
  std::string tex33 = "ps_2_0\ndcl t0\ndcl_2d s0\n";
  for (int i = 0; i < 33; ++i) tex33 += "texld r0, t0, s0\n";
  EXPECT_TRUE(hasError(tex33 + "mov oC0, r0\n", "ps_2_0 allows 32 texture instruction slots, this shader uses 33"));
  std::string x = "ps_2_x\ndcl t0\n";
  for (int i = 0; i < 96; ++i) x += "add r0, t0, c0\n";
  EXPECT_TRUE(hasError(x + "mov oC0, r0\n", "ps_2_x allows 96 instruction slots, this shader uses 97"));
  ValidationCaps big;
  big.ps2xInstructionSlots = 512;
  EXPECT_TRUE(isValid(x + "mov oC0, r0\n", big));
}

TEST(ValidatorPs20, Declarations) {
  EXPECT_TRUE(hasError("ps_2_0\ndcl t0\ntexld r0, t0, s0\nmov oC0, r0", "s0 is used before it is declared (dcl_2d, dcl_cube or dcl_volume)"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0", "t0 is read but not declared (dcl)"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl t0.xy\nmov r0, t0\nmov oC0, r0", "t0.zw is read but only t0.xy is declared"));
  EXPECT_TRUE(hasError("ps_1_1\ndcl t0\ntex t0\nmov r0, t0", "dcl is not a ps_1_1 instruction"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl s0\nmov oC0, c0", "dcl of s0 needs a texture type"));
  EXPECT_TRUE(isValid("ps_2_0\ndcl_centroid t0\nmov oC0, t0"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl t0\nmov r0, t0\nmov oC0, r0\ndcl v0", "dcl must come before"));
}

TEST(ValidatorPs20, Texld) {
  std::string h = "ps_2_0\ndcl t0\ndcl_2d s0\n";
  EXPECT_TRUE(isValid(h + "texld r0, t0, s0\nmov oC0, r0"));
  EXPECT_TRUE(hasError(h + "texld r0, t0.yxzw, s0\nmov oC0, r0", "texld coordinates take no swizzle or modifier in ps_2_0"));
  EXPECT_TRUE(hasError(h + "texld r0.xy, t0, s0\nmov oC0, r0", "texld in ps_2_0 writes the full .xyzw mask"));
  EXPECT_TRUE(hasError(h + "texld r0, t0, c0\nmov oC0, r0", "texld samples through an s register"));
  EXPECT_TRUE(hasError(h + "texld_sat r0, t0, s0\nmov oC0, r0", "texld cannot take _sat"));
  // Dependent reads: four levels allowed.
  std::string chain = h + "texld r0, t0, s0\ntexld r1, r0, s0\ntexld r2, r1, s0\ntexld r3, r2, s0\n";
  EXPECT_TRUE(isValid(chain + "mov oC0, r3"));
  EXPECT_TRUE(hasError(chain + "texld r4, r3, s0\nmov oC0, r4",
                       "ps_2_0 allows 4 levels of dependent texture reads, this texld is level 5"));
  ValidationCaps noLimit;
  noLimit.ps2xNoDependentReadLimit = true;
  std::string chainX = "ps_2_x\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\ntexld r1, r0, s0\ntexld r2, r1, s0\n"
                       "texld r3, r2, s0\ntexld r4, r3, s0\nmov oC0, r4";
  EXPECT_TRUE(isValid(chainX, noLimit));
  EXPECT_TRUE(hasError(chainX, "ps_2_x allows 4 levels of dependent texture reads"));
}

TEST(ValidatorPs20, ModifiersAndSwizzles) {
  std::string h = "ps_2_0\ndcl t0\n";
  EXPECT_TRUE(hasError(h + "mov r0, t0_bias\nmov oC0, r0", "source modifier _bias is not available in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov r0, t0_bx2\nmov oC0, r0", "source modifier _bx2 is not available in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov r0, t0_abs\nmov oC0, r0", "source modifier _abs is not available in ps_2_0"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0_abs\nmov oC0, r0"));
  EXPECT_TRUE(hasError(readRaw(h + "mul_x2 r0, t0, t0\nmov oC0, r0"), "_x2 is not available in ps_2_0"));
  EXPECT_TRUE(isValid(h + "mul_pp r0, t0, t0.yzxw\nmov oC0, r0"));
  EXPECT_TRUE(hasError(h + "mov r0, t0.yxzw\nmov oC0, r0", "ps_2_0 allows the swizzles .xyzw, replicate, .yzxw, .zxyw and .wzyx only"));
  ValidationCaps arb;
  arb.ps2xArbitrarySwizzle = true;
  EXPECT_TRUE(isValid("ps_2_x\ndcl t0\nmov r0, t0.yxzw\nmov oC0, r0", arb));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0.yxzw\nmov oC0, r0"));
}

TEST(ValidatorPs20, ColorOutputs) {
  std::string h = "ps_2_0\ndcl t0\n";
  EXPECT_TRUE(hasError(h + "mov r0, t0", "ps_2_0 must write oC0"));
  EXPECT_TRUE(hasError(h + "add oC0, t0, t0", "oC0 is written only by mov in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov_sat oC0, t0", "oC0 cannot be written with _sat in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov oC0, t0\nmov oC0, t0", "oC0 is written more than once"));
  EXPECT_TRUE(hasError(h + "mov oC0.xyz, t0", "oC0 is written with the full mask in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov oC0, t0\nmov oC2, t0", "oC2 is written but oC1 is not"));
  EXPECT_TRUE(hasError(h + "mov oC0, -t0", "mov to oC0 takes no source swizzle or modifier in ps_2_0"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nadd_sat oC0, v0, v0\nmul oC0.x, v0, c0"));
}

// oDepth takes one scalar: a replicate swizzle selects it (fxc writes mov oDepth, r0.x),
// any other swizzle and any modifier are errors, as for oCn.
TEST(ValidatorPs20, DepthOutputSwizzle) {
  for (std::string h : {"ps_2_0\ndcl t0\n", "ps_2_x\ndcl t0\n"}) {
    const std::string ver = h.substr(0, 6);
    for (const char* rep : {"x", "y", "z", "w", "r", "a"})
      EXPECT_TRUE(isValid(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0." + rep)) << ver << " ." << rep;
    EXPECT_TRUE(isValid(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0"));
    const std::string msg = "mov to oDepth takes no source modifier and no swizzle but .x .y .z .w in " + ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0.xy", msg)) << ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0.yx", msg)) << ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0.yzxw", msg)) << ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, -r0.x", msg)) << ver;
    // oCn keeps its rule: no swizzle at all.
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0.x", "mov to oC0 takes no source swizzle or modifier in " + ver));
  }
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.x"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.w"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0"));
  EXPECT_TRUE(hasError("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.xy",
                       "mov to oDepth takes no swizzle but .x .y .z .w in ps_3_0"));
  EXPECT_TRUE(hasError("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.yx",
                       "mov to oDepth takes no swizzle but .x .y .z .w in ps_3_0"));
}

TEST(ValidatorPs20, FlowControlAvailability) {
  EXPECT_TRUE(hasError("ps_2_0\ndefi i0, 2, 0, 0, 0\nrep i0\nendrep\nmov oC0, c0", "defi is not a ps_2_0 instruction"));
  EXPECT_TRUE(hasError("ps_2_0\nrep i0\nendrep\nmov oC0, c0", "rep is not a ps_2_0 instruction"));
  std::string x = "ps_2_x\ndefi i0, 2, 0, 0, 0\nrep i0\nadd r0, c0, c0\nendrep\nmov oC0, r0";
  EXPECT_TRUE(isValid(x));
  ValidationCaps none;
  none.ps2xFlowControl = false;
  EXPECT_TRUE(hasError(x, "rep in ps_2_x needs a device that reports it", none));
  EXPECT_TRUE(hasError("ps_2_x\ndefi i0, 2, 0, 0, 0\nloop aL, i0\nendloop\nmov oC0, c0", "loop is not a ps_2_x instruction"));
  EXPECT_TRUE(isValid("ps_3_0\ndefi i0, 2, 0, 0, 0\ndcl_texcoord0 v0\nloop aL, i0\nadd r0, v[aL], c0\nendloop\nmov oC0, r0"));
}

TEST(ValidatorPs20, Ps30OutputsInDynamicFlow) {
  std::string h = "ps_3_0\ndcl_texcoord0 v0\n";
  EXPECT_TRUE(hasError(h + "if_gt v0.x, c0.x\nmov oC0, v0\nendif",
                       "oC0 cannot be written inside dynamic flow control or predicated"));
  EXPECT_TRUE(isValid(h + "defb b0, true\nmov oC0, c0\nif b0\nmov oC0, v0\nendif"));
}

// ---- slot counting ---------------------------------------------------------------

TEST(CountSlots, MacrosAndVersions) {
  auto slots = [](const std::string& text) { return countSlots(read(text)); };
  // vs_1_1: m4x4 = 4, exp = 10, frc = 3, lit = 1; def/dcl free.
  SlotCount a = slots("vs_1_1\ndef c0, 1, 1, 1, 1\nm4x4 oPos, v0, c0\nexp r0, v0.x\nfrc r1.xy, v0\nlit r2, v0");
  EXPECT_EQ(a.arithmetic, 4 + 10 + 3 + 1);
  EXPECT_EQ(a.texture, 0);
  // vs_2_0: exp = 1, frc = 1, lit = 3, sincos = 8, nrm = 3, m3x3 = 3, rep = 3 + endrep = 2.
  SlotCount b = slots("vs_2_0\ndcl_position v0\nexp r0, v0.x\nfrc r1, v0\nlit r2, v0\nsincos r3.xy, v0.x, c0, c1\n"
                      "nrm r4, v0\nm3x3 r5.xyz, v0, c0\nrep i0\nendrep");
  EXPECT_EQ(b.arithmetic, 1 + 1 + 3 + 8 + 3 + 3);
  EXPECT_EQ(b.flowControl, 3 + 2);
  // ps_1_1: 4 texture; co-issued pair = 1 arithmetic slot (RacorX10 SpecDot3).
  SlotCount c = slots("ps.1.1\ntex t0\ntex t1\ntexm3x2pad t2, t1_bx2\ntexm3x2tex t3, t1_bx2\n"
                      "mul r1.rgb, t3, t0\n+mul r1.a, t0.a, t3.a\nadd r0, r1.a, r1");
  EXPECT_EQ(c.texture, 4);
  EXPECT_EQ(c.arithmetic, 2);
  // ps_1_2: cmp and dp4 take 2 slots each; phase and def are free in ps_1_4.
  EXPECT_EQ(slots("ps_1_2\ntex t0\ncmp r0, t0, c0, c1\ndp4 r1, t0, t0").arithmetic, 4);
  SlotCount d = slots("ps_1_4\ndef c0, 0, 0, 0, 0\ntexld r0, t0\nmov r1, r0\nphase\ntexld r2, r1\nmul r0, r2, r0");
  EXPECT_EQ(d.texture, 2);
  EXPECT_EQ(d.arithmetic, 2);
  // ps_3_0 texture costs: texld 1 (4 on a cube), texldp 3, texldb 6, texldl 2, texkill 2.
  SlotCount e = slots("ps_3_0\ndcl_2d s0\ndcl_cube s1\ntexld r0, v0, s0\ntexld r0, v0, s1\ntexldp r0, v0, s0\n"
                      "texldb r0, v0, s0\ntexldl r0, v0, s0\ntexkill r0");
  EXPECT_EQ(e.texture, 1 + 4 + 3 + 6 + 2 + 2);
  // ps_2_0: texld = 1 whatever the sampler; predication adds a slot (vs_3_0).
  EXPECT_EQ(slots("ps_2_0\ndcl_cube s0\ntexld r0, t0, s0\ntexldp r0, t0, s0").texture, 2);
  EXPECT_EQ(slots("vs_3_0\nsetp_gt p0, v0, c0\n(p0) add r0, v0, c0").arithmetic, 1 + 2);
  EXPECT_EQ(slots("vs_3_0\nsetp_gt p0, v0, c0\n(p0) add r0, v0, c0").total(), 3);
}

// ---- entry points ----------------------------------------------------------------

TEST(Validator, UnsupportedVersion) {
  Shader s;
  s.version = {ShaderType::Pixel, 4, 0};
  auto d = validate(s);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "ps_4_0 is not a supported shader version");
  // ps_1_0 is read as ps_1_1.
  EXPECT_TRUE(isValid("ps_1_0\ntex t0\nmov r0, t0"));
}

TEST(Validator, DeviceVersion) {
  const Version ps14{ShaderType::Pixel, 1, 4}, ps11{ShaderType::Pixel, 1, 1}, ps2x{ShaderType::Pixel, 2, 1};
  const Version vs11{ShaderType::Vertex, 1, 1};
  EXPECT_EQ(checkDeviceVersion(ps14, 0xFFFF0101, "dx8"), "ps_1_4 needs PixelShaderVersion 1.4, dx8 has 1.1");
  EXPECT_EQ(checkDeviceVersion(ps11, 0xFFFF0104, "dx81"), "");
  EXPECT_EQ(checkDeviceVersion(ps14, 0xFFFF0200, "dx9"), "");
  EXPECT_EQ(checkDeviceVersion(ps2x, 0xFFFF0200, "dx9"), "ps_2_x needs PixelShaderVersion above 2.0, dx9 has 2.0");
  EXPECT_EQ(checkDeviceVersion(ps2x, 0xFFFF0300, "dx9-sm3"), "");
  EXPECT_EQ(checkDeviceVersion(vs11, 0xFFFE0000, "dx7"), "vs_1_1 needs VertexShaderVersion 1.1, dx7 has none");
}

TEST(Validator, RequireValidThrowsLocatedError) {
  Shader s = assemble("ps_1_1\ntex t0\nmov r0, r1", "shader.psh");
  try {
    requireValid(s, "shader.psh");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "shader.psh:3:1: error: r1 is read before it is written");
  }
  EXPECT_NO_THROW(requireValid(read("ps_1_1\ntex t0\nmov r0, t0"), "ok.psh"));
}

TEST(Validator, MalformedShadersDoNotCrash) {
  // Decoded bytecode can hold anything: out-of-range indices, missing operands.
  Shader s;
  s.version = {ShaderType::Pixel, 1, 1};
  Instruction in;
  in.opcode = Opcode::Mov;
  in.hasDst = true;
  in.dst.type = RegType::Temp;
  in.dst.index = 2047;
  in.srcCount = 1;
  in.src[0].type = RegType::Label;
  in.src[0].index = 9999;
  s.instructions.push_back(in);
  Instruction bad;
  bad.opcode = Opcode(200);  // no such opcode
  s.instructions.push_back(bad);
  Instruction loop;
  loop.opcode = Opcode::EndLoop;
  s.instructions.push_back(loop);
  EXPECT_FALSE(validate(s).empty());
  for (const VersionRules* r : allVersionRules()) {
    s.version = r->version;
    EXPECT_FALSE(validate(s).empty()) << r->name;
  }
}

TEST(Validator, RandomShadersDoNotCrash) {
  // Deterministic pseudo-random instructions: any opcode, register type, index,
  // modifier, swizzle and flag combination must give diagnostics, never a crash.
  uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  const Opcode ops[] = {Opcode::Mov, Opcode::Add, Opcode::Mad, Opcode::Tex, Opcode::TexCoord,
                        Opcode::TexM3x2Pad, Opcode::TexM3x3Pad, Opcode::TexM3x3Spec, Opcode::Rep,
                        Opcode::EndRep, Opcode::Loop, Opcode::EndLoop, Opcode::If, Opcode::IfC,
                        Opcode::Else, Opcode::EndIf, Opcode::Call, Opcode::CallNZ, Opcode::Label,
                        Opcode::Ret, Opcode::Dcl, Opcode::Def, Opcode::Phase, Opcode::M4x4,
                        Opcode::SinCos, Opcode::Bem, Opcode::TexKill, Opcode::SetP, Opcode::TexLdl,
                        Opcode::Break, Opcode::Cnd, Opcode::Cmp, Opcode::Dp4, Opcode(9999)};
  for (int n = 0; n < 3000; ++n) {
    Shader s;
    s.version = allVersionRules()[next() % allVersionRules().size()]->version;
    int count = int(next() % 12);
    for (int i = 0; i < count; ++i) {
      Instruction in;
      in.opcode = ops[next() % std::size(ops)];
      in.coissue = next() % 4 == 0;
      in.predicated = next() % 6 == 0;
      in.hasDst = next() % 5 != 0;
      in.dst.type = RegType(next() % 20);
      in.dst.index = uint16_t(next() % 40);
      in.dst.writeMask = uint8_t(next() % 16);
      in.dst.resultMod = uint8_t(next() % 8);
      in.dst.shift = int8_t(int(next() % 16) - 8);
      in.dst.relative = next() % 8 == 0;
      in.srcCount = uint8_t(next() % 5);
      for (int k = 0; k < in.srcCount; ++k) {
        SrcParam& p = in.src[k];
        p.type = RegType(next() % 20);
        p.index = uint16_t(next() % 3000);
        p.swizzle = uint8_t(next());
        p.mod = SrcMod(next() % 16);
        p.relative = next() % 8 == 0;
        p.rel.type = next() % 2 ? RegType::Addr : RegType::Loop;
        p.rel.component = uint8_t(next() % 4);
      }
      in.literal = {next(), next(), next(), next()};
      in.textureType = TextureType(next() % 6);
      in.pos = {i + 2, 1};
      s.instructions.push_back(in);
    }
    validate(s);
    countSlots(s);
  }
  SUCCEED();
}

TEST(VersionRules, TablesCoverEveryVersion) {
  const char* names[] = {"vs_1_1", "vs_2_0", "vs_2_x", "vs_3_0", "ps_1_1", "ps_1_2",
                         "ps_1_3", "ps_1_4", "ps_2_0", "ps_2_x", "ps_3_0"};
  auto all = allVersionRules();
  ASSERT_EQ(all.size(), std::size(names));
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i]->name, names[i]);
    EXPECT_EQ(findVersionRules(all[i]->version), all[i]);
  }
  // Register counts the executor also relies on (registers-and-limits.md §1–2).
  auto count = [](Version v, RegType t) {
    const RegisterRule* r = findRegisterRule(*findVersionRules(v), t);
    return r ? int(r->count) : 0;
  };
  EXPECT_EQ(count({ShaderType::Pixel, 1, 1}, RegType::Temp), 2);
  EXPECT_EQ(count({ShaderType::Pixel, 1, 4}, RegType::Temp), 6);
  EXPECT_EQ(count({ShaderType::Pixel, 1, 4}, RegType::Texture), 6);
  EXPECT_EQ(count({ShaderType::Pixel, 2, 0}, RegType::Const), 32);
  EXPECT_EQ(count({ShaderType::Pixel, 3, 0}, RegType::Const), 224);
  EXPECT_EQ(count({ShaderType::Pixel, 3, 0}, RegType::Input), 10);
  EXPECT_EQ(count({ShaderType::Vertex, 1, 1}, RegType::Const), 96);
  EXPECT_EQ(count({ShaderType::Vertex, 3, 0}, RegType::Temp), 32);
  EXPECT_EQ(count({ShaderType::Vertex, 3, 0}, RegType::Sampler), 4);
  EXPECT_EQ(count({ShaderType::Vertex, 1, 1}, RegType::ConstInt), 0);
}

// ---- shaders the seeds describe as impossible ------------------------------------

// The seeds' shaders as shipped in data/shaders: every complete shader that assembles
// is valid, except the printed table-lookup shader that reads t3 without sampling it.
TEST(ValidatorSeeds, DataShadersAreValid) {
  namespace fs = std::filesystem;
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(REFX_DATA_DIR) / "shaders")) {
    std::string name = entry.path().filename().string();
    std::string ext = entry.path().extension().string();
    if ((ext != ".psh" && ext != ".vsh") || name.find("_fragment") != std::string::npos) continue;
    std::ifstream f(entry.path());
    std::stringstream ss;
    ss << f.rdbuf();
    Shader shader;
    try {
      shader = assemble(ss.str(), name);
    } catch (const Error&) {
      continue;  // printed typos (a page number, a missing version) are the assembler's to report
    }
    ++checked;
    if (name == "paper_specular_table.psh")
      EXPECT_TRUE(hasError(shader, "t3 is read before it is written (no texture instruction writes it)"));
    else
      EXPECT_TRUE(messages(shader).empty()) << name << ":\n" << joined(messages(shader));
  }
  EXPECT_GE(checked, 30);
}

// The assembler's test shaders (every version, every instruction family) are valid.
TEST(ValidatorSeeds, AssemblerTestShadersAreValid) {
  namespace fs = std::filesystem;
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(REFX_TEST_DIR) / "shader" / "asm")) {
    std::string ext = entry.path().extension().string();
    if (ext != ".psh" && ext != ".vsh") continue;
    std::ifstream f(entry.path());
    std::stringstream ss;
    ss << f.rdbuf();
    Shader shader = assemble(ss.str(), entry.path().filename().string());
    EXPECT_TRUE(messages(shader).empty()) << entry.path() << ":\n" << joined(messages(shader));
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

// Each file in asm_invalid/ starts with "; expect: <message>".
TEST(ValidatorSeeds, ShadersTheTextsRejectAreRejected) {
  namespace fs = std::filesystem;
  fs::path dir = fs::path(REFX_TEST_DIR) / "shader" / "asm_invalid";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ifstream f(entry.path());
    std::stringstream ss;
    ss << f.rdbuf();
    std::string text = ss.str();
    std::string first = text.substr(0, text.find('\n'));
    const std::string tag = "; expect: ";
    ASSERT_EQ(first.compare(0, tag.size(), tag), 0) << entry.path();
    std::string expected = trim(first.substr(tag.size()));
    EXPECT_TRUE(hasError(text, expected)) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 5);
}

}  // namespace
}  // namespace refx::shader

namespace {

// The validator's first message for `tokens`; "(valid)" when it has none.
std::string firstProblem(const std::vector<uint32_t>& tokens) {
  const auto d = refx::shader::validate(refx::shader::decode(tokens));
  return d.empty() ? "(valid)" : d[0].message;
}

// vs_2_0: one dcl of v0 with the given usage and register tokens; m4x4 oPos, v0, c0.
std::vector<uint32_t> vs20WithDcl(uint32_t usageToken, uint32_t registerToken) {
  return {0xFFFE0200, 0x0200001F, usageToken, registerToken, 0x03000014,
          0xC00F0000, 0x90E40000, 0xA0E40000, 0x0000FFFF};
}

}  // namespace

TEST(ValidatorTokens, ReservedSpecificControlBitsAreRejected) {
  using namespace refx::shader;
  // ps_1_1: tex t0; mul r0, t0, v0 with bits 23:16 = 0x39, which mul does not define
  // (bytecode.md: instruction token bits 23:16 are opcode-specific controls).
  const std::vector<uint32_t> mul = {0xFFFF0101, 0x00000042, 0xB00F0000, 0x00390005,
                                     0x800F0000, 0xB0E40000, 0x90E40000, 0x0000FFFF};
  const std::vector<Diagnostic> d = validate(decode(mul));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d[0].message, "mul has specific-control bits 0x39, which ps_1_1 does not define for it");
  // ps_2_0: dcl_2d s0; dcl t0; texld r0, t0, s0 with project and bias bits both set (3).
  const std::vector<uint32_t> texld = {0xFFFF0200, 0x0200001F, 0x90000000, 0xA00F0800,
                                       0x0200001F, 0x80000000, 0xB00F0000, 0x03030042,
                                       0x800F0000, 0xB0E40000, 0xA0E40800, 0x02000001,
                                       0x800F0800, 0x80E40000, 0x0000FFFF};
  EXPECT_FALSE(validate(decode(texld)).empty());
  // The same with the project bit alone is texldp, which ps_2_0 has.
  std::vector<uint32_t> texldp = texld;
  texldp[7] = 0x03010042;
  EXPECT_TRUE(validate(decode(texldp)).empty());
}

TEST(ValidatorTokens, DclTakesNoShift) {
  using namespace refx::shader;
  // vs_2_0: dcl_position v0 whose destination token has shift bits 27:24 = 0x9 (-7, a
  // "_d128" no assembler can write); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0x80000000, 0x990F0000)),
            "dcl takes no shift (_x2, _d2 ...)");
}

TEST(ValidatorTokens, TextureTypeBelongsToSamplerDcls) {
  using namespace refx::shader;
  // vs_2_0: dcl_position v0 with bits 30:27 of its usage token = 8 (0xC0000000: the
  // texture type field, which only a sampler dcl uses); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0xC0000000, 0x900F0000)),
            "dcl of v0 has a texture type; only samplers (s#) have one");
}

TEST(ValidatorTokens, UndefinedResultModifierBitsAreRejected) {
  using namespace refx::shader;
  // vs_1_1: mov oPos, v0 whose destination has result modifier bits 23:20 = 8 (defined:
  // 1 _sat, 2 _pp, 4 _centroid).
  const std::vector<uint32_t> tokens = {0xFFFE0101, 0x00000001, 0xC08F0000, 0x90E40000,
                                        0x0000FFFF};
  EXPECT_EQ(firstProblem(tokens), "mov has result modifier bits 0x8; only _sat, _pp and _centroid exist");
}

TEST(ValidatorTokens, DclUsageBeyondSampleIsRejected) {
  using namespace refx::shader;
  // vs_2_0: dcl v0 with usage 14 in its usage token (0x8000000E; D3DDECLUSAGE_SAMPLE = 13
  // is the last); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0x8000000E, 0x900F0000)),
            "dcl of v0 has usage 14; D3DDECLUSAGE ends at 13 (sample)");
}

TEST(ValidatorTokens, DclWithAnEmptyMaskIsRejected) {
  using namespace refx::shader;
  // vs_2_0: dcl_position v0 with write mask 0 (0x90000000); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0x80000000, 0x90000000)),
            "dcl of v0 declares no component (empty write mask)");
}

TEST(ValidatorTokens, DefTakesNoModifier) {
  using namespace refx::shader;
  // vs_2_0: defi i0, 4, 0, 1, 0 whose destination has shift 4 and _pp (0xF42F0000:
  // bits 27:24 = 4, 23:20 = 2); m4x4 oPos, v0, c0 after dcl_position v0.
  const std::vector<uint32_t> tokens = {0xFFFE0200, 0x0200001F, 0x80000000, 0x900F0000,
                                        0x05000030, 0xF42F0000, 4, 0, 1, 0,
                                        0x03000014, 0xC00F0000, 0x90E40000, 0xA0E40000,
                                        0x0000FFFF};
  EXPECT_EQ(firstProblem(tokens), "defi takes no instruction modifier");
}

TEST(ValidatorTokens, DefbIsFalseOrTrue) {
  using namespace refx::shader;
  // vs_2_0: defb b1 with the value 0x00100001 (TRUE is 1); then defb b2, true is fine.
  const std::vector<uint32_t> tokens = {0xFFFE0200, 0x0200002F, 0xE0010801, 0x00100001,
                                        0x0200002F, 0xE0010802, 0x00000001, 0x0000FFFF};
  const std::vector<Diagnostic> d = validate(decode(tokens));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d[0].message, "defb b1: value 0x100001 is neither FALSE (0) nor TRUE (1)");
  for (size_t i = 1; i < d.size(); ++i) EXPECT_EQ(d[i].message.find("defb b2"), std::string::npos);
}
