#include "refx/exec/interpreter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "exec/jit/jit.h"
#include "exec/lane_math.h"

namespace refx::exec {

namespace {

constexpr int N = kBatchLanes;
using Lanes = float[N];

void BatchRegistersResize(BatchRegisters& r, const Program& p) {
  r.temps.resize(std::max(p.tempCount, 1));
  r.inputs.resize(std::max(p.inputCount, 1));
  r.outputs.resize(std::max(p.outputCount, 1));
}


// Fetches a source operand into `scratch` unless it can be read in place; returns
// per-component lane pointers.
struct Operand {
  const float* c[4];
};

alignas(64) const float kZeroLanes[4][N] = {};

// Value of register `index` of a uniform file (relative indices may be anything).
inline Vec4 uniformValue(const Src& s, int index, const ExecContext& ctx, const Program& p) {
  Vec4 v{0, 0, 0, 0};
  switch (s.file) {
    case RegFile::Imm:
      if (index >= 0 && size_t(index) < p.immediates.size()) v = p.immediates[index];
      break;
    case RegFile::Const:
      // Local (def) constants override the API's for the shader's lifetime.
      if (index >= 0 && size_t(index) < p.localConstants.size() && p.localConstants[index] >= 0)
        v = p.immediates[size_t(p.localConstants[index])];
      else if (index >= 0 && index < ctx.constantCount)
        v = ctx.constants[index];
      break;
    case RegFile::ConstInt:
      if (index >= 0 && index < ctx.intConstantCount && ctx.intConstants) {
        const auto& i = ctx.intConstants[index];
        v = Vec4(float(i[0]), float(i[1]), float(i[2]), float(i[3]));
      }
      break;
    case RegFile::ConstBool:
      if (index >= 0 && index < ctx.boolConstantCount && ctx.boolConstants && ctx.boolConstants[index])
        v = Vec4(1, 1, 1, 1);
      break;
    default: break;
  }
  if (s.flags & kSrcClampUnit)
    for (int c = 0; c < 4; ++c) v[c] = std::min(std::max(v[c], -1.0f), 1.0f);
  return v;
}

inline bool isUniformFile(RegFile f) {
  return f == RegFile::Const || f == RegFile::Imm || f == RegFile::ConstInt || f == RegFile::ConstBool;
}

inline const LaneVec4* laneRegister(const BatchRegisters& regs, RegFile f, int index) {
  const std::vector<LaneVec4>* v = f == RegFile::Temp    ? &regs.temps
                                   : f == RegFile::Input ? &regs.inputs
                                   : f == RegFile::Output ? &regs.outputs
                                                          : nullptr;
  if (!v || index < 0 || size_t(index) >= v->size()) return nullptr;
  return &(*v)[size_t(index)];
}

// Relative source: per-lane register index, then the same swizzle and modifier.
// The register index + a0: a0 truncated toward zero (as cvttps2dq). NaN, values beyond
// int's range and sums past it give INT_MIN, outside every register range, as the
// native code's 32-bit conversion and add do.
inline int relativeIndex(int base, float a0) {
  if (!(a0 > -2147483648.0f && a0 < 2147483648.0f)) return INT32_MIN;
  const int64_t sum = int64_t(base) + int64_t(int32_t(a0));
  return sum >= INT32_MIN && sum <= INT32_MAX ? int(sum) : INT32_MIN;
}

void fetchRelative(const Src& s, const BatchRegisters& regs, const ExecContext& ctx,
                   const Program& p, float (*scratch)[N], Operand& o) {
  int index[N];
  if (s.rel == RelMode::Loop) {
    for (int l = 0; l < N; ++l) index[l] = s.index + regs.loopCounter;
  } else {
    const LaneVec4* a = laneRegister(regs, RegFile::Temp, s.relReg);
    for (int l = 0; l < N; ++l) index[l] = relativeIndex(s.index, a ? a->c[s.relComp & 3][l] : 0.0f);
  }
  const bool uniform = isUniformFile(s.file);
  for (int l = 0; l < N; ++l) {
    Vec4 v{0, 0, 0, 0};
    if (uniform) {
      v = uniformValue(s, index[l], ctx, p);
    } else if (index[l] >= s.relLo && index[l] < s.relHi) {
      if (const LaneVec4* r = laneRegister(regs, s.file, index[l]))
        v = Vec4(r->c[0][l], r->c[1][l], r->c[2][l], r->c[3][l]);
    }
    for (int c = 0; c < 4; ++c) scratch[c][l] = applySourceModifier(v[(s.swizzle >> (2 * c)) & 3], s.mod);
  }
  for (int c = 0; c < 4; ++c) o.c[c] = scratch[c];
}

inline void fetch(const Src& s, const BatchRegisters& regs, const ExecContext& ctx,
                  const Program& p, float (*scratch)[N], Operand& o) {
  if (s.rel != RelMode::None) {
    fetchRelative(s, regs, ctx, p, scratch, o);
    return;
  }
  const bool uniform = isUniformFile(s.file);
  if (!uniform) {
    const LaneVec4* base = laneRegister(regs, s.file, s.index);
    if (!base) base = reinterpret_cast<const LaneVec4*>(kZeroLanes);
    if (s.mod == SrcMod::None) {
      o.c[0] = base->c[s.swizzle & 3];
      o.c[1] = base->c[(s.swizzle >> 2) & 3];
      o.c[2] = base->c[(s.swizzle >> 4) & 3];
      o.c[3] = base->c[(s.swizzle >> 6) & 3];
      return;
    }
    for (int c = 0; c < 4; ++c) {
      const float* b = base->c[(s.swizzle >> (2 * c)) & 3];
      float* d = scratch[c];
      switch (s.mod) {
        case SrcMod::Neg: for (int l = 0; l < N; ++l) d[l] = -b[l]; break;
        case SrcMod::Comp: for (int l = 0; l < N; ++l) d[l] = 1.0f - b[l]; break;
        case SrcMod::Sign: for (int l = 0; l < N; ++l) d[l] = 2.0f * (b[l] - 0.5f); break;
        default: for (int l = 0; l < N; ++l) d[l] = applySourceModifier(b[l], s.mod); break;
      }
      o.c[c] = d;
    }
    return;
  }
  const Vec4 v = uniformValue(s, s.index, ctx, p);
  for (int c = 0; c < 4; ++c) {
    float x = applySourceModifier(v[(s.swizzle >> (2 * c)) & 3], s.mod);
    for (int l = 0; l < N; ++l) scratch[c][l] = x;
    o.c[c] = scratch[c];
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

void sample(const Instr& in, const Operand* src, const ExecContext& ctx, uint16_t laneMask,
            float (*out)[N]) {
  alignas(64) float co[12][N];
  const float(*cp)[N] = co;
  const Operand& coord = src[0];
  // Coordinates read in place when they are one register's .xyzw.
  const bool inPlace = in.op != Op::TexProj && in.op != Op::TexGrad &&
                       coord.c[1] == coord.c[0] + N && coord.c[2] == coord.c[0] + 2 * N &&
                       coord.c[3] == coord.c[0] + 3 * N;
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
    case Op::TexGrad:
      mode = SampleMode::Grad;
      for (int c = 0; c < 4; ++c) {
        std::memcpy(co[4 + c], src[1].c[c], sizeof(co[c]));
        std::memcpy(co[8 + c], src[2].c[c], sizeof(co[c]));
      }
      break;
    default: break;
  }
  if (in.sampler < ctx.samplerCount && ctx.samplers[in.sampler].sample) {
    const SamplerBinding& b = ctx.samplers[in.sampler];
    b.sample(b.context, mode, cp, quadLanes(laneMask), out);
  } else {
    // Unbound sampler: D3D returns (0,0,0,1).
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < N; ++l) out[c][l] = c == 3 ? 1.0f : 0.0f;
  }
}

// D3DSHADER_COMPARISON (0: always true).
inline bool compare(uint8_t cmp, float a, float b) {
  switch (cmp) {
    case 1: return a > b;
    case 2: return a == b;
    case 3: return a >= b;
    case 4: return a < b;
    case 5: return a != b;
    case 6: return a <= b;
    default: return true;
  }
}

// Result rounded to multiples of 2^-bits (fixed point of `bits` fractional bits).
inline V16 quantize(V16 r, int bits) {
  alignas(32) float t[N];
  store(t, r);
  const float k = std::ldexp(1.0f, bits), ik = std::ldexp(1.0f, -bits);
  for (int l = 0; l < N; ++l) t[l] = std::nearbyint(t[l] * k) * ik;
  return load(t);
}

}  // namespace

void BatchRegisters::resize(const Program& p) { BatchRegistersResize(*this, p); }

namespace {

constexpr int kOpCount = int(Op::Ret) + 1;

// Source counts by op, looked up once.
const std::array<uint8_t, 256> kSources = [] {
  std::array<uint8_t, 256> t{};
  for (int op = 0; op < kOpCount; ++op) t[op] = uint8_t(sourceCount(Op(op)));
  return t;
}();

inline bool isFlowOp(Op op) { return op >= Op::If && op <= Op::Ret; }

// The destination register of `in` (nullptr: none, or a relative index out of range).
LaneVec4* destination(const Instr& in, BatchRegisters& regs) {
  int index = in.dst.index;
  if (in.dst.rel == RelMode::Loop) {
    index += regs.loopCounter;
    if (index < in.dst.relLo || index >= in.dst.relHi) return nullptr;
  }
  return const_cast<LaneVec4*>(laneRegister(regs, in.dst.file, index));
}

// One instruction, decoded as it runs: the reference path for every op and operand.
void executeInstr(const Instr& in, const Program& program, const ExecContext& ctx,
                  BatchRegisters& regs) {
  if (isFlowOp(in.op)) return;  // run by executeFlow
  alignas(64) float scratch[3][4][N];
  alignas(64) float res[4][N];
  {
    const int nsrc = kSources[uint8_t(in.op)];
    Operand s[3];
    bool alias = false;  // the destination is also a source: stage results in res
    for (int i = 0; i < nsrc; ++i) {
      fetch(in.src[i], regs, ctx, program, scratch[i], s[i]);
      alias |= in.src[i].file == in.dst.file &&
               (in.src[i].index == in.dst.index || in.src[i].rel != RelMode::None ||
                in.dst.rel != RelMode::None);
    }
    uint8_t mask = in.dst.mask;
    LaneVec4* dstReg = destination(in, regs);
    const uint16_t execMask = regs.execMask;
    const bool allLanes = execMask == 0xffff;
    // Result modifiers: shift, then saturate or clamp to the version's range, then
    // the fixed-point grid of the hardware precision model.
    const bool clampResult = in.saturate || in.clamp;
    const v8f scale = splat8(in.shift == 0 ? 1.0f : std::ldexp(1.0f, in.shift));
    const v8f lo = splat8(in.saturate ? 0.0f : in.clampLo), hi = splat8(in.saturate ? 1.0f : in.clampHi);
    auto modify = [&](V16 r) {
      if (in.shift != 0) r = lanes([&](int h) { return part(r, h) * scale; });
      // Clamp with NaN -> lo (D3D saturates NaN to 0).
      if (clampResult) r = lanes([&](int h) { return vmin(vmax(part(r, h), lo), hi); });
      if (in.quantize) r = quantize(r, in.quantize);
      return r;
    };
    // Lanes outside the execution mask keep their values.
    auto put = [&](float* d, const V16& r) {
      if (allLanes) {
        store(d, r);
        return;
      }
      alignas(32) float t[N];
      store(t, r);
      for (int l = 0; l < N; ++l)
        if (execMask >> l & 1) d[l] = t[l];
    };
    // Without aliasing, results go straight to the destination.
    const bool direct = !alias && dstReg && allLanes;
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
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = detail::exp2Lane(s[0].c[c][l]); });
        break;
      case Op::Log2:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = detail::log2Lane(s[0].c[c][l]);
        });
        break;
      case Op::Pow:
        each([&](int c, float* r) { detail::powLanes(s[0].c[c], s[1].c[c], nullptr, r, 0); });
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
        // D3D nrm scales all four components; a zero vector gives (0, 0, 0, w).
        float k[N];
        for (int l = 0; l < N; ++l) {
          float d = s[0].c[0][l] * s[0].c[0][l] + s[0].c[1][l] * s[0].c[1][l] +
                    s[0].c[2][l] * s[0].c[2][l];
          k[l] = d == 0.0f ? 1.0f : 1.0f / std::sqrt(d);
        }
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = s[0].c[c][l] * k[l]; });
        break;
      }
      case Op::Tex:
      case Op::TexProj:
      case Op::TexBias:
      case Op::TexLod:
      case Op::TexGrad: {
        const uint16_t live = uint16_t(regs.laneMask & execMask);
        if (direct && mask == 0xF && in.shift == 0 && !clampResult && !in.quantize) {
          sample(in, s, ctx, live, dstReg->c);
          return;
        }
        sample(in, s, ctx, live, res);
        staged = true;
        break;
      }
      case Op::Kill: {
        uint16_t killed = 0;
        for (int c = 0; c < 4; ++c) {
          if (!(mask & (1 << c))) continue;
          for (int l = 0; l < N; ++l)
            if (s[0].c[c][l] < 0.0f) killed |= uint16_t(1u << l);
        }
        regs.laneMask &= uint16_t(~(killed & execMask));
        return;  // no register result
      }
      case Op::Floor:
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = std::floor(s[0].c[c][l]); });
        break;
      case Op::Round:
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = std::nearbyint(s[0].c[c][l]); });
        break;
      case Op::Lit:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = detail::litLane(c, s[0].c[0][l], s[0].c[1][l], s[0].c[3][l]);
        });
        break;
      case Op::Dist:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l)
            r[l] = c == 0 ? 1.0f
                   : c == 1 ? s[0].c[1][l] * s[1].c[1][l]
                   : c == 2 ? s[0].c[2][l]
                            : s[1].c[3][l];
        });
        break;
      case Op::Crs:
        mask &= 0x7;
        each([&](int c, float* r) {
          const int i = (c + 1) % 3, j = (c + 2) % 3;
          for (int l = 0; l < N; ++l) r[l] = s[0].c[i][l] * s[1].c[j][l] - s[0].c[j][l] * s[1].c[i][l];
        });
        break;
      case Op::Sgn:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) {
            const float v = s[0].c[c][l];
            r[l] = v < 0 ? -1.0f : v > 0 ? 1.0f : 0.0f;
          }
        });
        break;
      case Op::SinCos:
        mask &= 0x3;
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = detail::sinCosLane(c, s[0].c[0][l]);
        });
        break;
      case Op::ExpP:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = detail::expPLane(c, s[0].c[0][l]);
        });
        break;
      case Op::Quot:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) {
            const float d = s[1].c[c][l];
            r[l] = d == 0.0f ? 1.0f : s[0].c[c][l] / d;
          }
        });
        break;
      case Op::SetP:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = compare(in.cmp, s[0].c[c][l], s[1].c[c][l]) ? 1.0f : 0.0f;
        });
        break;
      case Op::Dsx:
      case Op::Dsy: {
        // lane = quad*4 + (y&1)*2 + (x&1): x pairs differ in bit 0, y pairs in bit 1.
        const int bit = in.op == Op::Dsx ? 1 : 2;
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = s[0].c[c][l | bit] - s[0].c[c][l & ~bit];
        });
        break;
      }
      default:
        return;
    }
    if (!dstReg || !staged) return;
    // Results staged in res (aliasing, masked lanes, or ops written per lane):
    // modifiers and store.
    for (int c = 0; c < 4; ++c)
      if (mask & (1 << c)) put(dstReg->c[c], modify(load(res[c])));
  }
}

