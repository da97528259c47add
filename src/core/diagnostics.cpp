#include "refx/core/diagnostics.h"

namespace refx {

std::string SourceLocation::str() const {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "x" + std::string.
  std::string s = file;
  if (line > 0) {
    if (!s.empty()) s += ':';
    s += std::to_string(line);
    if (column > 0) {
      s += ':';
      s += std::to_string(column);
    }
  }
  return s;
}

namespace {
// "<where>: error X3004: message" with `where` left out when unknown.
std::string located(std::string where, const Diagnostic& d) {
  if (!where.empty()) where += ": ";
  return where + (d.severity == Severity::Error ? "error " : "warning ") + d.code + ": " + d.message;
}
}  // namespace

std::string Diagnostic::fxcStyle() const {
  std::string s = where.file;
  if (where.line > 0) s += where.column > 0 ? fmt::format("({},{})", where.line, where.column) : fmt::format("({})", where.line);
  return located(std::move(s), *this);
}

std::string Diagnostic::str() const { return located(where.str(), *this); }

}  // namespace refx
