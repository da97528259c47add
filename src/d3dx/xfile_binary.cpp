// Binary .x files ("xof 0303bin 0032"): the lexer. Every record starts with a WORD
// token (little-endian):
//   NAME 1: DWORD count, count bytes       STRING 2: DWORD count, count bytes
//   INTEGER 3: DWORD                       GUID 5: DWORD, WORD, WORD, 8 bytes
//   INTEGER_LIST 6: DWORD n, n DWORDs      FLOAT_LIST 7: DWORD n, n floats (4 or 8 bytes
//                                          by the header's float size)
//   OBRACE 10, CBRACE 11, OPAREN 12, CPAREN 13, OBRACKET 14, CBRACKET 15, OANGLE 16,
//   CANGLE 17, DOT 18, COMMA 19, SEMICOLON 20, TEMPLATE 31, WORD 40, DWORD 41,
//   FLOAT 42, DOUBLE 43, CHAR 44, UCHAR 45, SWORD 46, SDWORD 47, VOID 48, LPSTR 49,
//   UNICODE 50, CSTRING 51, ARRAY 52: the token alone.
// A STRING's terminating ';' or ',' is the separator token that follows it (as
// DirectX's own reader treats it).
#include <cstring>

#include <fmt/format.h>

#include "d3dx/xfile_internal.h"
#include "refx/core/diagnostics.h"

namespace refx::d3dx::detail::xfile {

namespace {

enum : uint16_t {
  TOKEN_NAME = 1, TOKEN_STRING = 2, TOKEN_INTEGER = 3, TOKEN_GUID = 5, TOKEN_INTEGER_LIST = 6,
  TOKEN_FLOAT_LIST = 7, TOKEN_OBRACE = 10, TOKEN_CBRACE = 11, TOKEN_COMMA = 19,
  TOKEN_SEMICOLON = 20, TOKEN_TEMPLATE = 31,
};

// Tokens that only template declarations use, with their text spelling.
struct Keyword {
  uint16_t token;
  const char* text;
};
constexpr Keyword kKeywords[] = {
    {12, "("},     {13, ")"},      {14, "["},     {15, "]"},      {16, "<"},
    {17, ">"},     {18, "."},      {40, "WORD"},  {41, "DWORD"},  {42, "FLOAT"},
    {43, "DOUBLE"}, {44, "CHAR"},  {45, "UCHAR"}, {46, "SWORD"},  {47, "SDWORD"},
    {48, "VOID"},  {49, "STRING"}, {50, "UNICODE"}, {51, "CSTRING"}, {52, "array"},
};

class BinaryLexer final : public Lexer {
 public:
  BinaryLexer(std::span<const uint8_t> bytes, std::string name, int floatBits)
      : s_(bytes), name_(std::move(name)), floatBytes_(floatBits / 8), pos_(kHeaderSize) {}

  std::string where(const Token& t) const override {
    return fmt::format("{}:byte {}", name_, t.offset);
  }
  size_t bytesPerNumber() const override { return 4; }
  bool separatorsRequired() const override { return false; }

  Token next() override {
    Token t;
    while (listLeft_ == 0) {
      t.offset = pos_;
      if (pos_ >= s_.size()) return t;  // End
      if (s_.size() - pos_ < 2) fail(t, "a token is cut off by the end of the file");
      uint16_t token = uint16_t(s_[pos_] | (s_[pos_ + 1] << 8));
      pos_ += 2;
      switch (token) {
        case TOKEN_NAME:
        case TOKEN_STRING: {
          uint32_t n = dword(t, "length");
          need(t, n, token == TOKEN_NAME ? "name" : "string");
          t.kind = token == TOKEN_NAME ? Tok::Name : Tok::String;
          t.text.assign(reinterpret_cast<const char*>(s_.data()) + pos_, n);
          pos_ += n;
          return t;
        }
        case TOKEN_INTEGER:
          t.kind = Tok::Integer;
          t.number = dword(t, "value");
          return t;
        case TOKEN_GUID: {
          need(t, 16, "GUID");
          const uint8_t* g = s_.data() + pos_;
          uint32_t d1;
          std::memcpy(&d1, g, 4);
          t.kind = Tok::Guid;
          t.text = fmt::format("{:08X}-{:04X}-{:04X}-{:02X}{:02X}-{:02X}{:02X}{:02X}{:02X}{:02X}{:02X}",
                               d1, g[4] | (g[5] << 8), g[6] | (g[7] << 8), g[8], g[9], g[10], g[11],
                               g[12], g[13], g[14], g[15]);
          pos_ += 16;
          return t;
        }
        case TOKEN_INTEGER_LIST:
        case TOKEN_FLOAT_LIST: {
          uint32_t n = dword(t, "element count");
          listFloat_ = token == TOKEN_FLOAT_LIST;
          size_t size = listFloat_ ? size_t(floatBytes_) : 4;
          if (uint64_t(n) * size > s_.size() - pos_)
            fail(t, fmt::format("a list of {} {} runs past the end of the file", n,
                                listFloat_ ? "floats" : "integers"));
          listLeft_ = n;  // an empty list gives no token: read the next record
          break;
        }
        case TOKEN_OBRACE: return spelled(t, Tok::OBrace, "{");
        case TOKEN_CBRACE: return spelled(t, Tok::CBrace, "}");
        case TOKEN_COMMA: return spelled(t, Tok::Comma, ",");
        case TOKEN_SEMICOLON: return spelled(t, Tok::Semicolon, ";");
        case TOKEN_TEMPLATE: return spelled(t, Tok::Template, "template");
        default:
          for (const Keyword& k : kKeywords)
            if (k.token == token) return spelled(t, Tok::Other, k.text);
          fail(t, fmt::format("unknown token {}", token));
      }
    }
    // The next element of an INTEGER_LIST or FLOAT_LIST.
    --listLeft_;
    t.offset = pos_;
    if (!listFloat_) {
      t.kind = Tok::Integer;
      t.number = dword(t, "value");
    } else if (floatBytes_ == 8) {
      double d;
      std::memcpy(&d, s_.data() + pos_, 8);
      pos_ += 8;
      t.kind = Tok::Float;
      t.number = d;
    } else {
      float f;
      std::memcpy(&f, s_.data() + pos_, 4);
      pos_ += 4;
      t.kind = Tok::Float;
      t.number = f;
    }
    return t;
  }

 private:
  std::span<const uint8_t> s_;
  std::string name_;
  int floatBytes_;
  size_t pos_;
  uint32_t listLeft_ = 0;
  bool listFloat_ = false;

  static Token spelled(Token& t, Tok kind, std::string_view text) {
    t.kind = kind;
    t.text.assign(text.data(), text.size());
    return t;
  }
  [[noreturn]] void fail(const Token& t, const std::string& msg) const {
    throw Error(where(t) + ": error: " + msg);
  }
  void need(const Token& t, uint64_t n, const char* what) const {
    if (n > s_.size() - pos_) fail(t, fmt::format("the {} runs past the end of the file", what));
  }
  uint32_t dword(const Token& t, const char* what) {
    if (s_.size() - pos_ < 4) fail(t, fmt::format("the token's {} is cut off by the end of the file", what));
    uint32_t v;
    std::memcpy(&v, s_.data() + pos_, 4);  // little-endian hosts only, as the rest of refx
    pos_ += 4;
    return v;
  }
};

}  // namespace

std::unique_ptr<Lexer> makeBinaryLexer(std::span<const uint8_t> bytes, const std::string& name,
                                       int floatBits) {
  return std::make_unique<BinaryLexer>(bytes, name, floatBits);
}

}  // namespace refx::d3dx::detail::xfile
