#include "refx/shader/vs_declaration.h"

#include <charconv>
#include <cstring>
#include <string>

#include "refx/core/diagnostics.h"

namespace refx::shader {

namespace {

struct TypeInfo {
  VsdType type;
  int size, components;
  const char* name;
};
constexpr TypeInfo kTypes[] = {
    {VsdType::Float1, 4, 1, "D3DVSDT_FLOAT1"},     {VsdType::Float2, 8, 2, "D3DVSDT_FLOAT2"},
    {VsdType::Float3, 12, 3, "D3DVSDT_FLOAT3"},    {VsdType::Float4, 16, 4, "D3DVSDT_FLOAT4"},
    {VsdType::D3DColor, 4, 4, "D3DVSDT_D3DCOLOR"}, {VsdType::UByte4, 4, 4, "D3DVSDT_UBYTE4"},
    {VsdType::Short2, 4, 2, "D3DVSDT_SHORT2"},     {VsdType::Short4, 8, 4, "D3DVSDT_SHORT4"},
};

// D3DVSDE_*: the fixed-function names of the input registers.
struct RegName {
  const char* name;
  int reg;
};
constexpr RegName kRegNames[] = {
    {"D3DVSDE_POSITION", 0},   {"D3DVSDE_BLENDWEIGHT", 1}, {"D3DVSDE_BLENDINDICES", 2},
    {"D3DVSDE_NORMAL", 3},     {"D3DVSDE_PSIZE", 4},       {"D3DVSDE_DIFFUSE", 5},
    {"D3DVSDE_SPECULAR", 6},   {"D3DVSDE_TEXCOORD0", 7},   {"D3DVSDE_TEXCOORD1", 8},
    {"D3DVSDE_TEXCOORD2", 9},  {"D3DVSDE_TEXCOORD3", 10},  {"D3DVSDE_TEXCOORD4", 11},
    {"D3DVSDE_TEXCOORD5", 12}, {"D3DVSDE_TEXCOORD6", 13},  {"D3DVSDE_TEXCOORD7", 14},
    {"D3DVSDE_POSITION2", 15}, {"D3DVSDE_NORMAL2", 16},
};

constexpr uint32_t kEnd = 0xFFFFFFFFu;
constexpr int kMaxRegister = 15;  // v0..v15 (the 5-bit field allows more; D3D8 has 16 inputs)
constexpr uint32_t tokenType(VsdTokenType t) { return uint32_t(t) << 29; }

bool isIdentStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isIdentChar(char c) { return isIdentStart(c) || isDigit(c); }

std::string upper(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
  return r;
}

// A small C-like lexer shared by both text forms.
class Lexer {
 public:
  enum class Tok { End, Ident, Number, Punct };
  struct Token {
    Tok kind = Tok::End;
    std::string text;
    int line = 1, column = 1;
  };

  Lexer(std::string_view src, std::string_view file) : src_(src), file_(file) {}

  Token next() {
    skip();
    Token t;
    t.line = line_;
    t.column = int(p_ - lineStart_) + 1;
    if (p_ >= src_.size()) return t;
    char c = src_[p_];
    size_t s = p_;
    if (isIdentStart(c)) {
      while (p_ < src_.size() && isIdentChar(src_[p_])) ++p_;
      t.kind = Tok::Ident;
    } else if (isDigit(c) || (c == '.' && p_ + 1 < src_.size() && isDigit(src_[p_ + 1])) ||
               ((c == '-' || c == '+') && p_ + 1 < src_.size() &&
                (isDigit(src_[p_ + 1]) || src_[p_ + 1] == '.'))) {
      ++p_;
      while (p_ < src_.size()) {
        char d = src_[p_];
        bool exponentSign = (d == '-' || d == '+') && (src_[p_ - 1] == 'e' || src_[p_ - 1] == 'E') &&
                            !(s + 1 < src_.size() && (src_[s + 1] == 'x' || src_[s + 1] == 'X'));
        if (isIdentChar(d) || d == '.' || exponentSign)
          ++p_;
        else
          break;
      }
      t.kind = Tok::Number;
    } else {
      ++p_;
      t.kind = Tok::Punct;
    }
    t.text = std::string(src_.substr(s, p_ - s));
    return t;
  }

  template <typename... Args>
  [[noreturn]] void error(const Token& at, fmt::format_string<Args...> f, Args&&... args) {
    failAt(SourceLocation{file_, at.line, at.column}, f, std::forward<Args>(args)...);
  }

