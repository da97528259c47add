// Macro expansion follows Prosser's algorithm (the one behind the C standard's
// wording): every token carries a hide set, the macros it came out of, and a name in
// its own hide set is never expanded again ("painted blue").
#include "hlsl/preprocessor.h"

#include <algorithm>
#include <climits>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "hlsl/lexer.h"

namespace refx::hlsl::detail {

namespace {

namespace fs = std::filesystem;

// Limits that turn hostile input into a diagnostic instead of a hang or a crash.
constexpr size_t kMaxSubstitutedTokens = size_t{2} << 20;  // all macro expansions of one run together
constexpr int kMaxArgumentNesting = 200;                    // F(G(H(...))) argument pre-expansion depth
constexpr size_t kMaxIncludeDepth = 64;
constexpr int kMaxIncludes = 4096;                          // #include lines processed in one run
constexpr uintmax_t kMaxIncludeFileSize = uintmax_t{16} << 20;
constexpr int kMaxExpressionNesting = 256;                  // parentheses and unary operators in #if

bool isPunct(const PPToken& t, std::string_view text) { return t.kind == PPKind::Punct && t.text == text; }
bool isIdentifier(const PPToken& t, std::string_view text) {
  return t.kind == PPKind::Identifier && t.text == text;
}

// The tokens as one line of text, one space where the source had whitespace.
std::string spell(const std::vector<PPToken>& tokens) {
  std::string s;
  for (size_t i = 0; i < tokens.size(); ++i) {
    if (i > 0 && tokens[i].spaceBefore) s += ' ';
    s += tokens[i].text;
  }
  return s;
}

// Lets macros_ be searched with a string_view.
struct StringHash {
  using is_transparent = void;
  size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
};

// Hide sets interned as sorted vectors of macro-name ids; 0 is the empty set. The
// same few sets recur for every token of an expansion, so unions are memoized.
class HideSets {
 public:
  HideSets() { sets_.emplace_back(); }

  bool contains(uint32_t set, int name) const {
    return std::binary_search(sets_[set].begin(), sets_[set].end(), name);
  }
  uint32_t add(uint32_t set, int name) {
    if (contains(set, name)) return set;
    std::vector<int> v = sets_[set];
    v.insert(std::upper_bound(v.begin(), v.end(), name), name);
    return intern(std::move(v));
  }
  uint32_t unite(uint32_t a, uint32_t b) {
    if (a == b || b == 0) return a;
    if (a == 0) return b;
    const uint64_t key = uint64_t{a} << 32 | b;
    if (auto it = unions_.find(key); it != unions_.end()) return it->second;
    std::vector<int> v;
    std::set_union(sets_[a].begin(), sets_[a].end(), sets_[b].begin(), sets_[b].end(), std::back_inserter(v));
    const uint32_t id = intern(std::move(v));
    unions_.emplace(key, id);
    return id;
  }
  uint32_t intersect(uint32_t a, uint32_t b) {
    if (a == b) return a;
    if (a == 0 || b == 0) return 0;
    std::vector<int> v;
    std::set_intersection(sets_[a].begin(), sets_[a].end(), sets_[b].begin(), sets_[b].end(),
                          std::back_inserter(v));
    return intern(std::move(v));
  }

 private:
  uint32_t intern(std::vector<int> v) {
    auto [it, inserted] = ids_.emplace(std::move(v), static_cast<uint32_t>(sets_.size()));
    if (inserted) sets_.push_back(it->first);
    return it->second;
  }
  std::vector<std::vector<int>> sets_;
  std::map<std::vector<int>, uint32_t> ids_;
  std::unordered_map<uint64_t, uint32_t> unions_;
};

struct Macro {
  enum class Builtin : uint8_t { None, Line, File };
  int nameId = 0;
  Builtin builtin = Builtin::None;
  bool functionLike = false;
  std::vector<std::string> params;
  std::vector<PPToken> body;
  std::vector<int> paramOf;  // per body token: its parameter's index, or -1
  std::vector<int> paramUses;  // per parameter: how often the body names it

  bool sameDefinition(const Macro& other) const {
    if (builtin != other.builtin || functionLike != other.functionLike || params != other.params ||
        body.size() != other.body.size())
      return false;
    for (size_t i = 0; i < body.size(); ++i)
      if (body[i].text != other.body[i].text || (i > 0 && body[i].spaceBefore != other.body[i].spaceBefore))
        return false;
    return true;
  }
};

struct Conditional {
  SourceLocation where;  // the '#' of its #if
  bool taken = false;    // one of its groups was (or is being) read
  bool seenElse = false;
};

struct SourceFile {
  explicit SourceFile(std::string_view text) : lexer(text) {}
  Lexer lexer;
  uint32_t nameId = 0;  // the name tokens and diagnostics carry (#line may change it)
  int lineDelta = 0;    // #line: reported line minus physical line
  std::string directory;  // searched first by #include "..."
  std::string identity;   // canonical path, for include cycles and #pragma once ("" if not on disk)
  std::vector<Conditional> conditionals;
};

// Where expansion reads from: tokens pushed back or produced by a macro (kept in
// reverse, so the next one is at the back), then the files or nothing.
struct Input {
  std::vector<PPToken> pending;
  bool fromFiles = false;
};

// The value of a #if expression: C's intmax_t or uintmax_t.
struct Value {
  uint64_t bits = 0;
  bool isUnsigned = false;
  int64_t asSigned() const { return static_cast<int64_t>(bits); }
};

class Preprocessor {
 public:
  Preprocessor(const PreprocessOptions& options, DiagnosticSink& sink) : options_(options), sink_(sink) {}
  std::vector<Token> run(std::string_view source, std::string_view fileName);

 private:
  friend class ConditionParser;

