// fx_2_0 preshader blobs: writing, reading and running FXLC code (fx2-binary.md §5).
#include "fxlc.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "refx/core/diagnostics.h"

namespace refx::effect::detail {

namespace {

constexpr uint32_t kCtab = 0x42415443, kPrsi = 0x49535250, kClit = 0x54494C43, kFxlc = 0x434C5846;
constexpr uint32_t kEnd = 0x0000FFFF;
// fxc appends these two DWORDs after the instructions inside the FXLC comment.
constexpr uint32_t kTrailer0 = 0xF0F0F0F0, kTrailer1 = 0x0F0F0F0F;

uint32_t comment(uint32_t dwords) { return (dwords << 16) | 0xFFFE; }

struct OpInfo {
  uint32_t opcode;
  uint32_t inputs;
  const char* name;
};
constexpr OpInfo kOps[] = {
    {fxlc_op::Nop, 0, "nop"},   {fxlc_op::Mov, 1, "mov"},     {fxlc_op::Neg, 1, "neg"},   {fxlc_op::Rcp, 1, "rcp"},
    {fxlc_op::Frc, 1, "frc"},   {fxlc_op::Exp, 1, "exp"},     {fxlc_op::Log, 1, "log"},   {fxlc_op::Rsq, 1, "rsq"},
    {fxlc_op::Sin, 1, "sin"},   {fxlc_op::Cos, 1, "cos"},     {fxlc_op::Asin, 1, "asin"}, {fxlc_op::Acos, 1, "acos"},
    {fxlc_op::Atan, 1, "atan"}, {fxlc_op::Min, 2, "min"},     {fxlc_op::Max, 2, "max"},   {fxlc_op::Lt, 2, "lt"},
    {fxlc_op::Ge, 2, "ge"},     {fxlc_op::Add, 2, "add"},     {fxlc_op::Mul, 2, "mul"},   {fxlc_op::Atan2, 2, "atan2"},
    {fxlc_op::Div, 2, "div"},   {fxlc_op::Cmp, 3, "cmp"},     {fxlc_op::Dot, 2, "dot"},
};

const OpInfo* opInfo(uint32_t opcode, size_t inputs) {
  for (const OpInfo& o : kOps)
    if (o.opcode == opcode && o.inputs == inputs) return &o;
  return nullptr;
}

// A byte writer for the constant table (offsets relative to the table's start).
struct Bytes {
  std::vector<uint8_t> b;
  size_t u32(uint32_t v) {
    const size_t at = b.size();
    for (int i = 0; i < 4; ++i) b.push_back(uint8_t(v >> (8 * i)));
    return at;
  }
  void u16(uint16_t v) {
    b.push_back(uint8_t(v));
    b.push_back(uint8_t(v >> 8));
  }
  void patch32(size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + size_t(i)] = uint8_t(v >> (8 * i));
  }
  void patch16(size_t at, uint16_t v) {
    b[at] = uint8_t(v);
    b[at + 1] = uint8_t(v >> 8);
  }
  uint32_t str(const std::string& s) {
    align();
    const uint32_t at = uint32_t(b.size());
    b.insert(b.end(), s.begin(), s.end());
    b.push_back(0);
    return at;
  }
  void align() {
    while (b.size() % 4) b.push_back(0);
  }
};

std::string operandText(const FxlcOperand& o) {
  auto reg = [](FxlcTable t, uint32_t off) -> std::string {
    const char* c = "xyzw";
    switch (t) {
      case FxlcTable::Literal: return fmt::format("lit{}", off);
      case FxlcTable::Input: return fmt::format("c{}.{}", off / 4, c[off % 4]);
      case FxlcTable::Output: return fmt::format("oc{}.{}", off / 4, c[off % 4]);
      case FxlcTable::BoolOutput: return fmt::format("ob{}", off / 4);
      case FxlcTable::IntOutput: return fmt::format("oi{}.{}", off / 4, c[off % 4]);
      case FxlcTable::Temp: return fmt::format("r{}.{}", off / 4, c[off % 4]);
    }
    return fmt::format("?{}", off);
  };
  if (!o.indexed) return reg(o.table, o.offset);
  return fmt::format("{}[{}]", reg(o.table, o.offset), reg(o.indexTable, o.indexOffset));
}

}  // namespace

