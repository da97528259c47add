// The lexer under the HLSL preprocessor: source bytes → preprocessing tokens with
// their line and column, after backslash-newline splicing and with comments removed.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace refx::hlsl::detail {

enum class PPKind : uint8_t {
  Identifier,
  IntLiteral,
  FloatLiteral,
  StringLiteral,  // text keeps the quotes and the escapes as written (for '#' stringizing)
  Punct,
  Pragma,   // made by the preprocessor from a #pragma line
  Newline,  // only in directive mode: the end of a directive line
  End,      // end of the text (or of a token list)
};

struct PPToken {
  PPKind kind = PPKind::End;
  bool startOfLine = false;   // first token of its line: a '#' here starts a directive
  bool spaceBefore = false;   // whitespace or a comment precedes it
  bool noExpand = false;      // a macro name met inside its own expansion: never expanded again
  bool endsMainFile = false;  // End only: the outermost file ended, not an included one
  uint32_t hideset = 0;       // macros this token came out of (see HideSets in preprocessor.cpp)
  uint32_t file = 0;          // index into the preprocessor's file names
  int line = 0, column = 0;   // 1-based
  // Spelling as written: a view of the lexer's text or of a spelling the preprocessor
  // keeps, so that tokens copy and move without allocating.
  std::string_view text;
};

// A lexical problem found while lexing; the owner adds the file name and reports it.
struct LexProblem {
  int line = 0, column = 0;
  const char* code = "";
  std::string message;
};

class Lexer {
 public:
  explicit Lexer(std::string_view source);

  // The next token. In directive mode a newline ends the line and comes back as a
  // Newline token; otherwise newlines are whitespace. At the end: End, again and again.
  PPToken next(bool directiveMode);

  // The "file" or <file> after #include, read as raw characters (so `<a/b.h>` and
  // `"dir\x.h"` are not split into tokens); nothing if neither follows.
  struct HeaderName {
    std::string name;
    bool angled = false;
    bool terminated = false;
    int line = 0, column = 0;
  };
  std::optional<HeaderName> headerName();

  // While skipping a false #if group, stray characters and unterminated strings are
  // no error (an unterminated comment still is).
  bool quiet = false;
  std::vector<LexProblem> problems;

 private:
  PPToken make(PPKind kind, size_t start, size_t length) const;
  void locate(size_t offset, int& line, int& column) const;
  void problem(size_t offset, const char* code, std::string message);
  PPKind lexNumber();
  bool lexString(size_t start);  // false: unterminated
  size_t punctuatorLength(size_t start) const;

  std::string text_;  // the source with every backslash-newline removed
  // (offset in text_, bytes removed before it): maps text_ offsets back to the source.
  std::vector<std::pair<size_t, size_t>> splices_;
  std::vector<size_t> lineStarts_;  // source offsets where each line begins
  std::deque<std::string> ownSpellings_;  // spellings not in text_ (a closed unterminated string)
  size_t pos_ = 0;
  bool atLineStart_ = true;
  // Where locate() last looked: the splice and line indexes it reached.
  mutable size_t cursorOffset_ = 0, cursorSplice_ = 0, cursorLine_ = 0;
};

// True when `text` lexes as exactly one token (the result of a ## paste); it is put in
// `out`, whose text is then `text` itself (so `text` must outlive it).
bool lexSingleToken(std::string_view text, PPToken& out);

// The value of a string literal as written: quotes removed, escapes resolved.
std::string resolveEscapes(std::string_view spelling);

// `value` written as a string literal (quotes added, '"' and '\' escaped).
std::string quoteString(std::string_view value);

}  // namespace refx::hlsl::detail
