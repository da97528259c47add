// Text .x files ("xof 0303txt 0032"): the lexer. Comments are // and #; a word that
// is all digits is an integer, one that parses as a number is a float, anything
// else made of letters, digits, '_', '-' and '.' is a name (as DirectX's parser
// allows names such as "Box01-node").
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "d3dx/xfile_internal.h"
#include "refx/core/diagnostics.h"

namespace refx::d3dx::detail::xfile {

namespace {

bool isSpace(uint8_t c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// Characters that end a word on their own.
bool isDelimiter(uint8_t c) {
  switch (c) {
    case '{': case '}': case '[': case ']': case '(': case ')': case ',': case ';':
    case '<': case '>': case '"':
      return true;
    default:
      return isSpace(c);
  }
}

bool isNameChar(uint8_t c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.' || c >= 0x80;  // bytes of UTF-8 / code-page names
}

bool isHex(uint8_t c) {
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

class TextLexer final : public Lexer {
 public:
  TextLexer(std::span<const uint8_t> bytes, std::string name)
      : s_(bytes), name_(std::move(name)), pos_(kHeaderSize), col_(kHeaderSize + 1) {}

  std::string where(const Token& t) const override {
    return SourceLocation{name_, int(t.line), int(t.column)}.str();
  }
  size_t bytesPerNumber() const override { return 2; }
  bool separatorsRequired() const override { return true; }

  Token next() override {
    skipSpaceAndComments();
    Token t;
    t.offset = pos_;
    t.line = line_;
    t.column = col_;
    if (pos_ >= s_.size()) return t;  // End
    uint8_t c = s_[pos_];
    auto single = [&](Tok kind) {
      t.kind = kind;
      t.text = std::string(1, char(c));
      advance(1);
      return t;
    };
    switch (c) {
      case '{': return single(Tok::OBrace);
      case '}': return single(Tok::CBrace);
      case ',': return single(Tok::Comma);
      case ';': return single(Tok::Semicolon);
      case '[': case ']': case '(': case ')': case '>': return single(Tok::Other);
      case '"': return string(t);
      case '<': return guid(t);
      default: break;
    }
    size_t start = pos_;
    while (pos_ < s_.size() && !isDelimiter(s_[pos_])) advance(1);
    t.text.assign(reinterpret_cast<const char*>(s_.data()) + start, pos_ - start);
    classify(t);
    return t;
  }

 private:
  std::span<const uint8_t> s_;
  std::string name_;
  size_t pos_;
  uint32_t line_ = 1, col_;

  void advance(size_t n) {
    for (size_t i = 0; i < n && pos_ < s_.size(); ++i, ++pos_) {
      if (s_[pos_] == '\n') {
        ++line_;
        col_ = 1;
      } else {
        ++col_;
      }
    }
  }

  void skipSpaceAndComments() {
    while (pos_ < s_.size()) {
      uint8_t c = s_[pos_];
      if (isSpace(c)) {
        advance(1);
      } else if (c == '#' || (c == '/' && pos_ + 1 < s_.size() && s_[pos_ + 1] == '/')) {
        while (pos_ < s_.size() && s_[pos_] != '\n') advance(1);
      } else {
        break;
      }
    }
  }

  [[noreturn]] void failHere(const Token& t, const std::string& msg) const {
    throw Error(where(t) + ": error: " + msg);
  }

  // "..." without escapes, on one line (a missing quote is reported where it began).
  Token string(Token& t) {
    advance(1);
    size_t start = pos_;
    while (pos_ < s_.size() && s_[pos_] != '"' && s_[pos_] != '\n') advance(1);
    if (pos_ >= s_.size() || s_[pos_] != '"') failHere(t, "string without a closing '\"'");
    t.kind = Tok::String;
    t.text.assign(reinterpret_cast<const char*>(s_.data()) + start, pos_ - start);
    advance(1);
    return t;
  }

  // <4D5EB742-7DC2-11CF-8F52-0040333594A3>: hex digits and dashes.
  Token guid(Token& t) {
    advance(1);
    size_t start = pos_;
    while (pos_ < s_.size() && (isHex(s_[pos_]) || s_[pos_] == '-' || s_[pos_] == ' ')) advance(1);
    if (pos_ >= s_.size() || s_[pos_] != '>')
      failHere(t, "expected a GUID such as <3D82AB44-62DA-11CF-AB39-0020AF71E433>");
    t.kind = Tok::Guid;
    t.text.assign(reinterpret_cast<const char*>(s_.data()) + start, pos_ - start);
    advance(1);
    return t;
  }

  void classify(Token& t) const {
    const std::string& w = t.text;
    if (w == "template") {
      t.kind = Tok::Template;
      return;
    }
    bool digits = !w.empty();
    for (char ch : w) digits = digits && ch >= '0' && ch <= '9';
    if (digits) {
      t.kind = Tok::Integer;
      uint64_t v = 0;
      auto r = std::from_chars(w.data(), w.data() + w.size(), v);
      t.number = r.ec == std::errc() ? double(v) : 1e300;  // too large for any count
      return;
    }
    char c0 = w[0];
    if ((c0 >= '0' && c0 <= '9') || c0 == '-' || c0 == '+' || c0 == '.') {
      const char* b = w.data() + (c0 == '+' ? 1 : 0);
      double v = 0;
      auto r = std::from_chars(b, w.data() + w.size(), v);
      if (r.ptr == w.data() + w.size() && r.ec == std::errc()) {
        t.kind = Tok::Float;
        t.number = v;
        return;
      }
      if (r.ec == std::errc::result_out_of_range && r.ptr == w.data() + w.size()) {
        t.kind = Tok::Float;  // reported by the reader as out of range
        t.number = HUGE_VAL;
        return;
      }
    }
    bool name = true;
    for (char ch : w) name = name && isNameChar(uint8_t(ch));
    t.kind = name ? Tok::Name : Tok::Other;
  }
};

}  // namespace

std::unique_ptr<Lexer> makeTextLexer(std::span<const uint8_t> bytes, const std::string& name) {
  return std::make_unique<TextLexer>(bytes, name);
}

}  // namespace refx::d3dx::detail::xfile
