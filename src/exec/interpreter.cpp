#include "refx/exec/interpreter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace refx::exec {

namespace {

constexpr int N = kBatchLanes;
using Lanes = float[N];

void BatchRegistersResize(BatchRegisters& r, const Program& p) {
  r.temps.resize(std::max(p.tempCount, 1));
  r.inputs.resize(std::max(p.inputCount, 1));
  r.outputs.resize(std::max(p.outputCount, 1));
}

// Returns the lane array of component `c` of a lane-varying register, or nullptr
// for uniform files.
inline const float* laneBase(const BatchRegisters& regs, RegFile f, int index, int c) {
  switch (f) {
    case RegFile::Temp: return regs.temps[index].c[c];
    case RegFile::Input: return regs.inputs[index].c[c];
    case RegFile::Output: return regs.outputs[index].c[c];
    default: return nullptr;
  }
}

inline float applyMod(float x, SrcMod m) {
  switch (m) {
    case SrcMod::None: return x;
    case SrcMod::Neg: return -x;
    case SrcMod::Bias: return x - 0.5f;
    case SrcMod::BiasNeg: return -(x - 0.5f);
    case SrcMod::Sign: return 2.0f * (x - 0.5f);
    case SrcMod::SignNeg: return -2.0f * (x - 0.5f);
    case SrcMod::Comp: return 1.0f - x;
    case SrcMod::X2: return 2.0f * x;
    case SrcMod::X2Neg: return -2.0f * x;
    case SrcMod::Abs: return std::fabs(x);
    case SrcMod::AbsNeg: return -std::fabs(x);
  }
  return x;
}

// Fetches a source operand into `scratch` unless it can be read in place; returns
// per-component lane pointers.
struct Operand {
  const float* c[4];
};

inline void fetch(const Src& s, const BatchRegisters& regs, const ExecContext& ctx,
                  const Program& p, float (*scratch)[N], Operand& o) {
  bool uniform = s.file == RegFile::Const || s.file == RegFile::Imm;
  if (!uniform && s.mod == SrcMod::None) {
    const LaneVec4* base = s.file == RegFile::Temp    ? &regs.temps[s.index]
                           : s.file == RegFile::Input ? &regs.inputs[s.index]
                                                      : &regs.outputs[s.index];
    o.c[0] = base->c[s.swizzle & 3];
    o.c[1] = base->c[(s.swizzle >> 2) & 3];
    o.c[2] = base->c[(s.swizzle >> 4) & 3];
    o.c[3] = base->c[(s.swizzle >> 6) & 3];
    return;
  }
  if (uniform) {
    Vec4 v{0, 0, 0, 0};
    if (s.file == RegFile::Imm) {
      if (s.index < p.immediates.size()) v = p.immediates[s.index];
    } else if (s.index < ctx.constantCount) {
      v = ctx.constants[s.index];
    }
    for (int c = 0; c < 4; ++c) {
      float x = applyMod(v[(s.swizzle >> (2 * c)) & 3], s.mod);
      for (int l = 0; l < N; ++l) scratch[c][l] = x;
      o.c[c] = scratch[c];
    }
    return;
  }
  for (int c = 0; c < 4; ++c) {
    const float* b = laneBase(regs, s.file, s.index, (s.swizzle >> (2 * c)) & 3);
    float* d = scratch[c];
    switch (s.mod) {
      case SrcMod::Neg: for (int l = 0; l < N; ++l) d[l] = -b[l]; break;
      case SrcMod::Comp: for (int l = 0; l < N; ++l) d[l] = 1.0f - b[l]; break;
      case SrcMod::Sign: for (int l = 0; l < N; ++l) d[l] = 2.0f * (b[l] - 0.5f); break;
      default: for (int l = 0; l < N; ++l) d[l] = applyMod(b[l], s.mod); break;
    }
    o.c[c] = d;
  }
}

// Sixteen lanes as two 8-lane values (GCC/Clang vector extensions): the arithmetic
// below is vectorised whatever the compiler's loop heuristics decide, with the same
// IEEE operations per lane as a plain loop.
typedef float v8f __attribute__((vector_size(32)));
struct V16 {
  v8f lo, hi;
};
inline V16 load(const float* p) {
  V16 r;
  std::memcpy(&r.lo, p, sizeof r.lo);
  std::memcpy(&r.hi, p + 8, sizeof r.hi);
  return r;
}
inline void store(float* p, const V16& v) {
  std::memcpy(p, &v.lo, sizeof v.lo);
  std::memcpy(p + 8, &v.hi, sizeof v.hi);
}
template <class F>
inline V16 lanes(F f) {
  return V16{f(0), f(1)};
}
inline v8f part(const V16& v, int h) { return h ? v.hi : v.lo; }
// x in every lane (a broadcast: -0 stays -0, unlike 0 + x).
inline v8f splat8(float x) { return v8f{x, x, x, x, x, x, x, x}; }
inline v8f vmin(v8f a, v8f b) { return a < b ? a : b; }
inline v8f vmax(v8f a, v8f b) { return a > b ? a : b; }

void sample(const Instr& in, const Operand& coord, const ExecContext& ctx, uint16_t laneMask,
            float (*out)[N]) {
  alignas(64) float co[4][N];
  const float(*cp)[N] = co;
  // Coordinates read in place when they are one register's .xyzw.
  const bool inPlace = in.op != Op::TexProj && coord.c[1] == coord.c[0] + N &&
                       coord.c[2] == coord.c[0] + 2 * N && coord.c[3] == coord.c[0] + 3 * N;
  if (inPlace) cp = reinterpret_cast<const float(*)[N]>(coord.c[0]);
  else
    for (int c = 0; c < 4; ++c) std::memcpy(co[c], coord.c[c], sizeof(co[c]));
  SampleMode mode = SampleMode::Implicit;
  switch (in.op) {
    case Op::TexProj:
      // Projected lookup: divide by w before sampling (texldp / D3DTTFF_PROJECTED).
      for (int l = 0; l < N; ++l) {
        float iw = 1.0f / co[3][l];
        co[0][l] *= iw;
        co[1][l] *= iw;
        co[2][l] *= iw;
      }
      break;
    case Op::TexBias: mode = SampleMode::Bias; break;
    case Op::TexLod: mode = SampleMode::Lod; break;
    default: break;
  }
  if (in.sampler < ctx.samplerCount && ctx.samplers[in.sampler].sample) {
    const SamplerBinding& b = ctx.samplers[in.sampler];
    b.sample(b.context, mode, cp, laneMask, out);
  } else {
    // Unbound sampler: D3D returns (0,0,0,1).
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < N; ++l) out[c][l] = c == 3 ? 1.0f : 0.0f;
  }
}

}  // namespace