 private:
  void skip() {
    while (p_ < src_.size()) {
      char c = src_[p_];
      if (c == '\n') {
        ++p_;
        ++line_;
        lineStart_ = p_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++p_;
      } else if (c == '/' && p_ + 1 < src_.size() && src_[p_ + 1] == '/') {
        while (p_ < src_.size() && src_[p_] != '\n') ++p_;
      } else if (c == '/' && p_ + 1 < src_.size() && src_[p_ + 1] == '*') {
        p_ += 2;
        while (p_ < src_.size() && !(src_[p_] == '*' && p_ + 1 < src_.size() && src_[p_ + 1] == '/')) {
          if (src_[p_] == '\n') {
            ++line_;
            lineStart_ = p_ + 1;
          }
          ++p_;
        }
        p_ = std::min(src_.size(), p_ + 2);
      } else {
        return;
      }
    }
  }

  std::string_view src_;
  std::string file_;
  size_t p_ = 0;
  int line_ = 1;
  size_t lineStart_ = 0;
};

using Tok = Lexer::Tok;
using Token = Lexer::Token;

// Integer literal: decimal or 0x hex, optional u/l suffixes.
bool parseInteger(const std::string& text, long long& out) {
  std::string t = text;
  while (!t.empty() && (t.back() == 'u' || t.back() == 'U' || t.back() == 'l' || t.back() == 'L')) t.pop_back();
  bool neg = false;
  size_t i = 0;
  if (i < t.size() && (t[i] == '-' || t[i] == '+')) neg = t[i++] == '-';
  int base = 10;
  if (t.size() > i + 1 && t[i] == '0' && (t[i + 1] == 'x' || t[i + 1] == 'X')) base = 16, i += 2;
  if (i >= t.size()) return false;
  unsigned long long v = 0;
  auto [ptr, ec] = std::from_chars(t.data() + i, t.data() + t.size(), v, base);
  if (ec != std::errc() || ptr != t.data() + t.size() || v > 0xFFFFFFFFull) return false;
  out = neg ? -(long long)v : (long long)v;
  return true;
}

// A constant-data DWORD: a float literal (1.0, 1.0f, .5, 1e-3) or an integer DWORD.
bool parseDataWord(const std::string& text, uint32_t& out) {
  bool floatLike = text.find_first_of(".eEfF") != std::string::npos &&
                   !(text.size() > 2 && (text[1] == 'x' || text[1] == 'X' || text[2] == 'x' || text[2] == 'X'));
  if (!floatLike) {
    long long v;
    if (!parseInteger(text, v)) return false;
    out = uint32_t(v);
    return true;
  }
  std::string t = text;
  if (!t.empty() && (t.back() == 'f' || t.back() == 'F')) t.pop_back();
  bool neg = false;
  size_t i = 0;
  if (i < t.size() && (t[i] == '-' || t[i] == '+')) neg = t[i++] == '-';
  float f = 0;
  auto [ptr, ec] = std::from_chars(t.data() + i, t.data() + t.size(), f);
  if (ec != std::errc() || ptr != t.data() + t.size() || i == t.size()) return false;
  if (neg) f = -f;
  std::memcpy(&out, &f, 4);
  return true;
}

class MacroParser {
 public:
  MacroParser(std::string_view text, std::string_view file) : lex_(text, file) {}

