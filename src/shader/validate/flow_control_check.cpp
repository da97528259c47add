// Flow control: if / else / endif, rep / endrep and loop / endloop nest properly and
// within the version's depths (vs_2_x / ps_2_x: the device's StaticFlowControlDepth
// and DynamicFlowControlDepth); static flow-control instructions are counted where the
// version limits them; break sits inside a loop; subroutines start with label right
// after a ret, end with ret, are called only if they exist, never recursively and
// nested no deeper than the version allows.
#include <algorithm>
#include <functional>
#include <map>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class FlowControlCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    if (!ctx.rules.flow.labels && !isFlowOp(in.opcode)) return;
    const FlowLimits& F = ctx.rules.flow;
    const bool isX = ctx.v.major == 2 && ctx.v.minor == 1;
    int loopLimit = F.loopDepth, dynLimit = F.dynamicDepth;
    if (isX) {
      loopLimit = std::clamp(ctx.caps.staticFlowControlDepth, 1, 4);
      dynLimit = std::clamp(ctx.caps.dynamicFlowControlDepth, 0, 24);
    }
    std::vector<Block>& blocks = ctx.blocks;
    auto depth = [&](auto pred) { return int(std::count_if(blocks.begin(), blocks.end(), pred)); };
    auto countStatic = [&]() {
      if (F.staticFlowCount && ++staticFlowCount_ == F.staticFlowCount + 1)
        ctx.error(in, "V1703",
                  "{} allows {} static flow-control instructions (if b#, else, rep, loop, call, callnz b#), this shader has more",
                  ctx.name, F.staticFlowCount);
    };
    auto operand = [&](int s) -> const SrcParam* { return s < in.srcCount ? &in.src[s] : nullptr; };
    auto p0Written = [&]() { return ctx.written[registerKey(R::Predicate, 0)] != 0; };
    const Opcode o = in.opcode;

    if (mainEnded_ && o != O::Label && !ctx.inSubroutine)
      ctx.error(in, "V1704", "{} follows the ret that ends the main program; subroutines start with label", ctx.op(in));

    switch (o) {
      case O::If: case O::IfC: {
        bool dynamic = o == O::IfC;
        if (o == O::If) {
          const SrcParam* c = operand(0);
          if (!c || (c->type != R::ConstBool && c->type != R::Predicate))
            ctx.error(in, "V1705", "if takes a b# or p0 operand");
          else if (c->type == R::Predicate) {
            dynamic = true;
            if (!ctx.rules.predication) ctx.error(in, "V1705", "if p0 is not available in {}", ctx.name);
            else if (!p0Written()) ctx.error(in, "V1702", "p0 is read before it is written (setp)");
          }
        }
        if (!dynamic) countStatic();
        blocks.push_back({o, dynamic, false, in.pos});
        if (dynamic) {
          int dd = depth([](const Block& b) { return b.dynamic; });
          if (dd > dynLimit)
            ctx.error(in, "V1706", "{} allows dynamic flow-control nesting depth {}, this {} is at depth {}", ctx.name,
                      dynLimit, ctx.op(in), dd);
        } else {
          int sd = depth([](const Block& b) { return (b.opcode == O::If) && !b.dynamic; });
          if (F.staticIfDepth && sd > F.staticIfDepth)
            ctx.error(in, "V1706", "{} allows if nesting depth {}, this if is at depth {}", ctx.name, F.staticIfDepth,
                      sd);
        }
        break;
      }
      case O::Else:
        if (blocks.empty() || (blocks.back().opcode != O::If && blocks.back().opcode != O::IfC))
          ctx.error(in, "V1707", "else without if");
        else if (blocks.back().hasElse)
          ctx.error(in, "V1707", "if has a second else");
        else {
          blocks.back().hasElse = true;
          if (!blocks.back().dynamic) countStatic();
        }
        break;
      case O::EndIf:
        if (blocks.empty() || (blocks.back().opcode != O::If && blocks.back().opcode != O::IfC))
          ctx.error(in, "V1707", "endif without if{}",
                    blocks.empty() ? "" : fmt::format(" (the open block is {})", blockName(blocks.back().opcode)));
        else blocks.pop_back();
        break;
      case O::Rep: case O::Loop: {
        if (o == O::Rep) {
          const SrcParam* c = operand(0);
          if (!c || c->type != R::ConstInt) ctx.error(in, "V1708", "rep takes an integer constant (rep i#)");
        } else {
          const SrcParam* a = operand(0);
          const SrcParam* c = operand(1);
          if (!a || a->type != R::Loop || !c || c->type != R::ConstInt)
            ctx.error(in, "V1708", "loop takes aL and an integer constant (loop aL, i#)");
        }
        countStatic();
        blocks.push_back({o, false, false, in.pos});
        int ld = depth([](const Block& b) { return b.opcode == O::Rep || b.opcode == O::Loop; });
        if (ld > loopLimit)
          ctx.error(in, "V1706", "{} allows rep/loop nesting depth {}, this {} is at depth {}", ctx.name, loopLimit,
                    ctx.op(in), ld);
        break;
      }
      case O::EndRep: case O::EndLoop: {
        Opcode open = o == O::EndRep ? O::Rep : O::Loop;
        if (blocks.empty() || blocks.back().opcode != open)
          ctx.error(in, "V1707", "{} without {}{}", ctx.op(in), open == O::Rep ? "rep" : "loop",
                    blocks.empty() ? "" : fmt::format(" (the open block is {})", blockName(blocks.back().opcode)));
        else blocks.pop_back();
        break;
      }
      case O::Break: case O::BreakC: case O::BreakP: {
        if (!ctx.inLoop()) ctx.error(in, "V1709", "{} outside a rep or loop block", ctx.op(in));
        if (o == O::BreakP) {
          const SrcParam* p = operand(0);
          if (!p || p->type != R::Predicate) ctx.error(in, "V1705", "breakp takes p0");
          else if (!p0Written()) ctx.error(in, "V1702", "p0 is read before it is written (setp)");
        }
        break;
      }
      case O::Call: case O::CallNZ: {
        const SrcParam* l = operand(0);
        if (!l || l->type != R::Label) {
          ctx.error(in, "V1710", "{} takes a label (l#)", ctx.op(in));
          break;
        }
        if (o == O::Call) countStatic();
        if (o == O::CallNZ) {
          const SrcParam* c = operand(1);
          if (!c || (c->type != R::ConstBool && c->type != R::Predicate))
            ctx.error(in, "V1705", "callnz takes a b# or p0 condition");
          else if (c->type == R::ConstBool) countStatic();
          else if (!p0Written()) ctx.error(in, "V1702", "p0 is read before it is written (setp)");
        }
        calls_.push_back({ctx.inSubroutine ? currentLabel_ : -1, {int(l->index), in.pos}});
        // What the subroutines write counts as written after a call.
        for (auto& [k, m] : ctx.subWritten) ctx.written[k] |= m;
        break;
      }
      case O::Ret:
        if (!blocks.empty()) ctx.error(in, "V1711", "ret inside an open {} block", blockName(blocks.back().opcode));
        if (ctx.inSubroutine) ctx.inSubroutine = false;
        else mainEnded_ = true;
        break;
      case O::Label: {
        const SrcParam* l = operand(0);
        if (!l || l->type != R::Label) {
          ctx.error(in, "V1710", "label takes l#");
          break;
        }
        if (ctx.previous != O::Ret) ctx.error(in, "V1711", "label l{} must directly follow a ret", l->index);
        if (!blocks.empty()) ctx.error(in, "V1711", "label inside an open block");
        if (!labels_.emplace(int(l->index), in.pos).second)
          ctx.error(in, "V1712", "label l{} is defined twice", l->index);
        ctx.inSubroutine = true;
        mainEnded_ = true;
        currentLabel_ = int(l->index);
        break;
      }
      default:
        break;
    }
  }

  void finish(Context& ctx) override {
    for (const Block& b : ctx.blocks)
      ctx.errorAt(b.pos, "V1707", "{} is never closed with {}", blockName(b.opcode),
                  b.opcode == O::Rep ? "endrep" : b.opcode == O::Loop ? "endloop" : "endif");
    for (auto& [caller, callee] : calls_)
      if (!labels_.count(callee.first))
        ctx.errorAt(callee.second, "V1712", "call to l{}: the shader has no label l{}", callee.first, callee.first);
    if (ctx.inSubroutine) ctx.errorAt(ctx.end, "V1711", "subroutine l{} does not end with ret", currentLabel_);

    // Call nesting: main's calls are depth 1.
    if (calls_.empty()) return;
    std::map<int, std::vector<int>> graph;
    for (auto& [caller, callee] : calls_) graph[caller].push_back(callee.first);
    int limit = ctx.rules.flow.callDepth;
    if (ctx.v.major == 2 && ctx.v.minor == 1) limit = std::clamp(ctx.caps.staticFlowControlDepth, 1, 4);
    std::map<int, int> depthOf;  // -1 while being computed (recursion)
    bool recursive = false;
    std::function<int(int)> depthFrom = [&](int node) -> int {
      auto it = depthOf.find(node);
      if (it != depthOf.end()) {
        if (it->second < 0) recursive = true;
        return std::max(it->second, 0);
      }
      depthOf[node] = -1;
      int d = 0;
      for (int next : graph[node]) d = std::max(d, 1 + depthFrom(next));
      depthOf[node] = d;
      return d;
    };
    int worst = depthFrom(-1);
    if (recursive) ctx.errorAt(ctx.end, "V1713", "subroutines call themselves (recursion is not allowed)");
    else if (worst > limit)
      ctx.errorAt(ctx.end, "V1706", "{} allows call nesting depth {}, this shader nests calls {} deep", ctx.name,
                  limit, worst);
  }

 private:
  int staticFlowCount_ = 0;
  bool mainEnded_ = false;
  int currentLabel_ = -1;
  std::map<int, SourcePos> labels_;
  std::vector<std::pair<int, std::pair<int, SourcePos>>> calls_;  // (caller label or -1, (callee, pos))
};

}  // namespace

std::unique_ptr<Check> makeFlowControlCheck() { return std::make_unique<FlowControlCheck>(); }

}  // namespace refx::shader::checks