void BatchRegisters::resize(const Program& p) { BatchRegistersResize(*this, p); }

namespace {

// Source counts by op, looked up once.
const std::array<uint8_t, 256> kSources = [] {
  std::array<uint8_t, 256> t{};
  for (int op = 0; op <= int(Op::Kill); ++op) t[op] = uint8_t(sourceCount(Op(op)));
  return t;
}();

// One instruction, decoded as it runs: the reference path for every op and operand.
void executeInstr(const Instr& in, const Program& program, const ExecContext& ctx,
                  BatchRegisters& regs) {
  alignas(64) float scratch[3][4][N];
  alignas(64) float res[4][N];
  {
    const int nsrc = kSources[uint8_t(in.op)];
    Operand s[3];
    bool alias = false;  // the destination is also a source: stage results in res
    for (int i = 0; i < nsrc; ++i) {
      fetch(in.src[i], regs, ctx, program, scratch[i], s[i]);
      alias |= in.src[i].file == in.dst.file && in.src[i].index == in.dst.index;
    }
    const uint8_t mask = in.dst.mask;
    LaneVec4* dstReg = in.dst.file == RegFile::Temp    ? &regs.temps[in.dst.index]
                       : in.dst.file == RegFile::Input ? &regs.inputs[in.dst.index]
                       : in.dst.file == RegFile::Output ? &regs.outputs[in.dst.index]
                                                        : nullptr;
    // Result modifiers: shift, then saturate or clamp to the version's range.
    const bool clampResult = in.saturate || in.clamp;
    const v8f scale = splat8(in.shift == 0 ? 1.0f : std::ldexp(1.0f, in.shift));
    const v8f lo = splat8(in.saturate ? 0.0f : in.clampLo), hi = splat8(in.saturate ? 1.0f : in.clampHi);
    auto modify = [&](V16 r) {
      if (in.shift != 0) r = lanes([&](int h) { return part(r, h) * scale; });
      // Clamp with NaN -> lo (D3D saturates NaN to 0).
      if (clampResult) r = lanes([&](int h) { return vmin(vmax(part(r, h), lo), hi); });
      return r;
    };
    // Without aliasing, results go straight to the destination.
    const bool direct = !alias && dstReg;
    auto emit = [&](int c, const V16& r) {
      if (direct) store(dstReg->c[c], modify(r));
      else store(res[c], r);
    };
    // Lane-wise ops: f(h, a, b, c) on the 8-lane halves of each written component.
    auto each1 = [&](auto&& f) {
      for (int c = 0; c < 4; ++c)
        if (mask & (1 << c)) {
          const V16 a = load(s[0].c[c]);
          emit(c, lanes([&](int h) { return f(part(a, h)); }));
        }
    };
    auto each2 = [&](auto&& f) {
      for (int c = 0; c < 4; ++c)
        if (mask & (1 << c)) {
          const V16 a = load(s[0].c[c]), b = load(s[1].c[c]);
          emit(c, lanes([&](int h) { return f(part(a, h), part(b, h)); }));
        }
    };
    auto each3 = [&](auto&& f) {
      for (int c = 0; c < 4; ++c)
        if (mask & (1 << c)) {
          const V16 a = load(s[0].c[c]), b = load(s[1].c[c]), d = load(s[2].c[c]);
          emit(c, lanes([&](int h) { return f(part(a, h), part(b, h), part(d, h)); }));
        }
    };
    bool staged = !direct;  // results in res still to be stored
    auto each = [&](auto&& f) {  // per-lane ops: always staged
      staged = true;
      for (int c = 0; c < 4; ++c)
        if (mask & (1 << c)) f(c, res[c]);
    };
    const v8f zero = splat8(0.0f), one = splat8(1.0f);
    switch (in.op) {
      case Op::Mov:
        each1([](v8f a) { return a; });
        break;
      case Op::Add:
        each2([](v8f a, v8f b) { return a + b; });
        break;
      case Op::Sub:
        each2([](v8f a, v8f b) { return a - b; });
        break;
      case Op::Mul:
        each2([](v8f a, v8f b) { return a * b; });
        break;
      case Op::Mad:
        each3([](v8f a, v8f b, v8f d) { return a * b + d; });
        break;
      case Op::Dp3:
      case Op::Dp4:
      case Op::Dp2Add: {
        V16 x[2][4];
        const int comps = in.op == Op::Dp4 ? 4 : in.op == Op::Dp3 ? 3 : 2;
        for (int k = 0; k < comps; ++k) x[0][k] = load(s[0].c[k]), x[1][k] = load(s[1].c[k]);
        const V16 add = in.op == Op::Dp2Add ? load(s[2].c[0]) : V16{};
        const V16 d = lanes([&](int h) {
          v8f r = part(x[0][0], h) * part(x[1][0], h) + part(x[0][1], h) * part(x[1][1], h);
          if (in.op == Op::Dp2Add) return r + part(add, h);
          r += part(x[0][2], h) * part(x[1][2], h);
          if (in.op == Op::Dp4) r += part(x[0][3], h) * part(x[1][3], h);
          return r;
        });
        for (int c = 0; c < 4; ++c)
          if (mask & (1 << c)) emit(c, d);
        break;
      }
      case Op::Rcp:
        // D3D: rcp(0) = +inf; scalar op on the source's first (replicated) component.
        each1([&](v8f a) { return one / a; });
        break;
      case Op::Rsq:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = 1.0f / std::sqrt(std::fabs(s[0].c[c][l]));
        });
        break;
      case Op::Min:
        each2([](v8f a, v8f b) { return a < b ? a : b; });
        break;
      case Op::Max:
        each2([](v8f a, v8f b) { return a > b ? a : b; });
        break;
      case Op::Slt:
        each2([&](v8f a, v8f b) { return a < b ? one : zero; });
        break;
      case Op::Sge:
        each2([&](v8f a, v8f b) { return a >= b ? one : zero; });
        break;
      case Op::Frc:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = s[0].c[c][l] - std::floor(s[0].c[c][l]);
        });
        break;
      case Op::Exp2:
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = std::exp2(s[0].c[c][l]); });
        break;
      case Op::Log2:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = std::log2(std::fabs(s[0].c[c][l]));
        });
        break;
      case Op::Pow:
        // D3D pow: |x|^y.
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = std::pow(std::fabs(s[0].c[c][l]), s[1].c[c][l]);
        });
        break;
      case Op::Lrp:
        each3([](v8f a, v8f b, v8f d) { return a * (b - d) + d; });
        break;
      case Op::Cmp:
        each3([&](v8f a, v8f b, v8f d) { return a >= zero ? b : d; });
        break;
      case Op::Cnd:
        each3([](v8f a, v8f b, v8f d) { return a > splat8(0.5f) ? b : d; });
        break;
      case Op::Abs:
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = std::fabs(s[0].c[c][l]); });
        break;
      case Op::Nrm: {
        float k[N];
        for (int l = 0; l < N; ++l) {
          float d = s[0].c[0][l] * s[0].c[0][l] + s[0].c[1][l] * s[0].c[1][l] +
                    s[0].c[2][l] * s[0].c[2][l];
          k[l] = 1.0f / std::sqrt(d);
        }
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = s[0].c[c][l] * k[l]; });
        break;
      }
      case Op::Tex:
      case Op::TexProj:
      case Op::TexBias:
      case Op::TexLod:
        if (direct && mask == 0xF && in.shift == 0 && !clampResult) {
          sample(in, s[0], ctx, regs.laneMask, dstReg->c);
          return;
        }
        sample(in, s[0], ctx, regs.laneMask, res);
        if (direct) {
          for (int c = 0; c < 4; ++c)
            if (mask & (1 << c)) store(dstReg->c[c], modify(load(res[c])));
          return;
        }
        break;
      case Op::Kill: {
        uint16_t killed = 0;
        for (int c = 0; c < 4; ++c) {
          if (!(mask & (1 << c))) continue;
          for (int l = 0; l < N; ++l)
            if (s[0].c[c][l] < 0.0f) killed |= uint16_t(1u << l);
        }
        regs.laneMask &= uint16_t(~killed);
        return;  // no register result
      }
    }
    if (!dstReg || !staged) return;
    // Results staged in res (aliasing, or ops written per lane): modifiers and store.
    for (int c = 0; c < 4; ++c)
      if (mask & (1 << c)) store(dstReg->c[c], modify(load(res[c])));
  }
}

