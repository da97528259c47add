// A cursor over one line of a .shader_test file: words, numbers and punctuation,
// with spaces allowed between any two of them as vkd3d's runner allows.
#pragma once
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

namespace refx::scene::detail {

class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}

  void skipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool atEnd() {
    skipSpace();
    return pos_ >= text_.size();
  }
  std::string_view rest() {
    skipSpace();
    return std::string_view(text_).substr(pos_);
  }
  size_t position() const { return pos_; }
  void setPosition(size_t p) { pos_ = p; }

  // `w` (which may hold single spaces) as a whole word: followed by the end, a space
  // or punctuation, never by more letters or digits ("float" does not match "float4").
  bool word(std::string_view w) {
    skipSpace();
    std::string_view r = std::string_view(text_).substr(pos_);
    if (r.substr(0, w.size()) != w) return false;
    if (r.size() > w.size()) {
      const char next = r[w.size()];
      if (std::isalnum(static_cast<unsigned char>(next)) || next == '_' || next == '-' || next == '.') return false;
    }
    pos_ += w.size();
    return true;
  }
  // `s` exactly, whatever follows ("sm>=" before "4").
  bool literal(std::string_view s) {
    skipSpace();
    if (std::string_view(text_).substr(pos_, s.size()) != s) return false;
    pos_ += s.size();
    return true;
  }
  bool ch(char c) {
    skipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  char peek() {
    skipSpace();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  // A C float literal (strtof: decimal, exponent, hex, inf, nan).
  std::optional<float> number() {
    skipSpace();
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    errno = 0;
    const float v = std::strtof(begin, &end);
    if (end == begin) return std::nullopt;
    pos_ += size_t(end - begin);
    return v;
  }
  // A C integer literal (decimal, 0x hex, octal), signed.
  std::optional<int64_t> integer() {
    skipSpace();
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(begin, &end, 0);
    if (end == begin || errno == ERANGE) return std::nullopt;
    // "1.5" is not an integer.
    if (*end == '.' || *end == 'e' || *end == 'E') return std::nullopt;
    pos_ += size_t(end - begin);
    return v;
  }
  // Letters, digits, '-', '_' and '.': a name such as "r32g32b32a32-float".
  std::string_view name() {
    skipSpace();
    const size_t start = pos_;
    while (pos_ < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '-' || text_[pos_] == '_' ||
            text_[pos_] == '.'))
      ++pos_;
    return std::string_view(text_).substr(start, pos_ - start);
  }
  // Text up to the matching ')' of a '(' just consumed; nullopt when unbalanced.
  std::optional<std::string_view> parenthesized() {
    int depth = 1;
    const size_t start = pos_;
    for (; pos_ < text_.size(); ++pos_) {
      if (text_[pos_] == '(') ++depth;
      if (text_[pos_] == ')' && --depth == 0) {
        std::string_view inside = std::string_view(text_).substr(start, pos_ - start);
        ++pos_;
        return inside;
      }
    }
    return std::nullopt;
  }

 private:
  std::string text_;  // owned, so strtof/strtoll see a terminating NUL
  size_t pos_ = 0;
};

}  // namespace refx::scene::detail
