// `refx validate FILE [--caps PROFILE]`: checks a shader against the rules of its
// version. FILE is assembly text (.vsh/.psh/.asm, or anything that does not start with
// a version token) or binary D3D9 tokens (.vso/.pso). With --caps the device's
// shader version and constant count apply too. Prints "FILE: valid (vs_1_1, N
// instruction slots)" and exits 0, or every diagnostic as "FILE:line:col: error: …"
// and exits 1.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/core/text.h"
#include "refx/effect/effect.h"
#include "refx/pipeline/caps.h"
#include "refx/shader/assembler.h"
#include "refx/shader/validator.h"

namespace refx::cli {

namespace {

struct ValidateOptions {
  std::string input, caps;
};

// Binary token files start with a version token (0xFFFE/0xFFFF in the high word).
bool looksLikeTokens(const std::vector<uint8_t>& bytes) {
  if (bytes.size() < 8 || bytes.size() % 4) return false;
  uint32_t hi = uint32_t(bytes[2]) | uint32_t(bytes[3]) << 8;
  return hi == 0xFFFE || hi == 0xFFFF;
}

void printError(const std::string& file, const Error& e) {
  // Located errors already read "file:line:col: error: …".
  std::string what = e.what();
  if (what.find("error: ") != std::string::npos) std::fprintf(stderr, "%s\n", what.c_str());
  else std::fprintf(stderr, "%s: error: %s\n", file.c_str(), what.c_str());
}

// An effect: every technique against every profile (or --caps), as a table, then the
// reason for each invalid pair. Exit 1 only when the file itself has errors.
int runValidateEffect(const ValidateOptions& o) {
  auto fx = effect::Effect::fromFile(o.input);
  bool hadErrors = false;
  for (const effect::EffectDiagnostic& d : fx->diagnostics()) {
    std::fprintf(stderr, "%s\n", d.str().c_str());
    hadErrors |= d.error;
  }
  std::vector<CapsProfile> profiles;
  if (!o.caps.empty()) profiles.push_back(loadCapsProfile(o.caps));
  else
    for (const std::string& name : capsProfileNames()) profiles.push_back(loadCapsProfile(name));
  size_t nameWidth = 9;
  for (effect::Handle t = 0; t < fx->techniqueCount(); ++t)
    nameWidth = std::max(nameWidth, fx->techniqueDesc(t).name.size());
  // A column is as wide as its profile's name or "valid", whichever is longer; lines
  // end without padding.
  auto columnWidth = [](const CapsProfile& c) { return std::max<size_t>(c.name.size(), 5); };
  auto printRow = [&](const std::string& first, const std::vector<std::string>& cells) {
    std::string line = fmt::format("{:<{}}", first, nameWidth);
    for (size_t i = 0; i < cells.size(); ++i) line += fmt::format("  {:<{}}", cells[i], columnWidth(profiles[i]));
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::printf("%s\n", line.c_str());
  };
  std::vector<std::string> header;
  for (const CapsProfile& c : profiles) header.push_back(c.name);
  printRow("technique", header);
  std::vector<std::string> reasons;
  for (effect::Handle t = 0; t < fx->techniqueCount(); ++t) {
    const std::string& name = fx->techniqueDesc(t).name;
    // A technique with an error in the file fails everywhere for that one reason.
    if (!fx->techniqueDesc(t).brokenReason.empty())
      reasons.push_back(fmt::format("{} on every profile: {}", name, fx->techniqueDesc(t).brokenReason));
    std::vector<std::string> cells;
    for (const CapsProfile& c : profiles) {
      const effect::TechniqueValidation v = fx->validateTechnique(t, c);
      cells.push_back(v.ok ? "valid" : "-");
      if (!v.ok && fx->techniqueDesc(t).brokenReason.empty())
        reasons.push_back(fmt::format("{} on {}: {}", name, c.name, v.reason));
    }
    printRow(name, cells);
  }
  for (const std::string& r : reasons) std::printf("  %s\n", r.c_str());
  return hadErrors ? 1 : 0;
}

int runValidate(const ValidateOptions& o) {
  const std::string ext = toLower(std::filesystem::path(o.input).extension().string());
  if (ext == ".fx" || ext == ".fxh") return runValidateEffect(o);
  std::vector<uint8_t> bytes;
  {
    std::ifstream in(o.input, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "%s: error: cannot open the file for reading\n", o.input.c_str());
      return 1;
    }
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  shader::Shader sh;
  if (looksLikeTokens(bytes)) {
    try {
      sh = shader::decode(shader::tokensFromBytes(bytes));
    } catch (const Error& e) {
      printError(o.input, e);
      return 1;
    }
  } else {
    // Every assembler error of the file, each with its code.
    DiagnosticSink diagnostics;
    sh = shader::assemble(std::string(bytes.begin(), bytes.end()), o.input, diagnostics);
    for (const Diagnostic& d : diagnostics.all()) std::fprintf(stderr, "%s\n", d.str().c_str());
    if (diagnostics.hasErrors()) return 1;
  }

  shader::ValidationCaps vcaps;
  std::vector<std::string> errors;
  if (!o.caps.empty()) {
    CapsProfile caps = loadCapsProfile(o.caps);  // throws refx::Error for unknown profiles
    uint32_t device = sh.version.isVertex() ? caps.vertexShaderVersion : caps.pixelShaderVersion;
    std::string versionError = shader::checkDeviceVersion(sh.version, device, caps.name);
    if (!versionError.empty()) errors.push_back(Error(SourceLocation{o.input}, versionError).what());
    if (sh.version.isVertex() && caps.maxVertexShaderConst > 0)
      vcaps.maxVertexShaderConst = int(caps.maxVertexShaderConst);
  }
  DiagnosticSink violations;
  shader::validate(sh, violations, o.input, vcaps);
  for (const Diagnostic& d : violations.all()) errors.push_back(d.str());

  if (!errors.empty()) {
    for (const std::string& e : errors) std::fprintf(stderr, "%s\n", e.c_str());
    return 1;
  }
  std::printf("%s: valid (%s, %d instruction slots)\n", o.input.c_str(), sh.version.name().c_str(),
              shader::countSlots(sh).total());
  return 0;
}

}  // namespace

Action addValidateCommand(CLI::App& app) {
  auto o = std::make_shared<ValidateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate", "Check a shader (assembly text or .vso/.pso tokens) against its version's rules, or "
                  "an effect's techniques against every caps profile");
  cmd->add_option("file", o->input, "Shader assembly text, binary token file, or effect (.fx)")->required();
  cmd->add_option("--caps", o->caps,
                  "Device caps profile (see `refx caps`): its shader version and constant count apply");
  return [o] { return runValidate(*o); };
}

}  // namespace refx::cli
