#include "hlsl/lexer.h"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>

namespace refx::hlsl::detail {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isHexDigit(char c) { return isDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }
bool isIdentifierStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isIdentifierChar(char c) { return isIdentifierStart(c) || isDigit(c); }
// A plain search of a set of characters: strchr would also match the NUL that ends the set.
bool isOneOf(char c, std::string_view set) { return set.find(c) != std::string_view::npos; }

std::string describeChar(char c) {
  const auto byte = static_cast<unsigned char>(c);
  if (byte >= 0x21 && byte < 0x7f) return fmt::format("'{}'", c);
  return fmt::format("0x{:02x}", byte);
}

}  // namespace

Lexer::Lexer(std::string_view source) {
  lineStarts_.push_back(0);
  for (size_t i = 0; i < source.size(); ++i)
    if (source[i] == '\n') lineStarts_.push_back(i + 1);
  // Splice continuation lines once, up front: every later step sees logical lines,
  // and `splices_` turns offsets back into the positions the user wrote.
  text_.reserve(source.size());
  size_t removed = 0, i = 0;
  while (i < source.size()) {
    const size_t slash = source.find('\\', i);
    if (slash == std::string_view::npos) {
      text_.append(source.substr(i));
      break;
    }
    text_.append(source.substr(i, slash - i));
    size_t after = slash + 1;
    if (after + 1 < source.size() && source[after] == '\r' && source[after + 1] == '\n') {
      after += 2;
    } else if (after < source.size() && source[after] == '\n') {
      after += 1;
    } else {
      text_.push_back('\\');
      i = slash + 1;
      continue;
    }
    removed += after - slash;
    splices_.emplace_back(text_.size(), removed);
    i = after;
  }
}

void Lexer::locate(size_t offset, int& line, int& column) const {
  // Tokens come in order, so the cursors only move forward; a step back (rare) restarts them.
  if (offset < cursorOffset_) cursorSplice_ = cursorLine_ = 0;
  cursorOffset_ = offset;
  while (cursorSplice_ < splices_.size() && splices_[cursorSplice_].first <= offset) ++cursorSplice_;
  const size_t original = offset + (cursorSplice_ > 0 ? splices_[cursorSplice_ - 1].second : 0);
  while (cursorLine_ + 1 < lineStarts_.size() && lineStarts_[cursorLine_ + 1] <= original) ++cursorLine_;
  line = static_cast<int>(cursorLine_ + 1);
  column = static_cast<int>(original - lineStarts_[cursorLine_] + 1);
}

void Lexer::problem(size_t offset, const char* code, std::string message) {
  LexProblem p;
  locate(offset, p.line, p.column);
  p.code = code;
  p.message = std::move(message);
  problems.push_back(std::move(p));
}

PPToken Lexer::make(PPKind kind, size_t start, size_t length) const {
  PPToken t;
  t.kind = kind;
  t.text = std::string_view(text_).substr(start, length);
  locate(start, t.line, t.column);
  return t;
}

PPKind Lexer::lexNumber() {
  const size_t n = text_.size();
  size_t p = pos_;
  if (text_[p] == '0' && p + 2 < n && (text_[p + 1] == 'x' || text_[p + 1] == 'X') && isHexDigit(text_[p + 2])) {
    p += 2;
    while (p < n && isHexDigit(text_[p])) ++p;
    while (p < n && isOneOf(text_[p], "uUlL")) ++p;
    pos_ = p;
    return PPKind::IntLiteral;
  }
  bool isFloat = false;
  while (p < n && isDigit(text_[p])) ++p;
  if (p < n && text_[p] == '.') {
    isFloat = true;
    ++p;
    while (p < n && isDigit(text_[p])) ++p;
  }
  if (p < n && (text_[p] == 'e' || text_[p] == 'E')) {
    size_t q = p + 1;
    if (q < n && (text_[q] == '+' || text_[q] == '-')) ++q;
    if (q < n && isDigit(text_[q])) {  // otherwise the 'e' starts an identifier
      isFloat = true;
      p = q;
      while (p < n && isDigit(text_[p])) ++p;
    }
  }
  if (isFloat) {
    if (p < n && isOneOf(text_[p], "fFhHlL")) ++p;
  } else {
    while (p < n && isOneOf(text_[p], "uUlL")) ++p;
  }
  pos_ = p;
  return isFloat ? PPKind::FloatLiteral : PPKind::IntLiteral;
}

