// IR → ps_1_1 … ps_1_4, as fxc compiled HLSL for the DirectX 8 pixel shader models:
// texture instructions first (tex/texcoord; ps_1_4: texld/texcrd, with a phase of
// dependent reads when coordinates are computed), then arithmetic that maps onto
// the ps_1_x instructions and their modifiers. The steps, in order:
//   1. refuse what the profile cannot express (rcp, rsq, pow, min/max in ps_1_1 …),
//      naming the construct, the profile and the expression;
//   2. match the ps_1_x modifiers: x - 0.5 → x_bias, 2x - 1 → x_bx2, 1 - x → 1-x,
//      lerp → lrp, products by 2, 4, 8, 1/2 … → instruction shifts (_x2, _d2 …);
//   3. place uniforms in c#, samplers at texture stages, plan the texture
//      instructions and (ps_1_4) the phase of each instruction;
//   4. let results that only feed the color be written straight into it;
//   5. select instructions, reading each value with a selector the version allows
//      (extracting a component with dp3 where ps_1_1 – ps_1_3 cannot select it);
//   6. allocate registers per component (r#, and t# in ps_1_1 – ps_1_3);
//   7. pair an .rgb and an .a instruction into one slot (co-issue);
//   8. write the constant table, def and the instructions.
// Literals must lie in the [-1, 1] range of ps_1_x constants unless a modifier
// absorbs them; uniforms are read as the device clamps them.
#include "hlsl/codegen_ps1x.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <set>

#include "hlsl/constant_table.h"
#include "hlsl/ps1x_program.h"
#include "refx/shader/opcode_table.h"
#include "refx/shader/version_rules.h"

namespace refx::hlsl::detail {

namespace {

using shader::Opcode;
using shader::RegType;
using shader::SrcMod;

using namespace ps1x;

// A value read through a ps_1_x source modifier: x_bias, x_bx2, 1-x, x_x2.
struct Form {
  IrSrc base;
  SrcMod mod = SrcMod::None;
};

// A result written straight into (part of) a gather or the color register.
struct Coalesced {
  int gather = -1;
  uint8_t mask = 0;
  Comps result{kNone, kNone, kNone, kNone};  // logical component written at each physical one
};

class Ps1xCodeGen {
 public:
  Ps1xCodeGen(IrProgram& ir, const std::string& creator, DiagnosticSink& sink, const SourceLocation& entryWhere)
      : ir_(ir), creator_(creator), sink_(sink), entryWhere_(entryWhere), v_(ir.version),
        rules_(*shader::findVersionRules(ir.version)), ps14_(ir.version.atLeast(1, 4)) {
    prog_.rules = &rules_;
    prog_.ps14 = ps14_;
  }

  shader::Shader run() {
    shader::Shader out;
    out.version = v_;
    index();
    refuseWhatDoesNotFit();
    if (sink_.hasErrors()) return out;
    expandWholePowers();
    index();
    mergeRepeatedTextureReads();
    index();
    findModifierForms();
    findLerps();
    foldShiftsIntoProducers();
    index();
    placeUniforms();
    planTextureReads();
    if (sink_.hasErrors()) return out;
    planColorOutput();
    coalesceIntoGathers();
    for (size_t i = 0; i < ir_.code.size(); ++i) select(int(i));
    writeColorOutput();
    if (sink_.hasErrors()) return out;
    orderTextureInstructions();
    prog_.color = color_;
    if (!allocateRegisters(prog_, sink_, entryWhere_)) return out;
    removeNoOpMoves(prog_);
    pairCoissue(prog_);
    emit(out);
    return out;
  }

 private:
  std::string profile() const { return v_.name(); }

  template <typename... Args>
  void refuse(const SourceLocation& where, fmt::format_string<Args...> f, Args&&... args) {
    std::string what = fmt::format(f, std::forward<Args>(args)...);
    if (!reported_.insert({where.line, where.column, what}).second) return;
    sink_.error(where, "X4532", "cannot map expression to {} instruction set: {}", profile(), what);
  }

  // ---- analysis --------------------------------------------------------------------------------
  void index() {
    size_t n = ir_.regWidth.size();
    def_.assign(n, -1);
    uses_.assign(n, 0);
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (in.dst >= 0) def_[in.dst] = int(i);
      std::set<int> seen;
      for (int s = 0; s < in.srcCount; ++s) seen.insert(in.src[s].reg);
      for (const IrPart& p : in.parts)
        if (p.reg >= 0) seen.insert(p.reg);
      for (int r : seen)
        if (r >= 0) ++uses_[r];
    }
    for (const IrOutput& o : ir_.outputs) {
      std::set<int> seen;
      for (const IrPart& p : o.parts)
        if (p.reg >= 0) seen.insert(p.reg);
      for (int r : seen) ++uses_[r];
    }
  }

  const IrInst* producer(int vreg) const { return vreg >= 0 && def_[vreg] >= 0 ? &ir_.code[def_[vreg]] : nullptr; }
  bool isOp(int vreg, IrOp op) const {
    const IrInst* p = producer(vreg);
    return p && p->op == op;
  }

  // The value of `s` when it reads one literal in every component it uses.
  std::optional<float> splatLiteral(const IrSrc& s, int width) const {
    const IrInst* p = producer(s.reg);
    if (!p || p->op != IrOp::Constant || s.absolute) return std::nullopt;
    float v = p->literal[s.swizzle[0]];
    for (int c = 1; c < width; ++c)
      if (p->literal[s.swizzle[c]] != v) return std::nullopt;
    return s.negate ? -v : v;
  }

  // The first ps_1_x version whose table has `op` ("ps_1_2"), for messages.
  std::string firstPs1xWith(Opcode op) const {
    for (const shader::VersionRules* r : shader::allVersionRules())
      if (r->version.ps1x() && shader::findOpcodeRule(*r, op)) return std::string(r->name);
    return "ps_2_0";
  }
  bool has(Opcode op) const { return shader::findOpcodeRule(rules_, op) != nullptr; }

  // ---- 1. what does not fit --------------------------------------------------------------------
  void refuseWhatDoesNotFit() {
    const std::string p = profile();
    for (const IrInst& in : ir_.code) {
      const SourceLocation& at = in.where;
      switch (in.op) {
        case IrOp::Rcp: refuse(at, "division and rcp need a reciprocal (rcp), which {} does not have", p); break;
        case IrOp::Rsq: refuse(at, "sqrt, rsqrt, length and distance need rsq, which {} does not have", p); break;
        case IrOp::Nrm: refuse(at, "normalize needs rsq (a reciprocal square root), which {} does not have", p); break;
        case IrOp::Exp2: refuse(at, "exp and exp2 need exp, which {} does not have", p); break;
        case IrOp::Log2: refuse(at, "log, log2 and log10 need log, which {} does not have", p); break;
        case IrOp::SinCos: refuse(at, "sin and cos need sincos, which {} does not have", p); break;
        case IrOp::Frc: refuse(at, "frac, floor, ceil and fmod need frc, which {} does not have", p); break;
        case IrOp::Crs: refuse(at, "cross needs the swizzles .yzx and .zxy, which {} cannot read", p); break;
        case IrOp::Dsx: case IrOp::Dsy: refuse(at, "ddx and ddy are not in {}", p); break;
        case IrOp::Dp2: refuse(at, "dot of float2 values needs dp2add, which {} does not have", p); break;
        case IrOp::Kill: refuse(at, "clip and discard are not supported for {}", p); break;
        case IrOp::TexProj: case IrOp::TexBias: case IrOp::TexLod: case IrOp::TexGrad:
          refuse(at, "tex*proj, tex*bias, tex*lod and tex*grad need ps_2_0 or later; {} has plain texture reads only", p);
          break;
        case IrOp::Pow:
          if (!wholePower(in)) refuse(at, "pow needs log and exp, which {} does not have (only literal whole exponents 1..16 "
                                       "become multiplications)", p);
          break;
        case IrOp::Dp4:
          if (!has(Opcode::Dp4)) refuse(at, "dot of float4 values needs dp4, which {} does not have ({} or later)", p,
                                       firstPs1xWith(Opcode::Dp4));
          break;
        case IrOp::Min: case IrOp::Max:
          if (!has(Opcode::Cmp)) refuse(at, "min, max and clamp need cmp, which {} does not have ({} or later)", p,
                                       firstPs1xWith(Opcode::Cmp));
          break;
        case IrOp::Slt: case IrOp::Sge: case IrOp::Cmp:
          if (!has(Opcode::Cmp)) refuse(at, "comparisons and ?: need cmp, which {} does not have ({} or later)", p,
                                       firstPs1xWith(Opcode::Cmp));
          break;
        case IrOp::Abs:
          if (!has(Opcode::Cmp)) refuse(at, "abs needs cmp, which {} does not have ({} or later)", p, firstPs1xWith(Opcode::Cmp));
          break;
        default:
          break;
      }
      for (int s = 0; s < in.srcCount; ++s)
        if (in.src[s].absolute && !has(Opcode::Cmp))
          refuse(at, "abs needs cmp, which {} does not have ({} or later)", p, firstPs1xWith(Opcode::Cmp));
    }
    for (const IrOutput& o : ir_.outputs) {
      if (o.usage != shader::DeclUsage::Color) refuse(o.where, "{} has no depth output", p);
      else if (o.usageIndex != 0) refuse(o.where, "{} writes one color (r0), not COLOR{}", p, o.usageIndex);
    }
    for (const IrInput& in : ir_.inputs)
      if (in.usage != shader::DeclUsage::TexCoord && in.usage != shader::DeclUsage::Color)
        sink_.error(entryWhere_, "X4502", "invalid {} input semantic '{}'", p, in.semantic);
  }

