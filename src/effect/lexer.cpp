#include "lexer.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "effect_errors.h"
#include "refx/core/text.h"

namespace refx::effect::detail {

namespace {

constexpr int kMaxIncludeDepth = 32;
constexpr int kMaxExpansionDepth = 64;

bool identStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool identChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

constexpr uintmax_t kMaxIncludeBytes = 16u << 20;

std::optional<std::string> readFile(const std::string& path) {
  // Only regular files of a sane size: `#include "/dev/zero"` must not hang.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || std::filesystem::file_size(path, ec) > kMaxIncludeBytes)
    return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

bool Token::isIdent(std::string_view name) const {
  return kind == TokenKind::Ident && equalsNoCase(text, name);
}

Lexer::Lexer(std::string_view text, std::string file, std::vector<std::string> includeDirs,
             std::vector<std::pair<std::string, std::string>> defines)
    : includeDirs_(std::move(includeDirs)) {
  stack_.push_back({std::make_shared<std::string>(text), file});
  files_.push_back(file);
  for (auto& [name, value] : defines) {
    Macro m{name, {}};
    Lexer sub(value, "<define " + name + ">", {}, {});
    for (Token t = sub.next(); t.kind != TokenKind::End; t = sub.next()) m.body.push_back(t);
    macros_.push_back(std::move(m));
  }
}

char Lexer::cur() const { return at(0); }

char Lexer::at(size_t ahead) const {
  const Source& s = stack_.back();
  return s.pos + ahead < s.text->size() ? (*s.text)[s.pos + ahead] : '\0';
}

void Lexer::advance() {
  Source& s = stack_.back();
  if (s.pos >= s.text->size()) return;
  if ((*s.text)[s.pos] == '\n') {
    ++s.line;
    s.col = 1;
    atLineStart_ = true;
  } else {
    ++s.col;
  }
  ++s.pos;
}

SourceLocation Lexer::here() const {
  const Source& s = stack_.back();
  return {s.file, s.line, s.col};
}

std::string Lexer::restOfLine() {
  std::string line;
  while (cur() != '\0' && cur() != '\n') {
    if (cur() == '\\' && at(1) == '\n') {  // line continuation
      advance();
      advance();
      continue;
    }
    if (cur() == '/' && at(1) == '/') {
      while (cur() != '\0' && cur() != '\n') advance();
      break;
    }
    line += cur();
    advance();
  }
  return line;
}

void Lexer::skipSpaceAndComments() {
  for (;;) {
    const char c = cur();
    if (c == '\n') {
      advance();
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      advance();
    } else if (c == '\\' && (at(1) == '\n' || (at(1) == '\r' && at(2) == '\n'))) {
      advance();
    } else if (c == '/' && at(1) == '/') {
      while (cur() != '\0' && cur() != '\n') advance();
    } else if (c == '/' && at(1) == '*') {
      const SourceLocation start = here();
      advance();
      advance();
      while (!(cur() == '*' && at(1) == '/')) {
        if (cur() == '\0') failLex("F1000", start, "unterminated /* comment");
        advance();
      }
      advance();
      advance();
    } else if (c == '#' && atLineStart_) {
      directive();
    } else if (c == '\0' || !active()) {
      if (c == '\0') return;
      atLineStart_ = false;
      advance();  // text in a skipped #if region
    } else {
      return;
    }
  }
}

const Token& Lexer::peek() {
  if (!hasPeeked_) {
    peeked_ = next();
    hasPeeked_ = true;
  }
  return peeked_;
}

Token Lexer::next() {
  if (hasPeeked_) {
    hasPeeked_ = false;
    return std::move(peeked_);
  }
  for (;;) {
    Token t;
    if (!pending_.empty()) {
      t = std::move(pending_.front());
      pending_.erase(pending_.begin());
      if (pending_.empty()) expansionDepth_ = 0;
    } else {
      t = lex();
    }
    if (t.kind == TokenKind::Ident) {
      for (const Macro& m : macros_) {
        if (m.name != t.text) continue;
        if (++expansionDepth_ > kMaxExpansionDepth)
          failLex("F1004", t.where, "macro '{}' expands into itself", t.text);
        std::vector<Token> body = m.body;
        for (Token& b : body) b.where = t.where;
        pending_.insert(pending_.begin(), body.begin(), body.end());
        goto again;
      }
    }
    return t;
  again:;
  }
}

Token Lexer::lex() {
  for (;;) {
    skipSpaceAndComments();
    if (cur() != '\0') break;
    if (!conds_.empty() && stack_.size() == 1)
      failLex("F1005", here(), "#if without #endif at the end of the file");
    if (stack_.size() == 1) {
      Token end;
      end.where = here();
      return end;
    }
    stack_.pop_back();
    atLineStart_ = true;
  }
  atLineStart_ = false;
  Token t;
  t.where = here();
  const char c = cur();
  if (identStart(c)) {
    t.kind = TokenKind::Ident;
    while (identChar(cur())) {
      t.text += cur();
      advance();
    }
    return t;
  }
  if (std::isdigit(static_cast<unsigned char>(c)) ||
      (c == '.' && std::isdigit(static_cast<unsigned char>(at(1))))) {
    std::string s;
    bool isFloat = false;
    if (c == '0' && (at(1) == 'x' || at(1) == 'X')) {
      s += "0x";
      advance();
      advance();
      while (std::isxdigit(static_cast<unsigned char>(cur()))) {
        s += cur();
        advance();
      }
      if (s.size() == 2) failLex("F1003", t.where, "expected hexadecimal digits after '0x'");
      t.number = double(std::strtoull(s.c_str() + 2, nullptr, 16));
    } else {
      while (std::isdigit(static_cast<unsigned char>(cur())) || cur() == '.') {
        if (cur() == '.') isFloat = true;
        s += cur();
        advance();
      }
      if (cur() == 'e' || cur() == 'E') {
        const char sign = at(1);
        const bool digitNext = std::isdigit(static_cast<unsigned char>(sign)) ||
                               ((sign == '+' || sign == '-') && std::isdigit(static_cast<unsigned char>(at(2))));
        if (digitNext) {
          isFloat = true;
          s += cur();
          advance();
          if (cur() == '+' || cur() == '-') {
            s += cur();
            advance();
          }
          while (std::isdigit(static_cast<unsigned char>(cur()))) {
            s += cur();
            advance();
          }
        }
      }
      t.number = std::strtod(s.c_str(), nullptr);
    }
    // HLSL suffixes: f/F/h/H (float), u/U/l/L (integer).
    while (cur() == 'f' || cur() == 'F' || cur() == 'h' || cur() == 'H' || cur() == 'u' ||
           cur() == 'U' || cur() == 'l' || cur() == 'L') {
      if (cur() == 'f' || cur() == 'F' || cur() == 'h' || cur() == 'H') isFloat = true;
      advance();
    }
    if (identChar(cur())) failLex("F1003", here(), "unexpected '{}' in the number '{}'", cur(), s);
    t.kind = isFloat ? TokenKind::Float : TokenKind::Int;
    t.text = s;
    return t;
  }
  if (c == '"') {
    advance();
    t.kind = TokenKind::String;
    while (cur() != '"') {
      if (cur() == '\0' || cur() == '\n') failLex("F1001", t.where, "unterminated string");
      if (cur() == '\\' && at(1) != '\0') {
        advance();
        const char e = cur();
        t.text += e == 'n' ? '\n' : e == 't' ? '\t' : e;
        advance();
        continue;
      }
      t.text += cur();
      advance();
    }
    advance();
    return t;
  }
  static constexpr std::string_view kTwo[] = {"&&", "||", "==", "!=", "<=", ">=", "<<", ">>",
                                              "++", "--", "+=", "-=", "*=", "/=", "::"};
  t.kind = TokenKind::Punct;
  for (std::string_view two : kTwo) {
    if (c == two[0] && at(1) == two[1]) {
      t.text = std::string(two);
      advance();
      advance();
      return t;
    }
  }
  static constexpr std::string_view kOne = "{}[]()<>=;,:|+-*/.!~&^?%";
  if (kOne.find(c) == std::string_view::npos) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) failLex("F1002", t.where, "unexpected character '{}'", c);
    failLex("F1002", t.where, "unexpected byte 0x{:02X}", unsigned(u));
  }
  t.text = std::string(1, c);
  advance();
  return t;
}

RawBlock Lexer::rawBlockAfterBrace(const SourceLocation& brace, bool semicolonComments) {
  if (hasPeeked_ || !pending_.empty())
    failLex("F1011", brace, "a block's text cannot come from a macro");
  RawBlock b;
  b.file = stack_.back().file;
  b.where = brace;
  // Pad so positions inside the block match the file: the text starts right after '{'.
  const Source& s = stack_.back();
  b.text.assign(size_t(std::max(0, s.line - 1)), '\n');
  b.text.append(size_t(std::max(0, s.col - 1)), ' ');
  int depth = 1;
  for (;;) {
    const char c = cur();
    if (c == '\0') failLex("F1011", brace, "expected '}}' to close the block opened here");
    if (c == '/' && at(1) == '/') {
      while (cur() != '\0' && cur() != '\n') {
        b.text += cur();
        advance();
      }
      continue;
    }
    if (c == '/' && at(1) == '*') {
      const SourceLocation start = here();
      while (!(cur() == '*' && at(1) == '/')) {
        if (cur() == '\0') failLex("F1000", start, "unterminated /* comment");
        b.text += cur();
        advance();
      }
      b.text += "*/";
      advance();
      advance();
      continue;
    }
    if (c == ';' && semicolonComments) {  // an assembly comment: braces in it do not count
      while (cur() != '\0' && cur() != '\n') {
        b.text += cur();
        advance();
      }
      continue;
    }
    if (c == '{') ++depth;
    if (c == '}' && --depth == 0) {
      advance();
      atLineStart_ = false;
      return b;
    }
    b.text += c;
    advance();
  }
}

void Lexer::include(std::string_view name, bool angled, const SourceLocation& where) {
  if (stack_.size() >= kMaxIncludeDepth)
    failLex("F1006", where, "#include nested more than {} deep (an include cycle?)", kMaxIncludeDepth);
  namespace fs = std::filesystem;
  std::vector<std::string> candidates;
  const std::string self = stack_.back().file;
  if (!angled) candidates.push_back((fs::path(self).parent_path() / std::string(name)).string());
  for (const std::string& dir : includeDirs_) candidates.push_back((fs::path(dir) / std::string(name)).string());
  for (const std::string& path : candidates) {
    for (const Source& open : stack_)
      if (open.file == path) failLex("F1006", where, "#include cycle: '{}' includes itself", path);
    auto text = readFile(path);
    if (!text) continue;
    files_.push_back(path);
    stack_.push_back({std::make_shared<std::string>(std::move(*text)), path});
    atLineStart_ = true;
    return;
  }
  failLex("F1006", where, "cannot open include file '{}'", name);
}

bool Lexer::evalCondition(std::string_view expr, const SourceLocation& where) {
  // Integer expressions of defined(NAME), numbers and macros with ! && || == != < > ( ).
  std::string text;
  for (size_t i = 0; i < expr.size();) {
    if (identStart(expr[i])) {
      size_t j = i;
      while (j < expr.size() && identChar(expr[j])) ++j;
      std::string id(expr.substr(i, j - i));
      if (id == "defined") {
        size_t k = j;
        while (k < expr.size() && (expr[k] == ' ' || expr[k] == '(')) ++k;
        size_t e = k;
        while (e < expr.size() && identChar(expr[e])) ++e;
        const std::string name(expr.substr(k, e - k));
        while (e < expr.size() && (expr[e] == ' ' || expr[e] == ')')) ++e;
        bool found = false;
        for (const Macro& m : macros_) found |= m.name == name;
        text += found ? " 1 " : " 0 ";
        i = e;
        continue;
      }
      bool expanded = false;
      for (const Macro& m : macros_) {
        if (m.name != id) continue;
        for (const Token& b : m.body) text += " " + (b.kind == TokenKind::String ? "0" : b.text);
        expanded = true;
        break;
      }
      if (!expanded) text += " 0 ";  // undefined identifiers are 0, as in C
      i = j;
      continue;
    }
    text += expr[i++];
  }
  // A small recursive-descent evaluator over `text`.
  struct Eval {
    std::string_view s;
    size_t p = 0;
    SourceLocation where;
    void ws() { while (p < s.size() && std::isspace(static_cast<unsigned char>(s[p]))) ++p; }
    bool eat(std::string_view op) {
      ws();
      if (s.substr(p, op.size()) == op) { p += op.size(); return true; }
      return false;
    }
    long long primary() {
      ws();
      if (eat("!")) return !primary();
      if (eat("-")) return -primary();
      if (eat("(")) {
        long long v = orExpr();
        if (!eat(")")) failLex("F1007", where, "expected ')' in the #if expression");
        return v;
      }
      size_t e = p;
      while (e < s.size() && std::isalnum(static_cast<unsigned char>(s[e]))) ++e;
      if (e == p) failLex("F1007", where, "expected a number in the #if expression");
      long long v = std::strtoll(std::string(s.substr(p, e - p)).c_str(), nullptr, 0);
      p = e;
      return v;
    }
    long long cmp() {
      long long v = primary();
      for (;;) {
        if (eat("==")) v = v == primary();
        else if (eat("!=")) v = v != primary();
        else if (eat(">=")) v = v >= primary();
        else if (eat("<=")) v = v <= primary();
        else if (eat(">")) v = v > primary();
        else if (eat("<")) v = v < primary();
        else return v;
      }
    }
    long long andExpr() {
      long long v = cmp();
      while (eat("&&")) v = cmp() && v;
      return v;
    }
    long long orExpr() {
      long long v = andExpr();
      while (eat("||")) v = andExpr() || v;
      return v;
    }
  } ev{text, 0, where};
  const long long v = ev.orExpr();
  ev.ws();
  if (ev.p != text.size()) failLex("F1007", where, "unexpected '{}' in the #if expression", text.substr(ev.p));
  return v != 0;
}

void Lexer::directive() {
  const SourceLocation where = here();
  advance();  // '#'
  while (cur() == ' ' || cur() == '\t') advance();
  std::string name;
  while (identChar(cur())) {
    name += cur();
    advance();
  }
  const std::string rest(trim(restOfLine()));
  const bool on = active();
  if (name == "if" || name == "ifdef" || name == "ifndef") {
    bool value = false;
    if (on) {
      if (name == "if") {
        value = evalCondition(rest, where);
      } else {
        bool found = false;
        for (const Macro& m : macros_) found |= m.name == rest;
        value = (name == "ifdef") == found;
      }
    }
    conds_.push_back({on && value, on && value, on});
  } else if (name == "elif") {
    if (conds_.empty()) failLex("F1005", where, "#elif without #if");
    Cond& c = conds_.back();
    const bool value = c.parentOn && !c.taken && evalCondition(rest, where);
    c.active = value;
    c.taken |= value;
  } else if (name == "else") {
    if (conds_.empty()) failLex("F1005", where, "#else without #if");
    Cond& c = conds_.back();
    c.active = c.parentOn && !c.taken;
    c.taken = true;
  } else if (name == "endif") {
    if (conds_.empty()) failLex("F1005", where, "#endif without #if");
    conds_.pop_back();
  } else if (!on) {
    // Other directives in a skipped region are ignored.
  } else if (name == "define") {
    size_t i = 0;
    while (i < rest.size() && identChar(rest[i])) ++i;
    if (i == 0) failLex("F1008", where, "expected a macro name after #define");
    Macro m{rest.substr(0, i), {}};
    if (i < rest.size() && rest[i] == '(')
      failLex("F1008", where, "function-like macro '{}': effect files take object-like #defines only", m.name);
    Lexer sub(std::string_view(rest).substr(i), where.file, {}, {});
    for (Token t = sub.next(); t.kind != TokenKind::End; t = sub.next()) {
      t.where = where;
      m.body.push_back(std::move(t));
    }
    std::erase_if(macros_, [&](const Macro& x) { return x.name == m.name; });
    macros_.push_back(std::move(m));
  } else if (name == "undef") {
    std::erase_if(macros_, [&](const Macro& x) { return x.name == rest; });
  } else if (name == "include") {
    if (rest.size() >= 2 && rest.front() == '"' && rest.back() == '"') {
      include(std::string_view(rest).substr(1, rest.size() - 2), false, where);
    } else if (rest.size() >= 2 && rest.front() == '<' && rest.back() == '>') {
      include(std::string_view(rest).substr(1, rest.size() - 2), true, where);
    } else {
      failLex("F1010", where, "expected \"file\" or <file> after #include");
    }
  } else if (name == "error") {
    failLex("F1009", where, "#error {}", rest);
  } else if (name == "line") {
    Source& s = stack_.back();
    char* end = nullptr;
    const long line = std::strtol(rest.c_str(), &end, 10);
    if (end == rest.c_str() || line <= 0) failLex("F1010", where, "expected a line number after #line");
    std::string_view file = trim(std::string_view(end));
    if (file.size() >= 2 && file.front() == '"') s.file = std::string(file.substr(1, file.size() - 2));
    s.line = int(line) - 1;  // the newline that ends this directive makes it `line`
  } else if (name == "pragma") {
    // #pragma pack_matrix / warning: no effect on effect-level parsing.
  } else {
    failLex("F1010", where, "unknown preprocessor directive '#{}'", name);
  }
  atLineStart_ = true;
}

}  // namespace refx::effect::detail