bool Lexer::lexString(size_t start) {
  const size_t n = text_.size();
  pos_ = start + 1;
  while (pos_ < n) {
    const char c = text_[pos_];
    if (c == '\\' && pos_ + 1 < n && text_[pos_ + 1] != '\n') {
      pos_ += 2;
    } else if (c == '"') {
      ++pos_;
      return true;
    } else if (c == '\n') {
      break;
    } else {
      ++pos_;
    }
  }
  if (!quiet) problem(start, "X1552", "unterminated string literal");
  return false;
}

// Longest match: <<= >>= and the two-character operators before single characters.
size_t Lexer::punctuatorLength(size_t start) const {
  const char c = text_[start];
  const char d = start + 1 < text_.size() ? text_[start + 1] : '\0';
  const char e = start + 2 < text_.size() ? text_[start + 2] : '\0';
  switch (c) {
    case '<':
    case '>':
      if (d == c) return e == '=' ? 3 : 2;
      return d == '=' ? 2 : 1;
    case '+': return d == '+' || d == '=' ? 2 : 1;
    case '-': return d == '-' || d == '=' || d == '>' ? 2 : 1;
    case '&': return d == '&' || d == '=' ? 2 : 1;
    case '|': return d == '|' || d == '=' ? 2 : 1;
    case '*':
    case '/':
    case '%':
    case '^':
    case '!':
    case '=': return d == '=' ? 2 : 1;
    case ':': return d == ':' ? 2 : 1;
    case '#': return d == '#' ? 2 : 1;
    case '(':
    case ')':
    case '{':
    case '}':
    case '[':
    case ']':
    case ';':
    case ',':
    case '.':
    case '?':
    case '~': return 1;
    default: return 0;
  }
}

PPToken Lexer::next(bool directiveMode) {
  const size_t n = text_.size();
  bool space = false;
  for (;;) {
    while (pos_ < n) {
      const char c = text_[pos_];
      if (c == '\n') {
        if (directiveMode) {
          PPToken t = make(PPKind::Newline, pos_, 0);
          ++pos_;
          atLineStart_ = true;
          return t;
        }
        ++pos_;
        atLineStart_ = true;
        space = true;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') {
        ++pos_;
        space = true;
      } else if (c == '/' && pos_ + 1 < n && text_[pos_ + 1] == '/') {
        pos_ = std::min(text_.find('\n', pos_), n);
        space = true;
      } else if (c == '/' && pos_ + 1 < n && text_[pos_ + 1] == '*') {
        // A block comment is one space: newlines inside it do not end a directive.
        const size_t close = text_.find("*/", pos_ + 2);
        if (close == std::string::npos) {
          problem(pos_, "X1551", "unterminated comment");
          pos_ = n;
        } else {
          pos_ = close + 2;
        }
        space = true;
      } else {
        break;
      }
    }
    if (pos_ >= n) {
      PPToken t = make(PPKind::End, n, 0);
      t.startOfLine = atLineStart_;
      return t;
    }
    const size_t start = pos_;
    const char c = text_[pos_];
    PPKind kind;
    bool terminated = true;
    if (isIdentifierStart(c)) {
      while (pos_ < n && isIdentifierChar(text_[pos_])) ++pos_;
      kind = PPKind::Identifier;
    } else if (isDigit(c) || (c == '.' && pos_ + 1 < n && isDigit(text_[pos_ + 1]))) {
      kind = lexNumber();
    } else if (c == '"') {
      terminated = lexString(start);
      kind = PPKind::StringLiteral;
    } else if (const size_t length = punctuatorLength(start)) {
      pos_ += length;
      kind = PPKind::Punct;
    } else {
      if (!quiet) problem(start, "X1553", fmt::format("unexpected character {}", describeChar(c)));
      ++pos_;
      space = true;
      continue;
    }
    PPToken t = make(kind, start, pos_ - start);
    if (!terminated)  // already reported: closed here so that later steps see a whole literal
      t.text = ownSpellings_.emplace_back(std::string(t.text) + '"');
    t.spaceBefore = space;
    t.startOfLine = atLineStart_;
    atLineStart_ = false;
    return t;
  }
}

