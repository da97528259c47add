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

std::string Diagnostic::fxcStyle() const {
  std::string s = where.file;
  if (where.line > 0) s += where.column > 0 ? fmt::format("({},{})", where.line, where.column) : fmt::format("({})", where.line);
  if (!s.empty()) s += ": ";
  s += severity == Severity::Error ? "error " : "warning ";
  s += code;
  s += ": ";
  s += message;
  return s;
}

std::string Diagnostic::str() const {
  std::string s = where.str();
  if (!s.empty()) s += ": ";
  s += severity == Severity::Error ? "error " : "warning ";
  s += code;
  s += ": ";
  s += message;
  return s;
}

}  // namespace refx
