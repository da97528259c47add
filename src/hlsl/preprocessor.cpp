// Minimal tokenizer without directives (replaced by the full preprocessor).
#include "hlsl/preprocessor.h"

#include <cctype>
#include <cstring>

namespace refx::hlsl {

std::vector<Token> preprocess(std::string_view src, std::string_view fileName, const PreprocessOptions&,
                              DiagnosticSink& sink) {
  std::vector<Token> out;
  size_t i = 0;
  int line = 1, col = 1;
  auto adv = [&](size_t n) {
    for (size_t k = 0; k < n && i < src.size(); ++k, ++i) {
      if (src[i] == '\n') { ++line; col = 1; } else ++col;
    }
  };
  static const char* puncts[] = {"<<=", ">>=", "++", "--", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "&&",
                                 "||", "==", "!=", "<=", ">=", "<<", ">>", "::", "##"};
  while (i < src.size()) {
    char c = src[i];
    if (std::isspace((unsigned char)c)) { adv(1); continue; }
    if (c == '/' && i + 1 < src.size() && src[i + 1] == '/') { while (i < src.size() && src[i] != '\n') adv(1); continue; }
    if (c == '/' && i + 1 < src.size() && src[i + 1] == '*') {
      adv(2);
      while (i + 1 < src.size() && !(src[i] == '*' && src[i + 1] == '/')) adv(1);
      adv(2);
      continue;
    }
    if (c == '#') {  // skip directive lines, keep pragmas
      size_t s = i;
      while (i < src.size() && src[i] != '\n') adv(1);
      std::string d(src.substr(s, i - s));
      auto p = d.find("pragma");
      if (p != std::string::npos) out.push_back({TokenKind::Pragma, d.substr(p + 6), std::string(fileName), line, 1});
      continue;
    }
    Token t;
    t.file = std::string(fileName);
    t.line = line;
    t.column = col;
    size_t s = i;
    if (std::isalpha((unsigned char)c) || c == '_') {
      while (i < src.size() && (std::isalnum((unsigned char)src[i]) || src[i] == '_')) adv(1);
      t.kind = TokenKind::Identifier;
    } else if (std::isdigit((unsigned char)c) || (c == '.' && i + 1 < src.size() && std::isdigit((unsigned char)src[i + 1]))) {
      bool isFloat = false;
      if (c == '0' && i + 1 < src.size() && (src[i + 1] == 'x' || src[i + 1] == 'X')) {
        adv(2);
        while (i < src.size() && std::isxdigit((unsigned char)src[i])) adv(1);
      } else {
        while (i < src.size() && (std::isdigit((unsigned char)src[i]) || src[i] == '.')) { if (src[i] == '.') isFloat = true; adv(1); }
        if (i < src.size() && (src[i] == 'e' || src[i] == 'E')) {
          isFloat = true;
          adv(1);
          if (i < src.size() && (src[i] == '+' || src[i] == '-')) adv(1);
          while (i < src.size() && std::isdigit((unsigned char)src[i])) adv(1);
        }
      }
      while (i < src.size() && std::strchr("fFhHlLuU", src[i]) && src[i]) { if (std::strchr("fFhH", src[i])) isFloat = true; adv(1); }
      t.kind = isFloat ? TokenKind::FloatLiteral : TokenKind::IntLiteral;
    } else if (c == '"') {
      adv(1);
      s = i;
      while (i < src.size() && src[i] != '"') adv(1);
      t.kind = TokenKind::StringLiteral;
      t.text = std::string(src.substr(s, i - s));
      adv(1);
      out.push_back(t);
      continue;
    } else {
      t.kind = TokenKind::Punct;
      size_t n = 1;
      for (const char* p : puncts)
        if (src.substr(i, std::strlen(p)) == p) { n = std::strlen(p); break; }
      adv(n);
    }
    t.text = std::string(src.substr(s, i - s));
    out.push_back(std::move(t));
  }
  out.push_back({TokenKind::EndOfFile, "", std::string(fileName), line, col});
  (void)sink;
  return out;
}

}  // namespace refx::hlsl
