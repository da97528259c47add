// Register allocation and co-issue for the ps_1_x back end. Values live per
// component: a register component is free between the last read of one value and
// the write of the next, so a value written into .rgb can share a register with
// one still read in .a.
#include <algorithm>
#include <optional>
#include <set>

#include "hlsl/ps1x_program.h"

namespace refx::hlsl::detail::ps1x {

using shader::Opcode;
using shader::RegType;

uint8_t readMask(const MInst& m, int s) {
  uint8_t slots = m.mask;
  if (m.op == Opcode::Dp3 || m.texture) slots = 0x7;
  if (m.op == Opcode::Dp4) slots = 0xF;
  uint8_t r = 0;
  for (int c = 0; c < 4; ++c)
    if (slots >> c & 1) r |= uint8_t(1u << swizzleAt(m.src[s].swizzle, c));
  return r;
}

namespace {

// Per value and component: the position that writes it and the last that reads it.
struct Live {
  std::array<int, 4> start{-1, -1, -1, -1}, end{-1, -1, -1, -1};
  int first() const {
    int f = 1 << 30;
    for (int s : start)
      if (s >= 0) f = std::min(f, s);
    return f;
  }
};

// Two values may share a register component unless one is written while the other
// still has to be read (a write at the other's last read is fine: sources are read
// before the destination is written).
bool overlaps(const Live& a, const Live& b) {
  for (int k = 0; k < 4; ++k) {
    int sa = a.start[k], sb = b.start[k];
    if (sa < 0 || sb < 0) continue;
    int ea = std::max(a.end[k], sa), eb = std::max(b.end[k], sb);
    if (sa == sb || (sa < sb && sb < ea) || (sb < sa && sa < eb)) return true;
  }
  return false;
}

class Allocator {
 public:
  Allocator(Program& p, DiagnosticSink& sink, const SourceLocation& entryWhere)
      : p_(p), rules_(*p.rules), sink_(sink), entryWhere_(entryWhere) {
    for (int phase : {1, 2}) {
      for (MInst& m : p.tex[phase]) code_.push_back(&m);
      for (MInst& m : p.arith[phase]) code_.push_back(&m);
    }
  }

  bool run() {
    findLiveRanges();
    for (int v : allocationOrder())
      if (!place(v)) return false;
    p_.registers = assigned_;
    moveColorToR0();
    return true;
  }

 private:
  int count(RegType t) const {
    const shader::RegisterRule* r = shader::findRegisterRule(rules_, t);
    return r ? r->count : 0;
  }

  void findLiveRanges() {
    const int end = int(code_.size());
    for (int i = 0; i < end; ++i) {
      const MInst& m = *code_[i];
      for (int s = 0; s < m.srcCount; ++s) {
        if (m.src[s].value < 0) continue;
        Live& l = live_[m.src[s].value];
        uint8_t r = readMask(m, s);
        for (int k = 0; k < 4; ++k)
          if (r >> k & 1) l.end[k] = i;
      }
      if (m.dst < 0) continue;
      Live& l = live_[m.dst];
      for (int k = 0; k < 4; ++k)
        if ((m.mask >> k & 1) && l.start[k] < 0) l.start[k] = i;
    }
    if (p_.color >= 0)  // the color is read after the last instruction
      for (int k = 0; k < 4; ++k)
        if (live_[p_.color].start[k] >= 0) live_[p_.color].end[k] = end;
  }

  // Pinned values (texture stages) first, then the rest in order of their first write.
  std::vector<int> allocationOrder() {
    std::vector<int> order;
    for (auto& [v, l] : live_) order.push_back(v);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      bool pa = p_.homes[a].pinned, pb = p_.homes[b].pinned;
      if (pa != pb) return pa;
      return live_[a].first() < live_[b].first();
    });
    return order;
  }

