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

float* destBase(BatchRegisters& regs, const Dst& d, int c) {
  switch (d.file) {
    case RegFile::Temp: return regs.temps[d.index].c[c];
    case RegFile::Input: return regs.inputs[d.index].c[c];
    case RegFile::Output: return regs.outputs[d.index].c[c];
    default: return nullptr;
  }
}

void sample(const Instr& in, const Operand& coord, const ExecContext& ctx, uint16_t laneMask,
            float (*out)[N]) {
  alignas(64) float co[4][N];
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
    b.sample(b.context, mode, co, laneMask, out);
  } else {
    // Unbound sampler: D3D returns (0,0,0,1).
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < N; ++l) out[c][l] = c == 3 ? 1.0f : 0.0f;
  }
}

template <class F>
inline void map1(float* __restrict r, const float* __restrict a, F f) {
  for (int l = 0; l < N; ++l) r[l] = f(a[l]);
}
template <class F>
inline void map2(float* __restrict r, const float* __restrict a, const float* __restrict b, F f) {
  for (int l = 0; l < N; ++l) r[l] = f(a[l], b[l]);
}
template <class F>
inline void map3(float* __restrict r, const float* __restrict a, const float* __restrict b,
                 const float* __restrict c, F f) {
  for (int l = 0; l < N; ++l) r[l] = f(a[l], b[l], c[l]);
}

// Clamp with NaN -> lo (D3D saturates NaN to 0); written so it vectorises.
inline void writeClamped(float* __restrict d, const float* __restrict r, float lo, float hi) {
  for (int l = 0; l < N; ++l) {
    const float v = r[l] > lo ? r[l] : lo;
    d[l] = v < hi ? v : hi;
  }
}

inline void writeScaledClamped(float* __restrict d, const float* __restrict r, float k, float lo,
                               float hi) {
  for (int l = 0; l < N; ++l) {
    const float x = r[l] * k;
    const float v = x > lo ? x : lo;
    d[l] = v < hi ? v : hi;
  }
}

}  // namespace

void BatchRegisters::resize(const Program& p) { BatchRegistersResize(*this, p); }

