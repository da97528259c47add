// `refx fxc /T PROFILE [/E ENTRY] [/Fo OUT] [/Fc LISTING] [/Fh HEADER] [/D NAME=VAL]
// [/I DIR] [/Zpr|/Zpc] [/Gec] [/Od] [/Vn NAME] FILE`: HLSL → shader bytecode with
// fxc's command line (flags also as -T …, and /Tps_2_0 attached). Diagnostics are
// printed as fxc prints them; exit 1 on compile errors, 2 on usage errors.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "commands.h"
#include "refx/effect/effect.h"
#include "refx/effect/fx2_binary.h"
#include "refx/hlsl/compiler.h"
#include "refx/shader/disassembler.h"

namespace refx::cli {

namespace {

const char* kUsage =
    "usage: refx fxc /T <profile> [/E <entry>] [/Fo <file>] [/Fc <file>] [/Fh <file>] [/Vn <name>]\n"
    "                [/D <name>[=<value>]] [/I <dir>] [/Zpr | /Zpc] [/Gec] [/Od] [/nologo] <file>\n"
    "  /T <profile>  vs_1_1 vs_2_0 vs_2_x vs_3_0 ps_1_1 ps_1_2 ps_1_3 ps_1_4 ps_2_0 ps_2_x ps_3_0,\n"
    "                or fx_2_0: an effect file (.fx) to an fx_2_0 binary (.fxo); /Fc lists it\n"
    "  /E <entry>    entry point (default main)\n"
    "  /Fo <file>    write the shader bytecode\n"
    "  /Fc <file>    write the assembly listing\n"
    "  /Fh <file>    write a C header with the bytecode as a DWORD array\n"
    "  /Vn <name>    array name in the header (default g_<entry>)\n"
    "  /D name=val   define a macro;  /I <dir>  add an include directory\n"
    "  /Zpr /Zpc     matrices row_major / column_major by default\n"
    "  /Gec          accept the pre-release dialect of the DirectX 9 white paper\n"
    "  /Od           disable optimisations\n"
    "Flags may also be written -T, -E, … and with the value attached (/Tps_2_0).\n";

struct FxcArgs {
  hlsl::CompileOptions options;
  std::string input, objectFile, listingFile, headerFile, variableName;
  bool help = false;
};

int usageError(const std::string& message) {
  std::fprintf(stderr, "refx fxc: error: %s\n%s", message.c_str(), kUsage);
  return 2;
}

// Returns an empty string on success, or the usage error.
std::string parseArgs(const std::vector<std::string>& args, FxcArgs& out) {
  static const char* withValue[] = {"Fo", "Fc", "Fh", "Vn", "T", "E", "D", "I"};
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    // An absolute path (a second '/') is a file, not an fxc-style flag.
    bool path = a[0] == '/' && a.find('/', 1) != std::string::npos;
    if (a.size() < 2 || path || (a[0] != '/' && a[0] != '-')) {
      if (!out.input.empty()) return "more than one input file: '" + out.input + "' and '" + a + "'";
      out.input = a;
      continue;
    }
    std::string flag = a.substr(1);
    if (flag == "?" || flag == "help" || flag == "-help") { out.help = true; continue; }
    if (flag == "Zpr") { out.options.rowMajorDefault = true; continue; }
    if (flag == "Zpc") { out.options.rowMajorDefault = false; continue; }
    if (flag == "Gec") { out.options.compatibility = true; continue; }
    if (flag == "Od") { out.options.optimize = false; continue; }
    if (flag == "nologo" || flag == "Zi" || flag == "O1" || flag == "O2" || flag == "O3" || flag == "Gfp" || flag == "Gpp") continue;
    std::string name, value;
    for (const char* f : withValue) {
      std::string fs = f;
      if (flag.compare(0, fs.size(), fs) != 0) continue;
      // longest match first: "Fo" before "F"
      name = fs;
      value = flag.substr(fs.size());
      break;
    }
    if (name.empty()) return "unknown option '" + a + "'";
    if (value.empty()) {
      if (i + 1 >= args.size()) return "option '" + a + "' needs a value";
      value = args[++i];
    }
    if (name == "T") out.options.profile = value;
    else if (name == "E") out.options.entry = value;
    else if (name == "Fo") out.objectFile = value;
    else if (name == "Fc") out.listingFile = value;
    else if (name == "Fh") out.headerFile = value;
    else if (name == "Vn") out.variableName = value;
    else if (name == "I") out.options.includeDirs.push_back(value);
    else if (name == "D") {
      auto eq = value.find('=');
      out.options.defines.push_back({value.substr(0, eq), eq == std::string::npos ? "1" : value.substr(eq + 1)});
    }
  }
  return {};
}

bool writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), std::streamsize(bytes.size()));
  return bool(f);
}

