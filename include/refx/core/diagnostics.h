// Errors are part of the product: every failure names where it happened and what
// was expected, in the `file:line:col: error: message` form of compilers.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace refx {

struct SourceLocation {
  std::string file;  // may be empty
  int line = 0;      // 1-based, 0 = unknown
  int column = 0;    // 1-based, 0 = unknown
  std::string str() const;  // "file:line:col" with unknown parts left out
};

// The one exception type refx throws for user-facing errors (bad input, I/O).
class Error : public std::runtime_error {
 public:
  explicit Error(std::string message) : std::runtime_error(std::move(message)) {}
  Error(const SourceLocation& where, const std::string& message)
      : std::runtime_error(where.str().empty() ? "error: " + message
                                               : where.str() + ": error: " + message) {}
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> f, Args&&... args) {
  throw Error(fmt::format(f, std::forward<Args>(args)...));
}

template <typename... Args>
[[noreturn]] void failAt(const SourceLocation& where, fmt::format_string<Args...> f, Args&&... args) {
  throw Error(where, fmt::format(f, std::forward<Args>(args)...));
}

enum class Severity : uint8_t { Error, Warning };

// One finding of a front end: where, how bad, a stable code and the message. Codes
// are grouped by area (fxc's "X3000" numbers for HLSL) and listed in
// docs/diagnostics.md; tests match on codes, not on message text.
struct Diagnostic {
  SourceLocation where;
  Severity severity = Severity::Error;
  std::string code;     // "X3000"
  std::string message;
  // fxc's form: "file(line,col): error X3000: message".
  std::string fxcStyle() const;
  // refx's form: "file:line:col: error X3000: message".
  std::string str() const;
};

// Collects every diagnostic of a run, so that a user sees all problems at once.
class DiagnosticSink {
 public:
  void report(Diagnostic d) {
    if (d.severity == Severity::Error) ++errors_;
    all_.push_back(std::move(d));
  }
  template <typename... Args>
  void error(const SourceLocation& where, std::string code, fmt::format_string<Args...> f, Args&&... args) {
    report({where, Severity::Error, std::move(code), fmt::format(f, std::forward<Args>(args)...)});
  }
  template <typename... Args>
  void warning(const SourceLocation& where, std::string code, fmt::format_string<Args...> f, Args&&... args) {
    report({where, Severity::Warning, std::move(code), fmt::format(f, std::forward<Args>(args)...)});
  }
  const std::vector<Diagnostic>& all() const { return all_; }
  int errorCount() const { return errors_; }
  bool hasErrors() const { return errors_ > 0; }

 private:
  std::vector<Diagnostic> all_;
  int errors_ = 0;
};

}  // namespace refx