// Lanes (of the execution mask) meeting the condition of an If/Break/Call.
uint16_t condition(const Instr& in, const Program& program, const ExecContext& ctx,
                   const BatchRegisters& regs) {
  if (in.cmp == 0) return 0xffff;
  alignas(64) float scratch[2][4][N];
  Operand a, b;
  fetch(in.src[0], regs, ctx, program, scratch[0], a);
  fetch(in.src[1], regs, ctx, program, scratch[1], b);
  uint16_t m = 0;
  for (int l = 0; l < N; ++l) m |= uint16_t(compare(in.cmp, a.c[0][l], b.c[0][l]) ? 1u << l : 0u);
  return m;
}

// Programs with flow control: structured control on per-lane execution masks.
// Loop counts and aL are uniform (int constants); conditions may vary per lane.
// With native code, straight-line blocks run as one call while every lane executes
// (and the instruction budget covers the whole block).
void executeFlow(const Program& program, const ExecContext& ctx, BatchRegisters& regs,
                 const detail::JitProgram* jit = nullptr, detail::JitFrame* frame = nullptr) {
  enum class Kind : uint8_t { If, Loop, Call };
  struct Frame {
    Kind kind;
    uint16_t saved;   // execution mask on entry
    uint16_t taken;   // If: lanes that took the branch
    int remaining;    // Loop: passes left
    int step;         // Loop: aL increment (0 for rep)
    int savedCounter; // Loop: aL of the enclosing loop
    int pc;           // Loop: the Rep/Loop instruction; Call: return address
  };
  constexpr int kMaxDepth = 64, kMaxCallDepth = 8;
  Frame stack[kMaxDepth];
  int depth = 0, calls = 0;
  uint16_t& exec = regs.execMask;
  exec = 0xffff;
  const std::vector<Instr>& code = program.code;
  const int n = int(code.size());
  int pc = 0;
  long budget = kMaxExecutedInstructions;
  for (; pc >= 0 && pc < n && budget > 0; --budget) {
    const Instr& in = code[size_t(pc)];
    switch (in.op) {
      case Op::If: {
        if (depth == kMaxDepth) { pc = n; break; }
        const uint16_t cond = condition(in, program, ctx, regs);
        stack[depth++] = Frame{Kind::If, exec, uint16_t(exec & cond), 0, 0, 0, pc};
        exec &= cond;
        pc = exec ? pc + 1 : in.target;  // the Else (which switches) or the EndIf
        break;
      }
      case Op::Else:
        if (depth && stack[depth - 1].kind == Kind::If) {
          exec = uint16_t(stack[depth - 1].saved & ~stack[depth - 1].taken);
          pc = exec ? pc + 1 : in.target;
        } else {
          ++pc;
        }
        break;
      case Op::EndIf:
        if (depth && stack[depth - 1].kind == Kind::If) exec = stack[--depth].saved;
        ++pc;
        break;
      case Op::Rep:
      case Op::Loop: {
        alignas(64) float scratch[4][N];
        Operand a;
        fetch(in.src[0], regs, ctx, program, scratch, a);
        // Counts and start are bytes in D3D (0..255), the step a signed byte.
        const int count = std::clamp(int(a.c[0][0]), 0, 255);
        if (count == 0 || !exec || depth == kMaxDepth) {
          pc = in.target + 1;
          break;
        }
        const bool loop = in.op == Op::Loop;
        stack[depth++] = Frame{Kind::Loop, exec, 0, count, loop ? std::clamp(int(a.c[2][0]), -128, 127) : 0,
                               regs.loopCounter, pc};
        if (loop) regs.loopCounter = std::clamp(int(a.c[1][0]), 0, 255);
        ++pc;
        break;
      }
      case Op::EndRep:
      case Op::EndLoop: {
        if (!depth || stack[depth - 1].kind != Kind::Loop) {
          ++pc;
          break;
        }
        Frame& f = stack[depth - 1];
        regs.loopCounter += f.step;
        if (--f.remaining > 0 && exec) {
          pc = f.pc + 1;
        } else {
          exec = f.saved;  // lanes that left by break join again
          regs.loopCounter = f.savedCounter;
          --depth;
          ++pc;
        }
        break;
      }
      case Op::Break: {
        int loop = depth - 1;
        while (loop >= 0 && stack[loop].kind == Kind::If) --loop;
        if (loop < 0 || stack[loop].kind != Kind::Loop) {
          ++pc;
          break;
        }
        const uint16_t leave = uint16_t(exec & condition(in, program, ctx, regs));
        exec &= uint16_t(~leave);
        for (int k = loop + 1; k < depth; ++k) {
          stack[k].saved &= uint16_t(~leave);
          stack[k].taken &= uint16_t(~leave);
        }
        // Lanes still in the loop: those running, and those waiting in enclosing
        // if blocks inside it (saved at the outermost one).
        const uint16_t inLoop = loop + 1 < depth ? stack[loop + 1].saved : exec;
        if (!exec && !inLoop) {
          depth = loop + 1;
          pc = code[size_t(stack[loop].pc)].target;  // the EndRep/EndLoop: leaves the loop
        } else {
          ++pc;
        }
        break;
      }
      case Op::Call: {
        const uint16_t lanesIn = uint16_t(exec & condition(in, program, ctx, regs));
        if (!lanesIn || calls == kMaxCallDepth || depth == kMaxDepth || in.target < 0) {
          ++pc;
          break;
        }
        stack[depth++] = Frame{Kind::Call, exec, 0, 0, 0, 0, pc + 1};
        ++calls;
        exec = lanesIn;
        pc = in.target;
        break;
      }
      case Op::Ret: {
        int f = depth - 1;
        while (f >= 0 && stack[f].kind != Kind::Call) --f;
        if (f < 0) {
          pc = n;  // end of the main program
          break;
        }
        exec = stack[f].saved;
        pc = stack[f].pc;
        depth = f;
        --calls;
        break;
      }
      default:
        if (jit && exec == 0xffff) {
          const detail::JitBlock& block = jit->blocks[size_t(pc)];
          if (block.run && budget >= block.length) {
            detail::runJit(*jit, block.run, *frame, ctx);
            pc += block.length;
            budget -= block.length - 1;  // the loop counts one
            break;
          }
        }
        if (exec) executeInstr(in, program, ctx, regs);
        ++pc;
        break;
    }
  }
  if (budget == 0 && pc >= 0 && pc < n && ctx.boundStops)
    ctx.boundStops->fetch_add(1, std::memory_order_relaxed);
  exec = 0xffff;
  regs.loopCounter = 0;
  regs.executedInstructions = kMaxExecutedInstructions - budget;
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
  int quantize;            // fixed-point grid (0: none)
  // Source modifiers of lane-varying sources as v * modScale + modOffset (the
  // ps_1_x set is affine; the same roundings as applySourceModifier).
  uint8_t modded;          // bit i: source i has a modifier
  float modScale[3], modOffset[3];
  uint8_t comps[4], ncomps;  // written components, in order
};

