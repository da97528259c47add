// Read ports: ps_1_x and SM2+ pixel shaders (and vs constants) read at most N
// different registers of a file in one instruction (the table's readPorts).
#include <map>
#include <set>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;

class ReadPortCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    std::map<RegType, std::set<unsigned>> used;
    for (int s = 0; s < in.srcCount; ++s) used[in.src[s].type].insert(in.src[s].index);
    for (auto& [t, set] : used) {
      const RegisterRule* r = findRegisterRule(ctx.rules, t);
      if (!r || !r->readPorts || int(set.size()) <= r->readPorts) continue;
      std::string list;
      for (unsigned i : set) list += (list.empty() ? "" : ", ") + ctx.reg(t, i);
      ctx.error(in, "V1110", "{} reads at most {} different {} registers in one instruction, {} reads {} ({})",
                ctx.name, r->readPorts, r->meaning, ctx.op(in), set.size(), list);
    }
  }
};

}  // namespace

std::unique_ptr<Check> makeReadPortCheck() { return std::make_unique<ReadPortCheck>(); }

}  // namespace refx::shader::checks