std::vector<int> FxlcProgram::outputRegisters() const {
  std::set<int> regs;
  for (const FxlcInstruction& in : code)
    if (in.output.table == FxlcTable::Output)
      for (uint32_t c = 0; c < in.count; ++c) regs.insert(int((in.output.offset + c) / 4));
  return {regs.begin(), regs.end()};
}

std::vector<float> FxlcProgram::run(std::span<const float> inputRegisters) const {
  std::vector<double> temps;
  std::vector<float> out;
  auto indexOf = [&](const FxlcOperand& o, uint32_t c) -> size_t {
    size_t off = size_t(o.offset) + c;
    if (o.indexed) {
      FxlcOperand idx{o.indexTable, o.indexOffset};
      double v = 0;
      switch (idx.table) {
        case FxlcTable::Input: v = idx.indexOffset < inputRegisters.size() ? inputRegisters[idx.indexOffset] : 0.0; break;
        case FxlcTable::Temp: v = idx.indexOffset < temps.size() ? temps[idx.indexOffset] : 0.0; break;
        case FxlcTable::Literal: v = idx.indexOffset < literals.size() ? literals[idx.indexOffset] : 0.0; break;
        default: break;
      }
      const double r = std::nearbyint(v);
      if (r > 0 && r < 65536) off += size_t(r) * 4;
    }
    return off;
  };
  auto read = [&](const FxlcOperand& o, uint32_t c) -> double {
    const size_t i = indexOf(o, c);
    switch (o.table) {
      case FxlcTable::Literal: return i < literals.size() ? literals[i] : 0.0;
      case FxlcTable::Input: return i < inputRegisters.size() ? double(inputRegisters[i]) : 0.0;
      case FxlcTable::Temp: return i < temps.size() ? temps[i] : 0.0;
      case FxlcTable::Output: return i < out.size() ? double(out[i]) : 0.0;
      default: return 0.0;
    }
  };
  auto write = [&](const FxlcOperand& o, uint32_t c, double v) {
    const size_t i = size_t(o.offset) + c;
    if (i >= (size_t(1) << 16)) return;
    if (o.table == FxlcTable::Temp) {
      if (temps.size() <= i) temps.resize(i + 1, 0.0);
      temps[i] = v;
    } else if (o.table == FxlcTable::Output) {
      if (out.size() <= i) out.resize((i / 4 + 1) * 4, 0.0f);
      out[i] = float(v);
    }
  };
  for (const FxlcInstruction& in : code) {
    const uint32_t n = std::min<uint32_t>(in.count, 4);
    auto arg = [&](size_t k, uint32_t c) { return read(in.inputs[k], k == 0 && in.scalar ? 0 : c); };
    if (in.opcode == fxlc_op::Dot) {
      double sum = 0;
      for (uint32_t c = 0; c < n; ++c) sum += arg(0, c) * arg(1, c);
      write(in.output, 0, sum);
      continue;
    }
    double r[4] = {};
    for (uint32_t c = 0; c < n; ++c) {
      const double a = in.inputs.size() > 0 ? arg(0, c) : 0.0;
      const double b = in.inputs.size() > 1 ? arg(1, c) : 0.0;
      const double d = in.inputs.size() > 2 ? arg(2, c) : 0.0;
      double v = 0;
      switch (in.opcode) {
        case fxlc_op::Mov: v = a; break;
        case fxlc_op::Neg: v = -a; break;
        case fxlc_op::Rcp: v = 1.0 / a; break;
        case fxlc_op::Frc: v = a - std::floor(a); break;
        case fxlc_op::Exp: v = std::exp2(a); break;
        case fxlc_op::Log: v = a == 0 ? 0.0 : std::log2(std::fabs(a)); break;
        case fxlc_op::Rsq: v = a == 0 ? std::numeric_limits<double>::infinity() : 1.0 / std::sqrt(std::fabs(a)); break;
        case fxlc_op::Sin: v = std::sin(a); break;
        case fxlc_op::Cos: v = std::cos(a); break;
        case fxlc_op::Asin: v = std::asin(a); break;
        case fxlc_op::Acos: v = std::acos(a); break;
        case fxlc_op::Atan: v = std::atan(a); break;
        case fxlc_op::Min: v = std::fmin(a, b); break;
        case fxlc_op::Max: v = std::fmax(a, b); break;
        case fxlc_op::Lt: v = a < b ? 1.0 : 0.0; break;
        case fxlc_op::Ge: v = a >= b ? 1.0 : 0.0; break;
        case fxlc_op::Add: v = a + b; break;
        case fxlc_op::Mul: v = a * b; break;
        case fxlc_op::Atan2: v = std::atan2(a, b); break;
        case fxlc_op::Div: v = 0; break;  // native d3dx9 (Wine's tests): always 0
        case fxlc_op::Cmp: v = a >= 0 ? b : d; break;
        default: v = 0; break;
      }
      r[c] = v;
    }
    // All components are read before any is written (an output may overlap an input).
    for (uint32_t c = 0; c < n; ++c) write(in.output, c, r[c]);
  }
  return out;
}