// The reference path for ops and operands without a specialised routine.
void runGeneric(const Step& s, const ExecContext& ctx, BatchRegisters& regs) {
  executeInstr(*s.in, *s.program, ctx, regs);
}

// Source i, component c, with its modifier.
inline V16 loadSrc(const Step& s, int i, int c) {
  V16 v = load(s.src[i][c]);
  if (s.modded >> i & 1) {
    const v8f k = splat8(s.modScale[i]);
    if (s.modOffset[i] == 0.0f) return lanes([&](int h) { return part(v, h) * k; });
    const v8f o = splat8(s.modOffset[i]);
    return lanes([&](int h) { return part(v, h) * k + o; });
  }
  return v;
}

template <Op O>
inline V16 compute(const Step& s, int c) {
  auto src = [&](int i) { return loadSrc(s, i, c); };
  auto dot = [&](int n) {
    V16 a[4], b[4];
    for (int k = 0; k < n; ++k) a[k] = loadSrc(s, 0, k), b[k] = loadSrc(s, 1, k);
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
    if (s.quantize) v = quantize(v, s.quantize);
    store(s.dst[c], v);
  }
}

// The same operations as runArith, streamed per 8-lane half and component: used
// when no destination component is read by a later component's sources and no
// fixed-point grid applies (the common case), so nothing is staged. The step's
// fields are copied to locals first: stores through float* could otherwise alias
// them (uint8_t is a character type) and force reloads.
template <Op O, bool Shift, bool Clamp, bool Modded>
void runLanes(const Step& s, const ExecContext&, BatchRegisters&) {
  constexpr int nsrc = O == Op::Mov ? 1 : (O == Op::Mad || O == Op::Lrp || O == Op::Cmp) ? 3 : 2;
  const v8f scale = splat8(s.scale), lo = splat8(s.lo), hi = splat8(s.hi);
  // Modified sources as v * k + o; unmodified ones (k, o) = (1, -0), and o = -0 for
  // modifiers without an offset: x + (-0) is x for every x, -0 included.
  v8f k[3], o[3];
  if constexpr (Modded)
    for (int i = 0; i < nsrc; ++i) {
      k[i] = splat8(s.modScale[i]);
      o[i] = splat8(s.modOffset[i]);
    }
  const int ncomps = s.ncomps;
  int comps[4];
  for (int c = 0; c < 4; ++c) comps[c] = s.comps[c];
  const auto& src = s.src;
  const auto& dst = s.dst;
  auto ld = [&](int i, int c, int h) {
    v8f v;
    std::memcpy(&v, src[i][c] + 8 * h, sizeof v);
    if constexpr (Modded) v = v * k[i] + o[i];
    return v;
  };
  auto finish = [&](v8f v) {
    if constexpr (Shift) v = v * scale;
    if constexpr (Clamp) v = vmin(vmax(v, lo), hi);
    return v;
  };
  for (int h = 0; h < 2; ++h) {
    if constexpr (O == Op::Dp3 || O == Op::Dp4) {
      v8f r = ld(0, 0, h) * ld(1, 0, h) + ld(0, 1, h) * ld(1, 1, h);
      r += ld(0, 2, h) * ld(1, 2, h);
      if constexpr (O == Op::Dp4) r += ld(0, 3, h) * ld(1, 3, h);
      r = finish(r);
      for (int j = 0; j < ncomps; ++j) std::memcpy(dst[comps[j]] + 8 * h, &r, sizeof r);
    } else {
      for (int j = 0; j < ncomps; ++j) {
        const int c = comps[j];
        const v8f a = ld(0, c, h);
        v8f r;
        if constexpr (O == Op::Mov) {
          r = a;
        } else {
          const v8f b = ld(1, c, h);
          if constexpr (O == Op::Add) r = a + b;
          else if constexpr (O == Op::Sub) r = a - b;
          else if constexpr (O == Op::Mul) r = a * b;
          else if constexpr (O == Op::Min) r = vmin(a, b);
          else if constexpr (O == Op::Max) r = vmax(a, b);
          else {
            const v8f d = ld(2, c, h);
            if constexpr (O == Op::Mad) r = a * b + d;
            else if constexpr (O == Op::Lrp) r = a * (b - d) + d;
            else r = a >= splat8(0.0f) ? b : d;  // Cmp
          }
        }
        r = finish(r);
        std::memcpy(dst[c] + 8 * h, &r, sizeof r);
      }
    }
  }
}