  SourceLocation locationOf(const PPToken& t) const { return {fileNames_[t.file], t.line, t.column}; }
  void report(Severity severity, const SourceLocation& where, const char* code, std::string message) {
    sink_.report({where, severity, code, std::move(message)});
  }
  void error(const PPToken& at, const char* code, std::string message) {
    report(Severity::Error, locationOf(at), code, std::move(message));
  }
  void warning(const PPToken& at, const char* code, std::string message) {
    report(Severity::Warning, locationOf(at), code, std::move(message));
  }
  void giveUp(const PPToken& at, const char* code, std::string message) {
    error(at, code, std::move(message));
    aborted_ = true;
  }
  uint32_t internFileName(const std::string& name);
  int nameIdOf(const std::string& name);

  // Files and directives.
  void pushFile(std::string_view text, const std::string& name, std::string directory, std::string identity);
  PPToken lex(bool directiveMode);
  PPToken readFileToken();
  std::vector<PPToken> restOfLine(PPToken* terminator = nullptr);
  void warnExtraTokens(const std::vector<PPToken>& tokens, size_t from, std::string_view name);
  std::optional<PPToken> directive(const PPToken& hash);
  void defineMacro(const std::vector<PPToken>& tokens, const PPToken& directiveName);
  void undefineMacro(const PPToken& directiveName);
  void include(const PPToken& hash, const PPToken& directiveName);
  void beginConditional(const PPToken& hash, const PPToken& directiveName);
  void skipGroup();
  bool evaluateCondition(const std::vector<PPToken>& tokens, const PPToken& directiveName);
  void lineDirective(const PPToken& directiveName);

  // Macro expansion.
  PPToken next(Input& in);
  // Expands everything `in` gives, handing each resulting token to `emit`.
  template <typename Emit>
  void expand(Input& in, Emit&& emit);
  std::vector<PPToken> expandList(std::vector<PPToken> tokens);
  bool mayExpand(const std::vector<PPToken>& tokens) const;
  bool collectArguments(Input& in, const PPToken& name, std::vector<std::vector<PPToken>>& args, PPToken& closing);
  void substitute(const Macro& macro, std::vector<std::vector<PPToken>>& args, const PPToken& use,
                  uint32_t hideset, Input& in);
  void paste(std::vector<PPToken>& result, const PPToken& right, const PPToken& use);
  PPToken builtinToken(const Macro& macro, const PPToken& use);
  // Spellings made here (pastes, stringized arguments, __LINE__) live as long as the run.
  std::string_view keep(std::string spelling) { return spellings_.emplace_back(std::move(spelling)); }

  const PreprocessOptions& options_;
  DiagnosticSink& sink_;
  std::vector<std::string> fileNames_;
  std::unordered_map<std::string, uint32_t> fileNameIds_;
  std::unordered_map<std::string, int> macroNameIds_;
  std::unordered_map<std::string, std::shared_ptr<const Macro>, StringHash, std::equal_to<>> macros_;
  HideSets hidesets_;
  std::vector<std::unique_ptr<SourceFile>> files_;  // the include stack
  // Files already read: their text stays, as tokens and macro bodies are views of it.
  std::vector<std::unique_ptr<SourceFile>> finishedFiles_;
  std::deque<std::string> spellings_;
  std::unordered_set<std::string> onceFiles_;       // identities of files with #pragma once
  PPToken endOfMain_;
  size_t substitutedTokens_ = 0;
  int argumentNesting_ = 0;
  int includeCount_ = 0;
  bool aborted_ = false;
};

// A #if expression after `defined` and macro expansion: C's integer constant
// expressions. `live` is false in a branch that && || ?: skip, where division by zero
// is no error.
class ConditionParser {
 public:
  ConditionParser(Preprocessor& pp, const std::vector<PPToken>& tokens, const PPToken& directiveName)
      : pp_(pp), tokens_(tokens), directiveName_(directiveName) {}

  std::optional<Value> parse() {
    const Value v = conditional(true);
    if (!failed_ && pos_ < tokens_.size()) fail(tokens_[pos_], fmt::format("unexpected '{}' in #if", tokens_[pos_].text));
    if (failed_) return std::nullopt;
    return v;
  }

 private:
  struct DepthGuard {
    explicit DepthGuard(int& depth) : depth_(depth) { ++depth_; }
    ~DepthGuard() { --depth_; }
    int& depth_;
  };

  const PPToken* peek() const { return pos_ < tokens_.size() ? &tokens_[pos_] : nullptr; }
  bool peekPunct(std::string_view text) const { return pos_ < tokens_.size() && isPunct(tokens_[pos_], text); }
  void fail(const PPToken& at, std::string message) {
    if (!failed_) pp_.error(at, "X1559", std::move(message));
    failed_ = true;
  }
  bool tooDeep() {
    if (depth_ <= kMaxExpressionNesting) return false;
    fail(pos_ < tokens_.size() ? tokens_[pos_] : directiveName_, "#if expression nested too deeply");
    return true;
  }

  Value conditional(bool live) {
    DepthGuard guard(depth_);
    if (tooDeep()) return {};
    const Value condition = binary(1, live);
    if (failed_ || !peekPunct("?")) return condition;
    ++pos_;
    const bool chooseFirst = condition.bits != 0;
    const Value first = conditional(live && chooseFirst);
    if (failed_) return {};
    if (!peekPunct(":")) {
      fail(pos_ < tokens_.size() ? tokens_[pos_] : directiveName_, "expected ':' in #if");
      return {};
    }
    ++pos_;
    const Value second = conditional(live && !chooseFirst);
    Value v = chooseFirst ? first : second;
    v.isUnsigned = first.isUnsigned || second.isUnsigned;
    return v;
  }