  VsDeclaration run() {
    VsDeclaration d;
    bool ended = false;
    Token t;
    for (t = lex_.next(); t.kind != Tok::End; t = lex_.next()) {
      if (t.kind != Tok::Ident) continue;  // DWORD, names, braces, commas: C scaffolding
      const std::string name = upper(t.text);
      if (name.rfind("D3DVSD_", 0) != 0) continue;
      if (ended) lex_.error(t, "{} after D3DVSD_END()", t.text);
      VsdEntry e;
      if (name == "D3DVSD_END") {
        args(t, 0);
        ended = true;
        continue;
      } else if (name == "D3DVSD_NOP") {
        args(t, 0);
        e.kind = VsdEntry::Kind::Nop;
      } else if (name == "D3DVSD_STREAM") {
        auto a = args(t, 1);
        e.kind = VsdEntry::Kind::Stream;
        e.stream = uint8_t(number(a[0], 0, 15, "stream number"));
      } else if (name == "D3DVSD_STREAM_TESS") {
        args(t, 0);
        e.kind = VsdEntry::Kind::StreamTess;
      } else if (name == "D3DVSD_REG") {
        auto a = args(t, 2);
        e.kind = VsdEntry::Kind::Reg;
        e.reg = uint8_t(registerArg(a[0]));
        e.type = typeArg(a[1]);
      } else if (name == "D3DVSD_SKIP") {
        auto a = args(t, 1);
        e.kind = VsdEntry::Kind::Skip;
        e.count = uint8_t(number(a[0], 0, 15, "skip count (DWORDs)"));
      } else if (name == "D3DVSD_TESSNORMAL") {
        auto a = args(t, 2);
        e.kind = VsdEntry::Kind::TessNormal;
        e.regIn = uint8_t(registerArg(a[0]));
        if (e.regIn > 15) lex_.error(a[0], "D3DVSD_TESSNORMAL input register {} is out of range (0 to 15)", e.regIn);
        e.reg = uint8_t(registerArg(a[1]));
      } else if (name == "D3DVSD_TESSUV") {
        auto a = args(t, 1);
        e.kind = VsdEntry::Kind::TessUV;
        e.reg = uint8_t(registerArg(a[0]));
      } else if (name == "D3DVSD_CONST") {
        auto a = args(t, 2);
        e.kind = VsdEntry::Kind::Const;
        e.address = uint16_t(number(a[0], 0, 127, "constant address"));
        e.count = uint8_t(number(a[1], 0, 15, "constant count"));
        // count*4 data DWORDs follow as separate initializers.
        for (int i = 0; i < e.count * 4; ++i) {
          Token sep = lex_.next();
          if (!(sep.kind == Tok::Punct && sep.text == ","))
            lex_.error(sep, "D3DVSD_CONST({}, {}) needs {} data values after it, found {}", e.address, e.count,
                       e.count * 4, i);
          Token v = lex_.next();
          uint32_t word;
          if (v.kind != Tok::Number)
            lex_.error(v, "D3DVSD_CONST({}, {}) needs {} data values after it, found {}", e.address, e.count,
                       e.count * 4, i);
          if (!parseDataWord(v.text, word))
            lex_.error(v, "expected a constant data value (float or DWORD), found '{}'", v.text);
          e.data.push_back(word);
        }
      } else {
        lex_.error(t, "unknown declaration macro '{}' (expected D3DVSD_STREAM, D3DVSD_REG, D3DVSD_SKIP, "
                      "D3DVSD_CONST, D3DVSD_TESSNORMAL, D3DVSD_TESSUV, D3DVSD_NOP or D3DVSD_END)",
                   t.text);
      }
      d.entries.push_back(std::move(e));
    }
    if (!ended) lex_.error(t, "the declaration has no D3DVSD_END()");
    return d;
  }

 private:
  // `( a, b )` after a macro name; each argument is one token.
  std::vector<Token> args(const Token& macro, size_t count) {
    Token open = lex_.next();
    if (!(open.kind == Tok::Punct && open.text == "("))
      lex_.error(open, "expected '(' after {}", macro.text);
    std::vector<Token> out;
    Token t = lex_.next();
    if (t.kind == Tok::Punct && t.text == ")") {
      if (count != 0) lex_.error(t, "{} takes {} argument{}", macro.text, count, count == 1 ? "" : "s");
      return out;
    }
    for (;;) {
      if (t.kind != Tok::Ident && t.kind != Tok::Number) lex_.error(t, "expected an argument of {}, found '{}'", macro.text, t.text);
      out.push_back(t);
      Token sep = lex_.next();
      if (sep.kind == Tok::Punct && sep.text == ")") break;
      if (!(sep.kind == Tok::Punct && sep.text == ","))
        lex_.error(sep, "expected ',' or ')' in {}, found '{}'", macro.text, sep.text);
      t = lex_.next();
    }
    if (out.size() != count)
      lex_.error(macro, "{} takes {} argument{}, found {}", macro.text, count, count == 1 ? "" : "s", out.size());
    return out;
  }

  long long number(const Token& t, long long lo, long long hi, const char* what) {
    long long v;
    if (t.kind != Tok::Number || !parseInteger(t.text, v)) lex_.error(t, "expected the {} as an integer, found '{}'", what, t.text);
    if (v < lo || v > hi) lex_.error(t, "{} {} is out of range ({} to {})", what, v, lo, hi);
    return v;
  }

  int registerArg(const Token& t) {
    if (t.kind == Tok::Ident) {
      const std::string n = upper(t.text);
      for (const RegName& r : kRegNames)
        if (n == r.name) return r.reg;
      lex_.error(t, "unknown vertex register name '{}' (expected a number 0-{} or D3DVSDE_POSITION, D3DVSDE_NORMAL, "
                    "D3DVSDE_DIFFUSE, D3DVSDE_TEXCOORD0 …)",
                 t.text, kMaxRegister);
    }
    return int(number(t, 0, 16, "vertex register"));
  }