void execute(const Program& program, const ExecContext& ctx, BatchRegisters& regs) {
  alignas(64) float scratch[3][4][N];
  alignas(64) float res[4][N];
  for (const Instr& in : program.code) {
    const int nsrc = sourceCount(in.op);
    Operand s[3];
    for (int i = 0; i < nsrc; ++i) fetch(in.src[i], regs, ctx, program, scratch[i], s[i]);
    const uint8_t mask = in.dst.mask;
    auto each = [&](auto&& f) {
      for (int c = 0; c < 4; ++c)
        if (mask & (1 << c)) f(c, res[c]);
    };
    switch (in.op) {
      case Op::Mov:
        each([&](int c, float* r) { map1(r, s[0].c[c], [](float a) { return a; }); });
        break;
      case Op::Add:
        each([&](int c, float* r) { map2(r, s[0].c[c], s[1].c[c], [](float a, float b) { return a + b; }); });
        break;
      case Op::Sub:
        each([&](int c, float* r) { map2(r, s[0].c[c], s[1].c[c], [](float a, float b) { return a - b; }); });
        break;
      case Op::Mul:
        each([&](int c, float* r) { map2(r, s[0].c[c], s[1].c[c], [](float a, float b) { return a * b; }); });
        break;
      case Op::Mad:
        each([&](int c, float* r) {
          map3(r, s[0].c[c], s[1].c[c], s[2].c[c], [](float a, float b, float d) { return a * b + d; });
        });
        break;
      case Op::Dp3:
      case Op::Dp4:
      case Op::Dp2Add: {
        float d[N];
        for (int l = 0; l < N; ++l) d[l] = s[0].c[0][l] * s[1].c[0][l] + s[0].c[1][l] * s[1].c[1][l];
        if (in.op == Op::Dp2Add) {
          for (int l = 0; l < N; ++l) d[l] += s[2].c[0][l];
        } else {
          for (int l = 0; l < N; ++l) d[l] += s[0].c[2][l] * s[1].c[2][l];
          if (in.op == Op::Dp4)
            for (int l = 0; l < N; ++l) d[l] += s[0].c[3][l] * s[1].c[3][l];
        }
        each([&](int, float* r) { std::memcpy(r, d, sizeof(d)); });
        break;
      }
      case Op::Rcp:
        // D3D: rcp(0) = +inf; scalar op on the source's first (replicated) component.
        each([&](int c, float* r) { for (int l = 0; l < N; ++l) r[l] = 1.0f / s[0].c[c][l]; });
        break;
      case Op::Rsq:
        each([&](int c, float* r) {
          for (int l = 0; l < N; ++l) r[l] = 1.0f / std::sqrt(std::fabs(s[0].c[c][l]));
        });
        break;
      case Op::Min:
        each([&](int c, float* r) { map2(r, s[0].c[c], s[1].c[c], [](float a, float b) { return a < b ? a : b; }); });
        break;
      case Op::Max:
        each([&](int c, float* r) { map2(r, s[0].c[c], s[1].c[c], [](float a, float b) { return a > b ? a : b; }); });
        break;
      case Op::Slt:
        each([&](int c, float* r) { map2(r, s[0].c[c], s[1].c[c], [](float a, float b) { return a < b ? 1.0f : 0.0f; }); });
        break;
      case Op::Sge:
        each([&](int c, float* r) { map2(r, s[0].c[c], s[1].c[c], [](float a, float b) { return a >= b ? 1.0f : 0.0f; }); });
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
        each([&](int c, float* r) { map3(r, s[0].c[c], s[1].c[c], s[2].c[c], [](float a, float b, float d) { return a * (b - d) + d; }); });
        break;
      case Op::Cmp:
        each([&](int c, float* r) { map3(r, s[0].c[c], s[1].c[c], s[2].c[c], [](float a, float b, float d) { return a >= 0.0f ? b : d; }); });
        break;
      case Op::Cnd:
        each([&](int c, float* r) { map3(r, s[0].c[c], s[1].c[c], s[2].c[c], [](float a, float b, float d) { return a > 0.5f ? b : d; }); });
        break;
      case Op::Abs:
        each([&](int c, float* r) { map1(r, s[0].c[c], [](float a) { return std::fabs(a); }); });
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
        sample(in, s[0], ctx, regs.laneMask, res);
        break;
      case Op::Kill: {
        uint16_t killed = 0;
        for (int c = 0; c < 4; ++c) {
          if (!(mask & (1 << c))) continue;
          for (int l = 0; l < N; ++l)
            if (s[0].c[c][l] < 0.0f) killed |= uint16_t(1u << l);
        }
        regs.laneMask &= uint16_t(~killed);
        continue;  // no register result
      }
    }
    // Result modifiers: shift, then saturate or clamp to the version's range.
    const float scale = in.shift == 0 ? 1.0f : std::ldexp(1.0f, in.shift);
    const bool clampResult = in.saturate || in.clamp;
    const float lo = in.saturate ? 0.0f : in.clampLo, hi = in.saturate ? 1.0f : in.clampHi;
    for (int c = 0; c < 4; ++c) {
      if (!(mask & (1 << c))) continue;
      float* __restrict d = destBase(regs, in.dst, c);
      if (!d) continue;
      const float* __restrict r = res[c];
      if (in.shift != 0) {
        if (clampResult) writeScaledClamped(d, r, scale, lo, hi);
        else for (int l = 0; l < N; ++l) d[l] = r[l] * scale;
      } else if (clampResult) {
        writeClamped(d, r, lo, hi);
      } else {
        std::memcpy(d, r, sizeof(float) * N);
      }
    }
  }
}

}  // namespace refx::exec