std::string FxlcProgram::listing() const {
  std::string s;
  for (const FxlcInstruction& in : code) {
    const OpInfo* o = opInfo(in.opcode, in.inputs.size());
    s += fmt::format("{}{} {}", o ? o->name : "op?", in.count > 1 ? fmt::format("{}", in.count) : "",
                     operandText(in.output));
    for (const FxlcOperand& i : in.inputs) s += ", " + operandText(i);
    s += "\n";
  }
  return s;
}

std::vector<uint32_t> encodeConstantTable(const shader::ShaderConstantTable& table, uint32_t version) {
  Bytes w;
  w.u32(28);
  const size_t creatorAt = w.u32(0);
  w.u32(version);
  w.u32(uint32_t(table.constants.size()));
  const size_t infoOffsetAt = w.u32(0);
  w.u32(0x100);  // flags seen in fxc's preshader tables
  const size_t targetAt = w.u32(0);
  const size_t infoAt = w.b.size();
  if (!table.constants.empty()) w.patch32(infoOffsetAt, uint32_t(infoAt));
  for (size_t i = 0; i < table.constants.size(); ++i)
    for (int k = 0; k < 5; ++k) w.u32(0);
  for (size_t i = 0; i < table.constants.size(); ++i) {
    const shader::ShaderConstant& c = table.constants[i];
    const size_t at = infoAt + 20 * i;
    w.patch32(at, w.str(c.name));
    w.patch16(at + 4, uint16_t(c.registerSet));
    w.patch16(at + 6, uint16_t(c.registerIndex));
    w.patch16(at + 8, uint16_t(c.registerCount));
    w.align();
    w.patch32(at + 12, uint32_t(w.b.size()));
    w.u16(uint16_t(c.cls));
    w.u16(uint16_t(c.type));
    w.u16(uint16_t(c.rows));
    w.u16(uint16_t(c.columns));
    w.u16(uint16_t(c.elements));
    w.u16(0);
    w.u32(0);
    if (!c.defaultValue.empty()) {
      w.patch32(at + 16, uint32_t(w.b.size()));
      for (float f : c.defaultValue) w.u32(std::bit_cast<uint32_t>(f));
    }
  }
  w.patch32(creatorAt, w.str(table.creator.empty() ? "refx" : table.creator));
  w.patch32(targetAt, w.str(table.target.empty() ? "tx" : table.target));
  w.align();
  std::vector<uint32_t> out{kCtab};
  for (size_t i = 0; i < w.b.size(); i += 4)
    out.push_back(uint32_t(w.b[i]) | uint32_t(w.b[i + 1]) << 8 | uint32_t(w.b[i + 2]) << 16 |
                  uint32_t(w.b[i + 3]) << 24);
  return out;
}