  VsdType typeArg(const Token& t) {
    if (t.kind == Tok::Ident) {
      const std::string n = upper(t.text);
      for (const TypeInfo& ti : kTypes)
        if (n == ti.name) return ti.type;
      lex_.error(t, "unknown data type '{}' (expected D3DVSDT_FLOAT1..4, D3DVSDT_D3DCOLOR, D3DVSDT_UBYTE4, "
                    "D3DVSDT_SHORT2 or D3DVSDT_SHORT4)",
                 t.text);
    }
    return VsdType(number(t, 0, 7, "data type"));
  }

  Lexer lex_;
};

// `decl { stream 0; float v0[3]; d3dcolor v5; skip 2; }` (DirectX 8 effects).
class DeclBlockParser {
 public:
  DeclBlockParser(std::string_view text, std::string_view file) : lex_(text, file) {}

  VsDeclaration run() {
    VsDeclaration d;
    Token t = nextToken();
    bool braces = false;
    if (t.kind == Tok::Ident && upper(t.text) == "DECL") t = nextToken();
    if (t.kind == Tok::Punct && t.text == "{") braces = true, t = nextToken();
    for (;;) {
      if (t.kind == Tok::End) {
        if (braces) lex_.error(t, "expected '}}' to close the declaration");
        break;
      }
      if (t.kind == Tok::Punct && t.text == "}") {
        if (!braces) lex_.error(t, "unexpected '}}'");
        Token after = nextToken();
        if (after.kind == Tok::Punct && after.text == ";") after = nextToken();
        if (after.kind != Tok::End) lex_.error(after, "unexpected '{}' after the declaration", after.text);
        break;
      }
      if (t.kind == Tok::Punct && t.text == ";") {
        t = nextToken();
        continue;
      }
      if (t.kind != Tok::Ident)
        lex_.error(t, "expected 'stream', an element type (float, d3dcolor, ubyte, short) or 'skip', found '{}'", t.text);
      d.entries.push_back(statement(t));
      Token semi = nextToken();
      if (!(semi.kind == Tok::Punct && semi.text == ";"))
        lex_.error(semi, "expected ';' after the declaration statement, found '{}'", semi.text);
      t = nextToken();
    }
    return d;
  }

 private:
  VsdEntry statement(const Token& kw) {
    const std::string k = upper(kw.text);
    VsdEntry e;
    if (k == "STREAM") {
      e.kind = VsdEntry::Kind::Stream;
      e.stream = uint8_t(integer(nextToken(), 0, 15, "stream number"));
      return e;
    }
    if (k == "SKIP") {
      e.kind = VsdEntry::Kind::Skip;
      Token n = nextToken();
      bool bracket = n.kind == Tok::Punct && n.text == "[";
      if (bracket) n = nextToken();
      e.count = uint8_t(integer(n, 0, 15, "skip count (DWORDs)"));
      if (bracket) expectPunct("]");
      return e;
    }
    e.kind = VsdEntry::Kind::Reg;
    Token reg = nextToken();
    const std::string r = upper(reg.text);
    long long v = -1;
    if (reg.kind != Tok::Ident || r.size() < 2 || r[0] != 'V' || !parseInteger(r.substr(1), v) || v < 0 ||
        v > kMaxRegister)
      lex_.error(reg, "expected an input register v0..v{}, found '{}'", kMaxRegister, reg.text);
    e.reg = uint8_t(v);
    int n = 1;
    Token peek = nextToken();
    if (peek.kind == Tok::Punct && peek.text == "[") {
      n = int(integer(nextToken(), 1, 4, "element size"));
      expectPunct("]");
    } else {
      pushback_ = peek;
    }
    if (k == "FLOAT") {
      e.type = VsdType(n - 1);
    } else if (k == "D3DCOLOR") {
      if (n != 1 && n != 4) lex_.error(kw, "d3dcolor is one packed DWORD (write 'd3dcolor v{}' )", e.reg);
      e.type = VsdType::D3DColor;
    } else if (k == "UBYTE") {
      if (n != 4) lex_.error(kw, "ubyte elements have 4 components (ubyte v{}[4])", e.reg);
      e.type = VsdType::UByte4;
    } else if (k == "SHORT") {
      if (n != 2 && n != 4) lex_.error(kw, "short elements have 2 or 4 components");
      e.type = n == 2 ? VsdType::Short2 : VsdType::Short4;
    } else {
      lex_.error(kw, "unknown declaration statement '{}' (expected stream, float, d3dcolor, ubyte, short or skip)",
                 kw.text);
    }
    return e;
  }