// ---------------------------------------------------------------- prepared programs

struct Step;
using StepFn = void (*)(const Step&, const ExecContext&, BatchRegisters&);

// One instruction with its operands resolved to lane arrays.
struct Step {
  StepFn run;
  const Instr* in;
  const Program* program;
  const float* src[3][4];  // per source and component (swizzle applied)
  float* dst[4];           // written components, nullptr otherwise
  float scale, lo, hi;     // result modifiers
};

// The reference path for ops and operands without a specialised routine.
void runGeneric(const Step& s, const ExecContext& ctx, BatchRegisters& regs) {
  executeInstr(*s.in, *s.program, ctx, regs);
}

template <Op O>
inline V16 compute(const Step& s, int c) {
  auto src = [&](int i) { return load(s.src[i][c]); };
  auto dot = [&](int n) {
    V16 a[4], b[4];
    for (int k = 0; k < n; ++k) a[k] = load(s.src[0][k]), b[k] = load(s.src[1][k]);
    return lanes([&](int h) {
      v8f r = part(a[0], h) * part(b[0], h) + part(a[1], h) * part(b[1], h);
      for (int k = 2; k < n; ++k) r += part(a[k], h) * part(b[k], h);
      return r;
    });
  };
  if constexpr (O == Op::Mov) return src(0);
  else if constexpr (O == Op::Dp3) return dot(3);
  else if constexpr (O == Op::Dp4) return dot(4);
  else {
    const V16 a = src(0), b = src(1);
    if constexpr (O == Op::Add) return lanes([&](int h) { return part(a, h) + part(b, h); });
    else if constexpr (O == Op::Sub) return lanes([&](int h) { return part(a, h) - part(b, h); });
    else if constexpr (O == Op::Mul) return lanes([&](int h) { return part(a, h) * part(b, h); });
    else if constexpr (O == Op::Min) return lanes([&](int h) { return vmin(part(a, h), part(b, h)); });
    else if constexpr (O == Op::Max) return lanes([&](int h) { return vmax(part(a, h), part(b, h)); });
    else {
      const V16 d = src(2);
      if constexpr (O == Op::Mad)
        return lanes([&](int h) { return part(a, h) * part(b, h) + part(d, h); });
      else if constexpr (O == Op::Lrp)
        return lanes([&](int h) { return part(a, h) * (part(b, h) - part(d, h)) + part(d, h); });
      else  // Cmp
        return lanes([&](int h) { return part(a, h) >= splat8(0.0f) ? part(b, h) : part(d, h); });
    }
  }
}