std::optional<Lexer::HeaderName> Lexer::headerName() {
  const size_t n = text_.size();
  for (;;) {
    while (pos_ < n && isOneOf(text_[pos_], " \t\r\v\f")) ++pos_;
    if (pos_ + 1 < n && text_[pos_] == '/' && text_[pos_ + 1] == '*') {
      const size_t close = text_.find("*/", pos_ + 2);
      if (close == std::string::npos) return std::nullopt;  // next() reports it
      pos_ = close + 2;
      continue;
    }
    break;
  }
  if (pos_ >= n || (text_[pos_] != '"' && text_[pos_] != '<')) return std::nullopt;
  HeaderName h;
  h.angled = text_[pos_] == '<';
  const char close = h.angled ? '>' : '"';
  locate(pos_, h.line, h.column);
  size_t end = pos_ + 1;
  while (end < n && text_[end] != close && text_[end] != '\n') ++end;
  h.name = text_.substr(pos_ + 1, end - pos_ - 1);
  h.terminated = end < n && text_[end] == close;
  pos_ = h.terminated ? end + 1 : end;
  atLineStart_ = false;
  return h;
}

bool lexSingleToken(std::string_view text, PPToken& out) {
  Lexer lexer(text);
  PPToken first = lexer.next(false);
  const PPToken second = lexer.next(false);
  if (first.kind == PPKind::End || second.kind != PPKind::End || !lexer.problems.empty() ||
      first.text.size() != text.size())
    return false;
  out = first;
  out.text = text;
  return true;
}

std::string resolveEscapes(std::string_view spelling) {
  if (spelling.size() >= 1 && spelling.front() == '"') spelling.remove_prefix(1);
  if (spelling.size() >= 1 && spelling.back() == '"') spelling.remove_suffix(1);
  std::string value;
  value.reserve(spelling.size());
  for (size_t i = 0; i < spelling.size(); ++i) {
    const char c = spelling[i];
    if (c != '\\' || i + 1 == spelling.size()) {
      value += c;
      continue;
    }
    const char e = spelling[++i];
    switch (e) {
      case 'n': value += '\n'; break;
      case 't': value += '\t'; break;
      case 'r': value += '\r'; break;
      case 'a': value += '\a'; break;
      case 'b': value += '\b'; break;
      case 'f': value += '\f'; break;
      case 'v': value += '\v'; break;
      case 'x': {
        unsigned code = 0;
        size_t digits = 0;
        while (i + 1 < spelling.size() && isHexDigit(spelling[i + 1])) {
          const char h = spelling[++i];
          code = (code << 4 | static_cast<unsigned>(isDigit(h) ? h - '0' : (h | 0x20) - 'a' + 10)) & 0xff;
          ++digits;
        }
        value += digits ? static_cast<char>(code) : 'x';
        break;
      }
      default:
        if (e >= '0' && e <= '7') {
          unsigned code = static_cast<unsigned>(e - '0');
          for (int k = 0; k < 2 && i + 1 < spelling.size() && spelling[i + 1] >= '0' && spelling[i + 1] <= '7'; ++k)
            code = code * 8 + static_cast<unsigned>(spelling[++i] - '0');
          value += static_cast<char>(code & 0xff);
        } else {
          value += e;  // \" \' \\ \? and unknown escapes: the character itself
        }
    }
  }
  return value;
}

std::string quoteString(std::string_view value) {
  std::string s = "\"";
  for (char c : value) {
    if (c == '"' || c == '\\') s += '\\';
    s += c;
  }
  s += '"';
  return s;
}

}  // namespace refx::hlsl::detail