  static int precedence(const PPToken& t) {
    if (t.kind != PPKind::Punct) return 0;
    static const std::unordered_map<std::string_view, int> table = {
        {"||", 1}, {"&&", 2}, {"|", 3},  {"^", 4},  {"&", 5},  {"==", 6}, {"!=", 6}, {"<", 7}, {">", 7},
        {"<=", 7}, {">=", 7}, {"<<", 8}, {">>", 8}, {"+", 9},  {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
    auto it = table.find(t.text);
    return it == table.end() ? 0 : it->second;
  }

  Value binary(int minPrecedence, bool live) {
    Value left = unary(live);
    while (!failed_ && pos_ < tokens_.size()) {
      const PPToken& op = tokens_[pos_];
      const int p = precedence(op);
      if (p == 0 || p < minPrecedence) break;
      ++pos_;
      if (op.text == "||") {
        const Value right = binary(p + 1, live && left.bits == 0);
        left = {left.bits != 0 || right.bits != 0, false};
      } else if (op.text == "&&") {
        const Value right = binary(p + 1, live && left.bits != 0);
        left = {left.bits != 0 && right.bits != 0, false};
      } else {
        const Value right = binary(p + 1, live);
        left = apply(op, left, right, live);
      }
    }
    return left;
  }

  Value apply(const PPToken& op, Value a, Value b, bool live) {
    // Unsigned arithmetic wraps like the two's complement intmax_t of C compilers,
    // without the undefined behaviour of signed overflow here.
    const bool u = a.isUnsigned || b.isUnsigned;
    const std::string_view o = op.text;
    if (o == "*") return {a.bits * b.bits, u};
    if (o == "+") return {a.bits + b.bits, u};
    if (o == "-") return {a.bits - b.bits, u};
    if (o == "/" || o == "%") {
      if (!live) return {0, u};
      if (b.bits == 0) {
        if (!failed_) pp_.error(op, "X1560", "division by zero in #if");
        failed_ = true;
        return {};
      }
      if (u) return {o == "/" ? a.bits / b.bits : a.bits % b.bits, true};
      if (a.asSigned() == INT64_MIN && b.asSigned() == -1) return {o == "/" ? a.bits : 0, false};
      return {static_cast<uint64_t>(o == "/" ? a.asSigned() / b.asSigned() : a.asSigned() % b.asSigned()), false};
    }
    if (o == "<<" || o == ">>") {
      // The result has the left operand's type; a count outside 0..63 shifts everything out.
      const bool countInRange = b.isUnsigned ? b.bits < 64 : (b.asSigned() >= 0 && b.asSigned() < 64);
      const bool negative = !a.isUnsigned && a.asSigned() < 0;
      if (!countInRange) return {o == ">>" && negative ? ~uint64_t{0} : 0, a.isUnsigned};
      if (o == "<<") return {a.bits << b.bits, a.isUnsigned};
      if (a.isUnsigned) return {a.bits >> b.bits, true};
      return {static_cast<uint64_t>(a.asSigned() >> b.bits), false};
    }
    if (o == "<") return {u ? a.bits < b.bits : a.asSigned() < b.asSigned(), false};
    if (o == ">") return {u ? a.bits > b.bits : a.asSigned() > b.asSigned(), false};
    if (o == "<=") return {u ? a.bits <= b.bits : a.asSigned() <= b.asSigned(), false};
    if (o == ">=") return {u ? a.bits >= b.bits : a.asSigned() >= b.asSigned(), false};
    if (o == "==") return {a.bits == b.bits, false};
    if (o == "!=") return {a.bits != b.bits, false};
    if (o == "&") return {a.bits & b.bits, u};
    if (o == "|") return {a.bits | b.bits, u};
    return {a.bits ^ b.bits, u};  // "^"
  }

  Value unary(bool live) {
    DepthGuard guard(depth_);
    if (tooDeep()) return {};
    const PPToken* t = peek();
    if (t && t->kind == PPKind::Punct && (t->text == "-" || t->text == "+" || t->text == "!" || t->text == "~")) {
      ++pos_;
      const Value v = unary(live);
      if (t->text == "-") return {0 - v.bits, v.isUnsigned};
      if (t->text == "+") return v;
      if (t->text == "!") return {v.bits == 0, false};
      return {~v.bits, v.isUnsigned};
    }
    return primary(live);
  }

  Value primary(bool live) {
    const PPToken* t = peek();
    if (!t) {
      fail(directiveName_, "expected a value at the end of the #if expression");
      return {};
    }
    ++pos_;
    switch (t->kind) {
      case PPKind::IntLiteral: return integer(*t);
      case PPKind::Identifier: return {};  // a name that is no macro counts as 0
      case PPKind::Punct:
        if (t->text == "(") {
          const Value v = conditional(live);
          if (failed_) return {};
          if (!peekPunct(")")) {
            fail(pos_ < tokens_.size() ? tokens_[pos_] : directiveName_, "expected ')' in #if");
            return {};
          }
          ++pos_;
          return v;
        }
        break;
      case PPKind::FloatLiteral: fail(*t, fmt::format("floating-point value '{}' in #if", t->text)); return {};
      default: break;
    }
    fail(*t, fmt::format("expected a value in #if, found '{}'", t->text));
    return {};
  }

  Value integer(const PPToken& t) {
    std::string_view digits = t.text;
    bool isUnsigned = false;
    while (!digits.empty() && std::string_view("uUlL").find(digits.back()) != std::string_view::npos) {
      if (digits.back() == 'u' || digits.back() == 'U') isUnsigned = true;
      digits.remove_suffix(1);
    }
    unsigned base = 10;
    if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
      base = 16;
      digits.remove_prefix(2);
    } else if (digits.size() > 1 && digits[0] == '0') {
      base = 8;
    }
    uint64_t value = 0;
    for (char c : digits) {
      const unsigned d = c >= '0' && c <= '9' ? unsigned(c - '0') : unsigned((c | 0x20) - 'a' + 10);
      if (d >= base) {
        fail(t, fmt::format("invalid integer '{}' in #if", t.text));
        return {};
      }
      if (value > (UINT64_MAX - d) / base) {
        fail(t, fmt::format("integer '{}' in #if is too large", t.text));
        return {};
      }
      value = value * base + d;
    }
    return {value, isUnsigned || value > uint64_t{INT64_MAX}};
  }

  Preprocessor& pp_;
  const std::vector<PPToken>& tokens_;
  const PPToken& directiveName_;
  size_t pos_ = 0;
  int depth_ = 0;
  bool failed_ = false;
};

uint32_t Preprocessor::internFileName(const std::string& name) {
  auto [it, inserted] = fileNameIds_.emplace(name, static_cast<uint32_t>(fileNames_.size()));
  if (inserted) fileNames_.push_back(name);
  return it->second;
}

int Preprocessor::nameIdOf(const std::string& name) {
  return macroNameIds_.emplace(name, static_cast<int>(macroNameIds_.size())).first->second;
}

void Preprocessor::pushFile(std::string_view text, const std::string& name, std::string directory,
                            std::string identity) {
  auto file = std::make_unique<SourceFile>(text);
  file->nameId = internFileName(name);
  file->directory = std::move(directory);
  file->identity = std::move(identity);
  files_.push_back(std::move(file));
}

PPToken Preprocessor::lex(bool directiveMode) {
  SourceFile& f = *files_.back();
  PPToken t = f.lexer.next(directiveMode);
  t.file = f.nameId;
  t.line += f.lineDelta;
  if (!f.lexer.problems.empty()) {
    for (LexProblem& p : f.lexer.problems)
      report(Severity::Error, {fileNames_[f.nameId], p.line + f.lineDelta, p.column}, p.code, std::move(p.message));
    f.lexer.problems.clear();
  }
  return t;
}

// The next token of the files, after directives: what expansion reads.
PPToken Preprocessor::readFileToken() {
  while (!aborted_ && !files_.empty()) {
    PPToken t = lex(false);
    if (t.kind == PPKind::End) {
      for (const Conditional& c : files_.back()->conditionals)
        report(Severity::Error, c.where, "X1555", "#if without #endif");
      t.endsMainFile = files_.size() == 1;
      finishedFiles_.push_back(std::move(files_.back()));
      files_.pop_back();
      if (t.endsMainFile) endOfMain_ = t;
      return t;
    }
    if (t.startOfLine && isPunct(t, "#")) {
      if (std::optional<PPToken> pragma = directive(t)) return std::move(*pragma);
      continue;
    }
    return t;
  }
  return endOfMain_;
}

std::vector<PPToken> Preprocessor::restOfLine(PPToken* terminator) {
  std::vector<PPToken> tokens;
  for (;;) {
    PPToken t = lex(true);
    if (t.kind == PPKind::Newline || t.kind == PPKind::End) {
      if (terminator) *terminator = std::move(t);
      return tokens;
    }
    tokens.push_back(std::move(t));
  }
}

void Preprocessor::warnExtraTokens(const std::vector<PPToken>& tokens, size_t from, std::string_view name) {
  if (tokens.size() > from)
    warning(tokens[from], "X1567", fmt::format("extra tokens after #{} ignored", name));
}

std::optional<PPToken> Preprocessor::directive(const PPToken& hash) {
  PPToken name = lex(true);
  if (name.kind == PPKind::Newline || name.kind == PPKind::End) return std::nullopt;  // '#' alone
  const std::string_view d = name.text;
  if (name.kind != PPKind::Identifier) {
    error(name, "X1504", fmt::format("invalid preprocessor command '{}'", d));
    restOfLine();
  } else if (d == "define") {
    defineMacro(restOfLine(), name);
  } else if (d == "undef") {
    undefineMacro(name);
  } else if (d == "include") {
    include(hash, name);
  } else if (d == "if" || d == "ifdef" || d == "ifndef") {
    beginConditional(hash, name);
  } else if (d == "elif" || d == "else" || d == "endif") {
    const std::vector<PPToken> rest = restOfLine();
    std::vector<Conditional>& open = files_.back()->conditionals;
    if (open.empty()) {
      error(hash, "X1554", fmt::format("#{} without #if", d));
      return std::nullopt;
    }
    if (d == "endif") {
      warnExtraTokens(rest, 0, d);
      open.pop_back();
      return std::nullopt;
    }
    if (open.back().seenElse) error(hash, "X1556", fmt::format("#{} after #else", d));
    if (d == "else") {
      warnExtraTokens(rest, 0, d);
      open.back().seenElse = true;
    }
    skipGroup();  // the group being read was the one taken: every later one is skipped
  } else if (d == "error") {
    const std::vector<PPToken> rest = restOfLine();
    error(hash, "X1550", rest.empty() ? std::string("#error") : "#error " + spell(rest));
  } else if (d == "line") {
    lineDirective(name);
  } else if (d == "pragma") {
    const std::vector<PPToken> rest = restOfLine();
    if (rest.size() == 1 && isIdentifier(rest[0], "once")) {
      if (!files_.back()->identity.empty()) onceFiles_.insert(files_.back()->identity);
      return std::nullopt;
    }
    PPToken pragma = hash;
    pragma.kind = PPKind::Pragma;
    pragma.text = keep(spell(rest));
    pragma.startOfLine = false;
    return pragma;
  } else {
    error(name, "X1504", fmt::format("invalid preprocessor command '{}'", d));
    restOfLine();
  }
  return std::nullopt;
}

void Preprocessor::defineMacro(const std::vector<PPToken>& tokens, const PPToken& directiveName) {
  if (tokens.empty() || tokens[0].kind != PPKind::Identifier) {
    error(tokens.empty() ? directiveName : tokens[0], "X1500", "expected a macro name after #define");
    return;
  }
  const PPToken& name = tokens[0];
  if (name.text == "defined") {
    error(name, "X1500", "'defined' cannot be a macro name");
    return;
  }
  auto macro = std::make_shared<Macro>();
  macro->nameId = nameIdOf(std::string(name.text));
  size_t i = 1;
  // A '(' right after the name, with no space between, makes a function-like macro.
  if (i < tokens.size() && isPunct(tokens[i], "(") && !tokens[i].spaceBefore) {
    macro->functionLike = true;
    ++i;
    if (i < tokens.size() && isPunct(tokens[i], ")")) {
      ++i;
    } else {
      for (;;) {
        if (i >= tokens.size() || tokens[i].kind != PPKind::Identifier) {
          error(i < tokens.size() ? tokens[i] : name, "X1500", "expected a parameter name in the macro's parameter list");
          return;
        }
        if (std::find(macro->params.begin(), macro->params.end(), tokens[i].text) != macro->params.end()) {
          error(tokens[i], "X1500", fmt::format("parameter '{}' appears twice", tokens[i].text));
          return;
        }
        macro->params.emplace_back(tokens[i].text);
        ++i;
        if (i < tokens.size() && isPunct(tokens[i], ",")) {
          ++i;
        } else if (i < tokens.size() && isPunct(tokens[i], ")")) {
          ++i;
          break;
        } else {
          error(i < tokens.size() ? tokens[i] : name, "X1500", "expected ',' or ')' in the macro's parameter list");
          return;
        }
      }
    }
  }
  macro->body.assign(tokens.begin() + static_cast<ptrdiff_t>(i), tokens.end());
  for (PPToken& t : macro->body) t.startOfLine = false;
  if (!macro->body.empty()) macro->body.front().spaceBefore = false;
  macro->paramOf.assign(macro->body.size(), -1);
  macro->paramUses.assign(macro->params.size(), 0);
  for (size_t k = 0; k < macro->body.size(); ++k) {
    if (macro->body[k].kind != PPKind::Identifier) continue;
    auto it = std::find(macro->params.begin(), macro->params.end(), macro->body[k].text);
    if (it == macro->params.end()) continue;
    macro->paramOf[k] = static_cast<int>(it - macro->params.begin());
    ++macro->paramUses[macro->paramOf[k]];
  }
  const std::vector<PPToken>& body = macro->body;
  if (!body.empty() && (isPunct(body.front(), "##") || isPunct(body.back(), "##"))) {
    error(isPunct(body.front(), "##") ? body.front() : body.back(), "X1563", "'##' cannot be at either end of a macro");
    return;
  }
  if (macro->functionLike) {
    for (size_t k = 0; k < body.size(); ++k)
      if (isPunct(body[k], "#") && (k + 1 == body.size() || macro->paramOf[k + 1] < 0)) {
        error(body[k], "X1563", "'#' must be followed by a macro parameter");
        return;
      }
  }
  auto existing = macros_.find(name.text);
  if (existing != macros_.end()) {
    if (!existing->second->sameDefinition(*macro))
      warning(name, "X1519", fmt::format("'{}' : macro redefinition", name.text));
    existing->second = std::move(macro);
  } else {
    macros_.emplace(std::string(name.text), std::move(macro));
  }
}

void Preprocessor::undefineMacro(const PPToken& directiveName) {
  const std::vector<PPToken> tokens = restOfLine();
  if (tokens.empty() || tokens[0].kind != PPKind::Identifier) {
    error(tokens.empty() ? directiveName : tokens[0], "X1500", "expected a macro name after #undef");
    return;
  }
  if (auto it = macros_.find(tokens[0].text); it != macros_.end()) macros_.erase(it);
  warnExtraTokens(tokens, 1, "undef");
}

void Preprocessor::include(const PPToken& hash, const PPToken& directiveName) {
  const std::optional<Lexer::HeaderName> header = files_.back()->lexer.headerName();
  const std::vector<PPToken> rest = restOfLine();
  if (!header) {
    // fxc does not expand macros here either.
    error(rest.empty() ? directiveName : rest[0], "X1500", "expected \"file\" or <file> after #include");
    return;
  }
  const SourceFile& includer = *files_.back();
  PPToken nameToken = directiveName;
  nameToken.line = header->line + includer.lineDelta;
  nameToken.column = header->column;
  if (!header->terminated) {
    error(nameToken, "X1500", fmt::format("missing closing {} in #include", header->angled ? "'>'" : "'\"'"));
    return;
  }
  warnExtraTokens(rest, 0, "include");
  if (++includeCount_ > kMaxIncludes) {
    giveUp(hash, "X1506", fmt::format("more than {} #include directives", kMaxIncludes));
    return;
  }
  if (files_.size() >= kMaxIncludeDepth) {
    error(hash, "X1506", fmt::format("#include nested more than {} deep", kMaxIncludeDepth));
    return;
  }
  // Windows-style separators work too.
  std::string written = header->name;
  std::replace(written.begin(), written.end(), '\\', '/');
  const fs::path relative(written);
  std::vector<fs::path> candidates;
  if (relative.is_absolute()) {
    candidates.push_back(relative);
  } else {
    if (!header->angled) candidates.push_back(includer.directory.empty() ? relative : fs::path(includer.directory) / relative);
    for (const std::string& dir : options_.includeDirs) candidates.push_back(fs::path(dir) / relative);
  }
  for (const fs::path& candidate : candidates) {
    std::error_code ec;
    const fs::file_status status = fs::status(candidate, ec);
    if (ec || !fs::exists(status)) continue;
    if (!fs::is_regular_file(status)) {
      error(nameToken, "X1565", fmt::format("'{}' is not a regular file", header->name));
      return;
    }
    const uintmax_t size = fs::file_size(candidate, ec);
    if (ec || size > kMaxIncludeFileSize) {
      error(nameToken, "X1565", fmt::format("'{}' is larger than 16 MiB", header->name));
      return;
    }
    std::string identity = fs::weakly_canonical(candidate, ec).string();
    if (ec) identity = candidate.lexically_normal().string();
    if (onceFiles_.count(identity)) return;
    for (const auto& open : files_)
      if (open->identity == identity) {
        error(hash, "X1506", fmt::format("recursive #include of '{}'", header->name));
        return;
      }
    std::ifstream in(candidate, std::ios::binary);
    if (!in) {
      error(nameToken, "X1507", fmt::format("failed to open source file: '{}'", header->name));
      return;
    }
    std::string contents(size, '\0');
    in.read(contents.data(), static_cast<std::streamsize>(size));
    contents.resize(static_cast<size_t>(in.gcount()));
    const fs::path shown = candidate.lexically_normal();
    pushFile(contents, shown.string(), shown.parent_path().string(), std::move(identity));
    return;
  }
  error(nameToken, "X1507", fmt::format("failed to open source file: '{}'", header->name));
}

void Preprocessor::beginConditional(const PPToken& hash, const PPToken& directiveName) {
  const std::vector<PPToken> tokens = restOfLine();
  bool value = false;
  if (directiveName.text == "if") {
    value = evaluateCondition(tokens, directiveName);
  } else if (tokens.empty() || tokens[0].kind != PPKind::Identifier) {
    error(tokens.empty() ? directiveName : tokens[0], "X1500",
          fmt::format("expected a macro name after #{}", directiveName.text));
  } else {
    value = macros_.count(tokens[0].text) != 0;
    if (directiveName.text == "ifndef") value = !value;
    warnExtraTokens(tokens, 1, directiveName.text);
  }
  files_.back()->conditionals.push_back({locationOf(hash), value, false});
  if (!value) skipGroup();
}

// Skips lines up to the #elif, #else or #endif of the innermost open #if that ends
// the skipping: a true #elif, an #else of an #if none of whose groups was taken, or
// its #endif. Nested conditionals in between are skipped whole.
void Preprocessor::skipGroup() {
  SourceFile& file = *files_.back();
  file.lexer.quiet = true;
  int depth = 0;
  while (!aborted_) {
    const PPToken t = lex(false);
    if (t.kind == PPKind::End) break;  // readFileToken reports the missing #endif
    if (!t.startOfLine || !isPunct(t, "#")) continue;
    const PPToken name = lex(true);
    if (name.kind == PPKind::Newline || name.kind == PPKind::End) continue;
    const std::vector<PPToken> rest = restOfLine();
    if (name.kind != PPKind::Identifier) continue;
    const std::string_view d = name.text;
    if (d == "if" || d == "ifdef" || d == "ifndef") {
      ++depth;
      continue;
    }
    if (depth > 0) {
      if (d == "endif") --depth;
      continue;
    }
    Conditional& c = file.conditionals.back();
    if (d == "endif") {
      file.conditionals.pop_back();
      break;
    }
    if (d != "else" && d != "elif") continue;
    if (c.seenElse) error(t, "X1556", fmt::format("#{} after #else", d));
    if (d == "else") {
      c.seenElse = true;
      if (!c.taken) {
        c.taken = true;
        break;
      }
    } else if (!c.taken) {
      file.lexer.quiet = false;
      const bool value = evaluateCondition(rest, name);
      file.lexer.quiet = true;
      if (value) {
        c.taken = true;
        break;
      }
    }
  }
  file.lexer.quiet = false;
}

bool Preprocessor::evaluateCondition(const std::vector<PPToken>& tokens, const PPToken& directiveName) {
  // `defined X` and `defined(X)` are answered before expansion, so X stays a name.
  std::vector<PPToken> replaced;
  replaced.reserve(tokens.size());
  for (size_t i = 0; i < tokens.size(); ++i) {
    if (!isIdentifier(tokens[i], "defined")) {
      replaced.push_back(tokens[i]);
      continue;
    }
    size_t j = i + 1;
    const bool parenthesized = j < tokens.size() && isPunct(tokens[j], "(");
    if (parenthesized) ++j;
    if (j >= tokens.size() || tokens[j].kind != PPKind::Identifier) {
      error(j < tokens.size() ? tokens[j] : tokens[i], "X1500", "expected a macro name after 'defined'");
      return false;
    }
    const bool isDefined = macros_.count(tokens[j].text) != 0;
    ++j;
    if (parenthesized) {
      if (j >= tokens.size() || !isPunct(tokens[j], ")")) {
        error(j < tokens.size() ? tokens[j] : tokens[j - 1], "X1500", "expected ')' after 'defined(NAME'");
        return false;
      }
      ++j;
    }
    PPToken value = tokens[i];
    value.kind = PPKind::IntLiteral;
    value.text = isDefined ? "1" : "0";
    replaced.push_back(std::move(value));
    i = j - 1;
  }
  const std::vector<PPToken> expanded = expandList(std::move(replaced));
  if (aborted_) return false;
  if (expanded.empty()) {
    error(directiveName, "X1559", fmt::format("#{} without an expression", directiveName.text));
    return false;
  }
  const std::optional<Value> value = ConditionParser(*this, expanded, directiveName).parse();
  return value && value->bits != 0;
}

void Preprocessor::lineDirective(const PPToken& directiveName) {
  PPToken end;
  const std::vector<PPToken> tokens = expandList(restOfLine(&end));
  const bool digitsOnly = !tokens.empty() && tokens[0].kind == PPKind::IntLiteral &&
                          std::all_of(tokens[0].text.begin(), tokens[0].text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digitsOnly || tokens[0].text.size() > 9) {
    error(tokens.empty() ? directiveName : tokens[0], "X1500", "#line needs a line number (digits)");
    return;
  }
  SourceFile& file = *files_.back();
  if (tokens.size() > 1) {
    if (tokens[1].kind != PPKind::StringLiteral) {
      error(tokens[1], "X1500", "expected a file name in quotes after the #line number");
      return;
    }
    file.nameId = internFileName(resolveEscapes(tokens[1].text));
    warnExtraTokens(tokens, 2, "line");
  }
  // The line after the directive gets the number given.
  const int physicalNextLine = end.line - file.lineDelta + 1;
  file.lineDelta = std::stoi(std::string(tokens[0].text)) - physicalNextLine;
}

PPToken Preprocessor::next(Input& in) {
  if (!in.pending.empty()) {
    PPToken t = std::move(in.pending.back());
    in.pending.pop_back();
    return t;
  }
  if (in.fromFiles) return readFileToken();
  return PPToken{};  // End of a token list
}

template <typename Emit>
void Preprocessor::expand(Input& in, Emit&& emit) {
  while (!aborted_) {
    PPToken t = next(in);
    if (t.kind == PPKind::End) {
      if (!in.fromFiles || t.endsMainFile) return;
      continue;  // an included file ended
    }
    if (t.kind != PPKind::Identifier || t.noExpand) {
      emit(std::move(t));
      continue;
    }
    auto found = macros_.find(t.text);
    if (found == macros_.end()) {
      emit(std::move(t));
      continue;
    }
    // Held by value: a directive met while reading the arguments may #undef it.
    const std::shared_ptr<const Macro> macro = found->second;
    if (hidesets_.contains(t.hideset, macro->nameId)) {
      t.noExpand = true;
      emit(std::move(t));
      continue;
    }
    if (macro->builtin != Macro::Builtin::None) {
      emit(builtinToken(*macro, t));
      continue;
    }
    if (!macro->functionLike) {
      std::vector<std::vector<PPToken>> noArgs;
      substitute(*macro, noArgs, t, hidesets_.add(t.hideset, macro->nameId), in);
      continue;
    }
    PPToken after = next(in);
    if (!isPunct(after, "(")) {  // a function-like macro's name alone is just a name
      in.pending.push_back(std::move(after));
      emit(std::move(t));
      continue;
    }
    std::vector<std::vector<PPToken>> args;
    PPToken closing;
    if (!collectArguments(in, t, args, closing)) continue;
    const bool countMatches = macro->params.empty() ? args.size() == 1 && args[0].empty()
                                                    : args.size() == macro->params.size();
    if (!countMatches) {
      error(t, "X1558", fmt::format("macro '{}' takes {} argument{}, {} given", t.text, macro->params.size(),
                                    macro->params.size() == 1 ? "" : "s", args.size() == 1 && args[0].empty() ? 0 : args.size()));
      continue;
    }
    const uint32_t hideset = hidesets_.add(hidesets_.intersect(t.hideset, closing.hideset), macro->nameId);
    substitute(*macro, args, t, hideset, in);
  }
}

std::vector<PPToken> Preprocessor::expandList(std::vector<PPToken> tokens) {
  Input in;
  std::reverse(tokens.begin(), tokens.end());
  in.pending = std::move(tokens);
  std::vector<PPToken> out;
  out.reserve(in.pending.size());
  expand(in, [&out](PPToken&& t) { out.push_back(std::move(t)); });
  return out;
}

// Whether expanding `tokens` could change them: some name in it is a macro.
bool Preprocessor::mayExpand(const std::vector<PPToken>& tokens) const {
  return std::any_of(tokens.begin(), tokens.end(), [this](const PPToken& t) {
    return t.kind == PPKind::Identifier && !t.noExpand && macros_.count(t.text) != 0;
  });
}

bool Preprocessor::collectArguments(Input& in, const PPToken& name, std::vector<std::vector<PPToken>>& args,
                                    PPToken& closing) {
  args.assign(1, {});
  int depth = 0;
  while (!aborted_) {
    PPToken t = next(in);
    if (t.kind == PPKind::End) {
      error(name, "X1557", fmt::format("unterminated argument list invoking macro '{}'", name.text));
      in.pending.push_back(std::move(t));
      return false;
    }
    if (t.kind == PPKind::Punct) {
      if (t.text == "(") {
        ++depth;
      } else if (t.text == ")") {
        if (depth == 0) {
          closing = std::move(t);
          return true;
        }
        --depth;
      } else if (t.text == "," && depth == 0) {
        args.emplace_back();
        continue;
      }
    }
    args.back().push_back(std::move(t));
  }
  return false;
}

void Preprocessor::substitute(const Macro& macro, std::vector<std::vector<PPToken>>& args, const PPToken& use,
                              uint32_t hideset, Input& in) {
  const std::vector<PPToken>& body = macro.body;
  const size_t n = body.size();
  std::vector<std::optional<std::vector<PPToken>>> expandedArgs(args.size());
  auto expandedArg = [&](int index) -> std::vector<PPToken>& {
    if (!mayExpand(args[index])) return args[index];
    if (!expandedArgs[index]) {
      // Arguments are expanded on their own, before they are put in the body.
      if (++argumentNesting_ > kMaxArgumentNesting) {
        if (!aborted_) giveUp(use, "X1561", "macro arguments nested too deeply");
        expandedArgs[index] = args[index];
      } else {
        expandedArgs[index] = expandList(args[index]);
      }
      --argumentNesting_;
    }
    return *expandedArgs[index];
  };
  auto append = [](std::vector<PPToken>& to, const std::vector<PPToken>& tokens, size_t from = 0) {
    to.insert(to.end(), tokens.begin() + static_cast<ptrdiff_t>(from), tokens.end());
  };

  std::vector<PPToken> result;
  for (size_t i = 0; i < n && !aborted_; ++i) {
    // Checked as the result grows, so a blow-up stops before it fills the memory.
    if (substitutedTokens_ + result.size() > kMaxSubstitutedTokens) break;
    const PPToken& tok = body[i];
    const int param = macro.paramOf[i];
    if (macro.functionLike && isPunct(tok, "#")) {  // checked at #define: a parameter follows
      const std::vector<PPToken>& arg = args[macro.paramOf[i + 1]];
      PPToken str = tok;
      str.kind = PPKind::StringLiteral;
      std::string text;
      for (size_t k = 0; k < arg.size(); ++k) {
        if (k > 0 && arg[k].spaceBefore) text += ' ';
        text += arg[k].text;
      }
      str.text = keep(quoteString(text));
      // Only string literals' quotes and backslashes are escaped in C; elsewhere a
      // backslash can only be a stray character, already reported.
      result.push_back(std::move(str));
      ++i;
      continue;
    }
    if (isPunct(tok, "##")) {  // checked at #define: never first or last
      const int rightParam = macro.paramOf[i + 1];
      ++i;
      if (rightParam >= 0) {
        const std::vector<PPToken>& arg = args[rightParam];
        if (arg.empty()) continue;
        if (result.empty()) {
          append(result, arg);
        } else {
          paste(result, arg[0], use);
          append(result, arg, 1);
        }
      } else if (result.empty()) {
        result.push_back(body[i]);
      } else {
        paste(result, body[i], use);
      }
      continue;
    }
    if (param >= 0) {
      const bool pastedRight = i + 1 < n && isPunct(body[i + 1], "##");
      if (!pastedRight) {
        std::vector<PPToken>& arg = expandedArg(param);
        if (macro.paramUses[param] == 1)  // its only use: the tokens can move
          result.insert(result.end(), std::make_move_iterator(arg.begin()), std::make_move_iterator(arg.end()));
        else
          append(result, arg);
        continue;
      }
      const std::vector<PPToken>& arg = args[param];  // operands of ## are not expanded
      if (!arg.empty()) {
        append(result, arg);
        continue;
      }
      // An empty left operand: the right one stands alone, unexpanded.
      const int rightParam = i + 2 < n ? macro.paramOf[i + 2] : -1;
      if (rightParam >= 0) {
        append(result, args[rightParam]);
        i += 2;
      } else {
        ++i;  // past "##": the token after it is taken as it is
      }
      continue;
    }
    result.push_back(tok);
  }
  if (aborted_) return;

  substitutedTokens_ += result.size();
  if (substitutedTokens_ > kMaxSubstitutedTokens) {
    giveUp(use, "X1561", fmt::format("macro expansion produces more than {} tokens", kMaxSubstitutedTokens));
    return;
  }
  for (PPToken& t : result) {
    t.hideset = hidesets_.unite(t.hideset, hideset);
    t.file = use.file;
    t.line = use.line;
    t.column = use.column;
    t.startOfLine = false;
  }
  if (!result.empty()) result.front().spaceBefore = use.spaceBefore;
  in.pending.insert(in.pending.end(), std::make_move_iterator(result.rbegin()), std::make_move_iterator(result.rend()));
}

void Preprocessor::paste(std::vector<PPToken>& result, const PPToken& right, const PPToken& use) {
  PPToken& left = result.back();
  PPToken pasted;
  const std::string_view joined = keep(std::string(left.text) + std::string(right.text));
  if (lexSingleToken(joined, pasted)) {
    pasted.file = left.file;
    pasted.line = left.line;
    pasted.column = left.column;
    pasted.spaceBefore = left.spaceBefore;
    left = std::move(pasted);
    return;
  }
  error(use, "X1564", fmt::format("pasting '{}' and '{}' does not give a valid token", left.text, right.text));
  result.push_back(right);
}

PPToken Preprocessor::builtinToken(const Macro& macro, const PPToken& use) {
  PPToken t = use;
  t.hideset = 0;
  if (macro.builtin == Macro::Builtin::Line) {
    t.kind = PPKind::IntLiteral;
    t.text = keep(std::to_string(use.line));
  } else {
    t.kind = PPKind::StringLiteral;
    t.text = keep(quoteString(fileNames_[use.file]));
  }
  return t;
}

std::vector<Token> Preprocessor::run(std::string_view source, std::string_view fileName) {
  const std::string mainName(fileName);
  for (auto [name, builtin] : {std::pair{"__LINE__", Macro::Builtin::Line}, std::pair{"__FILE__", Macro::Builtin::File}}) {
    auto macro = std::make_shared<Macro>();
    macro->nameId = nameIdOf(name);
    macro->builtin = builtin;
    macros_.emplace(name, std::move(macro));
  }
  // Caller's definitions read as `#define NAME VALUE` lines (so NAME may be F(x) too).
  const uint32_t commandLine = internFileName("<command line>");
  for (const MacroDefinition& def : options_.defines) {
    // Kept as a finished file: the macro's body is a view of its text.
    finishedFiles_.push_back(std::make_unique<SourceFile>(def.name + " " + def.value));
    Lexer& lexer = finishedFiles_.back()->lexer;
    std::vector<PPToken> tokens;
    for (PPToken t = lexer.next(false); t.kind != PPKind::End; t = lexer.next(false)) {
      t.file = commandLine;
      tokens.push_back(std::move(t));
    }
    for (LexProblem& p : lexer.problems)
      report(Severity::Error, {"<command line>", p.line, p.column}, p.code, std::move(p.message));
    PPToken where;
    where.file = commandLine;
    defineMacro(tokens, where);
  }

  std::error_code ec;
  const fs::path mainPath(mainName);
  std::string identity;
  if (fs::is_regular_file(mainPath, ec)) identity = fs::weakly_canonical(mainPath, ec).string();
  pushFile(source, mainName, mainPath.parent_path().string(), identity);
  endOfMain_.file = files_.back()->nameId;
  endOfMain_.line = 1;
  endOfMain_.column = 1;
  endOfMain_.endsMainFile = true;

  Input in;
  in.fromFiles = true;
  std::vector<Token> tokens;
  tokens.reserve(source.size() / 2 + 1);  // shader code has about one token per three bytes
  expand(in, [&](PPToken&& t) {
    Token out;
    switch (t.kind) {
      case PPKind::Identifier: out.kind = TokenKind::Identifier; break;
      case PPKind::IntLiteral: out.kind = TokenKind::IntLiteral; break;
      case PPKind::FloatLiteral: out.kind = TokenKind::FloatLiteral; break;
      case PPKind::StringLiteral: out.kind = TokenKind::StringLiteral; break;
      case PPKind::Pragma: out.kind = TokenKind::Pragma; break;
      default: out.kind = TokenKind::Punct; break;
    }
    out.text = t.kind == PPKind::StringLiteral ? resolveEscapes(t.text) : std::string(t.text);
    out.file = fileNames_[t.file];
    out.line = t.line;
    out.column = t.column;
    tokens.push_back(std::move(out));
  });
  Token eof;
  eof.kind = TokenKind::EndOfFile;
  eof.file = fileNames_[endOfMain_.file];
  eof.line = endOfMain_.line;
  eof.column = endOfMain_.column;
  tokens.push_back(std::move(eof));
  return tokens;
}

}  // namespace

std::vector<Token> preprocess(std::string_view source, std::string_view fileName, const PreprocessOptions& options,
                              DiagnosticSink& sink) {
  return Preprocessor(options, sink).run(source, fileName);
}

}  // namespace refx::hlsl::detail
