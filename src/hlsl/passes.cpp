// IR optimisation passes. Each is one small function over the instruction list.
// Registers that Assign writes (variables of flow-control regions) have no single
// definition: no pass reads through them, copies them or moves them.
#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <vector>

#include "hlsl/ir.h"

namespace refx::hlsl::detail {

namespace {

// The instruction defining each register; -1 for variables (written by Assign).
std::vector<int> definitionIndex(const IrProgram& ir) {
  std::vector<int> def(ir.regWidth.size(), -1);
  for (size_t i = 0; i < ir.code.size(); ++i)
    if (ir.code[i].dst >= 0 && ir.code[i].op != IrOp::Assign) def[ir.code[i].dst] = int(i);
  for (const IrInst& in : ir.code)
    if (in.op == IrOp::Assign) def[in.dst] = -1;
  return def;
}

template <typename F>
void forEachUse(IrProgram& ir, F&& f) {
  for (IrInst& in : ir.code) {
    for (int s = 0; s < in.srcCount; ++s) f(in.src[s].reg);
    for (IrPart& p : in.parts)
      if (p.reg >= 0) f(p.reg);
  }
  for (IrOutput& o : ir.outputs)
    for (IrPart& p : o.parts)
      if (p.reg >= 0) f(p.reg);
}

}  // namespace

float evaluateComponent(IrOp op, float a, float b, float c) {
  switch (op) {
    case IrOp::Mov: return a;
    case IrOp::Add: return a + b;
    case IrOp::Mul: return a * b;
    case IrOp::Mad: return a * b + c;
    case IrOp::Min: return a < b ? a : b;
    case IrOp::Max: return a >= b ? a : b;
    case IrOp::Slt: return a < b ? 1.0f : 0.0f;
    case IrOp::Sge: return a >= b ? 1.0f : 0.0f;
    case IrOp::Cmp: return a >= 0 ? b : c;
    case IrOp::Lrp: return a * b + (1 - a) * c;
    case IrOp::Frc: return a - std::floor(a);
    case IrOp::Abs: return std::fabs(a);
    case IrOp::Rcp: return 1.0f / a;
    case IrOp::Rsq: return 1.0f / std::sqrt(std::fabs(a));
    case IrOp::Exp2: return std::exp2(a);
    case IrOp::Log2: return std::log2(std::fabs(a));
    case IrOp::Pow: return std::pow(std::fabs(a), b);
    default: return 0;
  }
}

// Instructions whose sources are all literals become literals. (The builder folds as it
// goes; this catches what copy propagation exposes.)
void foldConstants(IrProgram& ir) {
  std::vector<int> def = definitionIndex(ir);
  auto literalOf = [&](const IrSrc& s, int comp, float& out) {
    if (s.reg < 0 || def[s.reg] < 0) return false;
    const IrInst& d = ir.code[def[s.reg]];
    if (d.op != IrOp::Constant) return false;
    float v = d.literal[s.swizzle[comp]];
    if (s.absolute) v = std::fabs(v);
    if (s.negate) v = -v;
    out = v;
    return true;
  };
  for (IrInst& in : ir.code) {
    if (in.op != IrOp::Mov || in.saturate) continue;
    std::array<float, 4> v{};
    bool all = true;
    for (int c = 0; c < in.width && all; ++c) all = literalOf(in.src[0], c, v[c]);
    if (!all) continue;
    in.op = IrOp::Constant;
    in.literal = v;
    in.srcCount = 0;
  }
}

// Uses of a plain `mov` read its source directly (swizzles and negation composed).
// A saturating mov of a value nothing else reads moves its _sat onto the producer.
void propagateCopies(IrProgram& ir) {
  std::vector<int> def = definitionIndex(ir);
  const std::vector<bool> variable = ir.assignedRegisters();
  std::vector<int> uses(ir.regWidth.size(), 0);
  forEachUse(ir, [&](int& r) { ++uses[r]; });
  auto satCapable = [](IrOp op) {
    switch (op) {
      case IrOp::Input: case IrOp::Uniform: case IrOp::UniformRel: case IrOp::Constant: case IrOp::Combine:
      case IrOp::Kill:
      case IrOp::Tex: case IrOp::TexProj: case IrOp::TexBias: case IrOp::TexLod: case IrOp::TexGrad:
      case IrOp::SinCos: case IrOp::Frc:
        return false;
      default: return true;
    }
  };
  for (IrInst& in : ir.code) {
    if (in.op != IrOp::Mov || !in.saturate) continue;
    const IrSrc& s = in.src[0];
    if (s.negate || s.absolute || def[s.reg] < 0 || uses[s.reg] != 1) continue;
    IrInst& producer = ir.code[def[s.reg]];
    if (!satCapable(producer.op) || producer.saturate || producer.width != in.width) continue;
    bool identity = true;
    for (int c = 0; c < in.width; ++c) identity &= s.swizzle[c] == c;
    if (!identity) continue;
    producer.saturate = true;
    in.saturate = false;  // now a plain copy, removed below
  }
  std::vector<const IrInst*> copyOf(ir.regWidth.size(), nullptr);
  // A copy of a variable keeps the value it had there: it is not a copy to look through.
  for (const IrInst& in : ir.code)
    if (in.op == IrOp::Mov && !in.saturate && in.dst >= 0 && !variable[in.src[0].reg]) copyOf[in.dst] = &in;
  // Resolve chains: each use is rewritten to read the root source.
  auto resolveSrc = [&](IrSrc& s) {
    for (int guard = 0; guard < 64 && s.reg >= 0 && copyOf[s.reg]; ++guard) {
      const IrSrc& inner = copyOf[s.reg]->src[0];
      IrSrc composed = inner;
      for (int c = 0; c < 4; ++c) composed.swizzle[c] = inner.swizzle[s.swizzle[c]];
      if (s.absolute) { composed.absolute = true; composed.negate = s.negate; }
      else composed.negate = inner.negate != s.negate;
      if (inner.absolute && !s.absolute) composed.negate = s.negate != inner.negate;
      s = composed;
    }
  };
  auto resolvePart = [&](IrPart& p) {
    for (int guard = 0; guard < 64 && p.reg >= 0 && copyOf[p.reg]; ++guard) {
      const IrSrc& inner = copyOf[p.reg]->src[0];
      if (inner.negate || inner.absolute) return;
      p.component = inner.swizzle[p.component];
      p.reg = inner.reg;
    }
  };
  for (IrInst& in : ir.code) {
    for (int s = 0; s < in.srcCount; ++s) resolveSrc(in.src[s]);
    for (IrPart& p : in.parts) resolvePart(p);
  }
  for (IrOutput& o : ir.outputs)
    for (IrPart& p : o.parts) resolvePart(p);
}

// An instruction that computes what an earlier one computed (the same operation on the
// same sources, as copy propagation exposes them) is dropped for the earlier result.
void mergeDuplicates(IrProgram& ir) {
  std::vector<int> replacement(ir.regWidth.size(), -1);
  auto resolve = [&](int& r) {
    if (r >= 0 && replacement[size_t(r)] >= 0) r = replacement[size_t(r)];
  };
  // A value defined in a flow-control region is known only inside it: one table of
  // values per open region, searched from the innermost out.
  std::vector<std::map<std::vector<int>, int>> scopes(1);
  std::vector<bool> variable(ir.regWidth.size(), false);
  for (const IrInst& in : ir.code)
    if (in.op == IrOp::Assign && in.dst >= 0) variable[size_t(in.dst)] = true;
  for (IrInst& in : ir.code) {
    for (int s = 0; s < in.srcCount; ++s) resolve(in.src[s].reg);
    for (IrPart& p : in.parts) resolve(p.reg);
    if (in.op == IrOp::Rep || in.op == IrOp::If) scopes.emplace_back();
    if (in.op == IrOp::Else) scopes.back().clear();
    if ((in.op == IrOp::EndRep || in.op == IrOp::EndIf) && scopes.size() > 1) scopes.pop_back();
    if (in.dst < 0 || in.op == IrOp::Kill || in.op == IrOp::Assign || isFlowMarker(in.op) || variable[size_t(in.dst)])
      continue;
    bool readsVariable = false;
    for (int s = 0; s < in.srcCount; ++s) readsVariable |= in.src[s].reg >= 0 && variable[size_t(in.src[s].reg)];
    for (const IrPart& p : in.parts) readsVariable |= p.reg >= 0 && variable[size_t(p.reg)];
    if (readsVariable) continue;  // its value depends on when it runs
    std::vector<int> key{int(in.op), in.width, int(in.saturate), in.sampler, in.index, in.srcCount};
    for (int s = 0; s < in.srcCount; ++s) {
      const IrSrc& src = in.src[s];
      key.insert(key.end(), {src.reg, src.negate, src.absolute});
      for (int c = 0; c < in.width; ++c) key.push_back(src.swizzle[size_t(c)]);
    }
    for (const IrPart& p : in.parts) key.insert(key.end(), {p.reg, p.component, std::bit_cast<int>(p.literal)});
    if (in.op == IrOp::Constant)
      for (int c = 0; c < in.width; ++c) key.push_back(std::bit_cast<int>(in.literal[size_t(c)]));
    int earlier = -1;
    for (auto scope = scopes.rbegin(); scope != scopes.rend() && earlier < 0; ++scope)
      if (auto it = scope->find(key); it != scope->end()) earlier = it->second;
    if (earlier >= 0) replacement[size_t(in.dst)] = earlier;
    else scopes.back().emplace(std::move(key), in.dst);
  }
  for (IrOutput& o : ir.outputs)
    for (IrPart& p : o.parts) resolve(p.reg);
}

// Component-wise operations written one component at a time (r.x = a.x * b.x;
// r.y = a.y * b.y;) become one instruction writing both: the later one joins the
// earlier when they share the operation, the source registers and their modifiers, read
// nothing the other writes, and the joined swizzles are ones the version can read.
void vectorizeScalars(IrProgram& ir) {
  auto componentWise = [](IrOp op) {
    switch (op) {
      case IrOp::Mov: case IrOp::Add: case IrOp::Mul: case IrOp::Mad: case IrOp::Min: case IrOp::Max:
      case IrOp::Slt: case IrOp::Sge: case IrOp::Cmp: case IrOp::Lrp: case IrOp::Frc: case IrOp::Abs:
        return true;
      default: return false;
    }
  };
  // ps_2_0 and ps_1_x read a register with its components in order or one replicated.
  const bool anySwizzle = ir.version.isVertex() || ir.version.atLeast(2, 1);
  auto legal = [&](const std::array<uint8_t, 4>& swz, int width) {
    if (anySwizzle) return true;
    bool identity = true, replicate = true;
    for (int c = 0; c < width; ++c) {
      identity &= swz[size_t(c)] == c;
      replicate &= swz[size_t(c)] == swz[0];
    }
    return identity || replicate;
  };
  std::vector<bool> variable(ir.regWidth.size(), false);
  for (const IrInst& in : ir.code)
    if (in.op == IrOp::Assign && in.dst >= 0) variable[size_t(in.dst)] = true;
  // Where each register is now: (register, component offset) after joins.
  std::vector<std::pair<int, int>> movedTo(ir.regWidth.size(), {-1, 0});
  auto reads = [](const IrInst& in, int reg) {
    for (int s = 0; s < in.srcCount; ++s)
      if (in.src[s].reg == reg) return true;
    for (const IrPart& p : in.parts)
      if (p.reg == reg) return true;
    return false;
  };
  constexpr size_t kWindow = 16;  // how far back a partner is looked for
  auto moved = [&](int reg) { return reg >= 0 && size_t(reg) < movedTo.size() && movedTo[size_t(reg)].first >= 0; };
  // A wide register can join again: follow the moves to the last one.
  auto follow = [&](int& reg, int& offset) {
    while (moved(reg)) {
      offset += movedTo[size_t(reg)].second;
      reg = movedTo[size_t(reg)].first;
    }
  };
  auto rewrite = [&](IrInst& in) {
    for (int s = 0; s < in.srcCount; ++s) {
      IrSrc& src = in.src[s];
      int offset = 0;
      follow(src.reg, offset);
      // Entries past what the instruction reads stay valid components too.
      for (uint8_t& c : src.swizzle) c = uint8_t(std::min(c + offset, 3));
    }
    for (IrPart& p : in.parts) {
      int offset = 0;
      follow(p.reg, offset);
      p.component = uint8_t(p.component + offset);
    }
  };
  for (size_t j = 0; j < ir.code.size(); ++j) {
    rewrite(ir.code[j]);  // reads of registers joined earlier read the wide register
    IrInst& b = ir.code[j];
    if (b.dst < 0 || !componentWise(b.op) || variable[size_t(b.dst)]) continue;
    for (size_t back = 1; back <= kWindow && back <= j; ++back) {
      const size_t i = j - back;
      IrInst& a = ir.code[i];
      if (isFlowMarker(a.op) || a.op == IrOp::Assign || a.op == IrOp::Kill) break;
      if (a.dst < 0 || a.op != b.op || a.saturate != b.saturate || a.srcCount != b.srcCount) continue;
      if (variable[size_t(a.dst)] || a.width + b.width > 4 || reads(b, a.dst)) continue;
      bool same = true;
      for (int s = 0; s < a.srcCount && same; ++s)
        same = a.src[s].reg == b.src[s].reg && a.src[s].negate == b.src[s].negate &&
               a.src[s].absolute == b.src[s].absolute;
      if (!same) continue;
      std::array<std::array<uint8_t, 4>, 3> joined{};
      bool ok = true;
      for (int s = 0; s < a.srcCount && ok; ++s) {
        for (int c = 0; c < a.width; ++c) joined[size_t(s)][size_t(c)] = a.src[s].swizzle[size_t(c)];
        for (int c = 0; c < b.width; ++c) joined[size_t(s)][size_t(a.width + c)] = b.src[s].swizzle[size_t(c)];
        for (int c = a.width + b.width; c < 4; ++c) joined[size_t(s)][size_t(c)] = joined[size_t(s)][size_t(c - 1)];
        ok = legal(joined[size_t(s)], a.width + b.width);
      }
      // a's result moves to j, so nothing between them may read it.
      for (size_t k = i + 1; k < j && ok; ++k) ok = !reads(ir.code[k], a.dst);
      if (!ok) continue;
      const int wide = ir.newReg(a.width + b.width);
      movedTo.resize(ir.regWidth.size(), {-1, 0});
      variable.resize(ir.regWidth.size(), false);
      movedTo[size_t(a.dst)] = {wide, 0};
      movedTo[size_t(b.dst)] = {wide, a.width};
      IrInst joinedInst = b;
      joinedInst.dst = wide;
      joinedInst.width = a.width + b.width;
      for (int s = 0; s < a.srcCount; ++s) joinedInst.src[s].swizzle = joined[size_t(s)];
      a = IrInst{};  // an empty Mov with no destination: dropped below
      a.dst = -1;
      a.op = IrOp::Mov;
      ir.code[j] = joinedInst;
      break;
    }
  }
  for (IrOutput& o : ir.outputs)
    for (IrPart& p : o.parts) {
      int offset = 0;
      follow(p.reg, offset);
      p.component = uint8_t(p.component + offset);
    }
  std::erase_if(ir.code, [](const IrInst& in) { return in.op == IrOp::Mov && in.dst < 0 && in.srcCount == 0; });
}

// add(mul(a, b), c) → mad(a, b, c) when the product has no other reader.
void fuseMultiplyAdd(IrProgram& ir) {
  std::vector<int> def = definitionIndex(ir);
  const std::vector<bool> variable = ir.assignedRegisters();
  std::vector<int> uses(ir.regWidth.size(), 0);
  forEachUse(ir, [&](int& r) { ++uses[r]; });
  for (IrInst& in : ir.code) {
    if (in.op != IrOp::Add) continue;
    for (int k = 0; k < 2; ++k) {
      const IrSrc& prod = in.src[k];
      if (prod.absolute || def[prod.reg] < 0 || uses[prod.reg] != 1) continue;
      const IrInst& mul = ir.code[def[prod.reg]];
      if (mul.op != IrOp::Mul || mul.saturate) continue;
      if (variable[mul.src[0].reg] || variable[mul.src[1].reg]) continue;  // read where the mul is
      // The add reads the product through a swizzle: compose it into the mul's sources.
      IrSrc a = mul.src[0], b = mul.src[1];
      for (int c = 0; c < 4; ++c) {
        a.swizzle[c] = mul.src[0].swizzle[prod.swizzle[c]];
        b.swizzle[c] = mul.src[1].swizzle[prod.swizzle[c]];
      }
      if (prod.negate) a.negate = !a.negate;
      IrSrc addend = in.src[1 - k];
      in.op = IrOp::Mad;
      in.src[0] = a;
      in.src[1] = b;
      in.src[2] = addend;
      in.srcCount = 3;
      uses[prod.reg] = 0;  // the mul is now dead; removeDeadCode drops it
      break;
    }
  }
}

// Drops instructions whose results nothing reads (outputs, texkill and flow-control
// markers are the roots). A variable that is read keeps every Assign to it.
void removeDeadCode(IrProgram& ir) {
  std::vector<int> def = definitionIndex(ir);
  std::vector<std::vector<int>> assigns(ir.regWidth.size());
  for (size_t i = 0; i < ir.code.size(); ++i)
    if (ir.code[i].op == IrOp::Assign) assigns[ir.code[i].dst].push_back(int(i));
  std::vector<bool> live(ir.regWidth.size(), false);
  std::vector<bool> keep(ir.code.size(), false);
  std::vector<int> work;
  auto mark = [&](int r) {
    if (r >= 0 && !live[r]) { live[r] = true; work.push_back(r); }
  };
  for (const IrOutput& o : ir.outputs)
    for (const IrPart& p : o.parts) mark(p.reg);
  for (size_t i = 0; i < ir.code.size(); ++i)
    if (ir.code[i].op == IrOp::Kill || isFlowMarker(ir.code[i].op)) {
      keep[i] = true;
      for (int s = 0; s < ir.code[i].srcCount; ++s) mark(ir.code[i].src[s].reg);
    }
  while (!work.empty()) {
    int r = work.back();
    work.pop_back();
    for (int a : assigns[r]) {
      keep[a] = true;
      mark(ir.code[a].src[0].reg);
    }
    if (def[r] < 0) continue;
    keep[def[r]] = true;
    const IrInst& in = ir.code[def[r]];
    for (int s = 0; s < in.srcCount; ++s) mark(in.src[s].reg);
    for (const IrPart& p : in.parts) mark(p.reg);
  }
  std::vector<IrInst> out;
  for (size_t i = 0; i < ir.code.size(); ++i)
    if (keep[i]) out.push_back(std::move(ir.code[i]));
  ir.code = std::move(out);
  for (IrUniform& u : ir.uniforms) u.used = false;
  for (const IrInst& in : ir.code)
    if (in.op == IrOp::Uniform || in.op == IrOp::UniformRel) ir.uniforms[in.index & 0xFFFF].used = true;
}

}  // namespace refx::hlsl::detail
