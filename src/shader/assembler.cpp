// Shader assembly text → Shader. Reads the language of Microsoft's vsa/psa (DirectX 8,
// `vs.1.1`, `ps.1.4`) and of the D3D9 assembler (`vs_3_0`, `dcl_texcoord0`, `if_lt`,
// predicates), case-insensitively. Newlines carry no meaning: an instruction ends
// with its last operand, as in the D3DX assembler grammar.
#include "refx/shader/assembler.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <string>

#include "refx/core/diagnostics.h"
#include "shader/assembler_tables.h"

namespace refx::shader {
namespace {

using namespace asmtables;

bool isIdentStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isIdentChar(char c) { return isIdentStart(c) || isDigit(c); }
char lower(char c) { return (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c; }
std::string lowerCopy(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = lower(c);
  return r;
}

// A character as it may be quoted in a message (arbitrary input bytes included).
std::string quoteChar(char c) {
  if (c >= 0x20 && c < 0x7F) return fmt::format("'{}'", c);
  return fmt::format("byte 0x{:02X}", unsigned(uint8_t(c)));
}

const char* const kOperandNames[] = {"src0", "src1", "src2", "src3"};

// Diagnostic codes of the assembler (docs/diagnostics.md, "Assembler"): one per kind of
// mistake, so that tests and tools can tell them apart without reading the message.
constexpr const char* kSyntax = "A2000";               // expected one thing, found another
constexpr const char* kUnknownInstruction = "A2001";   // no such mnemonic
constexpr const char* kVersion = "A2002";              // version missing, unknown or repeated
constexpr const char* kNotInVersion = "A2003";         // instruction or modifier the version lacks
constexpr const char* kOperandCount = "A2004";         // too few or too many operands
constexpr const char* kRegister = "A2005";             // unknown register or one without its number
constexpr const char* kRegisterRange = "A2006";        // register number or offset out of range
constexpr const char* kRelative = "A2007";             // relative addressing
constexpr const char* kSwizzle = "A2008";              // swizzle or write mask
constexpr const char* kSourceModifier = "A2009";       // source modifier, or a modifier on a destination
constexpr const char* kInstructionModifier = "A2010";  // _x2, _sat, comparison suffix, co-issue/predicate misuse
constexpr const char* kDefinition = "A2011";           // def / defi / defb form
constexpr const char* kLiteral = "A2012";              // number or boolean value
constexpr const char* kDeclaration = "A2013";          // dcl_* usage, sampler type or register
constexpr const char* kPredicate = "A2014";            // predicate register
constexpr const char* kDirective = "A2015";            // preprocessor directive other than #line
constexpr const char* kUnterminatedComment = "A2016";  // /* without */
constexpr const char* kTooManyErrors = "A2099";        // error limit reached

// A file with more errors than this reports these and stops: the rest are mostly
// consequences of the first ones.
constexpr int kMaxErrors = 100;

// Abandons the instruction being parsed; the driver loop reports it and resynchronises.
struct InstructionError {
  refx::Diagnostic diagnostic;
};

class Parser {
 public:
  Parser(std::string_view text, std::string_view fileName, DiagnosticSink& sink)
      : src_(text), file_(fileName), sink_(sink) {}

  // Every error is reported; after one, parsing goes on at the next line (or at the
  // next instruction, when the bad one ran into it). Without a version nothing after
  // it can be read, so a version error ends the run.
  Shader run() {
    for (;;) {
      try {
        skipSpace();
      } catch (const InstructionError& e) {
        if (!report(e)) return std::move(shader_);
        resynchronise(physLine_, p_);
        continue;
      }
      if (atEnd() && errors_ > 0) return std::move(shader_);  // nothing but the bad comment or directive
      try {
        parseVersion();
      } catch (const InstructionError& e) {
        report(e);
        return std::move(shader_);
      }
      break;
    }
    for (;;) {
      int startLine = physLine_;
      size_t startPos = p_;
      try {
        skipSpace();
        if (atEnd()) break;
        startLine = physLine_;
        startPos = p_;
        parseInstruction();
      } catch (const InstructionError& e) {
        if (!report(e)) break;
        resynchronise(startLine, startPos);
      }
    }
    return std::move(shader_);
  }

 private:
  // False once the error limit is reached (the limit itself is reported then).
  bool report(const InstructionError& e) {
    sink_.report(e.diagnostic);
    if (++errors_ < kMaxErrors) return true;
    sink_.error(SourceLocation{file_, e.diagnostic.where.line, 0}, kTooManyErrors,
                "too many errors ({}); assembly stops here", kMaxErrors);
    return false;
  }

  // After an error: skip the rest of the line, unless the failed instruction (which began
  // at startLine, startPos) already reached the first word of a later line (a missing
  // operand): that word begins the next instruction.
  void resynchronise(int startLine, size_t startPos) {
    if (p_ > startPos && physLine_ > startLine && !atEnd() && onlySpaceBeforeOnLine(p_)) return;
    skipToLineEnd();
  }

  struct Pos {
    int line, column;
  };

  std::string_view src_;
  std::string file_;
  DiagnosticSink& sink_;
  int errors_ = 0;  // reported by this run (the sink may hold others')
  size_t p_ = 0;
  int physLine_ = 1;   // 1-based line of p_ in the text
  size_t lineStart_ = 0;
  int lineDelta_ = 0;  // `#line` adjustment: reported line = physLine_ + lineDelta_
  Shader shader_;
  // Context for messages: the instruction being parsed and the operand within it.
  std::string instrName_;
  std::string operandName_;

  // ---- positions and errors ----------------------------------------------------------
  Pos here() const { return {physLine_ + lineDelta_, int(p_ - lineStart_) + 1}; }
  bool atEnd() const { return p_ >= src_.size(); }
  char peek(size_t k = 0) const { return p_ + k < src_.size() ? src_[p_ + k] : '\0'; }

  template <typename... Args>
  [[noreturn]] void errorAt(const char* code, Pos pos, fmt::format_string<Args...> f, Args&&... args) {
    std::string what = fmt::format(f, std::forward<Args>(args)...);
    std::string prefix;
    if (!instrName_.empty()) {
      prefix = "'" + instrName_ + "'";
      if (!operandName_.empty()) prefix += " " + operandName_;
      prefix += ": ";
    }
    throw InstructionError{{SourceLocation{file_, pos.line, pos.column}, Severity::Error, code, prefix + what}};
  }

  // What the current position holds, for "found …" in messages.
  std::string describeHere() {
    if (atEnd()) return "end of input";
    char c = peek();
    if (isIdentChar(c)) {
      size_t e = p_;
      while (e < src_.size() && isIdentChar(src_[e]) && e - p_ < 40) ++e;
      return fmt::format("'{}'", src_.substr(p_, e - p_));
    }
    return quoteChar(c);
  }

  // ---- whitespace, comments, #line -----------------------------------------------------
  void newline() {
    ++physLine_;
    lineStart_ = p_;
  }

  bool onlySpaceBeforeOnLine(size_t at) const {
    for (size_t i = lineStart_; i < at; ++i)
      if (src_[i] != ' ' && src_[i] != '\t' && src_[i] != '\r' && src_[i] != '\f' && src_[i] != '\v')
        return false;
    return true;
  }

  void skipToLineEnd() {
    while (!atEnd() && peek() != '\n') ++p_;
  }

  void skipSpace() {
    for (;;) {
      if (atEnd()) return;
      char c = peek();
      if (c == '\n') {
        ++p_;
        newline();
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++p_;
      } else if (c == ';' || (c == '/' && peek(1) == '/')) {
        skipToLineEnd();
      } else if (c == '/' && peek(1) == '*') {
        Pos start = here();
        p_ += 2;
        for (;;) {
          if (atEnd()) {
            instrName_.clear();
            errorAt(kUnterminatedComment, start, "unterminated comment '/*' (expected '*/')");
          }
          if (peek() == '*' && peek(1) == '/') {
            p_ += 2;
            break;
          }
          if (peek() == '\n') {
            ++p_;
            newline();
          } else {
            ++p_;
          }
        }
      } else if (c == '#' && onlySpaceBeforeOnLine(p_)) {
        directive();
      } else {
        return;
      }
    }
  }

  // `#line N ["file"]` as preprocessors leave them; other directives are refused.
  void directive() {
    Pos start = here();
    ++p_;
    while (peek() == ' ' || peek() == '\t') ++p_;
    size_t w = p_;
    while (!atEnd() && isIdentChar(peek())) ++p_;
    std::string name(src_.substr(w, p_ - w));
    if (name != "line" && !(name.empty() && isDigit(peek()))) {
      instrName_.clear();
      errorAt(kDirective, start, "preprocessor directive '#{}' is not supported (assembly text is not preprocessed; only #line is accepted)",
                          name);
    }
    while (peek() == ' ' || peek() == '\t') ++p_;
    long n = 0;
    bool digits = false;
    while (isDigit(peek())) {
      digits = true;
      n = std::min<long>(n * 10 + (peek() - '0'), 1000000000L);
      ++p_;
    }
    while (peek() == ' ' || peek() == '\t') ++p_;
    if (peek() == '"') {
      ++p_;
      size_t f = p_;
      while (!atEnd() && peek() != '"' && peek() != '\n') ++p_;
      std::string fileName(src_.substr(f, p_ - f));
      if (peek() == '"') ++p_;
      if (!fileName.empty()) file_ = fileName;
    }
    skipToLineEnd();
    // The line after the directive is line n.
    if (digits) lineDelta_ = int(n) - (physLine_ + 1);
  }

  // ---- lexical pieces -------------------------------------------------------------------
  std::string_view readWord() {
    size_t s = p_;
    while (!atEnd() && isIdentChar(peek())) ++p_;
    return src_.substr(s, p_ - s);
  }

  bool accept(char c) {
    skipSpace();
    if (peek() == c) {
      ++p_;
      return true;
    }
    return false;
  }

  void expect(char c, const char* what) {
    skipSpace();
    if (peek() != c) errorAt(kSyntax, here(), "expected {}, found {}", what, describeHere());
    ++p_;
  }

  // ---- version ----------------------------------------------------------------------------
  void parseVersion() {
    Pos pos = here();
    if (atEnd())
      errorAt(kVersion, pos, "empty shader: expected a version (vs_1_1, vs_2_0, vs_3_0, ps_1_1 … ps_3_0) first");
    size_t s = p_;
    while (!atEnd() && (isIdentChar(peek()) || peek() == '.')) ++p_;
    std::string text = lowerCopy(src_.substr(s, p_ - s));
    if (text.empty() || !isIdentStart(text[0])) {
      p_ = s;
      errorAt(kVersion, pos, "expected the shader version (vs_1_1 … ps_3_0) first, found {}", describeHere());
    }
    auto v = parseVersionName(text);
    if (!v) {
      std::string shown(src_.substr(s, std::min<size_t>(p_ - s, 40)));
      if (findMnemonic(lowerCopy(shown.substr(0, shown.find('_')))))
        errorAt(kVersion, pos, "expected the shader version (vs_1_1 … ps_3_0) before the first instruction, found '{}'",
                          shown);
      errorAt(kVersion, pos,
                        "unknown shader version '{}' (expected vs_1_1, vs_2_0, vs_2_x, vs_3_0, ps_1_1, ps_1_2, ps_1_3, "
                        "ps_1_4, ps_2_0, ps_2_x, ps_3_0; `vs.1.1` spelling also accepted)",
                        shown);
    }
    shader_.version = *v;
  }

  // ---- instructions -----------------------------------------------------------------------
  void parseInstruction() {
    Instruction ins;
    instrName_.clear();
    operandName_.clear();
    const Version ver = shader_.version;
    Pos start = here();

    if (peek() == '+') {
      ++p_;
      ins.coissue = true;
      if (!ver.ps1x()) errorAt(kNotInVersion, start, "co-issue '+' is only available in ps_1_x, not in {}", ver.name());
      skipSpace();
    }
    if (peek() == '(') {
      Pos ppos = here();
      ++p_;
      parsePredicate(ins);
      if (!ver.sm2plus())
        errorAt(kNotInVersion, ppos, "predicated instructions need shader model 2.0 or later, not {}", ver.name());
      skipSpace();
    }

    Pos mpos = here();
    if (!isIdentStart(peek())) {
      if (peek() == '.' || isDigit(peek()))
        errorAt(kSyntax, mpos, "expected an instruction, found {}", describeHere());
      errorAt(kSyntax, mpos, "unexpected {} (expected an instruction)", quoteChar(peek()));
    }
    std::string_view word = readWord();
    std::string lw = lowerCopy(word);
    ins.pos = {mpos.line, mpos.column};

    // Mnemonic = base name, then `_`-separated suffixes (modifiers, comparison, dcl usage).
    std::vector<std::string> parts;
    {
      size_t a = 0;
      for (;;) {
        size_t b = lw.find('_', a);
        parts.push_back(lw.substr(a, b == std::string::npos ? std::string::npos : b - a));
        if (b == std::string::npos) break;
        a = b + 1;
      }
    }
    const MnemonicInfo* m = findMnemonic(parts[0]);
    if (!m) {
      if (lw == "vs" || lw == "ps" || parseVersionName(lw)) {
        while (!atEnd() && (isIdentChar(peek()) || peek() == '.') && p_ - (mpos.column - 1 + lineStart_) < 40) ++p_;
        errorAt(kVersion, mpos, "a second shader version '{}' (the version must appear once, first)",
                          src_.substr(lineStart_ + mpos.column - 1, p_ - (lineStart_ + mpos.column - 1)));
      }
      std::string near = nearestMnemonic(parts[0]);
      if (!near.empty())
        errorAt(kUnknownInstruction, mpos, "unknown instruction '{}' (did you mean '{}'?)", word, near);
      errorAt(kUnknownInstruction, mpos, "unknown instruction '{}' (expected an instruction such as mov, add, mul, mad, dp3, tex, texld, def, dcl_*)",
                                   word);
    }
    ins.opcode = m->opcode;
    ins.control = m->control;
    checkMnemonicVersion(*m, mpos);
    // phase is a bare token; declarations and definitions are not executed.
    if ((ins.predicated || ins.coissue) &&
        (m->kind == MnemonicKind::Def || m->kind == MnemonicKind::Dcl || ins.opcode == Opcode::Phase ||
         ins.opcode == Opcode::Label))
      errorAt(kInstructionModifier, start, "'{}' cannot be {}", m->name, ins.coissue ? "co-issued" : "predicated");

    size_t firstSuffix = 1;
    if (m->kind == MnemonicKind::Compare) {
      // `if_lt`, `break_ge`, `setp_eq` (also spelled `ifc_lt`, `breakc_ge`).
      Comparison cmp = parts.size() > 1 ? findComparison(parts[1]) : Comparison::None;
      if (cmp != Comparison::None) {
        ins.opcode = m->compareOpcode;
        ins.control = uint8_t(cmp);
        firstSuffix = 2;
      } else if (m->opcode == m->compareOpcode) {
        errorAt(kInstructionModifier, mpos, "'{}' needs a comparison suffix (_gt, _lt, _ge, _le, _eq, _ne)", word);
      }
    }
    if (m->kind == MnemonicKind::Dcl && parts.size() > 1 && !findResultModifier(parts[1])) {
      parseDclUsage(ins, parts[1], mpos);
      firstSuffix = 2;
    }
    instrName_ = std::string(word);
    for (size_t i = firstSuffix; i < parts.size(); ++i) applyInstructionModifier(ins, parts[i], mpos);

    switch (m->kind) {
      case MnemonicKind::Def: parseDef(ins); break;
      case MnemonicKind::Dcl: parseDcl(ins); break;
      default: parseOperands(ins, mpos); break;
    }
    // m3x3 r0, v3, c0 (as the DirectX 8 shaders write it) writes the components the
    // instruction computes: .xyz for m3x3/m4x3, .xy for m3x2, the only masks D3D9 accepts.
    if (ins.hasDst && !dstMaskGiven_) {
      if (const OpcodeInfo* info = findOpcode(ins.opcode); info && info->matrixRows)
        ins.dst.writeMask = uint8_t((1u << info->matrixRows) - 1);  // one component per row
    }
    if (ins.opcode == Opcode::Dcl && ins.dst.type != RegType::Sampler &&
        ins.textureType != TextureType::Unknown) {
      operandName_ = "dst";
      errorAt(kDeclaration, mpos, "expected a sampler register s# for a dcl_{} declaration, found {}",
                            textureTypeName(ins.textureType), registerText(ins.dst.type, ins.dst.index));
    }
    if (ins.opcode == Opcode::Dcl && ver.isPixel() && ver.major < 3 &&
        (ins.dst.type == RegType::Input || ins.dst.type == RegType::Texture)) {
      // ps_2_0/2_x: the usage token of v#/t# declarations is bit 31 alone.
      ins.usage = DeclUsage::Position;
      ins.usageIndex = 0;
    }
    if ((ins.dst.shift != 0 || ins.dst.resultMod != 0) && !ins.hasDst)
      errorAt(kInstructionModifier, mpos, "instruction modifiers need an instruction with a destination register");
    shader_.instructions.push_back(std::move(ins));
    instrName_.clear();
    operandName_.clear();
  }

  void checkMnemonicVersion(const MnemonicInfo& m, Pos pos) {
    const Version v = shader_.version;
    switch (m.form) {
      case FormRule::Any: break;
      case FormRule::Ps1Tex:  // tex, texcoord: ps_1_0–ps_1_3 spellings
        if (!(v.ps1x() && !v.atLeast(1, 4)))
          errorAt(kNotInVersion, pos, "'{}' is the ps_1_1–ps_1_3 instruction; {} uses '{}'", m.name, v.name(),
                                 m.opcode == Opcode::Tex ? "texld" : "texcrd");
        break;
      case FormRule::Ps14Up:  // texld: ps_1_4 and later (vs_3_0 samples with texldl)
        if (v.isVertex())
          errorAt(kNotInVersion, pos, "'{}' is a pixel shader instruction (vs_3_0 samples textures with texldl)", m.name);
        if (v.ps1x() && !v.atLeast(1, 4))
          errorAt(kNotInVersion, pos, "'{}' needs ps_1_4 or later; {} uses 'tex'", m.name, v.name());
        break;
      case FormRule::Ps14Only:  // texcrd
        if (!(v.isPixel() && v.major == 1 && v.minor == 4))
          errorAt(kNotInVersion, pos, "'{}' is a ps_1_4 instruction{}", m.name,
                                 v.ps1x() ? std::string("; ") + v.name() + " uses 'texcoord'" : std::string());
        break;
      case FormRule::Sm2Up:  // texldp, texldb: the control bits exist from SM2 on
        if (v.isVertex())
          errorAt(kNotInVersion, pos, "'{}' is a pixel shader instruction (vs_3_0 samples textures with texldl)", m.name);
        if (!v.sm2plus()) errorAt(kNotInVersion, pos, "'{}' needs shader model 2.0 or later, not {}", m.name, v.name());
        break;
      case FormRule::Reserved:
        errorAt(kNotInVersion, pos, "'{}' is a reserved opcode that no shader version accepts", m.name);
    }
  }

  void applyInstructionModifier(Instruction& ins, const std::string& s, Pos pos) {
    if (s.empty()) errorAt(kInstructionModifier, pos, "empty instruction modifier '_' in '{}'", instrName_);
    if (auto shift = findShift(s)) {
      if (!shader_.version.ps1x())
        errorAt(kNotInVersion, pos, "instruction modifier '_{}' is only available in ps_1_x, not in {}", s,
                               shader_.version.name());
      if (ins.dst.shift != 0) errorAt(kInstructionModifier, pos, "two scale modifiers ('_{}' and another) on one instruction", s);
      ins.dst.shift = *shift;
      return;
    }
    if (auto rm = findResultModifier(s)) {
      ins.dst.resultMod |= *rm;
      return;
    }
    if (findComparison(s) != Comparison::None)
      errorAt(kInstructionModifier, pos, "comparison '_{}' only applies to if, break and setp", s);
    errorAt(kInstructionModifier, pos, "unknown instruction modifier '_{}' (expected _x2, _x4, _x8, _d2, _d4, _d8, _sat, _pp or _centroid)",
                                  s);
  }

  void parsePredicate(Instruction& ins) {
    skipSpace();
    operandName_ = "predicate";
    if (peek() == '!') {
      ++p_;
      ins.predicateNot = true;
      skipSpace();
    }
    Pos rpos = here();
    std::string w = lowerCopy(readWord());
    if (w != "p0") errorAt(kPredicate, rpos, "expected the predicate register p0 inside '( )', found '{}'", w);
    ins.predicated = true;
    skipSpace();
    if (peek() == '.') {
      ++p_;
      Pos spos = here();
      std::string_view sw = readWord();
      ins.predicateSwizzle = parseSwizzle(sw, spos);
    }
    expect(')', "')' after the predicate");
    operandName_.clear();
  }

  void parseDclUsage(Instruction& ins, const std::string& s, Pos pos) {
    if (auto tt = findTextureType(s)) {
      ins.textureType = *tt;
      return;
    }
    if (s == "1d") errorAt(kDeclaration, pos, "1D samplers cannot be declared (expected dcl_2d, dcl_cube or dcl_volume)");
    size_t d = s.size();
    while (d > 0 && isDigit(s[d - 1])) --d;
    auto usage = findUsage(s.substr(0, d));
    if (!usage)
      errorAt(kDeclaration, pos,
                            "unknown declaration 'dcl_{}' (expected a usage such as dcl_position, dcl_normal, dcl_texcoord0, "
                            "dcl_color1, or a sampler type dcl_2d, dcl_cube, dcl_volume)",
                            s);
    int index = 0;
    if (d < s.size()) {
      if (s.size() - d > 2) errorAt(kDeclaration, pos, "usage index in 'dcl_{}' must be 0 to 15", s);
      index = std::stoi(s.substr(d));
      if (index > 15) errorAt(kDeclaration, pos, "usage index in 'dcl_{}' must be 0 to 15", s);
    }
    ins.usage = *usage;
    ins.usageIndex = uint8_t(index);
  }

  // ---- operands ---------------------------------------------------------------------------
  void parseOperands(Instruction& ins, Pos mpos) {
    OperandForm form = operandForm(ins.opcode, shader_.version);
    const int want = (form.dst ? 1 : 0) + form.src;
    int got = 0;
    std::vector<SrcParam> srcs;
    if (want > 0) {
      for (;;) {
        skipSpace();
        if (got >= want) {
          std::string name = quotedName();
          instrName_.clear();
          operandName_.clear();
          errorAt(kOperandCount, here(), "{} takes {} operand{} ({}) in {}, found more", name, want, want == 1 ? "" : "s",
                                 describeForm(form), shader_.version.name());
        }
        if (got == 0 && form.dst) {
          operandName_ = "dst";
          checkOperandStart(ins, form, got, mpos);
          ins.hasDst = true;
          parseDst(ins.dst);
        } else {
          int si = got - (form.dst ? 1 : 0);
          operandName_ = kOperandNames[si];
          checkOperandStart(ins, form, got, mpos);
          srcs.push_back(parseSrc());
        }
        ++got;
        operandName_.clear();
        if (!accept(',')) break;
      }
    }
    if (got != want) operandCountError(form, got, mpos);
    ins.srcCount = uint8_t(srcs.size());
    for (size_t i = 0; i < srcs.size(); ++i) ins.src[i] = srcs[i];
  }

  std::string quotedName() const { return "'" + instrName_ + "'"; }

  std::string describeForm(const OperandForm& f) const {
    std::string s;
    if (f.dst) s = "dst";
    for (int i = 0; i < f.src; ++i) s += std::string(s.empty() ? "" : ", ") + kOperandNames[i];
    return s.empty() ? "none" : s;
  }

  [[noreturn]] void operandCountError(const OperandForm& form, int got, Pos mpos) {
    const int want = (form.dst ? 1 : 0) + form.src;
    std::string saved = instrName_;
    instrName_.clear();
    operandName_.clear();
    errorAt(kOperandCount, mpos, "'{}' takes {} operand{} ({}) in {}, found {}", saved, want, want == 1 ? "" : "s",
                           describeForm(form), shader_.version.name(), got);
  }

  // Before an operand: a missing operand shows up as the next instruction's mnemonic.
  void checkOperandStart(const Instruction& ins, const OperandForm& form, int got, Pos mpos) {
    if (atEnd()) operandCountError(form, got, mpos);
    if (isIdentStart(peek())) {
      size_t s = p_;
      while (s < src_.size() && isIdentChar(src_[s])) ++s;
      std::string w = lowerCopy(src_.substr(p_, s - p_));
      std::string base = w.substr(0, w.find('_'));
      if (findMnemonic(base) && !looksLikeRegister(base)) operandCountError(form, got, mpos);
    } else if (peek() == '+' || peek() == '(') {
      operandCountError(form, got, mpos);
    }
  }

  static bool looksLikeRegister(const std::string& w) {
    // Register names that are also mnemonic prefixes do not exist, but keep `abs` etc. out.
    return w.size() >= 2 && std::all_of(w.begin() + 1, w.end(), isDigit);
  }

  // Register name (letters + number) → type and index for the current version.
  struct Reg {
    RegType type;
    uint32_t index;
    bool hasNumber;
  };

  Reg parseRegisterName(std::string_view word, Pos pos, bool allowBareForRelative) {
    std::string lw = lowerCopy(word);
    size_t d = 0;
    while (d < lw.size() && !isDigit(lw[d])) ++d;
    std::string letters = lw.substr(0, d);
    std::string digits = lw.substr(d);
    for (char c : digits)
      if (!isDigit(c)) errorAt(kRegister, pos, "unknown register '{}' ({})", word, registerHelp(shader_.version));
    const RegisterName* rn = findRegisterName(letters, shader_.version);
    if (!rn) {
      if (lw.empty()) errorAt(kRegister, pos, "expected a register, found {}", describeHere());
      errorAt(kRegister, pos, "unknown register '{}' ({})", word, registerHelp(shader_.version));
    }
    Reg r{rn->type, rn->fixedIndex, !digits.empty()};
    if (rn->indexed) {
      if (digits.empty()) {
        if (!allowBareForRelative || peekAfterSpace() != '[')
          errorAt(kRegister, pos, "register '{}' needs a number (e.g. {}0)", word, letters);
        r.index = 0;
      } else {
        if (digits.size() > 6) errorAt(kRegisterRange, pos, "register number of '{}' is out of range", word);
        r.index = uint32_t(std::stoul(digits));
      }
      if (r.index > rn->maxIndex)
        errorAt(kRegisterRange, pos, "register '{}' is out of range ({}{} is the highest encodable)", word, letters, rn->maxIndex);
    } else if (!digits.empty()) {
      errorAt(kRegister, pos, "unknown register '{}' ({})", word, registerHelp(shader_.version));
    }
    return r;
  }

  char peekAfterSpace() {
    size_t save = p_;
    int saveLine = physLine_;
    size_t saveLineStart = lineStart_;
    int saveDelta = lineDelta_;
    std::string saveFile = file_;
    skipSpace();
    char c = peek();
    p_ = save;
    physLine_ = saveLine;
    lineStart_ = saveLineStart;
    lineDelta_ = saveDelta;
    file_ = saveFile;
    return c;
  }

  std::string registerText(RegType t, uint32_t index) const {
    return registerName(t, index, shader_.version);
  }

  // `[a0.x + n]`, `[n + a0.x]`, `[aL]`, `[5]`: adds the constant part to `index`.
  // Returns true when an address register was named.
  bool parseRelative(uint32_t& index, RelativeAddress& rel, uint32_t maxIndex, Pos regPos) {
    Pos open = here();
    ++p_;  // '['
    bool haveAddr = false;
    long offset = 0;
    bool first = true;
    for (;;) {
      skipSpace();
      bool negative = false;
      if (!first) {
        if (peek() == ']') break;
        if (peek() == '+') {
          ++p_;
        } else if (peek() == '-') {
          ++p_;
          negative = true;
        } else {
          errorAt(kRelative, here(), "expected '+', '-' or ']' in the relative address, found {}", describeHere());
        }
        skipSpace();
      }
      first = false;
      Pos tpos = here();
      if (isDigit(peek())) {
        long n = 0;
        while (isDigit(peek())) {
          n = std::min<long>(n * 10 + (peek() - '0'), 100000L);
          ++p_;
        }
        offset += negative ? -n : n;
      } else if (isIdentStart(peek())) {
        if (negative) errorAt(kRelative, tpos, "an address register cannot be subtracted");
        std::string w = lowerCopy(readWord());
        if (haveAddr) errorAt(kRelative, tpos, "two address registers in one relative address");
        if (w == "a0") {
          rel.type = RegType::Addr;
          rel.component = 0;
          skipSpace();
          if (peek() == '.') {
            ++p_;
            Pos cpos = here();
            std::string c = lowerCopy(readWord());
            int comp = c.size() == 1 ? componentIndex(c[0]) : -1;
            if (comp < 0)
              errorAt(kRelative, cpos, "expected one component (.x, .y, .z or .w) of a0, found '.{}'", c);
            rel.component = uint8_t(comp);
          }
        } else if (w == "al") {
          rel.type = RegType::Loop;
          rel.component = 0;
        } else {
          errorAt(kRelative, tpos, "expected a0.x or aL in the relative address, found '{}'", w);
        }
        haveAddr = true;
      } else {
        errorAt(kRelative, tpos, "expected a number, a0.x or aL in the relative address, found {}", describeHere());
      }
    }
    ++p_;  // ']'
    long total = long(index) + offset;
    if (total < 0 || total > long(maxIndex))
      errorAt(kRegisterRange, open, "register offset {} is out of range (0 to {})", total, maxIndex);
    index = uint32_t(total);
    if (haveAddr) {
      const Version v = shader_.version;
      if (v.isPixel() && v.major < 3)
        errorAt(kRelative, regPos, "relative addressing is not available in {}", v.name());
      if (v.isVertex() && v.major < 2 && (rel.type != RegType::Addr || rel.component != 0))
        errorAt(kRelative, regPos, "{} relative addressing reads a0.x only", v.name());
    }
    return haveAddr;
  }

  bool dstMaskGiven_ = false;  // the last destination had an explicit write mask

  void parseDst(DstParam& d) {
    skipSpace();
    Pos pos = here();
    if (!isIdentStart(peek())) {
      if (peek() == '-' || peek() == '!' || (peek() == '1' && nextNonSpaceIs('-')))
        errorAt(kSourceModifier, pos, "a destination register takes no source modifier");
      errorAt(kSyntax, pos, "expected a destination register, found {}", describeHere());
    }
    std::string_view word = readWord();
    size_t us = word.find('_');
    if (us != std::string_view::npos)
      errorAt(kSourceModifier, pos, "a destination register takes no modifier ('{}'; instruction modifiers go on the mnemonic, e.g. mul_x2)",
                               word);
    Reg r = parseRegisterName(word, pos, true);
    d.type = r.type;
    d.index = uint16_t(r.index);
    skipSpace();
    if (peek() == '[') {
      const RegisterName* rn = findRegisterName(registerLetters(word), shader_.version);
      uint32_t idx = r.index;
      bool rel = parseRelative(idx, d.rel, rn ? rn->maxIndex : 2047, pos);
      d.index = uint16_t(idx);
      if (rel) {
        if (!(shader_.version.isVertex() && shader_.version.major >= 3))
          errorAt(kRelative, pos, "relative addressing of a destination needs vs_3_0 (o[aL + n])");
        d.relative = true;
      }
      skipSpace();
    } else if (!r.hasNumber && findRegisterName(registerLetters(word), shader_.version) &&
               findRegisterName(registerLetters(word), shader_.version)->indexed) {
      errorAt(kRegister, pos, "register '{}' needs a number", word);
    }
    dstMaskGiven_ = false;
    if (peek() == '.') {
      ++p_;
      Pos mpos = here();
      std::string_view mask = readWord();
      d.writeMask = parseWriteMask(mask, mpos);
      dstMaskGiven_ = true;
    }
  }

  static std::string registerLetters(std::string_view word) {
    std::string s;
    for (char c : word) {
      if (isDigit(c) || c == '_') break;
      s += lower(c);
    }
    return s;
  }

  bool nextNonSpaceIs(char c) const {
    size_t i = p_ + 1;
    while (i < src_.size() && (src_[i] == ' ' || src_[i] == '\t')) ++i;
    return i < src_.size() && src_[i] == c;
  }

  SrcParam parseSrc() {
    SrcParam s;
    skipSpace();
    Pos pos = here();
    bool neg = false, comp = false, logicalNot = false;
    if (peek() == '-') {
      ++p_;
      neg = true;
      skipSpace();
    } else if (peek() == '1' && !isIdentChar(peek(1)) && peek(1) != '.') {
      // `1-r0`: the invert modifier.
      ++p_;
      skipSpace();
      if (peek() != '-') errorAt(kSyntax, pos, "expected a source register, found a number (did you mean '1-' invert?)");
      ++p_;
      comp = true;
      skipSpace();
    }
    if (peek() == '!') {
      ++p_;
      logicalNot = true;
      skipSpace();
    }
    Pos rpos = here();
    if (!isIdentStart(peek())) {
      if (isDigit(peek()) || peek() == '.')
        errorAt(kSyntax, rpos, "expected a source register, found a number (immediate values need a def'd constant)");
      errorAt(kSyntax, rpos, "expected a source register, found {}", describeHere());
    }
    std::string_view word = readWord();
    std::string_view regPart = word.substr(0, word.find('_'));
    std::vector<std::pair<std::string, Pos>> mods;
    if (regPart.size() < word.size()) collectModifiers(word.substr(regPart.size() + 1), rpos, mods);
    Reg r = parseRegisterName(regPart, rpos, true);
    s.type = r.type;
    s.index = uint16_t(r.index);
    skipSpace();
    bool bracketed = false;
    if (peek() == '[') {
      const RegisterName* rn = findRegisterName(registerLetters(regPart), shader_.version);
      uint32_t idx = r.index;
      s.relative = parseRelative(idx, s.rel, rn ? rn->maxIndex : 2047, rpos);
      s.index = uint16_t(idx);
      bracketed = true;
    }
    if (!r.hasNumber && !bracketed) {
      const RegisterName* rn = findRegisterName(registerLetters(regPart), shader_.version);
      if (rn && rn->indexed) errorAt(kRegister, rpos, "register '{}' needs a number", regPart);
    }
    bool haveSwizzle = false;
    for (;;) {
      if (peek() == '.' && !haveSwizzle) {
        ++p_;
        Pos spos = here();
        std::string_view sw = readWord();
        std::string_view letters = sw.substr(0, sw.find('_'));
        s.swizzle = parseSwizzle(letters, spos);
        if (letters.size() < sw.size()) collectModifiers(sw.substr(letters.size() + 1), spos, mods);
        haveSwizzle = true;
      } else if (peek() == '_') {
        Pos mp = here();
        ++p_;
        collectModifiers(readWord(), mp, mods);
      } else {
        break;
      }
    }
    s.mod = combineModifiers(neg, comp, logicalNot, mods, pos);
    return s;
  }

  void collectModifiers(std::string_view text, Pos pos, std::vector<std::pair<std::string, Pos>>& out) {
    size_t a = 0;
    for (;;) {
      size_t b = text.find('_', a);
      std::string part = lowerCopy(text.substr(a, b == std::string_view::npos ? std::string_view::npos : b - a));
      out.emplace_back(part, pos);
      if (b == std::string_view::npos) break;
      a = b + 1;
    }
  }

  SrcMod combineModifiers(bool neg, bool comp, bool logicalNot, const std::vector<std::pair<std::string, Pos>>& mods,
                          Pos pos) {
    if (mods.size() > 1)
      errorAt(kSourceModifier, mods[1].second, "source modifiers '_{}' and '_{}' cannot be combined", mods[0].first, mods[1].first);
    if (logicalNot) {
      if (neg || comp || !mods.empty()) errorAt(kSourceModifier, pos, "'!' cannot be combined with other source modifiers");
      return SrcMod::Not;
    }
    if (comp) {
      if (!mods.empty()) errorAt(kSourceModifier, pos, "the invert modifier '1-' cannot be combined with '_{}'", mods[0].first);
      return SrcMod::Comp;
    }
    if (mods.empty()) return neg ? SrcMod::Neg : SrcMod::None;
    const std::string& m = mods[0].first;
    struct Pair {
      const char* name;
      SrcMod plain, negated;
    };
    static const Pair table[] = {
        {"bias", SrcMod::Bias, SrcMod::BiasNeg}, {"bx2", SrcMod::Sign, SrcMod::SignNeg},
        {"x2", SrcMod::X2, SrcMod::X2Neg},       {"abs", SrcMod::Abs, SrcMod::AbsNeg},
        {"dz", SrcMod::Dz, SrcMod::None},        {"db", SrcMod::Dz, SrcMod::None},
        {"dw", SrcMod::Dw, SrcMod::None},        {"da", SrcMod::Dw, SrcMod::None},
    };
    for (const Pair& e : table) {
      if (m != e.name) continue;
      if (neg) {
        if (e.negated == SrcMod::None) errorAt(kSourceModifier, pos, "'-' cannot be combined with '_{}'", m);
        return e.negated;
      }
      return e.plain;
    }
    errorAt(kSourceModifier, mods[0].second, "unknown source modifier '_{}' (expected _bias, _bx2, _x2, _abs, _dz, _db, _dw or _da)", m);
  }

  uint8_t parseSwizzle(std::string_view letters, Pos pos) {
    int sel[4];
    bool xyzw = false, rgba = false;
    if (letters.empty() || letters.size() > 4)
      errorAt(kSwizzle, pos, "bad swizzle '.{}' (expected 1 to 4 of x, y, z, w or r, g, b, a)", letters);
    for (size_t i = 0; i < letters.size(); ++i) {
      char c = lower(letters[i]);
      int k = componentIndex(c);
      if (k < 0) errorAt(kSwizzle, pos, "bad swizzle '.{}' (expected 1 to 4 of x, y, z, w or r, g, b, a)", letters);
      (c == 'x' || c == 'y' || c == 'z' || c == 'w' ? xyzw : rgba) = true;
      sel[i] = k;
    }
    if (xyzw && rgba) errorAt(kSwizzle, pos, "bad swizzle '.{}' (x y z w and r g b a letters cannot be mixed)", letters);
    for (size_t i = letters.size(); i < 4; ++i) sel[i] = sel[letters.size() - 1];  // `.xy` = `.xyyy`
    return uint8_t(sel[0] | sel[1] << 2 | sel[2] << 4 | sel[3] << 6);
  }

  uint8_t parseWriteMask(std::string_view letters, Pos pos) {
    if (letters.empty() || letters.size() > 4)
      errorAt(kSwizzle, pos, "bad write mask '.{}' (expected components of x, y, z, w or r, g, b, a in order)", letters);
    bool xyzw = false, rgba = false;
    int last = -1;
    uint8_t mask = 0;
    for (char ch : letters) {
      char c = lower(ch);
      int k = componentIndex(c);
      if (k < 0)
        errorAt(kSwizzle, pos, "bad write mask '.{}' (expected components of x, y, z, w or r, g, b, a in order)", letters);
      (c == 'x' || c == 'y' || c == 'z' || c == 'w' ? xyzw : rgba) = true;
      if (k <= last) errorAt(kSwizzle, pos, "bad write mask '.{}' (components must appear once, in x, y, z, w order)", letters);
      last = k;
      mask |= uint8_t(1 << k);
    }
    if (xyzw && rgba) errorAt(kSwizzle, pos, "bad write mask '.{}' (x y z w and r g b a letters cannot be mixed)", letters);
    return mask;
  }

  static int componentIndex(char c) {
    switch (c) {
      case 'x': case 'r': return 0;
      case 'y': case 'g': return 1;
      case 'z': case 'b': return 2;
      case 'w': case 'a': return 3;
      default: return -1;
    }
  }

  // ---- def / defi / defb --------------------------------------------------------------------
  void parseDef(Instruction& ins) {
    skipSpace();
    operandName_ = "dst";
    Pos pos = here();
    if (!isIdentStart(peek())) errorAt(kSyntax, pos, "expected a constant register, found {}", describeHere());
    std::string_view word = readWord();
    Reg r = parseRegisterName(word, pos, false);
    RegType want = ins.opcode == Opcode::Def ? RegType::Const
                   : ins.opcode == Opcode::DefI ? RegType::ConstInt
                                                : RegType::ConstBool;
    if (r.type != want)
      errorAt(kDefinition, pos, "expected a {} register, found '{}'",
                           want == RegType::Const ? "c#" : want == RegType::ConstInt ? "i#" : "b#", word);
    ins.hasDst = true;
    ins.dst.type = r.type;
    ins.dst.index = uint16_t(r.index);
    skipSpace();
    if (peek() == '.') errorAt(kDefinition, here(), "'{}' takes no write mask", instrName_);
    const int count = ins.opcode == Opcode::DefB ? 1 : 4;
    for (int i = 0; i < count; ++i) {
      operandName_.clear();
      if (!accept(',')) {
        instrName_.clear();
        errorAt(kDefinition, ins.pos.line ? Pos{ins.pos.line, ins.pos.column} : pos, "'{}' takes a register and {} value{}, found {}",
                             lowerCopy(opcodeMnemonic(ins.opcode)), count, count == 1 ? "" : "s", i);
      }
      skipSpace();
      operandName_ = fmt::format("value {}", i + 1);
      if (ins.opcode == Opcode::Def)
        ins.literal[i] = parseFloatLiteral();
      else if (ins.opcode == Opcode::DefI)
        ins.literal[i] = parseIntLiteral();
      else
        ins.literal[i] = parseBoolLiteral();
    }
    operandName_.clear();
    skipSpace();
    if (peek() == ',') errorAt(kDefinition, here(), "'{}' takes {} value{}, found more", instrName_, count, count == 1 ? "" : "s");
  }

  uint32_t parseFloatLiteral() {
    Pos pos = here();
    size_t s = p_;
    bool negative = false;
    if (peek() == '-' || peek() == '+') {
      negative = peek() == '-';
      ++p_;
      skipInlineSpace();
    }
    size_t numStart = p_;
    bool digits = false;
    while (isDigit(peek())) ++p_, digits = true;
    if (peek() == '.') {
      ++p_;
      while (isDigit(peek())) ++p_, digits = true;
    }
    if (!digits) {
      p_ = s;
      errorAt(kLiteral, pos, "expected a number, found {}", describeHere());
    }
    if ((peek() == 'e' || peek() == 'E') &&
        (isDigit(peek(1)) || ((peek(1) == '-' || peek(1) == '+') && isDigit(peek(2))))) {
      p_ += 2;
      while (isDigit(peek())) ++p_;
    }
    size_t numEnd = p_;
    if (peek() == 'f' || peek() == 'F') ++p_;
    if (isIdentChar(peek()) || peek() == '.')
      errorAt(kLiteral, pos, "malformed number '{}'", src_.substr(s, std::min<size_t>(p_ - s + 1, 40)));
    std::string text(src_.substr(numStart, numEnd - numStart));
    float value = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc::result_out_of_range) {
      // Overflow is an error; underflow rounds to zero as the C library does.
      double dv = 0;
      auto [p2, ec2] = std::from_chars(text.data(), text.data() + text.size(), dv);
      if (ec2 == std::errc::result_out_of_range || std::abs(dv) > 3.4028235e38)
        errorAt(kLiteral, pos, "number '{}' is out of the float range", src_.substr(s, std::min<size_t>(numEnd - s, 40)));
      value = float(dv);
    } else if (ec != std::errc() || ptr != text.data() + text.size()) {
      errorAt(kLiteral, pos, "malformed number '{}'", src_.substr(s, std::min<size_t>(numEnd - s, 40)));
    }
    if (negative) value = -value;
    uint32_t bits;
    std::memcpy(&bits, &value, 4);
    return bits;
  }

  void skipInlineSpace() {
    while (peek() == ' ' || peek() == '\t') ++p_;
  }

  uint32_t parseIntLiteral() {
    Pos pos = here();
    bool negative = false;
    if (peek() == '-' || peek() == '+') {
      negative = peek() == '-';
      ++p_;
      skipInlineSpace();
    }
    if (!isDigit(peek())) errorAt(kLiteral, pos, "expected an integer, found {}", describeHere());
    long long n = 0;
    while (isDigit(peek())) {
      n = n * 10 + (peek() - '0');
      if (n > 0x80000000LL) errorAt(kLiteral, pos, "integer is out of the 32-bit range");
      ++p_;
    }
    if (isIdentChar(peek()) || peek() == '.') errorAt(kLiteral, pos, "expected an integer (defi takes integers), found {}", describeAt(pos));
    if (negative) n = -n;
    if (n > 0x7FFFFFFFLL) errorAt(kLiteral, pos, "integer is out of the 32-bit range");
    return uint32_t(int32_t(n));
  }

  std::string describeAt(Pos) { return describeHere(); }

  uint32_t parseBoolLiteral() {
    Pos pos = here();
    if (isIdentStart(peek())) {
      std::string w = lowerCopy(readWord());
      if (w == "true") return 1;
      if (w == "false") return 0;
      errorAt(kLiteral, pos, "expected true or false, found '{}'", w);
    }
    if (isDigit(peek())) {
      bool nonzero = false;
      while (isDigit(peek())) nonzero |= peek() != '0', ++p_;
      if (isIdentChar(peek()) || peek() == '.') errorAt(kLiteral, pos, "expected true or false");
      return nonzero ? 1 : 0;
    }
    errorAt(kLiteral, pos, "expected true or false, found {}", describeHere());
  }

  // ---- dcl ------------------------------------------------------------------------------------
  void parseDcl(Instruction& ins) {
    skipSpace();
    operandName_ = "dst";
    Pos pos = here();
    if (atEnd() || !isIdentStart(peek())) errorAt(kSyntax, pos, "expected the register to declare, found {}", describeHere());
    ins.hasDst = true;
    parseDst(ins.dst);
    if (ins.dst.relative) errorAt(kDeclaration, pos, "a declaration names one register, not a relative address");
    operandName_.clear();
    skipSpace();
    if (peek() == ',') errorAt(kDeclaration, here(), "'{}' declares one register, found more operands", instrName_);
  }
};

}  // namespace

Shader assemble(std::string_view source, std::string_view fileName, DiagnosticSink& diagnostics) {
  return Parser(source, fileName, diagnostics).run();
}

Shader assemble(std::string_view source, std::string_view fileName) {
  DiagnosticSink sink;
  Shader shader = assemble(source, fileName, sink);
  if (sink.hasErrors()) {
    std::string message;
    for (const refx::Diagnostic& d : sink.all()) message += (message.empty() ? "" : "\n") + d.str();
    throw Error(std::move(message));
  }
  return shader;
}

std::vector<uint32_t> assembleTokens(std::string_view source, std::string_view fileName) {
  return encode(assemble(source, fileName));
}

}  // namespace refx::shader
