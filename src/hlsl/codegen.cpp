// IR → D3D9 shader instructions for one version, as a sequence of steps:
//   1. place inputs, uniforms, literals and samplers in registers;
//   2. coalesce: results that only feed one gather or one output are written there;
//   3. select instructions (with the version's lowerings: no cmp in vertex shaders,
//      no slt in pixel shaders, vs_1_1 without lrp/abs/nrm/pow …);
//   4. legalise operands (swizzles a version cannot read, read-port limits);
//   5. allocate temporaries (linear scan);
//   6. write dcl/def, the constant table and the instruction list.
// Flow-control markers become rep/if_comp/if b#/else/endif/break_comp in place;
// registers written by Assign (variables of those regions) are ordinary temps whose
// live ranges cover every loop they are read in.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <set>

#include "hlsl/constant_table.h"
#include "hlsl/ir.h"
#include "refx/shader/opcode_table.h"
#include "refx/shader/validator.h"
#include "refx/shader/version_rules.h"

namespace refx::hlsl::detail {

namespace {

using shader::Opcode;
using shader::RegType;
using shader::SrcMod;

using Map = std::array<uint8_t, 4>;
constexpr Map kIdentity{0, 1, 2, 3};

// Where a virtual register lives. `map[i]` = physical component of logical component i.
struct Loc {
  bool placed = false;
  bool temp = false;    // allocated by the register allocator (index filled in later)
  RegType type = RegType::Temp;
  int index = 0;
  Map map = kIdentity;
  int aliasOf = -1;     // coalesced into another virtual register's physical register
};

struct MSrc {
  int vreg = -1;        // virtual register, or -1 for a fixed physical register
  RegType type = RegType::Const;
  int index = 0;
  Map swizzle = kIdentity;  // logical (vreg) or physical (fixed) components
  bool negate = false;
  bool absolute = false;
  bool relative = false;  // fixed register indexed by a0.x: c[a0.x + index]
  int physicalOf = -1;  // names vreg's register with a physical swizzle
};

struct MDst {
  int vreg = -1;
  RegType type = RegType::Temp;
  int index = 0;
  uint8_t mask = 0xF;  // logical components of vreg (or physical for fixed)
  bool saturate = false;
};

// How the destination mask maps onto source swizzles.
enum class Shape : uint8_t {
  Componentwise,  // source slot = destination component
  Positional,     // sources read in slot order (dp3, texld, nrm …)
  Scalar,         // one source component (replicate), result replicated into the mask
};

struct MInst {
  Opcode op = Opcode::Nop;
  uint8_t control = 0;
  MDst dst;
  bool hasDst = true;
  std::array<MSrc, 4> src{};
  int srcCount = 0;
  Shape shape = Shape::Componentwise;
  int coordWidth = 4;  // texld: coordinate components the sampler reads
  SourceLocation where;
};

class CodeGen {
 public:
  CodeGen(IrProgram& ir, const std::string& creator, DiagnosticSink& sink, const SourceLocation& entryWhere)
      : ir_(ir), creator_(creator), sink_(sink), entryWhere_(entryWhere), v_(ir.version) {
    rules_ = shader::findVersionRules(v_);
  }

  shader::Shader run() {
    shader::Shader out;
    out.version = v_;
    if (!rules_) {
      sink_.error(entryWhere_, "X3501", "profile {} is not supported", v_.name());
      return out;
    }
    loc_.assign(ir_.regWidth.size(), Loc{});
    def_.assign(ir_.regWidth.size(), -1);
    for (size_t i = 0; i < ir_.code.size(); ++i)
      if (ir_.code[i].dst >= 0 && ir_.code[i].op != IrOp::Assign) def_[ir_.code[i].dst] = int(i);
    for (const IrInst& in : ir_.code)
      if (in.op == IrOp::Assign) def_[in.dst] = -1;  // a variable: no single producer
    countUses();
    placeInputs();
    placeUniformsAndSamplers();
    placeLiterals();
    placeSpecialResults();
    coalesceOutputs();
    coalesceGathers();
    coalesceAssigns();
    for (size_t i = 0; i < ir_.code.size(); ++i)
      if (!assignedInPlace_.count(int(i))) select(ir_.code[i]);
    writeOutputs();
    if (sink_.hasErrors()) return out;
    legalise();
    if (!allocateTemps()) return out;
    emit(out);
    return out;
  }

 private:
  bool isPixel() const { return v_.isPixel(); }
  bool sm3() const { return v_.major >= 3; }

  // ---- analysis --------------------------------------------------------------------------------
  void countUses() {
    uses_.assign(ir_.regWidth.size(), 0);
    for (const IrInst& in : ir_.code) {
      std::set<int> seen;
      for (int s = 0; s < in.srcCount; ++s) seen.insert(in.src[s].reg);
      for (const IrPart& p : in.parts)
        if (p.reg >= 0) seen.insert(p.reg);
      for (int r : seen) ++uses_[r];
    }
    for (const IrOutput& o : ir_.outputs) {
      std::set<int> seen;
      for (const IrPart& p : o.parts)
        if (p.reg >= 0) seen.insert(p.reg);
      for (int r : seen) ++uses_[r];
    }
  }

  int newTemp(int width) {
    int r = ir_.newReg(width);
    loc_.push_back(Loc{});
    loc_[r].placed = true;
    loc_[r].temp = true;
    def_.push_back(-1);
    uses_.push_back(0);
    return r;
  }

  // ---- 1. placement ----------------------------------------------------------------------------
  void placeInputs() {
    int nextV = 0;
    std::map<std::pair<int, int>, int> byUsage;
    for (const IrInst& in : ir_.code) {
      if (in.op != IrOp::Input) continue;
      const IrInput& input = ir_.inputs[in.index];
      Loc& l = loc_[in.dst];
      l.placed = true;
      auto key = std::make_pair(int(input.usage), input.usageIndex);
      if (!isPixel()) {
        l.type = RegType::Input;
        auto it = byUsage.find(key);
        l.index = it != byUsage.end() ? it->second : (byUsage[key] = nextV++);
        if (l.index >= 16) sink_.error(entryWhere_, "X4504", "too many vertex shader inputs (16 available)");
      } else if (input.isPosition) {
        l.type = RegType::MiscType;
        l.index = 0;
      } else if (input.isFace) {
        l.type = RegType::MiscType;
        l.index = 1;
      } else if (sm3()) {
        l.type = RegType::Input;
        auto it = byUsage.find(key);
        l.index = it != byUsage.end() ? it->second : (byUsage[key] = nextV++);
        if (l.index >= 10) sink_.error(entryWhere_, "X4504", "too many ps_3_0 inputs (10 available)");
      } else if (input.usage == shader::DeclUsage::TexCoord) {
        l.type = RegType::Texture;
        l.index = input.usageIndex;
        if (l.index >= 8) sink_.error(entryWhere_, "X4502", "invalid ps input semantic TEXCOORD{}", input.usageIndex);
      } else if (input.usage == shader::DeclUsage::Color) {
        l.type = RegType::Input;
        l.index = input.usageIndex;
        if (l.index >= 2) sink_.error(entryWhere_, "X4502", "invalid ps input semantic COLOR{}", input.usageIndex);
      } else {
        sink_.error(entryWhere_, "X4502", "invalid {} input semantic '{}'", v_.name(), input.semantic);
      }
      inputDecl_[{int(l.type), l.index}] |= uint8_t((1u << input.width) - 1);
      inputUsage_[{int(l.type), l.index}] = {input.usage, input.usageIndex};
    }
  }

  static int parseRegisterBinding(const std::string& s, char file) {
    if (s.empty() || std::tolower((unsigned char)s[0]) != file) return -1;
    const long n = std::strtol(s.c_str() + 1, nullptr, 10);
    return int(std::clamp(n, 0L, 1L << 20));  // far past any register file: reported as over the limit
  }