template <Op O, bool Shift, bool Clamp>
StepFn lanesFor(bool modded) {
  return modded ? runLanes<O, Shift, Clamp, true> : runLanes<O, Shift, Clamp, false>;
}

template <Op O>
StepFn arith(bool shift, bool clamp, bool streamed, bool modded) {
  if (streamed) {
    if (shift) return clamp ? lanesFor<O, true, true>(modded) : lanesFor<O, true, false>(modded);
    return clamp ? lanesFor<O, false, true>(modded) : lanesFor<O, false, false>(modded);
  }
  if (shift) return clamp ? runArith<O, true, true> : runArith<O, true, false>;
  return clamp ? runArith<O, false, true> : runArith<O, false, false>;
}

StepFn arithFor(Op op, bool shift, bool clamp, bool streamed = false, bool modded = false) {
  switch (op) {
    case Op::Mov: return arith<Op::Mov>(shift, clamp, streamed, modded);
    case Op::Add: return arith<Op::Add>(shift, clamp, streamed, modded);
    case Op::Sub: return arith<Op::Sub>(shift, clamp, streamed, modded);
    case Op::Mul: return arith<Op::Mul>(shift, clamp, streamed, modded);
    case Op::Mad: return arith<Op::Mad>(shift, clamp, streamed, modded);
    case Op::Min: return arith<Op::Min>(shift, clamp, streamed, modded);
    case Op::Max: return arith<Op::Max>(shift, clamp, streamed, modded);
    case Op::Lrp: return arith<Op::Lrp>(shift, clamp, streamed, modded);
    case Op::Cmp: return arith<Op::Cmp>(shift, clamp, streamed, modded);
    case Op::Dp3: return arith<Op::Dp3>(shift, clamp, streamed, modded);
    case Op::Dp4: return arith<Op::Dp4>(shift, clamp, streamed, modded);
    default: return nullptr;
  }
}