std::vector<uint32_t> encodeFxlc(const FxlcProgram& program, uint32_t version, bool prsi) {
  std::vector<uint32_t> out{version};
  auto block = [&](const std::vector<uint32_t>& payload) {
    out.push_back(comment(uint32_t(payload.size())));
    out.insert(out.end(), payload.begin(), payload.end());
  };
  shader::ShaderConstantTable inputs = program.inputs;
  if (inputs.target.empty()) inputs.target = "tx";
  block(encodeConstantTable(inputs, version));
  if (prsi) {
    // PRSI (§5.8): first output float register, two unknowns, the output register
    // count, two unknowns, then (register, count) runs and a closing zero pair.
    const std::vector<int> regs = program.outputRegisters();
    std::vector<std::pair<uint32_t, uint32_t>> runs;
    for (int r : regs) {
      if (!runs.empty() && runs.back().first + runs.back().second == uint32_t(r)) ++runs.back().second;
      else runs.push_back({uint32_t(r), 1});
    }
    const uint32_t first = regs.empty() ? 0 : uint32_t(regs.front());
    const uint32_t span = regs.empty() ? 0 : uint32_t(regs.back() - regs.front() + 1);
    std::vector<uint32_t> p{kPrsi, first, 0, 0, span, 0, 0, uint32_t(runs.size())};
    for (const auto& [r, n] : runs) {
      p.push_back(r);
      p.push_back(n);
    }
    p.push_back(0);
    p.push_back(0);
    block(p);
  }
  std::vector<double> lits = program.literals;
  while (lits.size() % 4) lits.push_back(0.0);  // Wine requires a multiple of 4
  std::vector<uint32_t> clit{kClit, uint32_t(lits.size())};
  for (double d : lits) {
    const uint64_t bits = std::bit_cast<uint64_t>(d);
    clit.push_back(uint32_t(bits));
    clit.push_back(uint32_t(bits >> 32));
  }
  block(clit);
  std::vector<uint32_t> code{kFxlc, uint32_t(program.code.size())};
  auto operand = [&](const FxlcOperand& o) {
    if (o.indexed) {
      for (uint32_t w : {1u, uint32_t(o.indexTable), o.indexOffset, uint32_t(o.table), o.offset}) code.push_back(w);
    } else {
      for (uint32_t w : {0u, uint32_t(o.table), o.offset}) code.push_back(w);
    }
  };
  for (const FxlcInstruction& in : program.code) {
    code.push_back((in.scalar ? 0x80000000u : 0u) | (in.opcode << 20) | (in.count & 0xFFFF));
    code.push_back(uint32_t(in.inputs.size()));
    for (const FxlcOperand& i : in.inputs) operand(i);
    operand(in.output);
  }
  code.push_back(kTrailer0);
  code.push_back(kTrailer1);
  block(code);
  out.push_back(kEnd);
  return out;
}