  Token nextToken() {
    if (pushback_.kind != Tok::End) {
      Token t = pushback_;
      pushback_ = Token{};
      return t;
    }
    return lex_.next();
  }

  void expectPunct(const char* p) {
    Token t = nextToken();
    if (!(t.kind == Tok::Punct && t.text == p)) lex_.error(t, "expected '{}', found '{}'", p, t.text);
  }

  long long integer(const Token& t, long long lo, long long hi, const char* what) {
    long long v;
    if (t.kind != Tok::Number || !parseInteger(t.text, v)) lex_.error(t, "expected the {}, found '{}'", what, t.text);
    if (v < lo || v > hi) lex_.error(t, "{} {} is out of range ({} to {})", what, v, lo, hi);
    return v;
  }

  Lexer lex_;
  Token pushback_;
};

}  // namespace

int vsdTypeSize(VsdType type) {
  return unsigned(type) < 8 ? kTypes[unsigned(type)].size : 0;
}
int vsdTypeComponents(VsdType type) {
  return unsigned(type) < 8 ? kTypes[unsigned(type)].components : 0;
}
const char* vsdTypeName(VsdType type) {
  return unsigned(type) < 8 ? kTypes[unsigned(type)].name : "D3DVSDT_?";
}

std::vector<VsdElement> vsdElements(const VsDeclaration& decl) {
  std::vector<VsdElement> out;
  uint8_t stream = 0;
  uint32_t offsets[16] = {};
  for (const VsdEntry& e : decl.entries) {
    switch (e.kind) {
      case VsdEntry::Kind::Stream: stream = e.stream & 15; break;
      case VsdEntry::Kind::Skip: offsets[stream] += 4u * e.count; break;
      case VsdEntry::Kind::Reg:
        out.push_back(VsdElement{stream, uint16_t(offsets[stream]), e.reg, e.type});
        offsets[stream] += uint32_t(vsdTypeSize(e.type));
        break;
      default: break;
    }
  }
  return out;
}

uint32_t vsdStreamSize(const VsDeclaration& decl, uint8_t stream) {
  uint8_t current = 0;
  uint32_t size = 0;
  for (const VsdEntry& e : decl.entries) {
    if (e.kind == VsdEntry::Kind::Stream) current = e.stream & 15;
    if (current != stream) continue;
    if (e.kind == VsdEntry::Kind::Skip) size += 4u * e.count;
    if (e.kind == VsdEntry::Kind::Reg) size += uint32_t(vsdTypeSize(e.type));
  }
  return size;
}

VsDeclaration parseVsDeclaration(std::string_view text, std::string_view fileName) {
  if (text.find("D3DVSD_") != std::string_view::npos || text.find("d3dvsd_") != std::string_view::npos)
    return MacroParser(text, fileName).run();
  return DeclBlockParser(text, fileName).run();
}

std::vector<uint32_t> encodeVsDeclaration(const VsDeclaration& decl) {
  std::vector<uint32_t> out;
  for (size_t i = 0; i < decl.entries.size(); ++i) {
    const VsdEntry& e = decl.entries[i];
    switch (e.kind) {
      case VsdEntry::Kind::Nop: out.push_back(0); break;
      case VsdEntry::Kind::Stream: out.push_back(tokenType(VsdTokenType::Stream) | (e.stream & 0xFu)); break;
      case VsdEntry::Kind::StreamTess: out.push_back(tokenType(VsdTokenType::Stream) | 1u << 28); break;
      case VsdEntry::Kind::Reg:
        out.push_back(tokenType(VsdTokenType::StreamData) | (uint32_t(e.type) & 0xFu) << 16 | (e.reg & 0x1Fu));
        break;
      case VsdEntry::Kind::Skip:
        out.push_back(tokenType(VsdTokenType::StreamData) | 1u << 28 | (e.count & 0xFu) << 16);
        break;
      case VsdEntry::Kind::TessNormal:
        out.push_back(tokenType(VsdTokenType::Tessellator) | (e.regIn & 0xFu) << 20 | 2u << 16 | (e.reg & 0x1Fu));
        break;
      case VsdEntry::Kind::TessUV:
        out.push_back(tokenType(VsdTokenType::Tessellator) | 1u << 28 | 1u << 16 | (e.reg & 0x1Fu));
        break;
      case VsdEntry::Kind::Const:
        if (e.count > 15 || e.data.size() != size_t(e.count) * 4)
          fail("declaration entry {}: D3DVSD_CONST with {} registers needs {} data DWORDs, has {}", i, e.count,
               e.count * 4, e.data.size());
        out.push_back(tokenType(VsdTokenType::ConstMem) | uint32_t(e.count) << 25 | (e.address & 0x7Fu));
        out.insert(out.end(), e.data.begin(), e.data.end());
        break;
      case VsdEntry::Kind::Ext:
        if (e.count > 31 || e.data.size() != e.count)
          fail("declaration entry {}: extension token with count {} has {} data DWORDs", i, e.count, e.data.size());
        out.push_back(tokenType(VsdTokenType::Ext) | uint32_t(e.count) << 24 | (e.info & 0xFFFFFFu));
        out.insert(out.end(), e.data.begin(), e.data.end());
        break;
    }
  }
  out.push_back(kEnd);
  return out;
}

VsDeclaration decodeVsDeclaration(std::span<const uint32_t> tokens) {
  VsDeclaration d;
  size_t i = 0;
  for (;;) {
    if (i >= tokens.size()) fail("declaration token {}: missing D3DVSD_END (0xFFFFFFFF)", i);
    const uint32_t t = tokens[i];
    if (t == kEnd) break;
    VsdEntry e;
    const uint32_t type = t >> 29;
    const bool flag = (t >> 28) & 1;
    switch (VsdTokenType(type)) {
      case VsdTokenType::Nop:
        if (t != 0) fail("declaration token {}: NOP token 0x{:08X} has nonzero bits", i, t);
        e.kind = VsdEntry::Kind::Nop;
        break;
      case VsdTokenType::Stream:
        if (flag) {
          if (t & 0x0FFFFFFFu) fail("declaration token {}: STREAM_TESS token 0x{:08X} has extra bits", i, t);
          e.kind = VsdEntry::Kind::StreamTess;
        } else {
          if (t & 0x0FFFFFF0u) fail("declaration token {}: STREAM token 0x{:08X} has bits beyond the stream number", i, t);
          e.kind = VsdEntry::Kind::Stream;
          e.stream = uint8_t(t & 0xF);
        }
        break;
      case VsdTokenType::StreamData:
        if (flag) {
          e.kind = VsdEntry::Kind::Skip;
          e.count = uint8_t((t >> 16) & 0xF);
        } else {
          e.kind = VsdEntry::Kind::Reg;
          const uint32_t dt = (t >> 16) & 0xF;
          if (dt > 7) fail("declaration token {}: unknown data type {} (D3DVSDT_* is 0..7)", i, dt);
          e.type = VsdType(dt);
          e.reg = uint8_t(t & 0x1F);
        }
        break;
      case VsdTokenType::Tessellator:
        if (flag) {
          e.kind = VsdEntry::Kind::TessUV;
        } else {
          e.kind = VsdEntry::Kind::TessNormal;
          e.regIn = uint8_t((t >> 20) & 0xF);
        }
        e.reg = uint8_t(t & 0x1F);
        break;
      case VsdTokenType::ConstMem: {
        e.kind = VsdEntry::Kind::Const;
        e.count = uint8_t((t >> 25) & 0xF);
        e.address = uint16_t(t & 0x7F);
        const size_t n = size_t(e.count) * 4;
        if (tokens.size() - i - 1 < n)
          fail("declaration token {}: D3DVSD_CONST needs {} data DWORDs, {} remain", i, n, tokens.size() - i - 1);
        e.data.assign(tokens.begin() + i + 1, tokens.begin() + i + 1 + n);
        i += n;
        break;
      }
      case VsdTokenType::Ext: {
        e.kind = VsdEntry::Kind::Ext;
        e.count = uint8_t((t >> 24) & 0x1F);
        e.info = t & 0xFFFFFF;
        const size_t n = e.count;
        if (tokens.size() - i - 1 < n)
          fail("declaration token {}: extension token needs {} data DWORDs, {} remain", i, n, tokens.size() - i - 1);
        e.data.assign(tokens.begin() + i + 1, tokens.begin() + i + 1 + n);
        i += n;
        break;
      }
      default: fail("declaration token {}: unknown token type {} in 0x{:08X}", i, type, t);
    }
    d.entries.push_back(std::move(e));
    ++i;
  }
  return d;
}

}  // namespace refx::shader
