// Tokens of effect files, with the preprocessor directives D3DX's effect compiler
// applies first: #include (quoted and angled), object-like #define / #undef,
// #ifdef / #ifndef / #if / #elif / #else / #endif, #error, #line, #pragma (ignored).
// `asm { … }` and `decl { … }` blocks are not tokenised: the parser takes their text
// raw and hands it to the assembler / declaration parser with positions intact.
#pragma once
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "refx/core/diagnostics.h"

namespace refx::effect::detail {

enum class TokenKind { End, Ident, Int, Float, String, Punct };

struct Token {
  TokenKind kind = TokenKind::End;
  std::string text;  // identifier, punctuation, string contents (unquoted) or number spelling
  double number = 0;
  SourceLocation where;
  bool is(std::string_view p) const { return kind == TokenKind::Punct && text == p; }
  bool isIdent(std::string_view name) const;  // case-insensitive
};

// A block taken raw: its text padded with newlines and spaces so that line/column
// positions inside it match the effect file.
struct RawBlock {
  std::string text;
  std::string file;
  SourceLocation where;  // the opening '{'
};

class Lexer {
 public:
  Lexer(std::string_view text, std::string file, std::vector<std::string> includeDirs,
        std::vector<std::pair<std::string, std::string>> defines);

  const Token& peek();
  Token next();
  // After the parser consumed a '{' with next(): the text up to the matching '}',
  // which is consumed. Braces in comments do not count; `;` starts a comment in
  // assembly (semicolonComments) but ends a statement in a decl block.
  RawBlock rawBlockAfterBrace(const SourceLocation& brace, bool semicolonComments);
  const std::vector<std::string>& files() const { return files_; }

 private:
  struct Source {
    std::shared_ptr<std::string> text;
    std::string file;
    size_t pos = 0;
    int line = 1, col = 1;
  };
  struct Macro {
    std::string name;
    std::vector<Token> body;
  };
  struct Cond {
    bool active;     // this branch is being read
    bool taken;      // some branch of this #if was taken
    bool parentOn;   // the enclosing region is active
  };

  Token lex();
  void skipSpaceAndComments();
  void directive();
  bool active() const { return conds_.empty() || conds_.back().active; }
  bool evalCondition(std::string_view expr, const SourceLocation& where);
  void include(std::string_view name, bool angled, const SourceLocation& where);
  char cur() const;
  char at(size_t ahead) const;
  void advance();
  SourceLocation here() const;
  std::string restOfLine();

  std::vector<Source> stack_;
  std::vector<Cond> conds_;
  std::vector<Macro> macros_;
  std::vector<Token> pending_;  // macro expansions, front = next
  std::vector<std::string> includeDirs_;
  std::vector<std::string> files_;
  Token peeked_;
  bool hasPeeked_ = false;
  bool atLineStart_ = true;
  int expansionDepth_ = 0;
};

}  // namespace refx::effect::detail