FxlcProgram decodeFxlc(std::span<const uint32_t> t, const std::string& what, size_t at) {
  auto bad = [&](size_t i, const std::string& msg) -> void {
    fail("{}: error: offset 0x{:x}: {}", what, at + 4 * i, msg);
  };
  if (t.empty() || (t[0] & 0xFFFF0000u) != 0x46580000u)
    bad(0, fmt::format("a preshader must start with its version token 0x4658xxxx, not 0x{:08x}", t.empty() ? 0 : t[0]));
  FxlcProgram p;
  bool haveCtab = false, haveFxlc = false, haveClit = false;
  size_t i = 1;
  for (;;) {
    if (i >= t.size()) bad(i, "the preshader ends without its end token 0x0000FFFF");
    if (t[i] == kEnd) break;
    if ((t[i] & 0xFFFF) != 0xFFFE) bad(i, fmt::format("expected a comment token in the preshader, found 0x{:08x}", t[i]));
    const size_t n = t[i] >> 16;
    if (n > t.size() - i - 1) bad(i, fmt::format("a comment of {} DWORDs runs past the preshader's end", n));
    const std::span<const uint32_t> body = t.subspan(i + 1, n);
    const size_t bodyAt = i + 1;
    if (n >= 1 && body[0] == kCtab) {
      auto table = shader::readConstantTable(body);
      if (!table) bad(bodyAt, "the preshader's constant table (CTAB) cannot be read");
      for (const shader::ShaderConstant& c : table->constants)
        if (c.registerSet != shader::RegisterSet::Float4 || c.registerCount > 4096)
          bad(bodyAt, fmt::format("preshader input '{}' is not in float4 registers", c.name));
      p.inputs = std::move(*table);
      haveCtab = true;
    } else if (n >= 1 && body[0] == kClit) {
      if (n < 2) bad(bodyAt, "CLIT without a literal count");
      const size_t count = body[1];
      if (count > (n - 2) / 2) bad(bodyAt + 1, fmt::format("CLIT says {} literals; the block holds {}", count, (n - 2) / 2));
      for (size_t k = 0; k < count; ++k)
        p.literals.push_back(std::bit_cast<double>(uint64_t(body[2 + 2 * k]) | uint64_t(body[3 + 2 * k]) << 32));
      haveClit = true;
    } else if (n >= 1 && body[0] == kFxlc) {
      if (n < 2) bad(bodyAt, "FXLC without an instruction count");
      size_t k = 2;
      const size_t count = body[1];
      auto need = [&](size_t words) {
        if (k + words > n) bad(bodyAt + k, "an FXLC instruction runs past the end of its block");
      };
      auto operand = [&]() {
        need(1);
        FxlcOperand o;
        const uint32_t kind = body[k];
        auto table = [&](uint32_t v, size_t where) {
          if (v != 1 && v != 2 && v != 4 && v != 5 && v != 6 && v != 7) bad(bodyAt + where, fmt::format("unknown FXLC register table {}", v));
          return FxlcTable(v);
        };
        if (kind == 0) {
          need(3);
          o.table = table(body[k + 1], k + 1);
          o.offset = body[k + 2];
          k += 3;
        } else if (kind == 1) {
          need(5);
          o.indexed = true;
          o.indexTable = table(body[k + 1], k + 1);
          o.indexOffset = body[k + 2];
          o.table = table(body[k + 3], k + 3);
          o.offset = body[k + 4];
          k += 5;
        } else {
          bad(bodyAt + k, fmt::format("an FXLC operand starts with {} (0 or 1 expected)", kind));
        }
        if (o.offset >= (1u << 16) || o.indexOffset >= (1u << 16))
          bad(bodyAt + k - 1, fmt::format("FXLC register offset {} is out of range", o.offset));
        return o;
      };
      for (size_t c = 0; c < count; ++c) {
        need(2);
        const size_t instAt = k;
        FxlcInstruction in;
        const uint32_t word = body[k];
        in.scalar = (word & 0x80000000u) != 0;
        in.opcode = (word >> 20) & 0x7FF;
        in.count = word & 0xFFFF;
        const uint32_t inputs = body[k + 1];
        k += 2;
        if (in.count < 1 || in.count > 4) bad(bodyAt + instAt, fmt::format("FXLC component count {} (1 to 4)", in.count));
        if (!opInfo(in.opcode, inputs))
          bad(bodyAt + instAt, fmt::format("unknown FXLC instruction: opcode 0x{:03x} with {} inputs", in.opcode, inputs));
        for (uint32_t a = 0; a < inputs; ++a) in.inputs.push_back(operand());
        in.output = operand();
        if (in.output.indexed) bad(bodyAt + k - 5, "an FXLC output cannot be indexed");
        if (in.output.table == FxlcTable::Literal || in.output.table == FxlcTable::Input)
          bad(bodyAt + k - 3, "an FXLC output must be a temporary or an output register");
        p.code.push_back(std::move(in));
      }
      haveFxlc = true;
    }
    i += 1 + n;
  }
  if (!haveCtab || !haveClit || !haveFxlc)
    bad(0, fmt::format("the preshader lacks its {} block", !haveCtab ? "CTAB" : !haveClit ? "CLIT" : "FXLC"));
  return p;
}

}  // namespace refx::effect::detail