  // r1… before r0, which the color wants at the end; ps_1_1 – 1_3 texture registers
  // not holding a texture are temporaries too.
  std::vector<Register> candidates(int v) const {
    const Home& h = p_.homes[v];
    if (h.pinned) return {{h.type, h.index}};
    std::vector<Register> c;
    if (v == p_.color) c.push_back({RegType::Temp, 0});
    for (int r = 1; r < count(RegType::Temp); ++r) c.push_back({RegType::Temp, r});
    if (v != p_.color) c.push_back({RegType::Temp, 0});
    if (!p_.ps14)
      for (int r = 0; r < count(RegType::Texture); ++r) c.push_back({RegType::Texture, r});
    return c;
  }

  bool place(int v) {
    for (const Register& r : candidates(v))
      if (fits(v, r)) {
        assigned_[v] = r;
        return true;
      }
    SourceLocation at = entryWhere_;
    for (const MInst* m : code_)
      if (m->dst == v) {
        at = m->where;
        break;
      }
    const Home& h = p_.homes[v];
    std::string what =
        h.pinned ? fmt::format("{}{} is needed by a texture read while it still holds a value",
                               h.type == RegType::Temp ? "r" : "t", h.index)
                 : fmt::format("needs more registers than the {} temporary registers {} has{}", count(RegType::Temp),
                               rules_.name, p_.ps14 ? "" : " (and the texture registers not holding a texture)");
    sink_.error(at, "X4532", "cannot map expression to {} instruction set: {}", rules_.name, what);
    return false;
  }

  std::optional<Register> registerOf(const Operand& o, int v, const Register& r) const {
    if (o.value == v) return r;
    if (o.value < 0) return Register{o.type, o.index};
    auto it = assigned_.find(o.value);
    if (it == assigned_.end()) return std::nullopt;
    return it->second;
  }

  // `v` in `r` clashes with no value already there, keeps every instruction within
  // its read ports, keeps ps_1_2/1_3 cmp from writing a register it reads, and
  // keeps ps_1_4 texture destinations of one phase apart.
  bool fits(int v, const Register& r) {
    for (const auto& [u, ur] : assigned_)
      if (ur == r && overlaps(live_[v], live_[u])) return false;
    for (const MInst* m : code_) {
      bool reads = false;
      for (int s = 0; s < m->srcCount; ++s) reads |= m->src[s].value == v;
      bool writes = m->dst == v;
      if (!reads && !writes) continue;
      if (reads && !withinReadPorts(*m, v, r)) return false;
      if (m->op == Opcode::Cmp && !p_.ps14) {
        std::optional<Register> d = writes ? std::optional<Register>(r) : std::nullopt;
        if (!d)
          if (auto it = assigned_.find(m->dst); it != assigned_.end()) d = it->second;
        if (d)
          for (int s = 0; s < m->srcCount; ++s)
            if (auto x = registerOf(m->src[s], v, r); x && *x == *d && (m->src[s].value == v || writes)) return false;
      }
      if (writes && m->texture && p_.ps14)
        for (const MInst* o : code_)
          if (o != m && o->texture && o->phase == m->phase && o->dst >= 0)
            if (auto it = assigned_.find(o->dst); it != assigned_.end() && it->second == r) return false;
    }
    return true;
  }

  bool withinReadPorts(const MInst& m, int v, const Register& r) const {
    std::map<RegType, std::set<int>> distinct;
    for (int s = 0; s < m.srcCount; ++s)
      if (auto x = registerOf(m.src[s], v, r)) distinct[x->type].insert(x->index);
    for (auto& [type, set] : distinct) {
      const shader::RegisterRule* rule = shader::findRegisterRule(rules_, type);
      if (rule && rule->readPorts && int(set.size()) > rule->readPorts) return false;
    }
    return true;
  }

  // The color landed elsewhere: r0 is free after the last instruction.
  void moveColorToR0() {
    if (p_.color < 0 || p_.registers.at(p_.color) == Register{RegType::Temp, 0}) return;
    int r0 = int(p_.homes.size());
    p_.homes.emplace_back();
    MInst m;
    m.op = Opcode::Mov;
    m.dst = r0;
    m.mask = p_.colorMask;
    m.src[m.srcCount++] = Operand{p_.color};
    m.where = p_.colorWhere;
    p_.arith[2].push_back(m);
    p_.registers[r0] = {RegType::Temp, 0};
  }