// Same operations as executeInstr; all components are computed before any is
// stored, so a destination that is also a source reads its old value.
template <Op O, bool Shift, bool Clamp>
void runArith(const Step& s, const ExecContext&, BatchRegisters&) {
  V16 r[4];
  for (int c = 0; c < 4; ++c)
    if (s.dst[c]) r[c] = (O == Op::Dp3 || O == Op::Dp4) && c > 0 && s.dst[0] ? r[0] : compute<O>(s, c);
  const v8f scale = splat8(s.scale), lo = splat8(s.lo), hi = splat8(s.hi);
  for (int c = 0; c < 4; ++c) {
    if (!s.dst[c]) continue;
    V16 v = r[c];
    if constexpr (Shift) v = lanes([&](int h) { return part(v, h) * scale; });
    if constexpr (Clamp) v = lanes([&](int h) { return vmin(vmax(part(v, h), lo), hi); });
    store(s.dst[c], v);
  }
}

template <Op O>
StepFn arith(bool shift, bool clamp) {
  if (shift) return clamp ? runArith<O, true, true> : runArith<O, true, false>;
  return clamp ? runArith<O, false, true> : runArith<O, false, false>;
}

StepFn arithFor(Op op, bool shift, bool clamp) {
  switch (op) {
    case Op::Mov: return arith<Op::Mov>(shift, clamp);
    case Op::Add: return arith<Op::Add>(shift, clamp);
    case Op::Sub: return arith<Op::Sub>(shift, clamp);
    case Op::Mul: return arith<Op::Mul>(shift, clamp);
    case Op::Mad: return arith<Op::Mad>(shift, clamp);
    case Op::Min: return arith<Op::Min>(shift, clamp);
    case Op::Max: return arith<Op::Max>(shift, clamp);
    case Op::Lrp: return arith<Op::Lrp>(shift, clamp);
    case Op::Cmp: return arith<Op::Cmp>(shift, clamp);
    case Op::Dp3: return arith<Op::Dp3>(shift, clamp);
    case Op::Dp4: return arith<Op::Dp4>(shift, clamp);
    default: return nullptr;
  }
}