  // pow(x, n) with a literal whole n in 1..16 is a chain of multiplications.
  int wholePower(const IrInst& in) const {
    auto n = splatLiteral(in.src[1], 1);
    if (!n || *n < 1 || *n > 16 || *n != std::floor(*n)) return 0;
    return int(*n);
  }

  void expandWholePowers() {
    std::vector<IrInst> code;
    for (IrInst& in : ir_.code) {
      int n = in.op == IrOp::Pow ? wholePower(in) : 0;
      if (!n) {
        code.push_back(std::move(in));
        continue;
      }
      auto mul = [&](const IrSrc& a, const IrSrc& b) {
        IrInst m;
        m.op = IrOp::Mul;
        m.width = 1;
        m.srcCount = 2;
        m.src[0] = a;
        m.src[1] = b;
        m.dst = ir_.newReg(1);
        m.where = in.where;
        code.push_back(m);
        IrSrc r;
        r.reg = m.dst;
        return r;
      };
      IrSrc base = in.src[0], acc;
      size_t first = code.size();
      for (int m = n; m; ) {
        if (m & 1) acc = acc.reg < 0 ? base : mul(acc, base);
        m >>= 1;
        if (m) base = mul(base, base);
      }
      if (code.size() == first) {  // pow(x, 1)
        IrInst mv;
        mv.op = IrOp::Mov;
        mv.width = 1;
        mv.srcCount = 1;
        mv.src[0] = acc;
        mv.dst = in.dst;
        mv.saturate = in.saturate;
        mv.where = in.where;
        code.push_back(mv);
        continue;
      }
      code.back().dst = in.dst;  // the last product is the power
      code.back().saturate = in.saturate;
    }
    ir_.code = std::move(code);
  }

  // The same texture read twice (the builder keeps every call) is one read: ps_1_x has
  // one texture instruction per stage (per phase in ps_1_4).
  void mergeRepeatedTextureReads() {
    std::map<std::tuple<int, int, std::array<uint8_t, 4>, bool, bool, int>, int> first;
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (in.op != IrOp::Tex) continue;
      const IrSrc& c = in.src[0];
      auto [it, fresh] = first.emplace(std::make_tuple(in.sampler, c.reg, c.swizzle, c.negate, c.absolute, in.index), in.dst);
      if (fresh) continue;
      IrSrc same;
      same.reg = it->second;
      replaceUses(in.dst, same);
      skip_.insert(int(i));
    }
  }

