// Errors of effect files with their codes (docs/diagnostics.md, "Effects"): F10xx for
// the lexer and preprocessor, F11xx for the parser, F12xx for binding names, values and
// shaders. Tests match on the codes.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "refx/core/diagnostics.h"

namespace refx::effect::detail {

// A located, coded error where the effect reader gives up on one construct. what()
// reads "file:line:col: error F1100: message".
class EffectError : public Error {
 public:
  EffectError(Diagnostic d, bool fatal) : Error(d.str()), diagnostic(std::move(d)), fatal(fatal) {}
  Diagnostic diagnostic;
  bool fatal;                    // the token stream itself is broken: nothing after it can be read
  std::vector<Diagnostic> also;  // more errors of the same construct (an asm block's other lines)
};

template <typename... Args>
[[noreturn]] void failCode(const char* code, const SourceLocation& where, fmt::format_string<Args...> f,
                           Args&&... args) {
  throw EffectError(Diagnostic{where, Severity::Error, code, fmt::format(f, std::forward<Args>(args)...)}, false);
}

// Lexical and preprocessor errors: reading stops there.
template <typename... Args>
[[noreturn]] void failLex(const char* code, const SourceLocation& where, fmt::format_string<Args...> f,
                          Args&&... args) {
  throw EffectError(Diagnostic{where, Severity::Error, code, fmt::format(f, std::forward<Args>(args)...)}, true);
}

}  // namespace refx::effect::detail