// tex with .xyzw coordinates of one register, all four components written, no
// result modifier and no overlap of coordinates and destination: the sampler reads
// and writes the registers in place.
void runTexInPlace(const Step& s, const ExecContext& ctx, BatchRegisters& regs) {
  const SamplerBinding& b = ctx.samplers[s.in->sampler];
  b.sample(b.context, SampleMode::Implicit, reinterpret_cast<const float(*)[N]>(s.src[0][0]),
           regs.laneMask, reinterpret_cast<float(*)[N]>(s.dst[0]));
}

float* laneArray(BatchRegisters& regs, RegFile f, int index, int c) {
  switch (f) {
    case RegFile::Temp: return index < int(regs.temps.size()) ? regs.temps[index].c[c] : nullptr;
    case RegFile::Input: return index < int(regs.inputs.size()) ? regs.inputs[index].c[c] : nullptr;
    case RegFile::Output: return index < int(regs.outputs.size()) ? regs.outputs[index].c[c] : nullptr;
    default: return nullptr;
  }
}

}  // namespace

struct PreparedProgram {
  const Program* program = nullptr;
  const Instr* code = nullptr;
  size_t size = 0;
  std::vector<Step> steps;
  std::vector<LaneVec4> uniforms;  // constant and immediate operands, splat over the lanes
};