  void placeUniformsAndSamplers() {
    // Explicit register(cN) bindings first, then the rest in declaration order.
    // Registers past the end of `taken` are free; firstFreeConst_ follows the uniforms
    // however far they reach, so that a program over the limit is reported below.
    std::vector<bool> taken(8192, false);
    auto isTaken = [&](int r) { return r < int(taken.size()) && taken[size_t(r)]; };
    auto take = [&](const IrUniform& u) {
      for (int k = 0; k < u.registerCount && u.firstRegister + k < int(taken.size()); ++k)
        taken[size_t(u.firstRegister + k)] = true;
      firstFreeConst_ = std::max(firstFreeConst_, u.firstRegister + u.registerCount);
    };
    for (IrUniform& u : ir_.uniforms) {
      if (!u.used || !u.decl) continue;
      int r = parseRegisterBinding(u.decl->registerBinding, 'c');
      if (r < 0) continue;
      u.firstRegister = r;
      take(u);
    }
    int next = 0;
    for (IrUniform& u : ir_.uniforms) {
      if (!u.used || u.firstRegister >= 0) continue;
      for (;;) {
        bool fits = true;
        for (int k = 0; k < u.registerCount; ++k)
          if (isTaken(next + k)) { fits = false; break; }
        if (fits) break;
        ++next;
      }
      u.firstRegister = next;
      take(u);
      next += u.registerCount;
    }
    for (const IrInst& in : ir_.code) {
      if (in.op != IrOp::Uniform) continue;
      const IrUniform& u = ir_.uniforms[in.index & 0xFFFF];
      Loc& l = loc_[in.dst];
      l.placed = true;
      l.type = RegType::Const;
      l.index = u.firstRegister + (in.index >> 16);
    }
    // Samplers: those a live texture instruction reads.
    std::set<int> used;
    for (const IrInst& in : ir_.code)
      if (in.sampler >= 0) used.insert(in.sampler);
    std::vector<bool> sTaken(16, false);
    for (int s : used) {
      int r = ir_.samplers[s].decl ? parseRegisterBinding(ir_.samplers[s].decl->registerBinding, 's') : -1;
      if (r >= 0 && r < 16) { ir_.samplers[s].registerIndex = r; sTaken[r] = true; }
    }
    int nextS = 0;
    for (int s : used) {
      if (ir_.samplers[s].registerIndex >= 0) continue;
      while (nextS < 16 && sTaken[nextS]) ++nextS;
      if (nextS >= 16) { sink_.error(entryWhere_, "X4509", "too many samplers (16 available)"); break; }
      ir_.samplers[s].registerIndex = nextS;
      sTaken[nextS++] = true;
    }
    placeFlowUniforms();
    int limit = constLimit();
    if (firstFreeConst_ > limit) {
      sink_.error(entryWhere_, "X4550", "{} has {} constant registers, the uniforms need {}", v_.name(), limit, firstFreeConst_);
      constOverflowReported_ = true;
    }
  }

  // Int uniforms counting [loop]s get i# registers, bool uniforms of [branch]es b#.
  void placeFlowUniforms() {
    for (int pass = 0; pass < 2; ++pass)
      for (IrUniform& u : ir_.uniforms) {
        if (!u.loopCount && !u.branchBool) continue;
        std::vector<bool>& taken = u.loopCount ? intTaken_ : boolTaken_;
        const char file = u.loopCount ? 'i' : 'b';
        int r = u.decl ? parseRegisterBinding(u.decl->registerBinding, file) : -1;
        if (pass == 0) {  // explicit bindings first
          if (r < 0) continue;
          if (r >= 16) {
            sink_.error(u.decl->where, "X4551", "'{}': {} has {}0..{}15", u.name, v_.name(), file, file);
            continue;
          }
          if (u.used)
            sink_.error(u.decl->where, "X4551",
                        "'{}' is a {} register for flow control and is also read as a value; {} gives a uniform "
                        "one register set",
                        u.name, u.loopCount ? "loop count (i#)" : "branch condition (b#)", v_.name());
          u.flowRegister = r;
          taken[r] = true;
          continue;
        }
        if (r >= 0) continue;
        if (u.used)
          sink_.error(u.decl ? u.decl->where : entryWhere_, "X4551",
                      "'{}' is a {} register for flow control and is also read as a value; {} gives a uniform "
                      "one register set",
                      u.name, u.loopCount ? "loop count (i#)" : "branch condition (b#)", v_.name());
        auto free = std::find(taken.begin(), taken.end(), false);
        if (free == taken.end()) {
          sink_.error(entryWhere_, "X4551", "{} has 16 {} registers", v_.name(), u.loopCount ? "int" : "bool");
          continue;
        }
        u.flowRegister = int(free - taken.begin());
        *free = true;
      }
  }

  // i# holding a literal rep count (defi), shared by equal counts.
  int repCountRegister(int count) {
    if (auto it = repCounts_.find(count); it != repCounts_.end()) return it->second;
    auto free = std::find(intTaken_.begin(), intTaken_.end(), false);
    if (free == intTaken_.end()) {
      sink_.error(entryWhere_, "X4551", "{} has 16 int registers; the loops need more", v_.name());
      return 0;
    }
    *free = true;
    return repCounts_[count] = int(free - intTaken_.begin());
  }

  int constLimit() const {
    const shader::RegisterRule* r = shader::findRegisterRule(*rules_, RegType::Const);
    int n = r ? r->count : 256;
    if (!isPixel() && v_.major >= 2) n = std::max(n, 256);
    return n;
  }

  // Literal values go into `def` registers: splats share packed scalar slots.
  void placeLiterals() {
    for (const IrInst& in : ir_.code) {
      if (in.op != IrOp::Constant) continue;
      bool splat = true;
      for (int c = 1; c < in.width; ++c) splat &= in.literal[c] == in.literal[0];
      Loc& l = loc_[in.dst];
      l.placed = true;
      l.type = RegType::Const;
      if (splat) {
        auto [reg, slot] = scalarSlot(in.literal[0]);
        l.index = reg;
        l.map = {slot, slot, slot, slot};
      } else {
        std::array<float, 4> v{};
        for (int c = 0; c < 4; ++c) v[c] = in.literal[std::min(c, in.width - 1)];
        l.index = vectorDef(v);
      }
    }
  }

  std::pair<int, uint8_t> scalarSlot(float value) {
    for (auto& d : defs_)
      for (int s = 0; s < d.used; ++s)
        if (std::memcmp(&d.values[s], &value, 4) == 0) return {d.reg, uint8_t(s)};
    for (auto& d : defs_)
      if (d.packed && d.used < 4) {
        d.values[d.used] = value;
        return {d.reg, uint8_t(d.used++)};
      }
    Def d;
    d.reg = allocConst();
    d.packed = true;
    d.values[0] = value;
    d.used = 1;
    defs_.push_back(d);
    return {d.reg, 0};
  }

  int vectorDef(const std::array<float, 4>& v) {
    for (auto& d : defs_)
      if (!d.packed && std::memcmp(d.values.data(), v.data(), 16) == 0) return d.reg;
    Def d;
    d.reg = allocConst();
    d.values = v;
    d.used = 4;
    defs_.push_back(d);
    return d.reg;
  }

  int allocConst() {
    int r = firstFreeConst_++;
    if (r >= constLimit() && !constOverflowReported_) {
      constOverflowReported_ = true;
      sink_.error(entryWhere_, "X4550", "{} has {} constant registers; uniforms and literals need more", v_.name(),
                  constLimit());
    }
    return r;
  }

  // sincos writes .x (cos) and .y (sin) of its own register.
  void placeSpecialResults() {
    for (const IrInst& in : ir_.code)
      if (in.op == IrOp::SinCos) fixedMap_.insert(in.dst);
  }

  // ---- 2. coalescing ---------------------------------------------------------------------------
  // Ops whose destination may land in any component mapping.
  bool remappable(int vreg) const {
    int d = def_[vreg];
    if (d < 0 || fixedMap_.count(vreg)) return false;
    switch (ir_.code[d].op) {
      case IrOp::Input: case IrOp::Uniform: case IrOp::Constant: case IrOp::Combine: case IrOp::Kill:
      case IrOp::Tex: case IrOp::TexProj: case IrOp::TexBias: case IrOp::TexLod: case IrOp::TexGrad:
      case IrOp::Nrm: case IrOp::Crs: case IrOp::SinCos: case IrOp::Frc: case IrOp::Assign:
        return false;
      default:
        return true;
    }
  }