// tex with .xyzw coordinates of one register, all four components written, no
// result modifier and no overlap of coordinates and destination: the sampler reads
// and writes the registers in place.
void runTexInPlace(const Step& s, const ExecContext& ctx, BatchRegisters& regs) {
  const SamplerBinding& b = ctx.samplers[s.in->sampler];
  b.sample(b.context, SampleMode::Implicit, reinterpret_cast<const float(*)[N]>(s.src[0][0]),
           quadLanes(regs.laneMask), reinterpret_cast<float(*)[N]>(s.dst[0]));
}

// Component 0 copied to components 1..3 of one register.
void runBroadcast(const Step& s, const ExecContext&, BatchRegisters&) {
  const V16 v = load(s.src[0][0]);
  for (int c = 1; c < 4; ++c) store(s.dst[c], v);
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
  std::shared_ptr<const detail::JitProgram> jit;  // native code (the steps are unused)
  mutable detail::JitFrame frame{};               // its frame in the prepared registers
  std::vector<Step> steps;
  std::vector<LaneVec4> uniforms;  // constant and immediate operands, splat over the lanes
};


// Native code for `program` in these registers (null: the interpreter runs it).
static std::shared_ptr<const detail::JitProgram> nativeCode(const Program& program,
                                                           const BatchRegisters& regs,
                                                           const PrepareOptions& options,
                                                           ProgramBuildInfo& info) {
  detail::JitIsa isa;
  if (!options.jit || !detail::chooseJitIsa(options, isa)) return nullptr;
  bool compiled = false;
  auto jit = detail::jitProgram(program, isa, compiled);
  if (!jit) return nullptr;
  if (compiled) info.compileMicroseconds = jit->compileMicroseconds;
  info.interpretedInstructions = jit->calledInstructions;
  // Inline code reads registers without bounds checks: every register it addresses
  // must exist (a missing one reads as zero in the interpreter).
  if (int(regs.temps.size()) < jit->tempsUsed || int(regs.inputs.size()) < jit->inputsUsed ||
      int(regs.outputs.size()) < jit->outputsUsed)
    return nullptr;
  info.backend = jit->isa == detail::JitIsa::Avx512 ? "jit-avx512" : "jit-avx2";
  return jit;
}

