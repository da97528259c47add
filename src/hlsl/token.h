// Tokens of HLSL source after preprocessing, with the position each came from.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace refx::hlsl::detail {

enum class TokenKind : uint8_t {
  Identifier,     // names and keywords alike: the parser decides
  IntLiteral,     // 12, 0x1F, 017, 12u, 12L: text as written
  FloatLiteral,   // 1.0, .5f, 1e-3, 2.h: text as written
  StringLiteral,  // "abc" without the quotes, escapes resolved
  Punct,          // operators and punctuation: ( ) { } [ ] ; , . : ? + ++ += << <<= ## etc.
  Pragma,         // a #pragma line the parser acts on (pack_matrix, warning): text after "pragma"
  EndOfFile,
};

struct Token {
  TokenKind kind = TokenKind::EndOfFile;
  std::string text;
  // Where the token was written (for tokens from a macro expansion: the macro's use).
  std::string file;
  int line = 0, column = 0;  // 1-based
};

}  // namespace refx::hlsl::detail
