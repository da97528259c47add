// Errors are part of the product: every failure names where it happened and what
// was expected, in the `file:line:col: error: message` form of compilers.
#pragma once
#include <stdexcept>
#include <string>

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

}  // namespace refx