  // Which components of `parts` come from `vreg`: map[comp of vreg] = position; false
  // unless each component of vreg appears exactly once.
  bool partMap(const std::vector<IrPart>& parts, int vreg, Map& map) const {
    int width = ir_.regWidth[vreg];
    std::array<int, 4> pos{-1, -1, -1, -1};
    for (size_t i = 0; i < parts.size(); ++i) {
      if (parts[i].reg != vreg) continue;
      if (pos[parts[i].component] >= 0) return false;
      pos[parts[i].component] = int(i);
    }
    for (int c = 0; c < width; ++c) {
      if (pos[c] < 0) return false;
      map[c] = uint8_t(pos[c]);
    }
    // Components past the width are never read, but maps compose through aliases
    // component by component: they must name a component too.
    for (int c = width; c < 4; ++c) map[c] = c > 0 ? map[c - 1] : 0;
    return true;
  }

  struct OutputReg {
    RegType type;
    int index;
    bool scalar = false;  // oFog, oPts, oDepth
  };

  OutputReg outputRegister(const IrOutput& o) {
    using shader::DeclUsage;
    if (isPixel()) {
      if (o.usage == DeclUsage::Depth) return {RegType::DepthOut, 0, true};
      return {RegType::ColorOut, o.usageIndex};
    }
    if (sm3()) {
      auto key = std::make_pair(int(o.usage), o.usageIndex);
      auto it = vs3Outputs_.find(key);
      if (it != vs3Outputs_.end()) return {RegType::Output, it->second};
      int r = int(vs3Outputs_.size());
      vs3Outputs_[key] = r;
      return {RegType::Output, r};
    }
    switch (o.usage) {
      case DeclUsage::Position: return {RegType::RastOut, 0};
      case DeclUsage::Fog: return {RegType::RastOut, 1, true};
      case DeclUsage::PSize: return {RegType::RastOut, 2, true};
      case DeclUsage::Color: return {RegType::AttrOut, o.usageIndex};
      case DeclUsage::TexCoord: return {RegType::TexCrdOut, o.usageIndex};
      default: return {RegType::Temp, -1};
    }
  }

  bool outputWritableByAnyOp() const { return !isPixel() || sm3(); }

  // Registers among `parts` whose only reader is this gather or output and whose
  // producer can write any component mapping: they can be written in place.
  std::vector<std::pair<int, Map>> producersToPlace(const std::vector<IrPart>& parts) const {
    std::set<int> regs;
    for (const IrPart& p : parts)
      if (p.reg >= 0) regs.insert(p.reg);
    std::vector<std::pair<int, Map>> out;
    for (int vreg : regs) {
      Map m;
      if (uses_[vreg] == 1 && remappable(vreg) && !loc_[vreg].placed && partMap(parts, vreg, m)) out.emplace_back(vreg, m);
    }
    return out;
  }

  void coalesceOutputs() {
    outputRegs_.clear();
    for (IrOutput& o : ir_.outputs) {
      OutputReg r = outputRegister(o);
      outputRegs_.push_back(r);
      if (r.index < 0) {
        sink_.error(o.where, "X4502", "invalid {} output semantic '{}'", v_.name(), o.semantic);
        continue;
      }
      if (!isPixel() && !sm3()) {
        if (r.type == RegType::AttrOut && r.index >= 2) sink_.error(o.where, "X4502", "invalid {} output semantic '{}'", v_.name(), o.semantic);
        if (r.type == RegType::TexCrdOut && r.index >= 8) sink_.error(o.where, "X4502", "invalid {} output semantic '{}'", v_.name(), o.semantic);
      }
      if (isPixel() && r.type == RegType::ColorOut && r.index >= 4) sink_.error(o.where, "X4502", "invalid ps output semantic '{}'", o.semantic);
      if (isPixel() && !sm3() && !r.scalar && r.type == RegType::ColorOut) {
        // ps_2_x writes oC# by one mov of a whole temp: producers write that temp.
        int gather = newTemp(4);
        outputGather_[&o - &ir_.outputs[0]] = gather;
        for (auto [vreg, m] : producersToPlace(o.parts)) {
          Loc& l = loc_[vreg];
          l.placed = true;
          l.aliasOf = gather;
          l.map = m;
        }
        continue;
      }
      if (!outputWritableByAnyOp() || r.scalar) continue;
      for (auto [vreg, m] : producersToPlace(o.parts)) {
        Loc& l = loc_[vreg];
        l.placed = true;
        l.type = r.type;
        l.index = r.index;
        l.map = m;
        coalescedIntoOutput_.insert(vreg);
      }
    }
  }

  // A value whose only reader is an Assign (the end of a loop or branch body) is
  // computed in the variable's register, when nothing between the two reads or writes
  // that register and no flow-control marker lies between them. (Every producer that
  // may be remapped writes its destination once, after reading its sources.)
  void coalesceAssigns() {
    for (size_t i = 0; i < ir_.code.size(); ++i) {
      const IrInst& a = ir_.code[i];
      if (a.op != IrOp::Assign) continue;
      const IrSrc& s = a.src[0];
      const int p = s.reg, var = a.dst;
      if (s.negate || s.absolute || ir_.regWidth[p] != a.width || uses_[p] != 1 || loc_[p].placed || !remappable(p))
        continue;
      bool identity = true;
      for (int c = 0; c < a.width; ++c) identity &= s.swizzle[c] == c;
      const int d = def_[p];
      if (!identity || d < 0 || size_t(d) > i) continue;
      bool clear = true;
      for (size_t k = size_t(d) + 1; k < i && clear; ++k) {
        const IrInst& in = ir_.code[k];
        if (isFlowMarker(in.op) || (in.op == IrOp::Assign && in.dst == var)) clear = false;
        for (int j = 0; j < in.srcCount; ++j) clear &= in.src[j].reg != var;
        for (const IrPart& part : in.parts) clear &= part.reg != var;
      }
      if (!clear) continue;
      Loc& l = loc_[p];
      l.placed = true;
      l.aliasOf = var;
      l.map = kIdentity;
      assignedInPlace_.insert(int(i));
    }
  }

  void coalesceGathers() {
    for (const IrInst& in : ir_.code) {
      if (in.op != IrOp::Combine) continue;
      for (auto [vreg, m] : producersToPlace(in.parts)) {
        Loc& l = loc_[vreg];
        l.placed = true;
        l.aliasOf = in.dst;
        l.map = m;
      }
    }
  }

  // ---- 3. instruction selection ----------------------------------------------------------------
  MSrc src(const IrSrc& s) {
    MSrc m;
    m.vreg = s.reg;
    m.swizzle = s.swizzle;
    m.negate = s.negate;
    m.absolute = s.absolute;
    return m;
  }
  MSrc vsrc(int vreg, Map swz = kIdentity, bool neg = false) {
    MSrc m;
    m.vreg = vreg;
    m.swizzle = swz;
    m.negate = neg;
    return m;
  }
  MSrc literal(float value) {
    auto [reg, slot] = scalarSlot(value);
    MSrc m;
    m.type = RegType::Const;
    m.index = reg;
    m.swizzle = {slot, slot, slot, slot};
    return m;
  }
  static uint8_t maskOf(int width) { return uint8_t((1u << width) - 1); }
  MDst dst(int vreg, int width, bool sat = false) {
    MDst d;
    d.vreg = vreg;
    d.mask = maskOf(width);
    d.saturate = sat;
    return d;
  }

  void push(Opcode op, MDst d, std::initializer_list<MSrc> srcs, Shape shape = Shape::Componentwise, uint8_t control = 0) {
    MInst m;
    m.op = op;
    m.dst = d;
    m.srcCount = 0;
    for (const MSrc& s : srcs) m.src[m.srcCount++] = s;
    // rcp, exp, pow, sincos …: the opcode table's scalar instructions.
    const shader::OpcodeInfo* info = shader::findOpcode(op);
    m.shape = info && info->has(shader::OpScalarSource) ? Shape::Scalar : shape;
    m.control = control;
    m.where = where_;
    code_.push_back(m);
  }

  bool has(Opcode op) const { return shader::findOpcodeRule(*rules_, op) != nullptr; }