  // ---- 2. modifiers ----------------------------------------------------------------------------
  // A value every reader can take through a source modifier instead of computing it.
  void findModifierForms() {
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (in.saturate || in.dst < 0) continue;
      std::optional<Form> f = formOf(in);
      if (!f || !formReadable(in.dst, f->mod)) continue;
      forms_[in.dst] = *f;
      skip_.insert(int(i));
    }
  }

  // A value that may carry a source modifier: computed by the shader or an input,
  // not a constant (modifiers on constants are undefined in ps_1_1 – 1_3 and invalid
  // in ps_1_4), and not already read through one.
  bool modifiable(const IrSrc& x) const {
    const IrInst* p = producer(x.reg);
    return p && p->op != IrOp::Constant && p->op != IrOp::Uniform && !forms_.count(x.reg) && !x.absolute;
  }

  std::optional<Form> formOf(const IrInst& in) const {
    const int w = in.width;
    auto plain = [&](const IrSrc& x) { return modifiable(x) && !x.negate; };
    if (in.op == IrOp::Add) {
      for (int k = 0; k < 2; ++k) {
        const IrSrc& x = in.src[1 - k];
        auto l = splatLiteral(in.src[k], w);
        if (!l || !modifiable(x)) continue;
        if (*l == -0.5f && !x.negate) return Form{x, SrcMod::Bias};  // x - 0.5
        if (*l == 1.0f && x.negate) {                                  // 1 - x
          IrSrc b = x;
          b.negate = false;
          return Form{b, SrcMod::Comp};
        }
      }
    }
    if (in.op == IrOp::Mad) {  // 2x - 1
      auto c = splatLiteral(in.src[2], w);
      for (int k = 0; k < 2 && c && *c == -1.0f; ++k) {
        auto two = splatLiteral(in.src[k], w);
        if (two && *two == 2.0f && plain(in.src[1 - k])) return Form{in.src[1 - k], SrcMod::Sign};
      }
    }
    if (in.op == IrOp::Mul) {
      for (int k = 0; k < 2; ++k) {
        auto two = splatLiteral(in.src[k], w);
        if (!two || *two != 2.0f) continue;
        const IrSrc& y = in.src[1 - k];
        // 2 * (x - 0.5)
        auto f = forms_.find(y.reg);
        if (f != forms_.end() && f->second.mod == SrcMod::Bias && !y.negate && !y.absolute) {
          Form bx2 = f->second;
          bx2.mod = SrcMod::Sign;
          for (int c = 0; c < 4; ++c) bx2.base.swizzle[c] = f->second.base.swizzle[y.swizzle[c]];
          return bx2;
        }
        if (ps14_ && plain(y)) return Form{y, SrcMod::X2};  // ps_1_4's x2 source modifier
      }
    }
    return std::nullopt;
  }

  // Every reader of `vreg` can take the modifier (1-x cannot be negated).
  bool formReadable(int vreg, SrcMod mod) const {
    for (const IrInst& in : ir_.code)
      for (int s = 0; s < in.srcCount; ++s) {
        const IrSrc& x = in.src[s];
        if (x.reg != vreg) continue;
        if (x.absolute || (mod == SrcMod::Comp && x.negate)) return false;
      }
    return true;
  }

  // lerp(a, b, s) is built as mad(s, b - a, a): one lrp.
  void findLerps() {
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (in.op != IrOp::Mad || skip_.count(int(i))) continue;
      const IrSrc& diff = in.src[1];
      const IrInst* add = producer(diff.reg);
      if (!add || add->op != IrOp::Add || add->saturate || uses_[diff.reg] != 1 || forms_.count(diff.reg)) continue;
      if (diff.negate || diff.absolute) continue;
      bool identity = true;
      for (int c = 0; c < in.width; ++c) identity &= diff.swizzle[c] == c;
      if (!identity) continue;
      for (int k = 0; k < 2; ++k) {
        IrSrc a = add->src[k];
        if (!a.negate) continue;
        a.negate = false;
        const IrSrc& addend = in.src[2];
        bool same = a.reg == addend.reg && !addend.negate && a.absolute == addend.absolute;
        for (int c = 0; c < in.width && same; ++c) same = a.swizzle[c] == addend.swizzle[c];
        if (!same) continue;
        lerps_[int(i)] = {in.src[0], add->src[1 - k], addend};
        skip_.insert(def_[diff.reg]);
        break;
      }
    }
  }

  // x * 2^k written by x's own instruction with a shift (_x2, _x4, _x8, _d2 …) when
  // nothing else reads x; the product's readers then read x.
  void foldShiftsIntoProducers() {
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      IrInst& in = ir_.code[i];
      if (in.op != IrOp::Mul || skip_.count(int(i))) continue;
      for (int k = 0; k < 2; ++k) {
        int shift = shiftOf(in.src[k], in.width);
        const IrSrc& x = in.src[1 - k];
        if (!shift || x.negate || x.absolute || uses_[x.reg] != 1) continue;
        IrInst* p = def_[x.reg] >= 0 ? &ir_.code[def_[x.reg]] : nullptr;
        if (!p || p->saturate || skip_.count(def_[x.reg]) || !takesShift(p->op)) continue;
        int total = shift_[x.reg] + shift;
        if (total < rules_.minShift || total > rules_.maxShift) continue;
        shift_[x.reg] = total;
        p->saturate = in.saturate;
        replaceUses(in.dst, x);
        skip_.insert(int(i));
        uses_[x.reg] = uses_[in.dst];
        break;
      }
    }
  }

  // A literal power of two the instruction shifts can express: 2 → 1, 0.5 → -1 …
  int shiftOf(const IrSrc& s, int width) const {
    auto l = splatLiteral(s, width);
    if (!l || *l <= 0) return 0;
    int e = 0;
    float m = std::frexp(*l, &e);
    if (m != 0.5f) return 0;
    int shift = e - 1;
    return shift >= rules_.minShift && shift <= rules_.maxShift ? shift : 0;
  }

  static bool takesShift(IrOp op) {
    switch (op) {
      case IrOp::Add: case IrOp::Mul: case IrOp::Mad: case IrOp::Dp3: case IrOp::Dp4: case IrOp::Lrp:
      case IrOp::Cmp: case IrOp::Min: case IrOp::Max: case IrOp::Slt: case IrOp::Sge: case IrOp::Abs:
        return true;  // the (last) instruction they select takes the shift
      default:
        return false;
    }
  }

  // Readers of `from` read `to` instead (swizzles composed).
  void replaceUses(int from, const IrSrc& to) {
    auto fix = [&](IrSrc& s) {
      if (s.reg != from) return;
      IrSrc r = to;
      for (int c = 0; c < 4; ++c) r.swizzle[c] = to.swizzle[s.swizzle[c]];
      r.negate = s.negate;
      r.absolute = s.absolute;
      s = r;
    };
    auto fixPart = [&](IrPart& p) {
      if (p.reg != from) return;
      p.component = to.swizzle[p.component];
      p.reg = to.reg;
    };
    for (IrInst& in : ir_.code) {
      for (int s = 0; s < in.srcCount; ++s) fix(in.src[s]);
      for (IrPart& p : in.parts) fixPart(p);
    }
    for (IrOutput& o : ir_.outputs)
      for (IrPart& p : o.parts) fixPart(p);
    for (auto& [k, f] : forms_) fix(f.base);
    for (auto& [k, l] : lerps_)
      for (IrSrc& s : l) fix(s);
  }

  // ---- 3. uniforms, samplers, texture instructions ---------------------------------------------
  static int registerBinding(const std::string& s, char file) {
    if (s.empty() || std::tolower((unsigned char)s[0]) != file) return -1;
    return std::atoi(s.c_str() + 1);
  }

  int constantCount() const {
    const shader::RegisterRule* r = shader::findRegisterRule(rules_, RegType::Const);
    return r ? r->count : 8;
  }
  int registerCount(RegType t) const {
    const shader::RegisterRule* r = shader::findRegisterRule(rules_, t);
    return r ? r->count : 0;
  }

  void placeUniforms() {
    std::vector<bool> taken(256, false);
    for (IrUniform& u : ir_.uniforms) {
      if (!u.used || !u.decl) continue;
      int r = registerBinding(u.decl->registerBinding, 'c');
      if (r < 0) continue;
      u.firstRegister = r;
      for (int k = 0; k < u.registerCount && r + k < 256; ++k) taken[r + k] = true;
    }
    int next = 0;
    for (IrUniform& u : ir_.uniforms) {
      if (!u.used || u.firstRegister >= 0) continue;
      for (;;) {
        bool fits = true;
        for (int k = 0; k < u.registerCount && fits; ++k) fits = next + k >= 256 || !taken[next + k];
        if (fits) break;
        ++next;
      }
      u.firstRegister = next;
      for (int k = 0; k < u.registerCount && next + k < 256; ++k) taken[next + k] = true;
      next += u.registerCount;
    }
    constTaken_ = taken;
    int needed = 0;
    for (int i = 0; i < 256; ++i)
      if (taken[i]) needed = i + 1;
    if (needed > constantCount())
      sink_.error(entryWhere_, "X4550", "{} has {} constant registers (c0..c{}), the uniforms need {}", profile(),
                  constantCount(), constantCount() - 1, needed);
    for (const IrInst& in : ir_.code) {
      if (in.op != IrOp::Uniform) continue;
      const IrUniform& u = ir_.uniforms[in.index & 0xFFFF];
      Home& h = home(in.dst);
      h.fixed = true;
      h.type = RegType::Const;
      h.index = u.firstRegister + (in.index >> 16);
    }
  }

  Home& home(int vreg) {
    if (prog_.homes.size() < ir_.regWidth.size()) prog_.homes.resize(ir_.regWidth.size());
    return prog_.homes[vreg];
  }

  const IrInput* texcoordInput(const IrSrc& s) const {
    const IrInst* p = producer(s.reg);
    if (!p || p->op != IrOp::Input) return nullptr;
    const IrInput& in = ir_.inputs[p->index];
    return in.usage == shader::DeclUsage::TexCoord ? &in : nullptr;
  }

  // The coordinate is an interpolated TEXCOORDn as it arrives: no swizzle, no modifier.
  const IrInput* plainTexcoord(const IrInst& tex) const {
    const IrSrc& c = tex.src[0];
    const IrInput* in = texcoordInput(c);
    if (!in || c.negate || c.absolute || forms_.count(c.reg)) return nullptr;
    for (int i = 0; i < tex.index; ++i)
      if (c.swizzle[i] != i) return nullptr;
    return in;
  }

  std::string samplerName(int s) const { return ir_.samplers[s].name; }

  void planTextureReads() {
    phaseOf_.assign(ir_.code.size(), 2);
    if (ps14_) markPhaseOne();
    if (sink_.hasErrors()) return;
    // Texture instructions needed: one per texture read, one per coordinate set read as a value.
    std::set<int> valueTexcoords;  // Input instructions read as values
    std::vector<int> reads;
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (in.op == IrOp::Tex && !skip_.count(int(i))) reads.push_back(int(i));
    }
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (skip_.count(int(i))) continue;
      for (int s = 0; s < in.srcCount; ++s) {
        if (in.op == IrOp::Tex && s == 0 && plainTexcoord(in)) continue;
        if (texcoordInput(in.src[s])) valueTexcoords.insert(def_[in.src[s].reg]);
      }
      for (const IrPart& p : in.parts)
        if (p.reg >= 0 && texcoordInput(IrSrc{p.reg})) valueTexcoords.insert(def_[p.reg]);
    }
    for (auto& [v, f] : forms_)
      if (texcoordInput(f.base)) valueTexcoords.insert(def_[f.base.reg]);
    for (auto& [i, l] : lerps_)
      for (const IrSrc& s : l)
        if (texcoordInput(s)) valueTexcoords.insert(def_[s.reg]);
    for (const IrOutput& o : ir_.outputs)
      for (const IrPart& p : o.parts)
        if (p.reg >= 0 && texcoordInput(IrSrc{p.reg})) valueTexcoords.insert(def_[p.reg]);
    if (!checkTextureCount(reads, valueTexcoords)) return;
    if (ps14_) planPs14Textures(reads, valueTexcoords);
    else planPs11Textures(reads, valueTexcoords);
    for (const IrInst& in : ir_.code) {
      if (in.op != IrOp::Input) continue;
      const IrInput& input = ir_.inputs[in.index];
      if (input.usage != shader::DeclUsage::Color) continue;
      Home& h = home(in.dst);
      h.fixed = true;
      h.type = RegType::Input;
      h.index = input.usageIndex;
      if (input.usageIndex >= registerCount(RegType::Input))
        sink_.error(entryWhere_, "X4502", "{} has color inputs COLOR0..COLOR{}, not {}", profile(),
                    registerCount(RegType::Input) - 1, input.semantic);
    }
  }

  bool checkTextureCount(const std::vector<int>& reads, const std::set<int>& valueTexcoords) {
    int limit = rules_.slots.texture;
    for (int phase : {1, 2}) {
      int n = 0;
      for (int i : reads) n += phaseOf_[i] == phase;
      for (int i : valueTexcoords) n += phaseOf_[i] == phase;
      if (n <= limit) continue;
      SourceLocation at = entryWhere_;
      for (int i : reads)
        if (phaseOf_[i] == phase) at = ir_.code[i].where;
      refuse(at, "{} allows {} texture instructions{}, this shader has {}", profile(), limit,
             rules_.slots.perPhase ? " per phase" : "", n);
      return false;
    }
    return true;
  }

  // ps_1_1 – ps_1_3: texture stage n reads TEXCOORDn; `tex tn` samples the sampler
  // at stage n, `texcoord tn` delivers the coordinates clamped to [0, 1].
  void planPs11Textures(const std::vector<int>& reads, const std::set<int>& valueTexcoords) {
    const int stages = registerCount(RegType::Texture);
    std::map<int, int> samplerAt;  // stage → sampler
    for (int i : reads) {
      const IrInst& in = ir_.code[i];
      const IrInput* tc = plainTexcoord(in);
      const std::string name = samplerName(in.sampler);
      if (!tc) {
        refuse(in.where, "'{}' is sampled at coordinates the shader computes (a dependent read); {} samples only "
               "TEXCOORDn as interpolated (use ps_1_4 or ps_2_0)", name, profile());
        continue;
      }
      int n = tc->usageIndex;
      IrSampler& s = ir_.samplers[in.sampler];
      int bound = s.decl ? registerBinding(s.decl->registerBinding, 's') : -1;
      if (n >= stages) {
        refuse(in.where, "{} has texture stages t0..t{}; '{}' reads TEXCOORD{}", profile(), stages - 1, name, n);
        continue;
      }
      if (bound >= 0 && bound != n) {
        refuse(in.where, "'{}' is bound to s{} but reads TEXCOORD{}; in {} a sampler reads the coordinates of its own stage",
               name, bound, n, profile());
        continue;
      }
      if (s.registerIndex >= 0 && s.registerIndex != n) {
        refuse(in.where, "'{}' reads TEXCOORD{} and TEXCOORD{}; in {} a sampler reads the coordinates of its own stage",
               name, s.registerIndex, n, profile());
        continue;
      }
      if (samplerAt.count(n) && samplerAt[n] != in.sampler) {
        refuse(in.where, "'{}' and '{}' both read TEXCOORD{}; {} has one texture instruction per stage",
               samplerName(samplerAt[n]), name, n, profile());
        continue;
      }
      if (stageRead_.count(n)) {
        refuse(in.where, "'{}' is read twice at TEXCOORD{}; {} has one texture instruction per stage", name, n, profile());
        continue;
      }
      samplerAt[n] = in.sampler;
      s.registerIndex = n;
      stageRead_[n] = i;
      Home& h = home(in.dst);
      h.pinned = true;
      h.type = RegType::Texture;
      h.index = n;
    }
    for (int i : valueTexcoords) {
      const IrInst& in = ir_.code[i];
      const IrInput& tc = ir_.inputs[in.index];
      int n = tc.usageIndex;
      if (n >= stages) {
        refuse(entryWhere_, "{} has texture coordinates t0..t{}; {} does not fit", profile(), stages - 1, tc.semantic);
        continue;
      }
      if (stageRead_.count(n)) {
        refuse(ir_.code[stageRead_[n]].where, "TEXCOORD{0} is sampled and also read as a value; in {1} t{0} holds either "
               "the texture color (tex) or the coordinates (texcoord)", n, profile());
        continue;
      }
      Home& h = home(in.dst);
      h.pinned = true;
      h.type = RegType::Texture;
      h.index = n;
      h.texcoord = true;
      h.texcoordIndex = n;
      texcoordValues_.push_back(i);
    }
  }

  // ps_1_4: `texld r(d), t(n)` samples stage d (the sampler register) at TEXCOORDn;
  // coordinates the shader computes are computed in phase 1 and read by a
  // phase-2 `texld r(d), r(k)`; `texcrd` copies TEXCOORDn into a register.
  void planPs14Textures(const std::vector<int>& reads, const std::set<int>& valueTexcoords) {
    const int stages = registerCount(RegType::Texture);
    std::vector<bool> taken(16, false);
    for (int i : reads) {
      IrSampler& s = ir_.samplers[ir_.code[i].sampler];
      int bound = s.decl ? registerBinding(s.decl->registerBinding, 's') : -1;
      if (bound >= 0 && s.registerIndex < 0) {
        s.registerIndex = bound;
        if (bound < 16) taken[bound] = true;
      }
    }
    for (int i : reads) {
      IrSampler& s = ir_.samplers[ir_.code[i].sampler];
      if (s.registerIndex >= 0) continue;
      int r = 0;
      while (r < 16 && taken[r]) ++r;
      s.registerIndex = r;
      if (r < 16) taken[r] = true;
    }
    std::set<std::pair<int, int>> stageInPhase;
    for (int i : reads) {
      const IrInst& in = ir_.code[i];
      int d = ir_.samplers[in.sampler].registerIndex;
      const IrInput* tc = plainTexcoord(in);
      if (d >= stages) {
        refuse(in.where, "{} has texture stages 0..{}; '{}' is at s{}", profile(), stages - 1, samplerName(in.sampler), d);
        continue;
      }
      if (tc && tc->usageIndex >= stages) {
        refuse(in.where, "{} has texture coordinates t0..t{}; '{}' reads TEXCOORD{}", profile(), stages - 1,
               samplerName(in.sampler), tc->usageIndex);
        continue;
      }
      if (!stageInPhase.insert({phaseOf_[i], d}).second) {
        refuse(in.where, "'{}' is read twice in phase {}; {} reads each texture stage once per phase",
               samplerName(in.sampler), phaseOf_[i], profile());
        continue;
      }
      Home& h = home(in.dst);
      h.pinned = true;
      h.type = RegType::Temp;
      h.index = d;
      h.phase = phaseOf_[i];
      if (phaseOf_[i] == 2) phase2Reads_[d] = i;
    }
    for (int i : valueTexcoords) {
      const IrInput& tc = ir_.inputs[ir_.code[i].index];
      if (tc.usageIndex >= stages) {
        refuse(entryWhere_, "{} has texture coordinates t0..t{}; {} does not fit", profile(), stages - 1, tc.semantic);
        continue;
      }
      Home& h = home(ir_.code[i].dst);
      h.phase = phaseOf_[i];
      h.texcoord = true;
      h.texcoordIndex = tc.usageIndex;
      texcoordValues_.push_back(i);
    }
  }

  // ps_1_4: everything the coordinates of a dependent read need runs in phase 1.
  void markPhaseOne() {
    std::vector<int> work;
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (in.op != IrOp::Tex || skip_.count(int(i)) || plainTexcoord(in)) continue;
      dependent_.insert(int(i));
      pushSources(in, work);
    }
    if (dependent_.empty()) return;
    std::set<int> seen;
    while (!work.empty()) {
      int r = work.back();
      work.pop_back();
      if (!seen.insert(r).second || def_[r] < 0) continue;
      int d = def_[r];
      const IrInst& in = ir_.code[d];
      if (in.op == IrOp::Uniform || in.op == IrOp::Constant) continue;
      if (in.op == IrOp::Input) {
        const IrInput& input = ir_.inputs[in.index];
        if (input.usage == shader::DeclUsage::Color)
          refuse(ir_.code[*dependent_.begin()].where, "texture coordinates computed from {} do not fit: {} computes "
                 "dependent coordinates in phase 1, before the colors arrive", input.semantic, profile());
        phaseOf_[d] = 1;
        continue;
      }
      if (in.op == IrOp::Tex && dependent_.count(d)) {
        refuse(in.where, "a texture read whose coordinates depend on a dependent read: {} allows one level of dependent "
               "reads", profile());
        continue;
      }
      phaseOf_[d] = 1;
      if (in.op != IrOp::Tex) pushSources(in, work);
    }
  }

  void pushSources(const IrInst& in, std::vector<int>& work) const {
    for (int s = 0; s < in.srcCount; ++s) work.push_back(in.src[s].reg);
    for (const IrPart& p : in.parts)
      if (p.reg >= 0) work.push_back(p.reg);
    if (auto f = forms_.find(in.dst); f != forms_.end()) work.push_back(f->second.base.reg);
  }

  // ---- 4. the color output and gathers ---------------------------------------------------------
  void planColorOutput() {
    for (size_t o = 0; o < ir_.outputs.size(); ++o) {
      if (ir_.outputs[o].usage != shader::DeclUsage::Color || ir_.outputs[o].usageIndex != 0) continue;
      color_ = newValue(int(ir_.outputs[o].parts.size()));
      colorOutput_ = int(o);
      home(color_).layout = Layout::Vector;
      prog_.colorMask = maskOf(int(ir_.outputs[o].parts.size()));
      if (!legalMask(prog_.colorMask, IrOp::Mov)) prog_.colorMask = 0xF;
      prog_.colorWhere = ir_.outputs[o].where;
    }
    if (color_ < 0) sink_.error(entryWhere_, "X4502", "a pixel shader writes COLOR0; this one has no color output");
  }

  int newValue(int width) {
    int r = ir_.newReg(width);
    def_.push_back(-1);
    uses_.push_back(0);
    home(r);
    return r;
  }

  // A result only the gather (or color) reads, in the layout the gather wants,
  // is written there by its own instruction.
  void coalesceIntoGathers() {
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& in = ir_.code[i];
      if (in.op == IrOp::Combine && !skip_.count(int(i))) coalesce(in.dst, in.parts, phaseOf_[i]);
    }
    if (color_ >= 0) coalesce(color_, ir_.outputs[colorOutput_].parts, 2);
  }

  void coalesce(int gather, const std::vector<IrPart>& parts, int phase) {
    std::map<int, std::pair<uint8_t, Comps>> groups;
    for (size_t p = 0; p < parts.size(); ++p) {
      if (parts[p].reg < 0) continue;
      auto& g = groups.try_emplace(parts[p].reg, uint8_t(0), Comps{kNone, kNone, kNone, kNone}).first->second;
      g.first |= uint8_t(1u << p);
      g.second[p] = parts[p].component;
    }
    for (auto& [v, g] : groups) {
      auto [mask, comps] = g;
      const IrInst* p = producer(v);
      if (!p || uses_[v] != 1 || skip_.count(def_[v]) || phaseOf_[def_[v]] != phase || !writesOneResult(p->op)) continue;
      bool natural = true;
      for (int c = 0; c < 4; ++c)
        if (comps[c] != kNone) natural &= p->width == 1 ? comps[c] == 0 : comps[c] == c;
      if (!natural || !legalMask(mask, p->op)) continue;
      coalesced_[v] = Coalesced{gather, mask, comps};
    }
  }

  static bool writesOneResult(IrOp op) {
    switch (op) {
      case IrOp::Add: case IrOp::Mul: case IrOp::Mad: case IrOp::Dp3: case IrOp::Dp4: case IrOp::Lrp:
      case IrOp::Cmp: case IrOp::Mov: case IrOp::Min: case IrOp::Max: case IrOp::Slt: case IrOp::Sge:
      case IrOp::Abs:
        return true;
      default:
        return false;
    }
  }

  // ps_1_1 – ps_1_3 write .rgba, .rgb or .a (dp3 .rgb or .rgba); ps_1_4 any mask.
  bool legalMask(uint8_t mask, IrOp op) const {
    if (rules_.writeMasks == shader::WriteMaskRule::Any) return mask != 0;
    if (op == IrOp::Dp3 || op == IrOp::Dp4) return mask == 0xF || mask == 0x7;
    return mask == 0xF || mask == 0x7 || mask == 0x8;
  }

  // ---- 5. instruction selection ----------------------------------------------------------------
  struct Dest {
    int value = -1;
    uint8_t mask = 0xF;
    Comps result{kNone, kNone, kNone, kNone};  // logical result component at each physical one
  };

  // Where an instruction's result goes: into a gather, or its own register in the
  // layout of its width (scalars in .a, where ps_1_x's alpha pipe computes them).
  Dest destination(const IrInst& in, Layout scalar) {
    if (auto c = coalesced_.find(in.dst); c != coalesced_.end()) return {c->second.gather, c->second.mask, c->second.result};
    Dest d;
    d.value = in.dst;
    Home& h = home(in.dst);
    h.phase = phase_;
    if (in.width == 1) {
      h.layout = scalar;
      d.mask = scalar == Layout::Alpha ? 0x8 : 0xF;
      for (int c = 0; c < 4; ++c) d.result[c] = (d.mask >> c & 1) ? 0 : kNone;
      return d;
    }
    h.layout = Layout::Vector;
    d.mask = in.width == 4 ? 0xF : 0x7;  // .rgb also for float2: every version can write it
    for (int c = 0; c < 4; ++c) d.result[c] = c < in.width ? uint8_t(c) : kNone;
    return d;
  }

  // Scalars go to .a (pairable with an .rgb instruction) unless they cross ps_1_4's
  // phase marker, which loses the alpha of every register.
  Layout scalarLayout() const { return ps14_ && phase_ == 1 ? Layout::Splat : Layout::Alpha; }

  void push(MInst m) {
    m.where = where_;
    m.phase = phase_;
    if (m.texture) {
      prog_.tex[phase_].push_back(m);
      return;
    }
    limitReadPorts(m);
    prog_.arith[phase_].push_back(m);
  }

  // At most N different registers of a file per instruction (2 c#, …): sources whose
  // register is already known (c#, v#, texture stages) beyond that are copied to a
  // temporary first. The allocator keeps the other values within the limits.
  void limitReadPorts(MInst& m) {
    for (RegType file : {RegType::Const, RegType::Input, RegType::Texture, RegType::Temp}) {
      const shader::RegisterRule* rule = shader::findRegisterRule(rules_, file);
      if (!rule || !rule->readPorts) continue;
      std::set<int> seen;
      for (int s = 0; s < m.srcCount; ++s) {
        std::optional<Register> r = knownRegister(m.src[s]);
        if (!r || r->type != file || seen.count(r->index)) continue;
        if (int(seen.size()) < rule->readPorts) {
          seen.insert(r->index);
          continue;
        }
        uint8_t read = readMask(m, s);
        uint8_t mask = !(read & 0x8) ? 0x7 : read == 0x8 ? 0x8 : 0xF;
        int t = newValue(4);
        Home& h = home(t);
        h.phase = phase_;
        h.layout = Layout::Vector;
        Operand plain = m.src[s];
        plain.swizzle = kIdentity;
        plain.mod = SrcMod::None;
        push(make(Opcode::Mov, Dest{t, mask, positional(4)}, {plain}));
        m.src[s].value = t;
      }
    }
  }

  std::optional<Register> knownRegister(const Operand& o) {
    if (o.value < 0) return Register{o.type, o.index};
    const Home& h = home(o.value);
    if (h.pinned) return Register{h.type, h.index};
    return std::nullopt;
  }

  MInst make(Opcode op, const Dest& d, std::initializer_list<Operand> srcs, bool saturate = false, int shift = 0) {
    MInst m;
    m.op = op;
    m.dst = d.value;
    m.mask = d.mask;
    m.saturate = saturate;
    m.shift = int8_t(shift);
    for (const Operand& s : srcs) m.src[m.srcCount++] = s;
    return m;
  }

  // Source components a componentwise instruction reads: the result component of each
  // physical destination component.
  static Comps componentwise(const Dest& d) { return d.result; }
  static Comps positional(int n) {
    Comps c{kNone, kNone, kNone, kNone};
    for (int i = 0; i < n; ++i) c[i] = uint8_t(i);
    return c;
  }

  void select(int i) {
    const IrInst& in = ir_.code[i];
    where_ = in.where;
    phase_ = phaseOf_[i];
    if (skip_.count(i)) return;
    const int shift = shift_.count(in.dst) ? shift_[in.dst] : 0;
    const bool sat = in.saturate;
    switch (in.op) {
      case IrOp::Uniform: case IrOp::Constant: return;
      case IrOp::Input: selectTexcoord(i); return;
      case IrOp::Tex: selectTextureRead(i); return;
      case IrOp::Combine: selectGather(in.dst, in.parts); return;
      case IrOp::Dp3: case IrOp::Dp4: {
        Dest d = destination(in, Layout::Splat);
        int n = in.op == IrOp::Dp3 ? 3 : 4;
        Operand a = read(in.src[0], positional(n), d.mask), b = read(in.src[1], positional(n), d.mask);
        push(make(in.op == IrOp::Dp3 ? Opcode::Dp3 : Opcode::Dp4, d, {a, b}, sat, shift));
        return;
      }
      default: break;
    }
    Dest d = destination(in, scalarLayout());
    Comps cw = componentwise(d);
    auto rd = [&](const IrSrc& s) { return read(s, cw, d.mask); };
    switch (in.op) {
      case IrOp::Mov: push(make(Opcode::Mov, d, {rd(in.src[0])}, sat, shift)); return;
      case IrOp::Add: {
        // a + (-c) with c a constant register: sub (constants take no modifiers)
        if (in.src[1].negate && constantRegister(in.src[1])) {
          IrSrc c = in.src[1];
          c.negate = false;
          push(make(Opcode::Sub, d, {rd(in.src[0]), rd(c)}, sat, shift));
          return;
        }
        push(make(Opcode::Add, d, {rd(in.src[0]), rd(in.src[1])}, sat, shift));
        return;
      }
      case IrOp::Mul:
        for (int k = 0; k < 2; ++k)
          if (int s = shiftOf(in.src[k], in.width); s && shift + s >= rules_.minShift && shift + s <= rules_.maxShift) {
            push(make(Opcode::Mov, d, {rd(in.src[1 - k])}, sat, shift + s));  // x * 2^s: mov with a shift
            return;
          }
        push(make(Opcode::Mul, d, {rd(in.src[0]), rd(in.src[1])}, sat, shift));
        return;
      case IrOp::Mad:
        if (auto l = lerps_.find(i); l != lerps_.end()) {
          auto& [s, b, a] = l->second;
          push(make(Opcode::Lrp, d, {rd(s), rd(b), rd(a)}, sat, shift));
          return;
        }
        push(make(Opcode::Mad, d, {rd(in.src[0]), rd(in.src[1]), rd(in.src[2])}, sat, shift));
        return;
      case IrOp::Lrp: push(make(Opcode::Lrp, d, {rd(in.src[0]), rd(in.src[1]), rd(in.src[2])}, sat, shift)); return;
      case IrOp::Cmp: push(make(Opcode::Cmp, d, {rd(in.src[0]), rd(in.src[1]), rd(in.src[2])}, sat, shift)); return;
      case IrOp::Max: case IrOp::Min: {
        // t = a - b; max: t >= 0 ? a : b; min: t >= 0 ? b : a
        Operand t = difference(in.src[0], in.src[1], d);
        bool max = in.op == IrOp::Max;
        push(make(Opcode::Cmp, d, {t, rd(in.src[max ? 0 : 1]), rd(in.src[max ? 1 : 0])}, sat, shift));
        return;
      }
      case IrOp::Sge: case IrOp::Slt: {
        // t = a - b; sge: t >= 0 ? 1 : 0; slt: t >= 0 ? 0 : 1
        Operand t = difference(in.src[0], in.src[1], d);
        bool ge = in.op == IrOp::Sge;
        push(make(Opcode::Cmp, d, {t, literalOperand(ge ? 1.f : 0.f), literalOperand(ge ? 0.f : 1.f)}, sat, shift));
        return;
      }
      case IrOp::Abs: {
        IrSrc x = in.src[0], nx = x;
        nx.negate = !nx.negate;
        push(make(Opcode::Cmp, d, {rd(x), rd(x), rd(nx)}, sat, shift));  // x >= 0 ? x : -x
        return;
      }
      default:
        refuse(in.where, "this operation is not in {}", profile());
        return;
    }
  }

  bool constantRegister(const IrSrc& s) const {
    const IrInst* p = producer(s.reg);
    return p && p->op == IrOp::Uniform && !forms_.count(s.reg);
  }

  // a - b into a temporary laid out as `d`, for cmp-based selections (min and max
  // of the same operands share it).
  Operand difference(const IrSrc& a, const IrSrc& b, const Dest& d) {
    auto key = std::make_tuple(a.reg, a.swizzle, a.negate, b.reg, b.swizzle, b.negate, d.mask, d.result, phase_);
    Operand o;
    if (auto it = differences_.find(key); it != differences_.end()) {
      o.value = it->second;
      return o;
    }
    int t = newValue(4);
    differences_[key] = t;
    Home& h = home(t);
    h.phase = phase_;
    h.layout = d.mask == 0x8 ? Layout::Alpha : Layout::Vector;
    Dest td{t, d.mask, d.result};
    IrSrc nb = b;
    nb.negate = !nb.negate;
    push(make(Opcode::Add, td, {read(a, d.result, d.mask), read(nb, d.result, d.mask)}));
    o.value = t;
    return o;
  }

  // `texcoord t(n)` (ps_1_1 – 1_3) or `texcrd r.rgb, t(n)` (ps_1_4) for a coordinate
  // set read as a value.
  void selectTexcoord(int i) {
    const IrInst& in = ir_.code[i];
    if (std::find(texcoordValues_.begin(), texcoordValues_.end(), i) == texcoordValues_.end()) return;
    const Home& h = home(in.dst);
    MInst m;
    m.op = Opcode::TexCoord;
    m.texture = true;
    m.dst = in.dst;
    if (ps14_) {
      m.mask = 0x7;
      Operand t;
      t.type = RegType::Texture;
      t.index = h.texcoordIndex;
      m.src[m.srcCount++] = t;
    }
    push(m);
  }

  void selectTextureRead(int i) {
    const IrInst& in = ir_.code[i];
    MInst m;
    m.op = Opcode::Tex;
    m.texture = true;
    m.dst = in.dst;
    if (!ps14_) {  // tex t(n): the stage's own coordinates
      push(m);
      return;
    }
    home(in.dst).phase = phase_;
    Operand coord;
    if (const IrInput* tc = plainTexcoord(in)) {
      coord.type = RegType::Texture;
      coord.index = tc->usageIndex;
      m.src[m.srcCount++] = coord;
      if (phase_ == 1) resampleable_[in.dst] = m;
      push(m);
      return;
    } else {
      coord = dependentCoordinate(in);
    }
    m.src[m.srcCount++] = coord;
    push(m);
  }

  // The coordinates of a dependent read, as phase 1 left them: .xyz of a register.
  Operand dependentCoordinate(const IrInst& tex) {
    int saved = phase_;
    phase_ = 1;
    Comps need = positional(std::min(tex.index, 3));
    Operand o = read(tex.src[0], need, 0x7);
    if (o.value < 0 || o.swizzle != kIdentity || o.mod != SrcMod::None || home(o.value).layout == Layout::Alpha) {
      int t = newValue(3);
      Home& h = home(t);
      h.phase = 1;
      h.layout = Layout::Vector;
      Dest d{t, 0x7, positional(3)};
      push(make(Opcode::Mov, d, {read(tex.src[0], need, 0x7)}));
      o = Operand{};
      o.value = t;
    }
    phase_ = saved;
    return o;
  }

  // The parts of a gather (a Combine, or the color) not written by their producers:
  // one mov per source value, one for the literals.
  void selectGather(int gather, const std::vector<IrPart>& parts) {
    Home& g = home(gather);
    g.phase = phase_;
    g.layout = Layout::Vector;
    std::map<int, std::pair<uint8_t, Comps>> groups;
    uint8_t literalMask = 0;
    std::array<float, 4> literals{};
    for (size_t p = 0; p < parts.size(); ++p) {
      const IrPart& part = parts[p];
      if (part.reg < 0) {
        literalMask |= uint8_t(1u << p);
        literals[p] = part.literal;
        continue;
      }
      auto c = coalesced_.find(part.reg);
      if (c != coalesced_.end() && c->second.gather == gather) continue;
      auto& grp = groups.try_emplace(part.reg, uint8_t(0), Comps{kNone, kNone, kNone, kNone}).first->second;
      grp.first |= uint8_t(1u << p);
      grp.second[p] = part.component;
    }
    for (auto& [reg, grp] : groups) {
      for (auto [mask, comps] : splitByComponent(grp.first, grp.second)) {
        if (!gatherMask(mask)) return;
        Dest d{gather, mask, comps};
        IrSrc s;
        s.reg = reg;  // identity swizzle: `comps` are components of reg
        push(make(Opcode::Mov, d, {read(s, comps, mask)}));
      }
    }
    if (literalMask) {
      if (!gatherMask(literalMask)) return;
      Dest d{gather, literalMask, {}};
      push(make(Opcode::Mov, d, {literalVector(literals, literalMask)}));
    }
  }

  // The parts of one source that stay in place, and one group per other component it
  // provides (each then reads with one selector), when the version can write those
  // masks; otherwise the group as it is.
  std::vector<std::pair<uint8_t, Comps>> splitByComponent(uint8_t mask, const Comps& comps) const {
    std::map<int, std::pair<uint8_t, Comps>> parts;  // -1: in place; c: component c
    for (int p = 0; p < 4; ++p) {
      if (!(mask >> p & 1)) continue;
      auto& part = parts.try_emplace(comps[p] == p ? -1 : comps[p], uint8_t(0), Comps{kNone, kNone, kNone, kNone})
                       .first->second;
      part.first |= uint8_t(1u << p);
      part.second[p] = comps[p];
    }
    std::vector<std::pair<uint8_t, Comps>> out;
    for (auto& [key, part] : parts) {
      if (!legalMask(part.first, IrOp::Mov)) return {{mask, comps}};
      out.push_back(part);
    }
    return out;
  }

  bool gatherMask(uint8_t mask) {
    if (legalMask(mask, IrOp::Mov)) return true;
    refuse(where_, "a vector gathered from several values writes components {} of a register; {} writes .rgba, .rgb or "
           ".a (ps_1_4 writes any components)", maskText(mask), profile());
    return false;
  }

  static std::string maskText(uint8_t mask) {
    std::string s = ".";
    for (int c = 0; c < 4; ++c)
      if (mask >> c & 1) s += "rgba"[c];
    return s;
  }

  void writeColorOutput() {
    if (color_ < 0) return;
    where_ = ir_.outputs[colorOutput_].where;
    phase_ = 2;
    selectGather(color_, ir_.outputs[colorOutput_].parts);
  }

  // ---- reading values --------------------------------------------------------------------------
  // An operand that delivers, at each physical component p of the destination, the
  // component want[p] of `s` (kNone: not read). Source modifiers and literals are
  // resolved here; selectors the version cannot express are made legal by copying
  // the component first (dp3 with a unit vector in ps_1_1 – 1_3; masked movs in
  // ps_1_4).
  Operand read(const IrSrc& s, Comps want, uint8_t dstMask) {
    Comps comp;
    for (int p = 0; p < 4; ++p) comp[p] = want[p] == kNone ? kNone : s.swizzle[want[p]];
    IrSrc base = s;
    SrcMod mod = SrcMod::None;
    if (auto f = forms_.find(s.reg); f != forms_.end()) {
      for (int p = 0; p < 4; ++p)
        if (comp[p] != kNone) comp[p] = f->second.base.swizzle[comp[p]];
      base.reg = f->second.base.reg;
      mod = f->second.mod;
    }
    const IrInst* p = producer(base.reg);
    if (p && p->op == IrOp::Constant) {
      std::array<float, 4> v{};
      uint8_t mask = 0;
      for (int c = 0; c < 4; ++c)
        if (comp[c] != kNone) {
          float x = p->literal[comp[c]];
          if (s.absolute) x = std::fabs(x);
          v[c] = s.negate ? -x : x;
          mask |= uint8_t(1u << c);
        }
      return literalVector(v, mask);
    }
    int value = base.reg;
    if (s.absolute) {
      value = absoluteOf(value);
    }
    Operand o = place(value, comp, dstMask);
    if (mod == SrcMod::Comp && s.negate) {
      // -(1 - x) has no modifier: compute 1 - x first
      uint8_t read = 0;
      for (int c = 0; c < 4; ++c)
        if (comp[c] != kNone) read |= uint8_t(1u << c);
      uint8_t mask = !(read & 0x8) ? 0x7 : read == 0x8 ? 0x8 : 0xF;
      int t = newValue(4);
      Home& h = home(t);
      h.phase = phase_;
      h.layout = Layout::Vector;
      o.mod = SrcMod::Comp;
      push(make(Opcode::Mov, Dest{t, mask, positional(4)}, {o}));
      o = Operand{};
      o.value = t;
      mod = SrcMod::None;
    }
    o.mod = combine(mod, s.negate);
    if (o.value < 0 && o.type == RegType::Const && o.mod != SrcMod::None) {
      // constants take no source modifiers: copy the register first
      Operand plain = o;
      plain.mod = SrcMod::None;
      int t = newValue(4);
      Home& h = home(t);
      h.phase = phase_;
      h.layout = Layout::Vector;
      push(make(Opcode::Mov, Dest{t, 0xF, positional(4)}, {plain}));
      Operand r;
      r.value = t;
      r.swizzle = o.swizzle;
      r.mod = o.mod;
      return r;
    }
    return o;
  }

  static SrcMod combine(SrcMod mod, bool negate) {
    if (!negate) return mod;
    switch (mod) {
      case SrcMod::None: return SrcMod::Neg;
      case SrcMod::Bias: return SrcMod::BiasNeg;
      case SrcMod::Sign: return SrcMod::SignNeg;
      case SrcMod::X2: return SrcMod::X2Neg;
      default: return mod;  // 1-x is never negated (read copies it first)
    }
  }

  // |x| as cmp(x, x, -x) in x's layout.
  int absoluteOf(int value) {
    if (auto it = absolute_.find(value); it != absolute_.end()) return it->second;
    const Home& src = home(value);
    int t = newValue(ir_.regWidth[value]);
    Home& h = home(t);
    h.phase = phase_;
    h.layout = src.fixed ? Layout::Vector : src.layout;
    uint8_t mask = h.layout == Layout::Alpha ? 0x8 : 0xF;
    Comps all = positional(4);
    Operand x = place(value, h.layout == Layout::Alpha ? Comps{kNone, kNone, kNone, 0} : all, mask);
    Operand nx = x;
    nx.mod = SrcMod::Neg;
    push(make(Opcode::Cmp, Dest{t, mask, all}, {x, x, nx}));
    absolute_[value] = t;
    return t;
  }

  // The register of `value` and a selector for the physical components wanted.
  Operand place(int value, Comps comp, uint8_t dstMask) {
    if (ps14_ && phase_ == 2 && home(value).phase == 1 && resampleable_.count(value) &&
        std::find(comp.begin(), comp.end(), 3) != comp.end()) {
      value = resampleInPhase2(value);
      if (value < 0) return Operand{};
    }
    Home& h = home(value);
    Operand o;
    if (h.fixed) {
      o.type = h.type;
      o.index = h.index;
    } else {
      o.value = value;
    }
    if (h.texcoord)
      for (int c : comp)
        if (c == 3)
          refuse(where_, "TEXCOORD{}.w cannot be read in {}: {} delivers x, y and z", h.texcoordIndex, profile(),
                 shader::mnemonicIn(shader::Opcode::TexCoord, 0, v_));
    if (h.type == RegType::Input && h.fixed && ps14_ && phase_ == 1)
      refuse(where_, "COLOR{} cannot be read in phase 1 of {} (colors arrive in phase 2)", h.index, profile());
    // physical components of the value
    const bool crossesPhase = ps14_ && !h.fixed && h.phase == 1 && phase_ == 2;
    Comps phys;
    for (int p = 0; p < 4; ++p) {
      if (comp[p] == kNone) { phys[p] = kNone; continue; }
      switch (h.layout) {
        case Layout::Vector: phys[p] = comp[p]; break;
        case Layout::Splat: phys[p] = crossesPhase ? 0 : kAny; break;
        case Layout::Alpha: phys[p] = 3; break;
      }
    }
    if (crossesPhase)
      for (uint8_t c : phys)
        if (c == 3) refuse(where_, "the alpha of a value computed in phase 1 is lost at {}'s phase marker", profile());
    if (auto sw = selector(phys, dstMask)) {
      o.swizzle = *sw;
      return o;
    }
    // not selectable: copy the components first
    int single = -1;
    bool replicated = true;
    for (uint8_t c : phys)
      if (c != kNone && c != kAny) {
        if (single < 0) single = c;
        else if (single != c) replicated = false;
      }
    if (!ps14_ && !replicated) {
      std::string sw;
      for (uint8_t c : phys) sw += c == kNone || c == kAny ? '_' : "rgba"[c];
      refuse(where_, "a value read with the swizzle .{} (by component) needs ps_1_4; {} selects .rgba, .a or .b", sw,
             profile());
      return o;
    }
    Operand copy;
    copy.value = ps14_ ? gatherComponents(o, phys) : extractComponent(o, single);
    return copy;
  }

  // ps_1_4 loses the alpha of phase-1 registers at the phase marker: a texture read
  // at interpolated coordinates whose alpha phase 2 needs is read again there (-1
  // when phase 2 already reads that stage elsewhere).
  int resampleInPhase2(int value) {
    if (auto it = resampled_.find(value); it != resampled_.end()) return it->second;
    const MInst& first = resampleable_.at(value);
    int stage = home(value).index;
    if (auto other = phase2Reads_.find(stage); other != phase2Reads_.end()) {
      // phase 2 reads this stage already: the same read, or no second one fits
      const IrInst& tex = ir_.code[other->second];
      const IrInput* tc = plainTexcoord(tex);
      if (tc && tc->usageIndex == first.src[0].index) return resampled_[value] = tex.dst;
      refuse(where_, "the alpha of a texture read in phase 1 is lost at {}'s phase marker, and phase 2 reads stage {} "
             "already", profile(), stage);
      return -1;
    }
    int again = newValue(4);
    Home& h = home(again);
    h = home(value);
    h.phase = 2;
    MInst m = first;
    m.dst = again;
    int saved = phase_;
    phase_ = 2;
    push(m);
    phase_ = saved;
    resampled_[value] = again;
    return again;
  }

  static constexpr uint8_t kAny = 254;  // a Splat value: every component holds it

  // The selector reading `phys[p]` at each needed p, if the version has it.
  std::optional<uint8_t> selector(const Comps& phys, uint8_t dstMask) const {
    auto all = [&](auto ok) {
      for (int p = 0; p < 4; ++p)
        if (phys[p] != kNone && phys[p] != kAny && !ok(p, phys[p])) return false;
      return true;
    };
    if (all([](int p, int c) { return p == c; })) return kIdentity;
    if (all([](int, int c) { return c == 3; })) return replicate(3);
    if (rules_.swizzles == shader::SwizzleRule::Ps11) {
      if (dstMask == 0x8 && all([](int, int c) { return c == 2; })) return replicate(2);
      return std::nullopt;
    }
    for (int k = 0; k < 3; ++k)
      if (all([k](int, int c) { return c == k; })) return replicate(k);
    return std::nullopt;
  }

  // ps_1_1 – 1_3 cannot select .r or .g on their own: dp3 with a unit vector copies
  // one component into all four.
  int extractComponent(const Operand& from, int c) {
    auto key = std::make_tuple(from.value, int(from.type), from.index, c);
    if (auto it = extracted_.find(key); it != extracted_.end()) return it->second;
    int t = newValue(1);
    Home& h = home(t);
    h.phase = phase_;
    h.layout = Layout::Splat;
    std::array<float, 4> unit{};
    unit[c] = 1;
    Operand v = from;
    v.swizzle = kIdentity;
    push(make(Opcode::Dp3, Dest{t, 0xF, {0, 0, 0, 0}}, {v, literalVector(unit, 0xF)}));
    extracted_[key] = t;
    return t;
  }

  // ps_1_4: one masked mov per distinct component, with replicate selectors.
  int gatherComponents(const Operand& from, const Comps& phys) {
    int t = newValue(4);
    Home& h = home(t);
    h.phase = phase_;
    h.layout = Layout::Vector;
    std::map<int, uint8_t> byComponent;
    for (int p = 0; p < 4; ++p)
      if (phys[p] != kNone) byComponent[phys[p] == kAny ? 0 : phys[p]] |= uint8_t(1u << p);
    for (auto [c, mask] : byComponent) {
      Operand v = from;
      v.swizzle = replicate(c);
      push(make(Opcode::Mov, Dest{t, mask, positional(4)}, {v}));
    }
    return t;
  }

  // A def register holding `values` at the components in `mask` (the rest 0, or the
  // same value when all are equal so that every reader can share it).
  Operand literalVector(std::array<float, 4> values, uint8_t mask) {
    bool splat = true;
    float first = 0;
    bool any = false;
    for (int c = 0; c < 4; ++c) {
      if (!(mask >> c & 1)) continue;
      if (!any) first = values[c], any = true;
      else if (values[c] != first) splat = false;
    }
    for (int c = 0; c < 4; ++c)
      if (!(mask >> c & 1)) values[c] = splat ? first : 0.0f;
    for (int c = 0; c < 4; ++c)
      if (values[c] < rules_.defMin || values[c] > rules_.defMax) {
        refuse(where_, "the literal {} is outside [{}, {}], the range of {} constants", values[c], rules_.defMin,
               rules_.defMax, profile());
        break;
      }
    Operand o;
    o.type = RegType::Const;
    o.index = defRegister(values);
    return o;
  }
  Operand literalOperand(float v) { return literalVector({v, v, v, v}, 0xF); }

  int defRegister(const std::array<float, 4>& values) {
    for (const auto& [reg, v] : defs_)
      if (std::memcmp(v.data(), values.data(), 16) == 0) return reg;
    int reg = 0;
    while (reg < int(constTaken_.size()) && constTaken_[reg]) ++reg;
    if (reg < int(constTaken_.size())) constTaken_[reg] = true;
    defs_.emplace_back(reg, values);
    if (reg >= constantCount() && !constantsReported_) {
      constantsReported_ = true;
      sink_.error(where_, "X4550", "{} has {} constant registers (c0..c{}); the uniforms and literals need more", profile(),
                  constantCount(), constantCount() - 1);
    }
    return reg;
  }

  // ps_1_1 – 1_3 process texture registers in increasing order.
  void orderTextureInstructions() {
    if (ps14_) return;
    for (int phase : {1, 2})
      std::stable_sort(prog_.tex[phase].begin(), prog_.tex[phase].end(),
                       [&](const MInst& a, const MInst& b) { return home(a.dst).index < home(b.dst).index; });
  }

  // ---- 8. emission -----------------------------------------------------------------------------
  shader::DstParam dstParam(const MInst& m) const {
    shader::DstParam d;
    Register r = prog_.registers.at(m.dst);
    d.type = r.type;
    d.index = uint16_t(r.index);
    d.writeMask = m.mask;
    d.shift = m.shift;
    if (m.saturate) d.resultMod = shader::ResultSaturate;
    return d;
  }

  void emit(shader::Shader& out) {
    out.instructions.push_back(constantTable());
    std::sort(defs_.begin(), defs_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [r, values] : defs_) {
      shader::Instruction in;
      in.opcode = Opcode::Def;
      in.hasDst = true;
      in.dst.type = RegType::Const;
      in.dst.index = uint16_t(r);
      for (int c = 0; c < 4; ++c) std::memcpy(&in.literal[c], &values[c], 4);
      out.instructions.push_back(in);
    }
    bool phases = ps14_ && (!prog_.tex[1].empty() || !prog_.arith[1].empty());
    for (int phase : {1, 2}) {
      if (phase == 2 && phases) {
        shader::Instruction marker;
        marker.opcode = Opcode::Phase;
        out.instructions.push_back(marker);
      }
      for (const auto* list : {&prog_.tex[phase], &prog_.arith[phase]})
        for (const MInst& m : *list) {
          shader::Instruction in;
          in.opcode = m.op;
          in.coissue = m.coissue;
          in.hasDst = true;
          in.dst = dstParam(m);
          in.srcCount = uint8_t(m.srcCount);
          for (int s = 0; s < m.srcCount; ++s) {
            Register r = prog_.registerOf(m.src[s]);
            in.src[s].type = r.type;
            in.src[s].index = uint16_t(r.index);
            in.src[s].swizzle = m.src[s].swizzle;
            in.src[s].mod = m.src[s].mod;
          }
          in.pos = {m.where.line, m.where.column};
          out.instructions.push_back(in);
        }
    }
  }

  shader::Instruction constantTable() const { return constantTableComment(ir_, creator_, v_); }

  IrProgram& ir_;
  std::string creator_;
  DiagnosticSink& sink_;
  SourceLocation entryWhere_;
  SourceLocation where_;
  shader::Version v_;
  const shader::VersionRules& rules_;
  const bool ps14_;
  int phase_ = 2;

  std::vector<int> def_, uses_;
  std::set<int> skip_;                                   // IR instructions that emit nothing
  std::map<int, Form> forms_;                            // vreg → read as base with a modifier
  std::map<int, std::array<IrSrc, 3>> lerps_;            // mad → lrp s, b, a
  std::map<int, int> shift_;                             // vreg → its instruction's shift
  std::vector<int> phaseOf_;                             // IR instruction → ps_1_4 phase
  std::set<int> dependent_;                              // ps_1_4 dependent texture reads
  std::map<int, int> stageRead_;                         // ps_1_1 stage → texture read
  std::vector<int> texcoordValues_;                      // Input instructions read as values
  std::map<int, Coalesced> coalesced_;
  std::map<int, int> absolute_;
  std::map<int, MInst> resampleable_;                    // ps_1_4 phase-1 texld at t#: the instruction
  std::map<int, int> resampled_;                         // … and its phase-2 repetition
  std::map<int, int> phase2Reads_;                       // ps_1_4 stage → its phase-2 texture read
  std::map<std::tuple<int, std::array<uint8_t, 4>, bool, int, std::array<uint8_t, 4>, bool, uint8_t, Comps, int>, int>
      differences_;
  std::map<std::tuple<int, int, int, int>, int> extracted_;
  int color_ = -1, colorOutput_ = -1;
  std::vector<bool> constTaken_;
  std::vector<std::pair<int, std::array<float, 4>>> defs_;
  bool constantsReported_ = false;
  ps1x::Program prog_;                                       // the selected instructions
  std::set<std::tuple<int, int, std::string>> reported_;
};

}  // namespace

shader::Shader generateCodePs1x(IrProgram& ir, const std::string& creator, DiagnosticSink& sink,
                                const SourceLocation& entryWhere) {
  Ps1xCodeGen g(ir, creator, sink, entryWhere);
  return g.run();
}

}  // namespace refx::hlsl::detail
