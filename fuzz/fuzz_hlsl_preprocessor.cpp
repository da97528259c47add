// HLSL preprocessor fuzz target: any bytes give tokens ending with one EndOfFile and
// perhaps diagnostics; never a crash, a hang or a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "hlsl/preprocessor.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  hlsl::detail::PreprocessOptions options;
  options.defines = {{"FUZZ", "1"}, {"F(x)", "((x) + 1)"}};
  DiagnosticSink sink;
  const std::vector<hlsl::detail::Token> tokens = hlsl::detail::preprocess(text, "fuzz.hlsl", options, sink);
  if (tokens.empty() || tokens.back().kind != hlsl::detail::TokenKind::EndOfFile) std::abort();
  for (size_t i = 0; i + 1 < tokens.size(); ++i)
    if (tokens[i].kind == hlsl::detail::TokenKind::EndOfFile) std::abort();
  return 0;
}