void prepare(const Program& program, const ExecContext& ctx, BatchRegisters& regs) {
  auto pp = std::make_shared<PreparedProgram>();
  pp->program = &program;
  pp->code = program.code.data();
  pp->size = program.code.size();
  size_t uniformCount = 0;
  for (const Instr& in : program.code)
    for (int i = 0; i < kSources[uint8_t(in.op)]; ++i)
      uniformCount += in.src[i].file == RegFile::Const || in.src[i].file == RegFile::Imm;
  pp->uniforms.resize(uniformCount);
  size_t nextUniform = 0;
  for (const Instr& in : program.code) {
    Step st{};
    st.run = runGeneric;
    st.in = &in;
    st.program = &program;
    pp->steps.push_back(st);
    Step& s = pp->steps.back();
    const int nsrc = kSources[uint8_t(in.op)];
    bool resolved = true;
    for (int i = 0; i < nsrc; ++i) {
      const Src& src = in.src[i];
      if (src.file == RegFile::Const || src.file == RegFile::Imm) {
        // fetch() expands these per batch; the values are fixed for the draw.
        LaneVec4& u = pp->uniforms[nextUniform++];
        Vec4 v{0, 0, 0, 0};
        if (src.file == RegFile::Imm) {
          if (src.index < program.immediates.size()) v = program.immediates[src.index];
        } else if (src.index < ctx.constantCount) {
          v = ctx.constants[src.index];
        }
        for (int c = 0; c < 4; ++c) {
          const float x = applyMod(v[(src.swizzle >> (2 * c)) & 3], src.mod);
          for (int l = 0; l < N; ++l) u.c[c][l] = x;
          s.src[i][c] = u.c[c];
        }
        continue;
      }
      if (src.mod != SrcMod::None) resolved = false;
      for (int c = 0; c < 4; ++c) {
        s.src[i][c] = laneArray(regs, src.file, src.index, (src.swizzle >> (2 * c)) & 3);
        resolved &= s.src[i][c] != nullptr;
      }
    }
    for (int c = 0; c < 4; ++c)
      s.dst[c] = in.dst.mask >> c & 1 ? laneArray(regs, in.dst.file, in.dst.index, c) : nullptr;
    const bool anyDst = s.dst[0] || s.dst[1] || s.dst[2] || s.dst[3];
    const bool clamp = in.saturate || in.clamp;
    s.scale = in.shift == 0 ? 1.0f : std::ldexp(1.0f, in.shift);
    s.lo = in.saturate ? 0.0f : in.clampLo;
    s.hi = in.saturate ? 1.0f : in.clampHi;
    if (!resolved || !anyDst) continue;
    if (StepFn f = arithFor(in.op, in.shift != 0, clamp)) {
      s.run = f;
    } else if (in.op == Op::Tex && in.dst.mask == 0xF && in.shift == 0 && !clamp &&
               in.sampler < ctx.samplerCount && ctx.samplers[in.sampler].sample) {
      const float* c0 = s.src[0][0];
      const bool xyzw = s.src[0][1] == c0 + N && s.src[0][2] == c0 + 2 * N && s.src[0][3] == c0 + 3 * N;
      const bool disjoint = c0 + 4 * N <= s.dst[0] || s.dst[0] + 4 * N <= c0;
      if (xyzw && disjoint && s.dst[1] == s.dst[0] + N && s.dst[2] == s.dst[0] + 2 * N &&
          s.dst[3] == s.dst[0] + 3 * N)
        s.run = runTexInPlace;
    }
  }
  regs.prepared = std::move(pp);
}

void execute(const Program& program, const ExecContext& ctx, BatchRegisters& regs) {
  const PreparedProgram* pp = regs.prepared.get();
  if (pp && pp->program == &program && pp->code == program.code.data() &&
      pp->size == program.code.size()) {
    for (const Step& s : pp->steps) s.run(s, ctx, regs);
    return;
  }
  for (const Instr& in : program.code) executeInstr(in, program, ctx, regs);
}

}  // namespace refx::exec
