// The HLSL preprocessor: C preprocessor rules as fxc applies them.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "hlsl/token.h"
#include "refx/core/diagnostics.h"
#include "refx/hlsl/compiler.h"

namespace refx::hlsl::detail {

struct PreprocessOptions {
  std::vector<MacroDefinition> defines;   // predefined by the caller (/D and the profile macros)
  std::vector<std::string> includeDirs;   // searched after the including file's directory
};

// Source text → tokens ending with one EndOfFile token. Errors and warnings go to
// `sink` with codes (see docs/diagnostics.md); after an error the preprocessor goes
// on with the rest of the file, so every problem is reported.
std::vector<Token> preprocess(std::string_view source, std::string_view fileName, const PreprocessOptions& options,
                              DiagnosticSink& sink);

}  // namespace refx::hlsl::detail