  void select(const IrInst& in) {
    where_ = in.where;
    const int w = in.width;
    const int d = in.dst;
    switch (in.op) {
      case IrOp::Input: case IrOp::Uniform: case IrOp::Constant: return;
      case IrOp::Rep: {
        MSrc count;
        count.type = RegType::ConstInt;
        count.index = in.uniform >= 0 ? ir_.uniforms[in.uniform].flowRegister : repCountRegister(in.index);
        flow(Opcode::Rep, {count});
        return;
      }
      case IrOp::EndRep: flow(Opcode::EndRep, {}); return;
      case IrOp::If:
        if (in.uniform >= 0) {
          MSrc b;
          b.type = RegType::ConstBool;
          b.index = ir_.uniforms[in.uniform].flowRegister;
          b.negate = in.index == 1;  // if !b#
          flow(Opcode::If, {b});
        } else {
          flow(Opcode::IfC, {replicated(in.src[0]), replicated(in.src[1])}, uint8_t(in.compare));
        }
        return;
      case IrOp::Else: flow(Opcode::Else, {}); return;
      case IrOp::EndIf: flow(Opcode::EndIf, {}); return;
      case IrOp::Break:
        if (in.srcCount == 0) flow(Opcode::Break, {});
        else flow(Opcode::BreakC, {replicated(in.src[0]), replicated(in.src[1])}, uint8_t(in.compare));
        return;
      case IrOp::Assign:
        a0Holds_ = {-1, -1, -1, -1};
        push(Opcode::Mov, dst(d, w), {src(in.src[0])});
        return;
      case IrOp::UniformRel: {
        loadAddress(in.src[0]);
        const IrUniform& u = ir_.uniforms[in.index & 0xFFFF];
        MSrc c;
        c.type = RegType::Const;
        c.index = u.firstRegister + (in.index >> 16);
        c.relative = true;
        push(Opcode::Mov, dst(d, 4), {c});
        return;
      }
      case IrOp::Combine: {
        // One mov per source register (or literal value) for the parts not coalesced.
        std::map<int, uint8_t> byReg;
        std::map<float, uint8_t> byLiteral;
        for (size_t i = 0; i < in.parts.size(); ++i) {
          const IrPart& p = in.parts[i];
          if (p.reg >= 0 && loc_[p.reg].aliasOf == d) continue;
          if (p.reg >= 0) byReg[p.reg] |= uint8_t(1u << i);
          else byLiteral[p.literal] |= uint8_t(1u << i);
        }
        for (auto [reg, mask] : byReg) {
          Map swz = kIdentity;
          for (size_t i = 0; i < in.parts.size(); ++i)
            if (mask & (1u << i)) swz[i] = in.parts[i].component;
          MDst md = dst(d, w);
          md.mask = mask;
          push(Opcode::Mov, md, {vsrc(reg, swz)});
        }
        movLiterals(byLiteral, in.parts, dst(d, w));
        return;
      }
      case IrOp::Mov:
        if (in.src[0].absolute && !sm3()) {
          IrSrc plain = in.src[0];
          plain.absolute = false;
          absolute(d, w, src(plain), in.saturate);
          return;
        }
        push(Opcode::Mov, dst(d, w, in.saturate), {src(in.src[0])});
        return;
      case IrOp::Add: push(Opcode::Add, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1])}); return;
      case IrOp::Mul: push(Opcode::Mul, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1])}); return;
      case IrOp::Mad: push(Opcode::Mad, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1]), src(in.src[2])}); return;
      case IrOp::Min: push(Opcode::Min, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1])}); return;
      case IrOp::Max: push(Opcode::Max, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1])}); return;
      case IrOp::Dp3: push(Opcode::Dp3, dst(d, 1, in.saturate), {src(in.src[0]), src(in.src[1])}, Shape::Positional); return;
      case IrOp::Dp4: push(Opcode::Dp4, dst(d, 1, in.saturate), {src(in.src[0]), src(in.src[1])}, Shape::Positional); return;
      case IrOp::Dp2:
        if (isPixel() && has(Opcode::Dp2Add)) {
          push(Opcode::Dp2Add, dst(d, 1, in.saturate), {src(in.src[0]), src(in.src[1]), literal(0)}, Shape::Positional);
        } else {
          int t = newTemp(2);
          push(Opcode::Mul, dst(t, 2), {src(in.src[0]), src(in.src[1])});
          push(Opcode::Add, dst(d, 1, in.saturate), {vsrc(t, {0, 0, 0, 0}), vsrc(t, {1, 1, 1, 1})});
        }
        return;
      case IrOp::Slt: case IrOp::Sge:
        if (!isPixel()) {
          push(in.op == IrOp::Slt ? Opcode::Slt : Opcode::Sge, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1])});
        } else {
          // a - b >= 0 ? (sge: 1, slt: 0) : (sge: 0, slt: 1)
          int t = newTemp(w);
          MSrc nb = src(in.src[1]);
          nb.negate = !nb.negate;
          push(Opcode::Add, dst(t, w), {src(in.src[0]), nb});
          bool ge = in.op == IrOp::Sge;
          push(Opcode::Cmp, dst(d, w, in.saturate), {vsrc(t), literal(ge ? 1.f : 0.f), literal(ge ? 0.f : 1.f)});
        }
        return;
      case IrOp::Cmp:
        if (isPixel()) {
          push(Opcode::Cmp, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1]), src(in.src[2])});
        } else {
          // t = (x >= 0); d = z + t * (y - z)
          int t = newTemp(w), u = newTemp(w);
          push(Opcode::Sge, dst(t, w), {src(in.src[0]), literal(0)});
          MSrc nz = src(in.src[2]);
          nz.negate = !nz.negate;
          push(Opcode::Add, dst(u, w), {src(in.src[1]), nz});
          push(Opcode::Mad, dst(d, w, in.saturate), {vsrc(t), vsrc(u), src(in.src[2])});
        }
        return;
      case IrOp::Lrp:
        if (has(Opcode::Lrp)) {
          push(Opcode::Lrp, dst(d, w, in.saturate), {src(in.src[0]), src(in.src[1]), src(in.src[2])});
        } else {
          int u = newTemp(w);
          MSrc nz = src(in.src[2]);
          nz.negate = !nz.negate;
          push(Opcode::Add, dst(u, w), {src(in.src[1]), nz});
          push(Opcode::Mad, dst(d, w, in.saturate), {src(in.src[0]), vsrc(u), src(in.src[2])});
        }
        return;
      case IrOp::Frc:
        if (v_ == shader::Version{shader::ShaderType::Vertex, 1, 1}) {
          // vs_1_1 frc writes only .x/.y: one frc per pair of components into .xy
          for (int c = 0; c < w; c += 2) {
            int t = newTemp(2);
            Map swz = in.src[0].swizzle;
            Map pair = {swz[c], swz[std::min(c + 1, w - 1)], swz[std::min(c + 1, w - 1)], swz[std::min(c + 1, w - 1)]};
            MSrc s = src(in.src[0]);
            s.swizzle = pair;
            push(Opcode::Frc, dst(t, 2), {s});  // .xy: vs_1_1 allows only .y and .xy
            MDst md = dst(d, w, in.saturate);
            md.mask = uint8_t((c + 1 < w ? 3u : 1u) << c);
            Map back = {0, 0, 0, 0};
            back[c] = 0;
            if (c + 1 < 4) back[c + 1] = 1;
            push(Opcode::Mov, md, {vsrc(t, back)});
          }
          return;
        }
        push(Opcode::Frc, dst(d, w, in.saturate), {src(in.src[0])});
        return;
      case IrOp::Abs:
        absolute(d, w, src(in.src[0]), in.saturate);
        return;
      case IrOp::Nrm:
        if (has(Opcode::Nrm)) {
          push(Opcode::Nrm, dst(d, 3, in.saturate), {src(in.src[0])}, Shape::Positional);
        } else {
          int t = newTemp(1);
          push(Opcode::Dp3, dst(t, 1), {src(in.src[0]), src(in.src[0])}, Shape::Positional);
          push(Opcode::Rsq, dst(t, 1), {vsrc(t, {0, 0, 0, 0})});
          push(Opcode::Mul, dst(d, 3, in.saturate), {src(in.src[0]), vsrc(t, {0, 0, 0, 0})});
        }
        return;
      case IrOp::Crs: {
        // a.yzx * b.zxy - a.zxy * b.yzx
        auto rot = [](MSrc s, Map order) {
          Map o;
          for (int i = 0; i < 4; ++i) o[i] = s.swizzle[order[i]];
          s.swizzle = o;
          return s;
        };
        MSrc a = src(in.src[0]), b = src(in.src[1]);
        int t = newTemp(3);
        push(Opcode::Mul, dst(t, 3), {rot(a, {2, 0, 1, 3}), rot(b, {1, 2, 0, 3})});
        MSrc na = rot(a, {1, 2, 0, 3});
        push(Opcode::Mad, dst(d, 3, in.saturate), {na, rot(b, {2, 0, 1, 3}), vsrc(t, kIdentity, true)});
        return;
      }
      case IrOp::Rcp: scalar(Opcode::Rcp, in); return;
      case IrOp::Rsq: scalar(Opcode::Rsq, in); return;
      case IrOp::Exp2: scalar(Opcode::Exp, in); return;
      case IrOp::Log2: {
        // log of |x|, as the instruction defines it; log(0) = -inf is what HLSL expects
        scalar(Opcode::Log, in);
        return;
      }
      case IrOp::Pow:
        if (has(Opcode::Pow)) {
          MSrc a = src(in.src[0]), b = src(in.src[1]);
          a.swizzle.fill(in.src[0].swizzle[0]);
          b.swizzle.fill(in.src[1].swizzle[0]);
          push(Opcode::Pow, dst(d, 1, in.saturate), {a, b});
        } else {
          int t = newTemp(1);
          MSrc a = src(in.src[0]);
          a.swizzle.fill(in.src[0].swizzle[0]);
          push(Opcode::Log, dst(t, 1), {a});
          MSrc b = src(in.src[1]);
          b.swizzle.fill(in.src[1].swizzle[0]);
          push(Opcode::Mul, dst(t, 1), {vsrc(t, {0, 0, 0, 0}), b});
          push(Opcode::Exp, dst(d, 1, in.saturate), {vsrc(t, {0, 0, 0, 0})});
        }
        return;
      case IrOp::SinCos: sinCos(in); return;
      case IrOp::Dsx: push(Opcode::Dsx, dst(d, w, in.saturate), {src(in.src[0])}); return;
      case IrOp::Dsy: push(Opcode::Dsy, dst(d, w, in.saturate), {src(in.src[0])}); return;
      case IrOp::Tex: case IrOp::TexProj: case IrOp::TexBias: case IrOp::TexLod: case IrOp::TexGrad: {
        MSrc s;
        s.vreg = -1;
        s.type = RegType::Sampler;
        s.index = ir_.samplers[in.sampler].registerIndex;
        Opcode op = Opcode::Tex;
        uint8_t control = 0;
        if (in.op == IrOp::TexProj) control = 1;
        if (in.op == IrOp::TexBias) control = 2;
        if (in.op == IrOp::TexLod) op = Opcode::TexLdl;
        if (in.op == IrOp::TexGrad) op = Opcode::TexLdd;
        if (op == Opcode::TexLdd) push(op, dst(d, 4), {src(in.src[0]), s, src(in.src[1]), src(in.src[2])}, Shape::Positional);
        else push(op, dst(d, 4), {src(in.src[0]), s}, Shape::Positional, control);
        if (in.op == IrOp::Tex) code_.back().coordWidth = in.index;
        return;
      }
      case IrOp::Kill: {
        // texkill's operand is a destination token: a whole register, no swizzle or
        // modifier. Anything else is first copied into a temp with all four components.
        MSrc operand = src(in.src[0]);
        const int reg = in.src[0].reg;
        const bool whole = !operand.negate && !operand.absolute && operand.swizzle == kIdentity &&
                           ir_.regWidth[reg] == 4 && !loc_[reg].placed;
        if (!whole) {
          int t = newTemp(4);
          push(Opcode::Mov, dst(t, 4), {operand});
          operand = vsrc(t);
        }
        MInst m;
        m.op = Opcode::TexKill;
        m.hasDst = false;
        m.srcCount = 1;
        m.src[0] = operand;
        m.shape = Shape::Positional;
        m.where = where_;
        code_.push_back(m);
        return;
      }
    }
  }

  MSrc replicated(const IrSrc& s) {
    MSrc m = src(s);
    m.swizzle.fill(s.swizzle[0]);
    return m;
  }

  // A flow-control instruction (no destination). a0.x is not trusted across one.
  void flow(Opcode op, std::initializer_list<MSrc> srcs, uint8_t control = 0) {
    MInst m;
    m.op = op;
    m.hasDst = false;
    for (const MSrc& s : srcs) m.src[m.srcCount++] = s;
    m.shape = Shape::Scalar;
    m.control = control;
    m.where = where_;
    code_.push_back(m);
    a0Holds_ = {-1, -1, -1, -1};
  }

  // a0.x = the value of `s` (mova rounds it in vs_2_0+; vs_1_1's mov floors it), unless
  // a0.x holds it already.
  void loadAddress(const IrSrc& s) {
    const std::array<int, 4> key{s.reg, s.swizzle[0], int(s.negate), int(s.absolute)};
    if (a0Holds_ == key) return;
    a0Holds_ = key;
    MDst a;
    a.vreg = -1;
    a.type = RegType::Addr;
    a.index = 0;
    a.mask = 0x1;
    MSrc value = src(s);
    value.swizzle.fill(s.swizzle[0]);
    push(v_.atLeast(2, 0) ? Opcode::MovA : Opcode::Mov, a, {value});
  }

  // Literal parts of a gather or an output: one mov from a def register holding them
  // in place (or from a shared scalar slot when they are all the same value).
  void movLiterals(const std::map<float, uint8_t>& byLiteral, const std::vector<IrPart>& parts, MDst d) {
    if (byLiteral.empty()) return;
    uint8_t mask = 0;
    for (auto [value, m] : byLiteral) mask |= m;
    d.mask = mask;
    if (byLiteral.size() == 1) {
      push(Opcode::Mov, d, {literal(byLiteral.begin()->first)});
      return;
    }
    std::array<float, 4> v{};
    Map dm = d.vreg >= 0 ? physicalMap(d.vreg) : kIdentity;
    for (size_t i = 0; i < parts.size(); ++i)
      if (mask & (1u << i)) v[dm[i]] = parts[i].literal;
    MSrc s;
    s.type = RegType::Const;
    s.index = vectorDef(v);
    s.swizzle = kIdentity;
    s.physicalOf = -1;
    // a fixed register read in physical components: mark as physical by vreg = -1
    push(Opcode::Mov, d, {s});
  }

  void absolute(int d, int w, MSrc s, bool sat) {
    if (has(Opcode::Abs)) {
      push(Opcode::Abs, dst(d, w, sat), {s});
      return;
    }
    MSrc n = s;
    n.negate = !n.negate;
    push(Opcode::Max, dst(d, w, sat), {s, n});
  }

  void scalar(Opcode op, const IrInst& in) {
    MSrc a = src(in.src[0]);
    a.swizzle.fill(in.src[0].swizzle[0]);
    push(op, dst(in.dst, 1, in.saturate), {a});
  }

  // The builder has reduced the argument to [-pi, pi]; .x = cos, .y = sin.
  void sinCos(const IrInst& in) {
    if (!has(Opcode::SinCos)) {
      sink_.error(in.where, "X9000", "internal error: {} has no sincos", v_.name());
      return;
    }
    MSrc a = src(in.src[0]);
    a.swizzle.fill(in.src[0].swizzle[0]);
    MDst md = dst(in.dst, 2, in.saturate);
    if (v_.major >= 3) {
      push(Opcode::SinCos, md, {a});
    } else {
      MSrc c1, c2;
      c1.type = c2.type = RegType::Const;
      c1.index = vectorDef({-1.55009923e-6f, -2.17013894e-5f, 0.00260416674f, 0.00026041668f});
      c2.index = vectorDef({-0.020833334f, -0.125f, 1.0f, 0.5f});
      push(Opcode::SinCos, md, {a, c1, c2});
    }
  }

  void writeOutputs() {
    for (size_t i = 0; i < ir_.outputs.size(); ++i) {
      const IrOutput& o = ir_.outputs[i];
      where_ = o.where;
      OutputReg r = outputRegs_[i];
      if (r.index < 0) continue;
      int width = int(o.parts.size());
      // Parts not already written by their producers.
      std::map<int, uint8_t> byReg;
      std::map<float, uint8_t> byLiteral;
      for (int c = 0; c < width; ++c) {
        const IrPart& p = o.parts[c];
        if (p.reg >= 0 && coalescedIntoOutput_.count(p.reg)) continue;
        if (p.reg >= 0 && outputGather_.count(int(i)) && loc_[p.reg].aliasOf == outputGather_[int(i)]) continue;
        if (p.reg >= 0) byReg[p.reg] |= uint8_t(1u << c);
        else byLiteral[p.literal] |= uint8_t(1u << c);
      }
      auto outDst = [&](uint8_t mask) {
        MDst md;
        md.vreg = -1;
        md.type = r.type;
        md.index = r.index;
        md.mask = mask;
        return md;
      };
      if (r.scalar) {
        const IrPart& p = o.parts[0];
        MSrc s = p.reg >= 0 ? vsrc(p.reg, {p.component, p.component, p.component, p.component}) : literal(p.literal);
        push(Opcode::Mov, outDst(r.type == RegType::DepthOut ? 0xF : 0x1), {s});
        outputMasks_[{int(r.type), r.index}] |= 1;
        continue;
      }
      if (isPixel() && !sm3()) {
        // ps_2_x: oC# only by one mov of a whole register.
        bool allLiteral = true;
        for (const IrPart& p : o.parts) allLiteral &= p.reg < 0;
        if (width == 4 && allLiteral) {
          MSrc lit;
          lit.type = RegType::Const;
          lit.index = vectorDef({o.parts[0].literal, o.parts[1].literal, o.parts[2].literal, o.parts[3].literal});
          push(Opcode::Mov, outDst(0xF), {lit});
          outputMasks_[{int(r.type), r.index}] = 0xF;
          continue;
        }
        int src = -1;
        bool whole = width == 4 && byLiteral.empty() && byReg.size() == 1;
        if (whole) {
          src = byReg.begin()->first;
          for (int c = 0; c < 4; ++c)
            if (o.parts[c].reg != src || o.parts[c].component != c || ir_.regWidth[src] != 4) whole = false;
        }
        if (!whole) {
          src = outputGather_.count(int(i)) ? outputGather_[int(i)] : newTemp(4);
          for (auto [reg, mask] : byReg) {
            Map swz = kIdentity;
            for (int c = 0; c < width; ++c)
              if (mask & (1u << c)) swz[c] = o.parts[c].component;
            MDst md = dst(src, 4);
            md.mask = mask;
            push(Opcode::Mov, md, {vsrc(reg, swz)});
          }
          movLiterals(byLiteral, o.parts, dst(src, 4));
          if (width < 4) {
            MDst md = dst(src, 4);
            md.mask = uint8_t(0xF & ~maskOf(width));
            push(Opcode::Mov, md, {literal(1.0f)});
          }
        }
        push(Opcode::Mov, outDst(0xF), {vsrc(src)});
        outputMasks_[{int(r.type), r.index}] = 0xF;
        continue;
      }
      for (auto [reg, mask] : byReg) {
        Map swz = kIdentity;
        for (int c = 0; c < width; ++c)
          if (mask & (1u << c)) swz[c] = o.parts[c].component;
        push(Opcode::Mov, outDst(mask), {vsrc(reg, swz)});
      }
      movLiterals(byLiteral, o.parts, outDst(0xF));
      outputMasks_[{int(r.type), r.index}] |= maskOf(width);
    }
  }

  // ---- 4. legalisation -------------------------------------------------------------------------
  // Physical location of a virtual register after aliasing.
  const Loc& root(int vreg) const {
    const Loc* l = &loc_[vreg];
    while (l->aliasOf >= 0) l = &loc_[l->aliasOf];
    return *l;
  }
  Map physicalMap(int vreg) const {
    // aliases compose: vreg comp i → alias comp map[i] → root comp
    Map m = loc_[vreg].map;
    int a = loc_[vreg].aliasOf;
    while (a >= 0) {
      Map next;
      for (int i = 0; i < 4; ++i) next[i] = loc_[a].map[m[i]];
      m = next;
      a = loc_[a].aliasOf;
    }
    return m;
  }
  RegType physicalType(int vreg) const {
    const Loc& l = root(vreg);
    return l.temp || !l.placed ? RegType::Temp : l.type;
  }

  // Destination components (physical) an instruction writes.
  uint8_t physicalMask(const MDst& d) const {
    if (d.vreg < 0) return d.mask;
    Map m = physicalMap(d.vreg);
    uint8_t out = 0;
    for (int i = 0; i < 4; ++i)
      if (d.mask & (1u << i)) out |= uint8_t(1u << m[i]);
    return out;
  }

  // The physical swizzle a source needs, per physical slot (255 = don't care).
  std::array<uint8_t, 4> physicalSwizzle(const MInst& m, const MSrc& s) const {
    std::array<uint8_t, 4> need{255, 255, 255, 255};
    // Fixed registers (and physical reads) carry their swizzle in physical slots.
    const bool physical = s.vreg < 0 || s.physicalOf >= 0;
    Map sm = !physical ? physicalMap(s.vreg) : kIdentity;
    auto comp = [&](int logical) { return !physical ? sm[s.swizzle[logical]] : s.swizzle[logical]; };
    if (m.shape == Shape::Componentwise && m.hasDst) {
      Map dm = m.dst.vreg >= 0 ? physicalMap(m.dst.vreg) : kIdentity;
      for (int i = 0; i < 4; ++i)
        if (m.dst.mask & (1u << i)) need[dm[i]] = physical ? s.swizzle[dm[i]] : comp(i);
    } else {
      for (int i = 0; i < 4; ++i) need[i] = comp(i);
    }
    return need;
  }

  static bool matches(const std::array<uint8_t, 4>& need, Map swz) {
    for (int i = 0; i < 4; ++i)
      if (need[i] != 255 && need[i] != swz[i]) return false;
    return true;
  }

  // A legal swizzle for the version that satisfies `need`, if one exists.
  std::optional<Map> legalSwizzle(const std::array<uint8_t, 4>& need, bool texCoord) const {
    Map filled;
    uint8_t last = 0;
    bool any = false;
    for (int i = 0; i < 4; ++i)
      if (need[i] != 255) { last = need[i]; any = true; }
    if (!any) return kIdentity;
    for (int i = 0; i < 4; ++i) filled[i] = need[i] == 255 ? last : need[i];
    if (texCoord && v_.isPixel() && v_.major == 2) {
      if (matches(need, kIdentity)) return kIdentity;
      return std::nullopt;
    }
    if (matches(need, kIdentity)) return kIdentity;
    if (rules_->swizzles == shader::SwizzleRule::Arbitrary) {
      // don't-cares repeat the component before them, so listings read ".xy", ".z"
      Map m;
      uint8_t prev = 255;
      for (int i = 0; i < 4; ++i)
        if (need[i] != 255) { prev = need[i]; break; }
      for (int i = 0; i < 4; ++i) {
        if (need[i] != 255) prev = need[i];
        m[i] = prev;
      }
      return m;
    }
    static const Map candidates[] = {{0, 1, 2, 3}, {0, 0, 0, 0}, {1, 1, 1, 1}, {2, 2, 2, 2}, {3, 3, 3, 3},
                                     {1, 2, 0, 3}, {2, 0, 1, 3}, {3, 2, 1, 0}};
    for (const Map& c : candidates)
      if (matches(need, c)) return c;
    (void)filled;
    return std::nullopt;
  }

  bool ps2xArbitrary() const { return false; }

  void legalise() {
    std::vector<MInst> out;
    out.reserve(code_.size());
    for (MInst m : code_) {
      // (a) swizzles the version cannot read: gather the components first.
      for (int s = 0; s < m.srcCount; ++s) {
        MSrc& src = m.src[s];
        if (src.vreg < 0 && (src.type == RegType::Sampler || src.type == RegType::ConstInt ||
                             src.type == RegType::ConstBool))
          continue;
        if (m.op == Opcode::SinCos && s > 0) continue;
        bool texCoord = (m.op == Opcode::Tex || m.op == Opcode::TexKill) && s == 0;
        auto need = sourceNeed(m, src);
        if (texCoord && v_.major == 2) {
          // ps_2_x reads coordinates from t# or r# only: a literal (def c#) goes through a temp.
          const RegType t = src.vreg >= 0 ? physicalType(src.vreg) : src.type;
          if (t != RegType::Temp && t != RegType::Texture) {
            gatherInto(out, m, src, need);
            continue;
          }
        }
        if (legalSwizzle(need, texCoord)) continue;
        gatherInto(out, m, src, need);
      }
      // (b) read ports: at most N different registers of a file per instruction.
      limitReadPorts(out, m);
      out.push_back(m);
    }
    code_ = std::move(out);
  }

  // Physical components a source must deliver; texld reads only the coordinate's
  // used components.
  std::array<uint8_t, 4> sourceNeed(const MInst& m, const MSrc& s) const {
    auto need = physicalSwizzle(m, s);
    int slots = 4;
    if (m.op == Opcode::Tex && &s == &m.src[0] && m.control == 0) slots = m.coordWidth;
    if (m.op == Opcode::Dp3 || m.op == Opcode::Nrm) slots = 3;
    if (m.op == Opcode::Dp2Add && &s != &m.src[2]) slots = 2;
    if (m.shape == Shape::Positional)
      for (int i = slots; i < 4; ++i) need[i] = 255;
    return need;
  }

  // Copies the needed components of `src` into a fresh temp laid out so that the
  // identity swizzle reads them; `src` then reads that temp.
  void gatherInto(std::vector<MInst>& out, const MInst& user, MSrc& src, const std::array<uint8_t, 4>& need) {
    int t = newTemp(4);
    MSrc base = physicalSource(src);
    base.negate = false;
    base.absolute = false;
    auto movInto = [&](uint8_t mask, Map swz) {
      MInst mv;
      mv.op = Opcode::Mov;
      mv.dst = dst(t, 4);
      mv.dst.mask = mask;
      mv.srcCount = 1;
      MSrc s = base;
      s.swizzle = swz;
      mv.src[0] = s;
      mv.shape = Shape::Componentwise;
      mv.where = user.where;
      out.push_back(mv);
    };
    uint8_t mask = 0;
    for (int i = 0; i < 4; ++i)
      if (need[i] != 255) mask |= uint8_t(1u << i);
    bool replicate = true;
    for (int i = 0; i < 4; ++i)
      if (need[i] != 255 && need[i] != need[std::countr_zero(unsigned(mask))]) replicate = false;
    // texkill reads the whole register, texld its coordinate without a swizzle.
    const bool wholeRegister = user.op == Opcode::TexKill || (user.op == Opcode::Tex && &src == &user.src[0]);
    if (replicate && !wholeRegister) {
      // one component read everywhere: copy it once and read it replicated
      uint8_t c = need[std::countr_zero(unsigned(mask))];
      movInto(1, {c, c, c, c});
      MSrc r = vsrc(t, {0, 0, 0, 0});
      r.negate = src.negate;
      r.absolute = src.absolute;
      src = r;
      return;
    }
    if (auto one = legalSwizzle(need, false)) {
      movInto(mask, *one);  // one mov when the version can read the swizzle
    } else {
      for (int i = 0; i < 4; ++i)
        if (need[i] != 255) movInto(uint8_t(1u << i), {need[i], need[i], need[i], need[i]});
    }
    MSrc r = vsrc(t);
    r.negate = src.negate;
    r.absolute = src.absolute;
    // the user reads the temp with the physical slots it needs: identity in logical
    // space for positional users; for componentwise users, logical comp i sits in slot dm[i].
    if (user.shape == Shape::Componentwise && user.hasDst) {
      Map dm = user.dst.vreg >= 0 ? physicalMap(user.dst.vreg) : kIdentity;
      for (int i = 0; i < 4; ++i) r.swizzle[i] = dm[i];
    }
    src = r;
  }

  // A source that names its register physically (swizzle in physical components).
  MSrc physicalSource(const MSrc& s) {
    if (s.vreg < 0) return s;
    MSrc p = s;
    p.physicalOf = s.vreg;
    return p;
  }

  void limitReadPorts(std::vector<MInst>& out, MInst& m) {
    for (RegType file : {RegType::Const, RegType::Input, RegType::Texture, RegType::Temp}) {
      const shader::RegisterRule* rule = shader::findRegisterRule(*rules_, file);
      if (!rule || rule->readPorts == 0) continue;
      std::vector<int> seen;
      for (int s = 0; s < m.srcCount; ++s) {
        MSrc& src = m.src[s];
        int key = registerKey(src);
        if (key < 0 || fileOf(src) != file) continue;
        if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
        if (int(seen.size()) < rule->readPorts) { seen.push_back(key); continue; }
        // over the limit: copy this source into a temp
        auto need = sourceNeed(m, src);
        gatherInto(out, m, src, need);
      }
    }
  }

  RegType fileOf(const MSrc& s) const {
    if (s.physicalOf >= 0) return physicalType(s.physicalOf);
    if (s.vreg >= 0) return physicalType(s.vreg);
    return s.type;
  }
  int registerKey(const MSrc& s) const {
    int v = s.physicalOf >= 0 ? s.physicalOf : s.vreg;
    if (v >= 0) {
      const Loc& l = root(v);
      if (l.temp || !l.placed) return 1000000 + rootId(v);
      return int(l.type) * 100000 + l.index;
    }
    return int(s.type) * 100000 + s.index;
  }
  int rootId(int v) const {
    while (loc_[v].aliasOf >= 0) v = loc_[v].aliasOf;
    return v;
  }

  // ---- 5. register allocation ------------------------------------------------------------------
  bool allocateTemps() {
    // Live range of each root temp: first write .. last read.
    size_t n = loc_.size();
    std::vector<int> first(n, -1), last(n, -1);
    auto isTempRoot = [&](int v) { const Loc& l = root(v); return l.temp || !l.placed; };
    for (int i = 0; i < int(code_.size()); ++i) {
      const MInst& m = code_[i];
      for (int s = 0; s < m.srcCount; ++s) {
        int v = m.src[s].physicalOf >= 0 ? m.src[s].physicalOf : m.src[s].vreg;
        if (v >= 0 && isTempRoot(v)) last[rootId(v)] = i;
      }
      if (m.hasDst && m.dst.vreg >= 0 && isTempRoot(m.dst.vreg)) {
        int r = rootId(m.dst.vreg);
        if (first[r] < 0) first[r] = i;
        last[r] = std::max(last[r], i);
      }
    }
    // A register read inside a loop but written before it is read again by the next
    // iteration: it stays live to the loop's end. (Nested loops: until nothing grows.)
    std::vector<std::pair<int, int>> loops;
    std::vector<int> open;
    for (int i = 0; i < int(code_.size()); ++i) {
      if (code_[i].op == Opcode::Rep || code_[i].op == Opcode::Loop) open.push_back(i);
      if ((code_[i].op == Opcode::EndRep || code_[i].op == Opcode::EndLoop) && !open.empty()) {
        loops.emplace_back(open.back(), i);
        open.pop_back();
      }
    }
    for (bool grew = !loops.empty(); grew;) {
      grew = false;
      for (auto [begin, end] : loops)
        for (size_t v = 0; v < n; ++v)
          if (first[v] >= 0 && first[v] < begin && last[v] > begin && last[v] < end) {
            last[v] = end;
            grew = true;
          }
    }
    const shader::RegisterRule* rule = shader::findRegisterRule(*rules_, RegType::Temp);
    int limit = rule ? rule->count : 12;
    physTemp_.assign(n, -1);
    std::vector<int> busyUntil;  // per physical temp: last instruction index using it
    int maxUsed = 0;
    // Process in order of first definition.
    std::vector<int> order;
    for (size_t v = 0; v < n; ++v)
      if (first[v] >= 0) order.push_back(int(v));
    std::sort(order.begin(), order.end(), [&](int a, int b) { return first[a] < first[b]; });
    for (int v : order) {
      int chosen = -1;
      for (size_t p = 0; p < busyUntil.size(); ++p)
        if (busyUntil[p] < first[v]) { chosen = int(p); break; }
      if (chosen < 0) { chosen = int(busyUntil.size()); busyUntil.push_back(-1); }
      busyUntil[chosen] = std::max(last[v], first[v]);
      physTemp_[v] = chosen;
      maxUsed = std::max(maxUsed, chosen + 1);
    }
    if (maxUsed > limit) {
      sink_.error(entryWhere_, "X4532", "cannot map expression to {} instruction set: needs {} temporary registers, {} has {}",
                  v_.name(), maxUsed, v_.name(), limit);
      return false;
    }
    return true;
  }

  // ---- 6. emission -----------------------------------------------------------------------------
  shader::DstParam physicalDst(const MDst& d) const {
    shader::DstParam p;
    if (d.vreg < 0) {
      p.type = d.type;
      p.index = uint16_t(d.index);
      p.writeMask = d.mask;
    } else {
      const Loc& l = root(d.vreg);
      if (l.temp || !l.placed) {
        p.type = RegType::Temp;
        p.index = uint16_t(physTemp_[rootId(d.vreg)]);
      } else {
        p.type = l.type;
        p.index = uint16_t(l.index);
      }
      p.writeMask = physicalMask(d);
    }
    if (d.saturate) p.resultMod = shader::ResultSaturate;
    return p;
  }

  shader::SrcParam physicalSrc(const MInst& m, const MSrc& s) const {
    shader::SrcParam p;
    int v = s.physicalOf >= 0 ? s.physicalOf : s.vreg;
    if (v < 0) {
      p.type = s.type;
      p.index = uint16_t(s.index);
    } else {
      const Loc& l = root(v);
      if (l.temp || !l.placed) {
        p.type = RegType::Temp;
        p.index = uint16_t(physTemp_[rootId(v)]);
      } else {
        p.type = l.type;
        p.index = uint16_t(l.index);
      }
    }
    std::array<uint8_t, 4> need;
    if (s.physicalOf >= 0 || s.vreg < 0) need = {s.swizzle[0], s.swizzle[1], s.swizzle[2], s.swizzle[3]};
    else need = sourceNeed(m, s);
    bool texCoord = (m.op == Opcode::Tex || m.op == Opcode::TexKill) && &s == &m.src[0];
    auto legal = legalSwizzle(need, texCoord);
    Map swz = legal ? *legal : Map{need[0] == 255 ? uint8_t(0) : need[0], need[1] == 255 ? uint8_t(1) : need[1],
                                   need[2] == 255 ? uint8_t(2) : need[2], need[3] == 255 ? uint8_t(3) : need[3]};
    if (s.physicalOf >= 0 || s.vreg < 0) swz = s.swizzle;
    if (p.type == RegType::Sampler) swz = kIdentity;
    if (s.relative) {
      p.relative = true;
      p.rel.type = RegType::Addr;
      p.rel.component = 0;
    }
    p.swizzle = uint8_t(swz[0] | (swz[1] << 2) | (swz[2] << 4) | (swz[3] << 6));
    if (s.absolute) p.mod = s.negate ? SrcMod::AbsNeg : SrcMod::Abs;
    else if (s.negate) p.mod = p.type == RegType::ConstBool ? SrcMod::Not : SrcMod::Neg;
    return p;
  }

  void emit(shader::Shader& out) {
    using shader::Instruction;
    // CTAB first, as fxc writes it.
    out.instructions.push_back(constantTableComment());
    // def
    for (const Def& d : defs_) {
      Instruction in;
      in.opcode = Opcode::Def;
      in.hasDst = true;
      in.dst.type = RegType::Const;
      in.dst.index = uint16_t(d.reg);
      for (int c = 0; c < 4; ++c) std::memcpy(&in.literal[c], &d.values[c], 4);
      out.instructions.push_back(in);
    }
    // defi: literal rep counts
    for (auto [count, reg] : repCounts_) {
      Instruction in;
      in.opcode = Opcode::DefI;
      in.hasDst = true;
      in.dst.type = RegType::ConstInt;
      in.dst.index = uint16_t(reg);
      in.literal = {uint32_t(count), 0, 0, 0};
      out.instructions.push_back(in);
    }
    // dcl inputs
    for (auto& [key, mask] : inputDecl_) {
      Instruction in;
      in.opcode = Opcode::Dcl;
      in.hasDst = true;
      in.dst.type = RegType(key.first);
      in.dst.index = uint16_t(key.second);
      auto usage = inputUsage_[key];
      in.usage = usage.first;
      in.usageIndex = uint8_t(usage.second);
      if (isPixel() && !sm3() && (in.dst.type == RegType::Input || in.dst.type == RegType::Texture)) {
        in.usage = shader::DeclUsage::Position;
        in.usageIndex = 0;
      }
      in.dst.writeMask = isPixel() ? mask : 0xF;
      if (in.dst.type == RegType::MiscType) {
        in.usage = shader::DeclUsage::Position;
        in.usageIndex = 0;
        in.dst.writeMask = in.dst.index == 0 ? 0x3 : 0xF;
        if (in.dst.index == 1) in.dst.writeMask = 0xF;
      }
      out.instructions.push_back(in);
    }
    // dcl outputs (vs_3_0)
    if (!isPixel() && sm3()) {
      for (size_t i = 0; i < ir_.outputs.size(); ++i) {
        const IrOutput& o = ir_.outputs[i];
        const OutputReg& r = outputRegs_[i];
        if (r.index < 0) continue;
        Instruction in;
        in.opcode = Opcode::Dcl;
        in.hasDst = true;
        in.dst.type = RegType::Output;
        in.dst.index = uint16_t(r.index);
        in.dst.writeMask = maskOf(int(o.parts.size()));
        in.usage = o.usage;
        in.usageIndex = uint8_t(o.usageIndex);
        out.instructions.push_back(in);
      }
    }
    // dcl samplers
    for (const IrSampler& s : ir_.samplers) {
      if (s.registerIndex < 0) continue;
      Instruction in;
      in.opcode = Opcode::Dcl;
      in.hasDst = true;
      in.dst.type = RegType::Sampler;
      in.dst.index = uint16_t(s.registerIndex);
      switch (s.dim) {
        case SamplerDim::Cube: in.textureType = shader::TextureType::Cube; break;
        case SamplerDim::Dim3D: in.textureType = shader::TextureType::Volume; break;
        default: in.textureType = shader::TextureType::Tex2D; break;
      }
      out.instructions.push_back(in);
    }
    for (const MInst& m : code_) {
      Instruction in;
      in.opcode = m.op;
      in.control = m.control;
      in.hasDst = m.hasDst;
      if (m.hasDst) in.dst = physicalDst(m.dst);
      in.srcCount = uint8_t(m.srcCount);
      for (int s = 0; s < m.srcCount; ++s) in.src[s] = physicalSrc(m, m.src[s]);
      if (m.op == Opcode::TexKill) {  // the operand is encoded as a destination
        in.hasDst = true;
        in.dst.type = in.src[0].type;
        in.dst.index = in.src[0].index;
        in.dst.writeMask = 0xF;
        in.srcCount = 0;
      }
      in.pos = {m.where.line, m.where.column};
      out.instructions.push_back(in);
    }
  }

  shader::Instruction constantTableComment() const { return detail::constantTableComment(ir_, creator_, v_); }

  struct Def {
    int reg = 0;
    std::array<float, 4> values{};
    int used = 0;
    bool packed = false;
  };

  IrProgram& ir_;
  std::string creator_;
  DiagnosticSink& sink_;
  SourceLocation entryWhere_;
  SourceLocation where_;
  shader::Version v_;
  const shader::VersionRules* rules_ = nullptr;
  std::vector<Loc> loc_;
  std::vector<int> def_;
  std::vector<int> uses_;
  std::vector<int> physTemp_;
  std::set<int> fixedMap_;
  std::set<int> coalescedIntoOutput_;
  std::map<int, int> outputGather_;  // ps_2_x: output index → gather temp
  std::vector<OutputReg> outputRegs_;
  std::map<std::pair<int, int>, int> vs3Outputs_;
  std::map<std::pair<int, int>, uint8_t> inputDecl_;
  std::map<std::pair<int, int>, std::pair<shader::DeclUsage, int>> inputUsage_;
  std::map<std::pair<int, int>, uint8_t> outputMasks_;
  std::vector<Def> defs_;
  int firstFreeConst_ = 0;
  bool constOverflowReported_ = false;
  std::vector<MInst> code_;
  std::array<int, 4> a0Holds_{-1, -1, -1, -1};  // the source a0.x was last loaded from
  std::vector<bool> intTaken_ = std::vector<bool>(16, false), boolTaken_ = std::vector<bool>(16, false);
  std::map<int, int> repCounts_;  // literal rep count → i# (defi)
  std::set<int> assignedInPlace_;  // Assigns whose value was computed in the variable's register
};

}  // namespace

shader::Shader generateCode(IrProgram& ir, const std::string& creator, DiagnosticSink& sink,
                            const SourceLocation& entryWhere) {
  CodeGen g(ir, creator, sink, entryWhere);
  return g.run();
}

}  // namespace refx::hlsl::detail
