// The validator's driver: one walk over the instructions that hands each one to the
// checks of the shader's version (src/shader/validate/), in the order of the table
// below, then lets each check report what only the whole shader shows.
#include "refx/shader/validator.h"

#include <algorithm>
#include <memory>

#include <fmt/format.h>

#include "refx/shader/version_rules.h"
#include "shader/validate/check.h"

namespace refx::shader {
namespace {

using checks::Check;
using checks::Context;

// Version groups a check applies to.
enum VersionGroup : uint8_t {
  kVs1 = 1,    // vs_1_1
  kVs2 = 2,    // vs_2_0, vs_2_x
  kVs3 = 4,    // vs_3_0
  kPs11 = 8,   // ps_1_1 – ps_1_3
  kPs14 = 16,  // ps_1_4
  kPs2 = 32,   // ps_2_0, ps_2_x
  kPs3 = 64,   // ps_3_0
};
constexpr uint8_t kAllVersions = 0x7F;
constexpr uint8_t kSm2Up = kVs2 | kVs3 | kPs2 | kPs3;

struct CheckEntry {
  const char* name;
  std::unique_ptr<Check> (*make)();
  uint8_t versions;   // VersionGroup bits
  int finishOrder;    // order of the end-of-shader reports (0: none)
};

// The checks, in the order they see each instruction. An instruction's violations are
// reported in this order; the whole-shader ones by finishOrder (slot totals first,
// flow control last).
const CheckEntry kChecks[] = {
    {"co-issue", checks::makeCoissueCheck, kAllVersions, 0},
    {"predication", checks::makePredicationCheck, kAllVersions, 0},
    {"instruction order", checks::makeInstructionOrderCheck, kAllVersions, 0},
    {"def", checks::makeDefCheck, kAllVersions, 0},
    {"dcl", checks::makeDclCheck, kVs1 | kSm2Up, 0},
    {"ps_1_4 phases", checks::makePhaseCheck, kPs14, 0},
    {"registers", checks::makeRegisterCheck, kAllVersions, 0},
    {"modifiers", checks::makeModifierCheck, kAllVersions, 0},
    {"read ports", checks::makeReadPortCheck, kAllVersions, 0},
    {"texture sequences", checks::makeTextureSequenceCheck, kPs11, 2},
    {"ps_1_4 texture instructions", checks::makePs14TextureCheck, kPs14, 0},
    {"instruction forms", checks::makeInstructionFormCheck, kVs1 | kSm2Up, 0},
    {"ps_1_1 – ps_1_3 instruction forms", checks::makePs11FormCheck, kPs11, 0},
    {"sampling", checks::makeSamplingCheck, kSm2Up, 0},
    {"declared inputs", checks::makeDeclaredInputCheck, kVs1 | kSm2Up, 0},
    {"flow control", checks::makeFlowControlCheck, kSm2Up, 4},
    {"initialised reads", checks::makeInitialisedReadCheck, kAllVersions, 0},
    {"outputs", checks::makeOutputCheck, kAllVersions, 3},
    {"per-shader counts", checks::makePerShaderCountCheck, kAllVersions, 0},
    {"slots", checks::makeSlotCheck, kAllVersions, 1},
};

uint8_t versionGroup(Version v) {
  if (v.isVertex()) return v.major >= 3 ? kVs3 : v.major == 2 ? kVs2 : kVs1;
  if (v.major == 1) return v.minor >= 4 ? kPs14 : kPs11;
  return v.major >= 3 ? kPs3 : kPs2;
}

void run(const Shader& shader, const VersionRules& rules, const ValidationCaps& caps, DiagnosticSink& sink,
         std::string_view fileName) {
  Context ctx(shader, rules, caps, sink, std::string(fileName));
  const uint8_t group = versionGroup(rules.version);
  std::vector<std::pair<const CheckEntry*, std::unique_ptr<Check>>> checks;
  for (const CheckEntry& e : kChecks)
    if (e.versions & group) checks.emplace_back(&e, e.make());

  checks::OpcodeCheck opcodes;
  for (const Instruction& in : shader.instructions) {
    if (in.opcode == Opcode::Comment) continue;
    if (!opcodes.accept(ctx, in)) {
      ctx.previous = Opcode::Nop;
      continue;
    }
    for (auto& [entry, check] : checks) check->instruction(ctx, in);
    ctx.previous = in.opcode;
  }

  std::vector<std::pair<const CheckEntry*, Check*>> finishing;
  for (auto& [entry, check] : checks)
    if (entry->finishOrder) finishing.emplace_back(entry, check.get());
  std::stable_sort(finishing.begin(), finishing.end(),
                   [](const auto& a, const auto& b) { return a.first->finishOrder < b.first->finishOrder; });
  for (auto& [entry, check] : finishing) check->finish(ctx);
}

}  // namespace

SlotCount countSlots(const Shader& shader) {
  SlotCount sc;
  const VersionRules* rules = findVersionRules(shader.version);
  auto samplers = checks::samplerTypes(shader);
  for (const Instruction& in : shader.instructions) {
    if (checks::isFreeOp(in.opcode)) continue;
    if (!rules) {
      ++sc.arithmetic;
      continue;
    }
    checks::Cost c = checks::instructionCost(*rules, in, samplers);
    sc.texture += c.texture;
    sc.arithmetic += c.arithmetic;
    sc.flowControl += c.flow;
  }
  return sc;
}

void validate(const Shader& shader, DiagnosticSink& sink, std::string_view fileName, const ValidationCaps& caps) {
  const VersionRules* rules = findVersionRules(shader.version);
  if (!rules) {
    sink.error(SourceLocation{std::string(fileName)}, "V1000", "{} is not a supported shader version",
               checks::versionName(shader.version));
    return;
  }
  run(shader, *rules, caps, sink, fileName);
}

std::vector<Diagnostic> validate(const Shader& shader, const ValidationCaps& caps) {
  DiagnosticSink sink;
  validate(shader, sink, "", caps);
  return sink.all();
}

std::string describeViolations(std::string_view prefix, const std::vector<Diagnostic>& violations) {
  std::string out;
  for (const Diagnostic& d : violations) {
    if (!out.empty()) out += '\n';
    out += fmt::format("{}: {}: {}", prefix, d.code, d.message);
  }
  return out;
}

std::string checkDeviceVersion(Version shader, uint32_t deviceVersion, std::string_view deviceName) {
  const bool vs = shader.isVertex();
  const char* field = vs ? "VertexShaderVersion" : "PixelShaderVersion";
  int devMajor = (deviceVersion >> 8) & 0xFF, devMinor = deviceVersion & 0xFF;
  std::string has = (devMajor == 0 && devMinor == 0) ? "none" : fmt::format("{}.{}", devMajor, devMinor);
  // 2_x is minor 1; vs_1_0/ps_1_0 run wherever 1_1 does.
  int major = shader.major, minor = shader.minor == 0xFF ? 0 : shader.minor;
  if (major == 1 && minor == 0) minor = 1;
  bool covered = devMajor > major || (devMajor == major && devMinor >= minor);
  if (covered) return {};
  std::string need = (major == 2 && minor == 1) ? std::string("above 2.0") : fmt::format("{}.{}", major, minor);
  return fmt::format("{} needs {} {}, {} has {}", checks::versionName(shader), field, need, deviceName, has);
}

void requireValid(const Shader& shader, std::string_view fileName, const ValidationCaps& caps) {
  DiagnosticSink sink;
  validate(shader, sink, fileName, caps);
  if (!sink.hasErrors()) return;
  std::string lines;
  for (const Diagnostic& d : sink.all()) {
    if (!lines.empty()) lines += '\n';
    lines += d.str();
  }
  throw Error(lines);
}

}  // namespace refx::shader
