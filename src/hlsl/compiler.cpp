#include "refx/hlsl/compiler.h"

#include <fstream>
#include <sstream>

namespace refx::hlsl {

std::string CompileResult::messages() const {
  std::string s;
  for (const Diagnostic& d : diagnostics) s += d.fxcStyle() + "\n";
  return s;
}

CompileResult compile(std::string_view source, std::string_view fileName, const CompileOptions& options) {
  CompileResult result;
  result.diagnostics.push_back({{std::string(fileName), 1, 1}, Severity::Error, "X3501", "the HLSL compiler is not built yet"});
  return result;
}

CompileResult compileFile(const std::string& path, const CompileOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    CompileResult result;
    result.diagnostics.push_back({{path, 0, 0}, Severity::Error, "X1507", "failed to open source file: " + path});
    return result;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return compile(ss.str(), path, options);
}

}  // namespace refx::hlsl