// /T fx_2_0: the effect file, loaded as the effect framework loads it, written as an
// fx_2_0 binary.
int runEffectFxc(const FxcArgs& a) {
  effect::EffectOptions eo;
  eo.includeDirs = a.options.includeDirs;
  for (const hlsl::MacroDefinition& d : a.options.defines) eo.defines.emplace_back(d.name, d.value);
  effect::Fx2Binary bin;
  try {
    std::unique_ptr<effect::Effect> fx = effect::Effect::fromFile(a.input, eo);
    for (const effect::EffectDiagnostic& d : fx->diagnostics()) std::fprintf(stderr, "%s\n", d.str().c_str());
    bin = effect::writeFx2(*fx);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\ncompilation failed; no code produced\n", e.what());
    return 1;
  }
  const std::string bytes(bin.bytes.begin(), bin.bytes.end());
  if (!a.objectFile.empty() && !writeFile(a.objectFile, bytes)) {
    std::fprintf(stderr, "refx fxc: error: cannot write '%s'\n", a.objectFile.c_str());
    return 1;
  }
  if (!a.listingFile.empty() && !writeFile(a.listingFile, bin.listing)) {
    std::fprintf(stderr, "refx fxc: error: cannot write '%s'\n", a.listingFile.c_str());
    return 1;
  }
  if (!a.headerFile.empty()) {
    const std::string name = a.variableName.empty() ? "g_effect" : a.variableName;
    std::string h = "#if 0\n" + bin.listing + "#endif\n\nconst unsigned int " + name + "[] =\n{\n";
    const size_t words = bin.bytes.size() / 4;
    for (size_t i = 0; i < words; ++i) {
      uint32_t w = 0;
      for (size_t k = 0; k < 4; ++k) w |= uint32_t(bin.bytes[4 * i + k]) << (8 * k);
      h += fmt::format("{}0x{:08x}{}", i % 6 == 0 ? "    " : "", w, i + 1 == words ? "\n" : (i % 6 == 5 ? ",\n" : ", "));
    }
    h += "};\n";
    if (!writeFile(a.headerFile, h)) {
      std::fprintf(stderr, "refx fxc: error: cannot write '%s'\n", a.headerFile.c_str());
      return 1;
    }
  }
  if (a.objectFile.empty() && a.listingFile.empty() && a.headerFile.empty()) std::fputs(bin.listing.c_str(), stdout);
  std::fprintf(stderr, "compilation succeeded: fx_2_0 effect, %zu bytes\n", bin.bytes.size());
  return 0;
}

int runFxc(const std::vector<std::string>& raw) {
  FxcArgs a;
  a.options.profile.clear();
  if (std::string err = parseArgs(raw, a); !err.empty()) return usageError(err);
  if (a.help) { std::fputs(kUsage, stdout); return 0; }
  if (a.options.profile.empty()) return usageError("no target profile: give /T <profile>");
  if (a.input.empty()) return usageError("no input file");
  {
    std::ifstream probe(a.input);
    if (!probe) return usageError("cannot open input file '" + a.input + "'");
  }
  if (a.options.profile == "fx_2_0") return runEffectFxc(a);
  hlsl::CompileResult r = hlsl::compileFile(a.input, a.options);
  std::fputs(r.messages().c_str(), stderr);
  if (!r.ok()) {
    std::fprintf(stderr, "compilation failed; no code produced\n");
    return 1;
  }
  std::string bytes;
  for (uint32_t t : r.tokens)
    for (int i = 0; i < 4; ++i) bytes.push_back(char(t >> (8 * i)));
  if (!a.objectFile.empty() && !writeFile(a.objectFile, bytes)) {
    std::fprintf(stderr, "refx fxc: error: cannot write '%s'\n", a.objectFile.c_str());
    return 1;
  }
  shader::DisassemblyOptions dopt;
  dopt.listing = true;
  std::string listing = shader::disassemble(r.tokens, dopt);
  if (!a.listingFile.empty() && !writeFile(a.listingFile, listing)) {
    std::fprintf(stderr, "refx fxc: error: cannot write '%s'\n", a.listingFile.c_str());
    return 1;
  }
  if (!a.headerFile.empty()) {
    std::string name = a.variableName.empty() ? "g_" + a.options.entry : a.variableName;
    std::string h = "#if 0\n" + listing + "#endif\n\nconst unsigned int " + name + "[] =\n{\n";
    for (size_t i = 0; i < r.tokens.size(); ++i)
      h += fmt::format("{}0x{:08x}{}", i % 6 == 0 ? "    " : "", r.tokens[i],
                       i + 1 == r.tokens.size() ? "\n" : (i % 6 == 5 ? ",\n" : ", "));
    h += "};\n";
    if (!writeFile(a.headerFile, h)) {
      std::fprintf(stderr, "refx fxc: error: cannot write '%s'\n", a.headerFile.c_str());
      return 1;
    }
  }
  if (a.objectFile.empty() && a.listingFile.empty() && a.headerFile.empty()) std::fputs(listing.c_str(), stdout);
  std::fprintf(stderr, "compilation succeeded: %d instruction slots\n", r.instructionSlots);
  return 0;
}

}  // namespace

Action addFxcCommand(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("fxc", "Compile HLSL to shader bytecode (fxc's command line: refx fxc /? for help)");
  sub->prefix_command();
  sub->set_help_flag();  // /? and -help are ours
  return [sub] { return runFxc(sub->remaining()); };
}

}  // namespace refx::cli