  Program& p_;
  const shader::VersionRules& rules_;
  DiagnosticSink& sink_;
  SourceLocation entryWhere_;
  std::vector<MInst*> code_;
  std::map<int, Live> live_;
  std::map<int, Register> assigned_;
};

bool identityOn(uint8_t swizzle, uint8_t mask) {
  for (int c = 0; c < 4; ++c)
    if ((mask >> c & 1) && swizzleAt(swizzle, c) != c) return false;
  return true;
}

// `x` reads a register component `w` writes.
bool readsWhatWrites(const Program& p, const MInst& x, const MInst& w) {
  Register wr = p.registers.at(w.dst);
  for (int s = 0; s < x.srcCount; ++s)
    if (p.registerOf(x.src[s]) == wr && (readMask(x, s) & w.mask)) return true;
  return false;
}

// Moving b above a would change what either computes.
bool touches(const Program& p, const MInst& a, const MInst& b) {
  if (readsWhatWrites(p, a, b) || readsWhatWrites(p, b, a)) return true;
  return p.registers.at(a.dst) == p.registers.at(b.dst) && (a.mask & b.mask);
}

// One writes .rgb (ps_1_4: part of it), the other .a; both may co-issue (dp3 only as
// the .rgb half); neither reads what the other writes, so DX8 hardware (both read
// first) and D3D9 (in order) compute the same.
bool pairable(const Program& p, const MInst& a, const MInst& b) {
  const shader::OpcodeRule* ra = shader::findOpcodeRule(*p.rules, a.op);
  const shader::OpcodeRule* rb = shader::findOpcodeRule(*p.rules, b.op);
  if (!ra || !rb || (ra->flags & shader::OpNoCoissue) || (rb->flags & shader::OpNoCoissue)) return false;
  auto color = [&](uint8_t m) { return p.ps14 ? (m && !(m & 0x8)) : m == 0x7; };
  bool aColor = color(a.mask) && b.mask == 0x8, bColor = color(b.mask) && a.mask == 0x8;
  if (!aColor && !bColor) return false;
  if ((aColor ? rb : ra)->flags & shader::OpVectorOnly) return false;
  return !readsWhatWrites(p, b, a) && !readsWhatWrites(p, a, b);
}

}  // namespace

bool allocateRegisters(Program& program, DiagnosticSink& sink, const SourceLocation& entryWhere) {
  return Allocator(program, sink, entryWhere).run();
}

void removeNoOpMoves(Program& p) {
  for (int phase : {1, 2}) {
    auto& list = p.arith[phase];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](const MInst& m) {
                                return m.op == Opcode::Mov && !m.saturate && !m.shift &&
                                       m.src[0].mod == shader::SrcMod::None && m.src[0].value >= 0 &&
                                       p.registerOf(m.src[0]) == p.registers.at(m.dst) &&
                                       identityOn(m.src[0].swizzle, m.mask);
                              }),
               list.end());
  }
}

// An instruction writing .a moves up beside an earlier one writing .rgb (or the other
// way round) when nothing in between touches what it reads or writes.
void pairCoissue(Program& p) {
  for (int phase : {1, 2}) {
    auto& list = p.arith[phase];
    std::vector<bool> paired(list.size(), false);
    for (size_t j = 1; j < list.size(); ++j) {
      if (paired[j]) continue;
      for (size_t i = j; i-- > 0;) {
        if (paired[i]) break;
        if (!pairable(p, list[i], list[j])) {
          if (touches(p, list[i], list[j])) break;
          continue;
        }
        MInst b = list[j];
        b.coissue = true;
        list.erase(list.begin() + long(j));
        list.insert(list.begin() + long(i) + 1, b);
        paired.erase(paired.begin() + long(j));
        paired.insert(paired.begin() + long(i) + 1, true);
        paired[i] = true;
        break;
      }
    }
  }
}

}  // namespace refx::hlsl::detail::ps1x
