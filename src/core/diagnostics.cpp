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

}  // namespace refx
