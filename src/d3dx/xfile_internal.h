// .x file reading: the text and binary encodings become one token stream that a
// single object parser (xfile.cpp) reads.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace refx::d3dx::detail::xfile {

// Tokens of the .x grammar. Binary INTEGER_LIST / FLOAT_LIST records arrive as one
// Integer / Float token per element; template member keywords (DWORD, array, '[', …)
// arrive as Other, since only templates use them and templates are skipped.
enum class Tok : uint8_t {
  End, Name, String, Integer, Float, Guid, OBrace, CBrace, Comma, Semicolon, Template, Other
};

struct Token {
  Tok kind = Tok::End;
  // Name, String, Guid, Other: the text. Integer, Float: the spelling in a text file
  // (parsed by the reader at the precision the member needs); empty in binary files.
  std::string text;
  double number = 0;  // Integer, Float from a binary file; Integer from a text file
  size_t offset = 0;  // byte offset of the token in the file
  uint32_t line = 0, column = 0;  // text files (1-based)
};

class Lexer {
 public:
  virtual ~Lexer() = default;
  virtual Token next() = 0;
  // "name:line:col" (text) or "name:byte N" (binary).
  virtual std::string where(const Token& t) const = 0;
  // Fewest bytes one number takes in this encoding ("0;" in text, a DWORD in binary):
  // a count larger than the rest of the file can hold is rejected before allocating.
  virtual size_t bytesPerNumber() const = 0;
  virtual bool separatorsRequired() const = 0;  // text: ',' or ';' after each member
};

// Header fields (bytes 0..15: "xof 0303txt 0032").
struct Header {
  bool binary = false;
  int floatBits = 32;
};
// Checks the 16-byte header; throws refx::Error for a bad magic, unknown format or
// float size, and for the compressed formats.
Header readHeader(std::span<const uint8_t> bytes, const std::string& name);

std::unique_ptr<Lexer> makeTextLexer(std::span<const uint8_t> bytes, const std::string& name);
std::unique_ptr<Lexer> makeBinaryLexer(std::span<const uint8_t> bytes, const std::string& name,
                                       int floatBits);

inline constexpr size_t kHeaderSize = 16;

}  // namespace refx::d3dx::detail::xfile