ProgramBuildInfo prepare(const Program& program, const ExecContext& ctx, BatchRegisters& regs,
                         const PrepareOptions& options) {
  ProgramBuildInfo info;
  info.instructions = int(program.code.size());
  auto jit = nativeCode(program, regs, options, info);
  if (!jit && program.flowControl) {  // runs on execution masks: decoded as it runs
    regs.prepared.reset();
    return info;
  }
  auto pp = std::make_shared<PreparedProgram>();
  pp->program = &program;
  pp->code = program.code.data();
  pp->size = program.code.size();
  if (jit) {
    pp->jit = std::move(jit);
    pp->frame = detail::jitFrame(program, regs);
    regs.prepared = std::move(pp);
    return info;
  }
  size_t uniformCount = 0;
  for (const Instr& in : program.code)
    for (int i = 0; i < kSources[uint8_t(in.op)]; ++i)
      uniformCount += (in.src[i].file == RegFile::Const || in.src[i].file == RegFile::Imm) &&
                      in.src[i].rel == RelMode::None;
  pp->uniforms.resize(uniformCount);
  size_t nextUniform = 0;
  // Registers whose four components hold one value (a dp3 result, a product of such
  // values …) are written as component 0 only and read through it ("narrow")
  // until an instruction needs the four arrays; then a broadcast step fills them.
  std::vector<float*> narrow;  // component-0 arrays of the narrow registers
  auto isNarrow = [&](const float* base) {
    return std::find(narrow.begin(), narrow.end(), base) != narrow.end();
  };
  auto widen = [&](float* base) {
    auto it = std::find(narrow.begin(), narrow.end(), base);
    if (it == narrow.end()) return;
    narrow.erase(it);
    Step b{};
    b.run = runBroadcast;
    b.program = &program;
    b.src[0][0] = base;
    for (int c = 0; c < 4; ++c) b.dst[c] = base + c * N;
    pp->steps.push_back(b);
  };
  auto registerBase = [&](RegFile f, int index) { return laneArray(regs, f, index, 0); };
  for (const Instr& in : program.code) {
    Step s{};
    s.run = runGeneric;
    s.in = &in;
    s.program = &program;
    const int nsrc = kSources[uint8_t(in.op)];
    bool resolved = in.dst.rel == RelMode::None;
    for (int i = 0; i < 3; ++i) s.modScale[i] = 1.0f, s.modOffset[i] = -0.0f;
    for (int i = 0; i < nsrc; ++i) {
      const Src& src = in.src[i];
      if (src.rel != RelMode::None) {
        resolved = false;
        continue;
      }
      if (src.file == RegFile::Const || src.file == RegFile::Imm) {
        // fetch() expands these per batch; the values are fixed for the draw.
        LaneVec4& u = pp->uniforms[nextUniform++];
        const Vec4 v = uniformValue(src, src.index, ctx, program);
        for (int c = 0; c < 4; ++c) {
          const float x = applySourceModifier(v[(src.swizzle >> (2 * c)) & 3], src.mod);
          for (int l = 0; l < N; ++l) u.c[c][l] = x;
          // Equal values share one array, so replicated results are recognised.
          s.src[i][c] = std::memcmp(&x, &u.c[0][0], sizeof x) == 0 ? u.c[0] : u.c[c];
        }
        continue;
      }
      if (src.mod != SrcMod::None) {
        if (affineSourceModifier(src.mod, s.modScale[i], s.modOffset[i])) s.modded |= uint8_t(1u << i);
        else resolved = false;
        if (s.modOffset[i] == 0.0f) s.modOffset[i] = -0.0f;
      }
      const bool n = isNarrow(registerBase(src.file, src.index));
      for (int c = 0; c < 4; ++c) {
        s.src[i][c] = laneArray(regs, src.file, src.index, n ? 0 : (src.swizzle >> (2 * c)) & 3);
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
    s.quantize = in.quantize;
    float* dstBase = registerBase(in.dst.file, in.dst.index);
    StepFn arithmetic = resolved && anyDst ? arithFor(in.op, in.shift != 0, clamp, false) : nullptr;
    if (arithmetic) {
      // One value in all four components: dot products, or per-component ops whose
      // sources repeat one array.
      bool replicated = in.op == Op::Dp3 || in.op == Op::Dp4;
      if (!replicated) {
        replicated = true;
        for (int i = 0; i < nsrc; ++i)
          for (int c = 1; c < 4; ++c) replicated &= s.src[i][c] == s.src[i][0];
      }
      if (replicated && in.dst.mask == 0xF && dstBase) {
        s.dst[1] = s.dst[2] = s.dst[3] = nullptr;
        if (!isNarrow(dstBase)) narrow.push_back(dstBase);
      } else if (isNarrow(dstBase)) {
        if (in.dst.mask == 0xF) {
          narrow.erase(std::find(narrow.begin(), narrow.end(), dstBase));
        } else {
          // Sources reading the register were resolved to component 0; the broadcast
          // happens before this step, so they stay valid.
          widen(dstBase);
        }
      }
      // Streamed when no written component is a source array of another written
      // component, or when only one is and it can be written last (a narrow
      // register read and rewritten); otherwise staged (every source read first).
      int readByOthers = 0, last = -1;
      for (int c = 0; c < 4; ++c) {
        if (!s.dst[c]) continue;
        bool read = false;
        for (int i = 0; i < nsrc; ++i)
          for (int k = 0; k < 4; ++k) read |= k != c && s.dst[k] && s.src[i][k] == s.dst[c];
        if (read) ++readByOthers, last = c;
      }
      bool hazard = s.quantize != 0 || readByOthers > 1;
      s.ncomps = 0;
      for (int c = 0; c < 4; ++c)
        if (s.dst[c] && c != last) s.comps[s.ncomps++] = uint8_t(c);
      if (last >= 0) s.comps[s.ncomps++] = uint8_t(last);
      if (in.op == Op::Dp3 || in.op == Op::Dp4) hazard = s.quantize != 0;  // read before any store
      s.run = arithFor(in.op, in.shift != 0, clamp, !hazard, s.modded != 0);
      pp->steps.push_back(s);
      continue;
    }
    // Other steps read and write whole registers.
    for (int i = 0; i < nsrc; ++i) {
      const Src& src = in.src[i];
      if (src.file == RegFile::Const || src.file == RegFile::Imm || src.rel != RelMode::None) {
        if (src.rel != RelMode::None)  // any register of the file may be read
          for (float* base : std::vector<float*>(narrow)) widen(base);
        continue;
      }
      float* base = registerBase(src.file, src.index);
      if (base && isNarrow(base)) {
        widen(base);
        for (int c = 0; c < 4; ++c) s.src[i][c] = laneArray(regs, src.file, src.index, (src.swizzle >> (2 * c)) & 3);
      }
    }
    if (dstBase) widen(dstBase);
    if (in.dst.rel != RelMode::None)
      for (float* base : std::vector<float*>(narrow)) widen(base);
    if (resolved && anyDst && in.op == Op::Tex && in.dst.mask == 0xF && in.shift == 0 && !clamp &&
        !in.quantize && !s.modded && in.sampler < ctx.samplerCount && ctx.samplers[in.sampler].sample) {
      const float* c0 = s.src[0][0];
      const bool xyzw = s.src[0][1] == c0 + N && s.src[0][2] == c0 + 2 * N && s.src[0][3] == c0 + 3 * N;
      const bool disjoint = c0 + 4 * N <= s.dst[0] || s.dst[0] + 4 * N <= c0;
      if (xyzw && disjoint && s.dst[1] == s.dst[0] + N && s.dst[2] == s.dst[0] + 2 * N &&
          s.dst[3] == s.dst[0] + 3 * N)
        s.run = runTexInPlace;
    }
    pp->steps.push_back(s);
  }
  // Every register ends with its four components, as without preparation.
  for (float* base : std::vector<float*>(narrow)) widen(base);
  regs.prepared = std::move(pp);
  return info;
}

// What prepare() made of `program` in `regs`, if it still is that program's.
static const PreparedProgram* preparedFor(const Program& program, const BatchRegisters& regs) {
  const PreparedProgram* pp = regs.prepared.get();
  const bool prepared = pp && pp->program == &program && pp->code == program.code.data() &&
                        pp->size == program.code.size();
  return prepared ? pp : nullptr;
}

ProgramRunner runnerFor(const Program& program, const ExecContext& ctx, BatchRegisters& regs) {
  ProgramRunner r;
  const PreparedProgram* pp = preparedFor(program, regs);
  if (!pp || !pp->jit || program.flowControl || pp->frame.regs != &regs) return r;
  const detail::JitProgram& jit = *pp->jit;
  if (detail::constantsToPad(jit, ctx)) return r;
  // What runJit sets on each call.
  pp->frame.ctx = &ctx;
  pp->frame.constants = ctx.constants;
  r.fn_ = jit.run;
  r.frame_ = &pp->frame;
  return r;
}

void execute(const Program& program, const ExecContext& ctx, BatchRegisters& regs) {
  const PreparedProgram* pp = preparedFor(program, regs);
  const bool prepared = pp != nullptr;
  if (prepared && pp->jit) {
    detail::JitFrame copy;
    detail::JitFrame* frame = &pp->frame;
    if (frame->regs != &regs) {  // a copy of the registers prepared
      copy = detail::jitFrame(program, regs);
      frame = &copy;
    }
    if (program.flowControl) executeFlow(program, ctx, regs, pp->jit.get(), frame);
    else detail::runJit(*pp->jit, pp->jit->run, *frame, ctx);
    return;
  }
  if (program.flowControl) {
    executeFlow(program, ctx, regs);
    return;
  }
  if (prepared) {
    for (const Step& s : pp->steps) s.run(s, ctx, regs);
    return;
  }
  for (const Instr& in : program.code) executeInstr(in, program, ctx, regs);
}

namespace detail {

void executeInstruction(const Instr& in, const Program& program, const ExecContext& ctx,
                        BatchRegisters& regs) {
  executeInstr(in, program, ctx, regs);
}


Vec4 uniformRegisterValue(const Src& s, int index, const ExecContext& ctx, const Program& p) {
  return uniformValue(s, index, ctx, p);
}

void fetchSource(const Src& s, const Program& p, const ExecContext& ctx, const BatchRegisters& regs,
                 float (*out)[kBatchLanes]) {
  Operand o;
  fetch(s, regs, ctx, p, out, o);
  for (int c = 0; c < 4; ++c)
    if (o.c[c] != out[c]) std::memcpy(out[c], o.c[c], sizeof out[c]);
}

}  // namespace detail

}  // namespace refx::exec
