// Per-shader instruction counts of their own (ps_1_2 – ps_1_3: cmp at most 3, dp4 at
// most 4; ps_1_4: bem once).
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

class PerShaderCountCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    const OpcodeRule* rule = ctx.rule;
    if (!rule || !rule->maxPerShader) return;
    int n = ++count_[uint32_t(in.opcode)];
    if (n == rule->maxPerShader + 1)
      ctx.error(in, "V1903", "{} allows {} {} instruction{} per shader, this shader has more", ctx.name,
                rule->maxPerShader, ctx.op(in), rule->maxPerShader == 1 ? "" : "s");
  }

 private:
  std::unordered_map<uint32_t, int> count_;
};

}  // namespace

std::unique_ptr<Check> makePerShaderCountCheck() { return std::make_unique<PerShaderCountCheck>(); }

}  // namespace refx::shader::checks
