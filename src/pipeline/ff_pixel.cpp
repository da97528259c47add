// Texture stage state -> straight-line pixel program. Formulas follow the D3D9
// texture stage documentation (reference/fixed-function.md §1-§3, §6).
#include "pipeline/ff_pixel.h"

#include "pipeline/texture_op_use.h"

#include <algorithm>
#include <cmath>

namespace refx::pipeline {

using namespace exec;
using namespace d3d;

namespace {

constexpr int kStages = 8;

// What a combiner instruction reads, in terms of the stage's arguments (A0, A1, A2
// after their COMPLEMENT/ALPHAREPLICATE modifiers) and the implicit blend alphas.
enum class Operand : uint8_t {
  None,
  A0, A1, A2,
  A1Alpha,       // A1.a replicated
  A1Comp,        // 1 - A1
  A1AlphaComp,   // 1 - A1.a replicated
  A2Bias,        // A2 - 0.5
  A1Sign,        // 2*(A1 - 0.5)
  A2Sign,        // 2*(A2 - 0.5)
  DiffuseAlpha,  // interpolated diffuse alpha
  TextureAlpha,  // this stage's TEXTURE alpha
  TextureAlphaComp,
  FactorAlpha,   // TFACTOR alpha
  CurrentAlpha,  // CURRENT alpha
};

// One D3DTOP as a single IR instruction (saturated by the caller).
struct Recipe {
  uint32_t top;
  Op op;
  int8_t shift;
  std::array<Operand, 3> src;
  bool colorOnly = false;  // D3D9 accepts the op as COLOROP only
};

using O = Operand;
constexpr Recipe kRecipes[] = {
    {TOP_SELECTARG1, Op::Mov, 0, {O::A1}},                        // A1
    {TOP_SELECTARG2, Op::Mov, 0, {O::A2}},                        // A2
    {TOP_MODULATE, Op::Mul, 0, {O::A1, O::A2}},                   // A1*A2
    {TOP_MODULATE2X, Op::Mul, 1, {O::A1, O::A2}},                 // 2*A1*A2
    {TOP_MODULATE4X, Op::Mul, 2, {O::A1, O::A2}},                 // 4*A1*A2
    {TOP_ADD, Op::Add, 0, {O::A1, O::A2}},                        // A1+A2
    {TOP_ADDSIGNED, Op::Add, 0, {O::A1, O::A2Bias}},              // A1+A2-0.5
    {TOP_ADDSIGNED2X, Op::Add, 1, {O::A1, O::A2Bias}},            // 2*(A1+A2-0.5)
    {TOP_SUBTRACT, Op::Sub, 0, {O::A1, O::A2}},                   // A1-A2
    {TOP_ADDSMOOTH, Op::Mad, 0, {O::A2, O::A1Comp, O::A1}},       // A1 + A2*(1-A1)
    // Blends: lrp(a, A1, A2) = A1*a + A2*(1-a)
    {TOP_BLENDDIFFUSEALPHA, Op::Lrp, 0, {O::DiffuseAlpha, O::A1, O::A2}},
    {TOP_BLENDTEXTUREALPHA, Op::Lrp, 0, {O::TextureAlpha, O::A1, O::A2}},
    {TOP_BLENDFACTORALPHA, Op::Lrp, 0, {O::FactorAlpha, O::A1, O::A2}},
    {TOP_BLENDTEXTUREALPHAPM, Op::Mad, 0, {O::A2, O::TextureAlphaComp, O::A1}},  // A1 + A2*(1-At)
    {TOP_BLENDCURRENTALPHA, Op::Lrp, 0, {O::CurrentAlpha, O::A1, O::A2}},
    {TOP_PREMODULATE, Op::Mov, 0, {O::A1}},  // A1; next stage's CURRENT *= its texture
    {TOP_MODULATEALPHA_ADDCOLOR, Op::Mad, 0, {O::A1Alpha, O::A2, O::A1}, true},         // A1 + A1.a*A2
    {TOP_MODULATECOLOR_ADDALPHA, Op::Mad, 0, {O::A1, O::A2, O::A1Alpha}, true},         // A1*A2 + A1.a
    {TOP_MODULATEINVALPHA_ADDCOLOR, Op::Mad, 0, {O::A1AlphaComp, O::A2, O::A1}, true},  // A1 + (1-A1.a)*A2
    {TOP_MODULATEINVCOLOR_ADDALPHA, Op::Mad, 0, {O::A1Comp, O::A2, O::A1Alpha}, true},  // (1-A1)*A2 + A1.a
    // 4*sum((A1-0.5)*(A2-0.5)) = dot(2*(A1-0.5), 2*(A2-0.5)), replicated to all channels
    {TOP_DOTPRODUCT3, Op::Dp3, 0, {O::A1Sign, O::A2Sign}},
    {TOP_MULTIPLYADD, Op::Mad, 0, {O::A1, O::A2, O::A0}},  // A0 + A1*A2
    {TOP_LERP, Op::Lrp, 0, {O::A0, O::A1, O::A2}},         // A0*A1 + (1-A0)*A2
};

// nullptr for DISABLE, the bump ops and values outside D3DTEXTUREOP.
const Recipe* recipeFor(uint32_t top) {
  for (const Recipe& r : kRecipes)
    if (r.top == top) return &r;
  return nullptr;
}

bool isBumpOp(uint32_t top) { return top == TOP_BUMPENVMAP || top == TOP_BUMPENVMAPLUMINANCE; }

// Which of A0/A1/A2 an operand reads (-1: none).
int argIndex(Operand o) {
  switch (o) {
    case O::A0: return 0;
    case O::A1: case O::A1Alpha: case O::A1Comp: case O::A1AlphaComp: case O::A1Sign: return 1;
    case O::A2: case O::A2Bias: case O::A2Sign: return 2;
    default: return -1;
  }
}

// A stage whose op takes TEXTURE as an argument while no texture is bound to it
// passes the previous stage's result through: D3D9's runtime turns the op into
// SELECTARG1(CURRENT), so the default stage 0, MODULATE(TEXTURE, CURRENT), draws an
// untextured triangle in its plain diffuse colour (it does not read CURRENT twice).
// An argument counts when the op's recipe reads it (ARG0 only for MULTIPLYADD and
// LERP, ARG2 not for SELECTARG1 or PREMODULATE, ARG1 not for SELECTARG2).
void passThroughWithoutTexture(uint32_t& op, std::array<uint32_t, 3>& args) {
  if (op == TOP_DISABLE || !recipeFor(op)) return;
  auto isTexture = [&](int i) { return (args[size_t(i)] & TA_SELECTMASK) == TA_TEXTURE; };
  const TextureOpUse use = textureOpUse(op);
  const bool reads = (use.arg0 && isTexture(0)) || (use.arg1 && isTexture(1)) || (use.arg2 && isTexture(2));
  if (!reads) return;
  op = TOP_SELECTARG1;
  args[1] = TA_CURRENT;
}

bool recipeReadsTexture(const Recipe* r, const std::array<uint32_t, 3>& args) {
  if (!r) return false;
  for (Operand o : r->src) {
    if (o == O::TextureAlpha || o == O::TextureAlphaComp) return true;
    int a = argIndex(o);
    if (a >= 0 && (args[a] & TA_SELECTMASK) == TA_TEXTURE) return true;
  }
  return false;
}

}  // namespace

TextureOpUse textureOpUse(uint32_t top) {
  TextureOpUse use;
  if (top == TOP_DISABLE) {
    use.valid = true;
    return use;
  }
  // The bump stage's texture holds du/dv (and luminance); its arguments are not read.
  if (isBumpOp(top)) {
    use.valid = use.ownTexture = use.colorOnly = true;
    return use;
  }
  const Recipe* r = recipeFor(top);
  if (!r) return use;
  use.valid = true;
  use.colorOnly = r->colorOnly;
  for (Operand o : r->src) {
    if (o == O::TextureAlpha || o == O::TextureAlphaComp) use.ownTexture = true;
    switch (argIndex(o)) {
      case 0: use.arg0 = true; break;
      case 1: use.arg1 = true; break;
      case 2: use.arg2 = true; break;
      default: break;
    }
  }
  return use;
}

namespace {

Vec4 toVec4(Color4 c) { return {c.r, c.g, c.b, c.a}; }

// Swizzle `outer` applied after `inner` (both D3D 2-bit-per-component).
uint8_t composeSwizzle(uint8_t inner, uint8_t outer) {
  uint8_t r = 0;
  for (int i = 0; i < 4; ++i) {
    int sel = (outer >> (2 * i)) & 3;
    r |= uint8_t(((inner >> (2 * sel)) & 3) << (2 * i));
  }
  return r;
}

Src replicateAlpha(Src s) {
  s.swizzle = composeSwizzle(s.swizzle, kSwzWWWW);
  return s;
}
// 1 - x. Argument sources carry no modifier or COMPLEMENT; 1 - (1 - x) = x.
Src complement(Src s) {
  s.mod = s.mod == SrcMod::Comp ? SrcMod::None : SrcMod::Comp;
  return s;
}
// x - 0.5; for a complemented source (1 - x) - 0.5 = -(x - 0.5).
Src bias(Src s) {
  s.mod = s.mod == SrcMod::Comp ? SrcMod::BiasNeg : SrcMod::Bias;
  return s;
}
// 2*(x - 0.5); for a complemented source 2*((1 - x) - 0.5) = -2*(x - 0.5).
Src signedScale(Src s) {
  s.mod = s.mod == SrcMod::Comp ? SrcMod::SignNeg : SrcMod::Sign;
  return s;
}

bool sameSrc(const Src& a, const Src& b) {
  return a.file == b.file && a.index == b.index && a.swizzle == b.swizzle && a.mod == b.mod;
}

struct StageState {
  uint32_t colorOp = TOP_DISABLE, alphaOp = TOP_DISABLE;
  std::array<uint32_t, 3> colorArgs{}, alphaArgs{};  // A0, A1, A2
  bool bump = false, luminance = false;
  bool resultTemp = false;
  bool projected = false;
  bool hasTexture = false;
  bool sample = false;  // the stage's texture is sampled
};

// Registers the arguments of the stage being compiled resolve to.
struct StageRegs {
  Src current, texture, diffuse;
  Src temp;
  bool tempWritten = false;  // TEMP not yet written reads (0,0,0,0)
  Src tfactor, constant;     // the constants holding TFACTOR and the stage's CONSTANT
};

class Builder {
 public:
  Builder(const DeviceState& state, const FixedFunctionPixelConfig& cfg) : state_(state), cfg_(cfg) {}

  Program build() {
    p_.name = "fixed-function pixel";
    p_.inputCount = kPixelInputCount;
    p_.outputCount = kPixelOutputCount;
    if (!cfg_.shaderPath) {
      analyse();
      emitStages();
    }
    return std::move(p_);
  }

 private:
  void analyse() {
    // The cascade ends at the first stage whose COLOROP is DISABLE (or not a D3DTOP).
    active_ = 0;
    while (active_ < kStages) {
      uint32_t op = state_.tss(active_, TSS_COLOROP);
      if (!isBumpOp(op) && !recipeFor(op)) break;
      ++active_;
    }
    for (int s = 0; s < active_; ++s) {
      StageState& st = stages_[s];
      st.colorOp = state_.tss(s, TSS_COLOROP);
      st.alphaOp = state_.tss(s, TSS_ALPHAOP);
      st.colorArgs = {state_.tss(s, TSS_COLORARG0), state_.tss(s, TSS_COLORARG1),
                      state_.tss(s, TSS_COLORARG2)};
      st.alphaArgs = {state_.tss(s, TSS_ALPHAARG0), state_.tss(s, TSS_ALPHAARG1),
                      state_.tss(s, TSS_ALPHAARG2)};
      st.bump = isBumpOp(st.colorOp);
      st.luminance = st.colorOp == TOP_BUMPENVMAPLUMINANCE;
      st.resultTemp = (state_.tss(s, TSS_RESULTARG) & TA_SELECTMASK) == TA_TEMP;
      st.projected = (state_.tss(s, TSS_TEXTURETRANSFORMFLAGS) & TTFF_PROJECTED) != 0;
      st.hasTexture = cfg_.textures[s] != nullptr;
      if (!st.hasTexture && !st.bump) {
        passThroughWithoutTexture(st.colorOp, st.colorArgs);
        passThroughWithoutTexture(st.alphaOp, st.alphaArgs);
      }
    }
    // A stage samples its texture when its combiner reads TEXTURE, when it is a
    // bump stage feeding a sampled stage, or after a PREMODULATE stage. Decided
    // from the last stage backwards. Without a texture the stage passes CURRENT
    // through (passThroughWithoutTexture); what is left reading TEXTURE (the
    // BLENDTEXTUREALPHA ops' implicit alpha) reads CURRENT.
    for (int s = active_ - 1; s >= 0; --s) {
      StageState& st = stages_[s];
      bool reads = false;
      if (st.bump) {
        reads = s + 1 < active_ && stages_[s + 1].sample;
      } else {
        const Recipe* color = recipeFor(st.colorOp);
        reads = recipeReadsTexture(color, st.colorArgs);
        if (st.colorOp != TOP_DOTPRODUCT3) reads |= recipeReadsTexture(recipeFor(st.alphaOp), st.alphaArgs);
      }
      if (s > 0 && stages_[s - 1].colorOp == TOP_PREMODULATE) reads = true;
      st.sample = reads && st.hasTexture;
    }
  }

  // Texture coordinates of stage s: the interpolated set, perturbed when stage s-1
  // is a bump stage (§3):
  //   u' = u + du*BUMPENVMAT00(s-1) + dv*BUMPENVMAT10(s-1)
  //   v' = v + du*BUMPENVMAT01(s-1) + dv*BUMPENVMAT11(s-1)
  // with (du, dv) = TEXTURE of stage s-1 (.r, .g). With PROJECTED the division comes
  // first, so the perturbation is added to the projected (u, v).
  Src emitSample(int s, Src bumpTexture) {
    const StageState& st = stages_[s];
    Src coords = reg(RegFile::Input, kPixelInTex0 + s);
    Op texOp = st.projected ? Op::TexProj : Op::Tex;
    const bool perturbed = s > 0 && stages_[s - 1].bump;
    if (perturbed) {
      const int b = s - 1;
      int c = p_.newTemp();
      if (st.projected) {
        // (u, v, w, q) * (1/q)
        p_.emit(Op::Rcp, dst(RegFile::Temp, c), replicateAlpha(coords));
        p_.emit(Op::Mul, dst(RegFile::Temp, c), coords, reg(RegFile::Temp, c));
        coords = reg(RegFile::Temp, c);
        texOp = Op::Tex;
      }
      Src du = bumpTexture, dv = bumpTexture;
      du.swizzle = composeSwizzle(du.swizzle, kSwzXXXX);
      dv.swizzle = composeSwizzle(dv.swizzle, kSwzYYYY);
      // Const[kConstBumpEnvRows + 2b] = (BUMPENVMAT00, 01, 0, 0), + 1: (10, 11, 0, 0).
      const Src row0 = reg(RegFile::Const, kConstBumpEnvRows + 2 * b);
      const Src row1 = reg(RegFile::Const, kConstBumpEnvRows + 2 * b + 1);
      p_.emit(Op::Mad, dst(RegFile::Temp, c), du, row0, coords);
      p_.emit(Op::Mad, dst(RegFile::Temp, c), dv, row1, reg(RegFile::Temp, c));
      coords = reg(RegFile::Temp, c);
    }
    int t = p_.newTemp();
    p_.emit(texOp, dst(RegFile::Temp, t), coords).sampler = uint8_t(s);
    if (perturbed && stages_[s - 1].luminance) {
      // Lf = saturate(L*BUMPENVLSCALE + BUMPENVLOFFSET), L = bump texel .b; all four
      // channels of the environment sample are scaled.
      const int b = s - 1;
      Src l = bumpTexture;
      l.swizzle = composeSwizzle(l.swizzle, kSwzZZZZ);
      // Const[kConstBumpEnv + 2b + 1] = (BUMPENVLSCALE, BUMPENVLOFFSET, 0, 0).
      const int env = kConstBumpEnv + 2 * b + 1;
      int lf = p_.newTemp();
      p_.emit(Op::Mad, dst(RegFile::Temp, lf), l, reg(RegFile::Const, env, kSwzXXXX),
              reg(RegFile::Const, env, kSwzYYYY))
          .saturate = true;
      p_.emit(Op::Mul, dst(RegFile::Temp, t), reg(RegFile::Temp, t), reg(RegFile::Temp, lf));
    }
    return reg(RegFile::Temp, t);
  }

  Src argSource(uint32_t arg, const StageRegs& r) {
    Src s;
    switch (arg & TA_SELECTMASK) {
      case TA_DIFFUSE: s = r.diffuse; break;
      case TA_CURRENT: s = r.current; break;
      case TA_TEXTURE: s = r.texture; break;
      case TA_TFACTOR: s = r.tfactor; break;
      case TA_SPECULAR: s = reg(RegFile::Input, kPixelInSpecular); break;
      case TA_TEMP: s = r.tempWritten ? r.temp : p_.imm({0, 0, 0, 0}); break;
      case TA_CONSTANT: s = r.constant; break;
      default: s = p_.imm({0, 0, 0, 0}); break;  // not a D3DTA selector
    }
    if (arg & TA_ALPHAREPLICATE) s = replicateAlpha(s);  // (x.a, x.a, x.a, x.a)
    if (arg & TA_COMPLEMENT) s = complement(s);          // 1 - x
    return s;
  }

  Src operand(Operand o, const std::array<Src, 3>& a, const StageRegs& r) {
    switch (o) {
      case O::None: return {};
      case O::A0: return a[0];
      case O::A1: return a[1];
      case O::A2: return a[2];
      case O::A1Alpha: return replicateAlpha(a[1]);
      case O::A1Comp: return complement(a[1]);
      case O::A1AlphaComp: return complement(replicateAlpha(a[1]));
      case O::A2Bias: return bias(a[2]);
      case O::A1Sign: return signedScale(a[1]);
      case O::A2Sign: return signedScale(a[2]);
      case O::DiffuseAlpha: return replicateAlpha(r.diffuse);
      case O::TextureAlpha: return replicateAlpha(r.texture);
      case O::TextureAlphaComp: return complement(replicateAlpha(r.texture));
      case O::FactorAlpha: return replicateAlpha(r.tfactor);
      case O::CurrentAlpha: return replicateAlpha(r.current);
    }
    return {};
  }

  Instr combiner(const Recipe& rc, const std::array<uint32_t, 3>& args, const StageRegs& r,
                 Dst d) {
    std::array<Src, 3> a{};
    for (int i = 0; i < 3; ++i)
      if (std::any_of(rc.src.begin(), rc.src.end(), [&](Operand o) { return argIndex(o) == i; }))
        a[i] = argSource(args[i], r);
    Instr in;
    in.op = rc.op;
    in.dst = d;
    in.shift = rc.shift;
    in.saturate = true;  // results are saturated after every stage
    for (int i = 0; i < 3; ++i) in.src[i] = operand(rc.src[i], a, r);
    return in;
  }

  void emitStages() {
    Src current = reg(RegFile::Input, kPixelInDiffuse);  // CURRENT in stage 0 = DIFFUSE
    Src temp{};
    bool tempWritten = false;  // TEMP starts at (0,0,0,0)
    Src previousTexture{};
    bool finalWritten = false;

    for (int s = 0; s < active_; ++s) {
      const StageState& st = stages_[s];
      StageRegs r;
      r.diffuse = reg(RegFile::Input, kPixelInDiffuse);
      r.tfactor = reg(RegFile::Const, kConstTextureFactor);
      r.constant = reg(RegFile::Const, kConstStageConstant + s);
      r.temp = temp;
      r.tempWritten = tempWritten;
      r.texture = current;  // no texture bound (see passThroughWithoutTexture)
      if (st.sample) r.texture = emitSample(s, previousTexture);
      if (s > 0 && stages_[s - 1].colorOp == TOP_PREMODULATE && st.hasTexture) {
        // PREMODULATE in stage s-1: CURRENT of this stage = CURRENT * TEXTURE.
        int c = p_.newTemp();
        p_.emit(Op::Mul, dst(RegFile::Temp, c), current, r.texture).saturate = true;
        current = reg(RegFile::Temp, c);
      }
      r.current = current;
      previousTexture = r.texture;

      // A bump stage only perturbs the next stage's coordinates; CURRENT in the
      // next stage stays the output of stage s-1.
      if (st.bump) continue;

      // The last stage writes the pixel color directly when its result is CURRENT.
      Dst result;
      const bool last = s + 1 == active_;
      if (last && !st.resultTemp) {
        result = dst(RegFile::Output, kPixelOutColor);
        finalWritten = true;
      } else {
        result = dst(RegFile::Temp, p_.newTemp());
      }

      const Recipe& colorRecipe = *recipeFor(st.colorOp);
      if (st.colorOp == TOP_DOTPRODUCT3) {
        // DOTPRODUCT3 replicates into alpha too, overriding the alpha op.
        p_.code.push_back(combiner(colorRecipe, st.colorArgs, r, result));
      } else {
        Dst rgb = result, alpha = result;
        rgb.mask = 0x7;
        alpha.mask = 0x8;
        Instr c = combiner(colorRecipe, st.colorArgs, r, rgb);
        Instr a;
        if (const Recipe* alphaRecipe = recipeFor(st.alphaOp)) {
          a = combiner(*alphaRecipe, st.alphaArgs, r, alpha);
        } else {
          // ALPHAOP DISABLE (or a color-only bump op) with COLOROP enabled: CURRENT
          // alpha passes through.
          a.op = Op::Mov;
          a.dst = alpha;
          a.src[0] = current;
          a.saturate = true;
        }
        if (c.op == a.op && c.shift == a.shift && sameSrc(c.src[0], a.src[0]) &&
            sameSrc(c.src[1], a.src[1]) && sameSrc(c.src[2], a.src[2])) {
          c.dst.mask = 0xF;  // same instruction for rgb and alpha
          p_.code.push_back(c);
        } else {
          p_.code.push_back(c);
          p_.code.push_back(a);
        }
      }
      // RESULTARG: CURRENT (default) or TEMP; TEMP leaves CURRENT unchanged.
      Src out = reg(result.file, result.index);
      if (st.resultTemp) {
        temp = out;
        tempWritten = true;
      } else {
        current = out;
      }
    }
    if (!finalWritten) p_.emit(Op::Mov, dst(RegFile::Output, kPixelOutColor), current);
  }

  const DeviceState& state_;
  const FixedFunctionPixelConfig& cfg_;
  Program p_;
  int active_ = 0;
  std::array<StageState, kStages> stages_{};
};

}  // namespace

Program buildFixedFunctionPixelProgram(const DeviceState& state,
                                       const FixedFunctionPixelConfig& cfg) {
  return Builder(state, cfg).build();
}

void appendSpecularAndFog(Program& p, const DeviceState& state, bool fixedFunctionStages) {
  p.inputCount = std::max(p.inputCount, int(kPixelInputCount));
  p.outputCount = std::max(p.outputCount, int(kPixelOutputCount));
  const Src color = reg(RegFile::Output, kPixelOutColor);
  const Dst rgb = dst(RegFile::Output, kPixelOutColor, 0x7);

  // SPECULARENABLE: color.rgb = saturate(color.rgb + specular.rgb) (§2, after the cascade).
  if (fixedFunctionStages && state.rs(RS_SPECULARENABLE))
    p.emit(Op::Add, rgb, color, reg(RegFile::Input, kPixelInSpecular)).saturate = true;

  if (!state.rs(RS_FOGENABLE)) return;

  // Fog factor f (1 = no fog), clamped to [0,1] (§6).
  const int f = p.newTemp();
  const Dst fx = dst(RegFile::Temp, f, 0x1);
  const Src fxxxx = reg(RegFile::Temp, f, kSwzXXXX);
  const uint32_t table = state.rs(RS_FOGTABLEMODE);
  if (table == FOG_LINEAR || table == FOG_EXP || table == FOG_EXP2) {
    // Pixel fog: d = device z in [0,1], or eye-space w when the projection is
    // perspective (W-fog: start/end in camera units).
    const bool wFog = state.projection.m[2][3] != 0.0f;
    const Src d = reg(RegFile::Input, kPixelInPosition, wFog ? kSwzWWWW : kSwzZZZZ);
    // The values: fixedFunctionPixelConstants.
    auto fogValue = [](int i) { return reg(RegFile::Const, kConstPixelFog + i); };
    if (table == FOG_LINEAR) {
      if (state.rsFloat(RS_FOGEND) != state.rsFloat(RS_FOGSTART)) {
        // f = (end - d)/(end - start) = d * (-1/(end - start)) + end/(end - start)
        p.emit(Op::Mad, fx, d, fogValue(0), fogValue(1)).saturate = true;
      } else {
        // end == start: the ramp degenerates to a step, f = d < end ? 1 : 0.
        p.emit(Op::Slt, fx, d, fogValue(2));
      }
    } else if (table == FOG_EXP) {
      // f = 1/e^(d*density) = 2^(-d*density*log2(e))
      p.emit(Op::Mul, fx, d, fogValue(3));
      p.emit(Op::Exp2, fx, fxxxx).saturate = true;
    } else {
      // f = 1/e^((d*density)^2) = 2^(-(d*density*sqrt(log2(e)))^2)
      p.emit(Op::Mul, fx, d, fogValue(4));
      Src neg = fxxxx;
      neg.mod = SrcMod::Neg;
      p.emit(Op::Mul, fx, fxxxx, neg);
      p.emit(Op::Exp2, fx, fxxxx).saturate = true;
    }
  } else {
    // Vertex fog: f interpolated from the vertex stage.
    p.emit(Op::Mov, fx, reg(RegFile::Input, kPixelInFog, kSwzXXXX)).saturate = true;
  }
  // rgb = f*C + (1 - f)*FOGCOLOR; alpha unchanged.
  p.emit(Op::Lrp, rgb, fxxxx, color, reg(RegFile::Const, kConstPixelFog + 5));
}

void fixedFunctionPixelConstants(const DeviceState& state, std::vector<Vec4>& c) {
  c.resize(std::max(c.size(), size_t(kConstFixedPixelEnd)));
  for (int n = 0; n < kBumpEnvStages && n < kStages; ++n) {
    c[kConstBumpEnv + 2 * n] = Vec4(state.tssFloat(n, TSS_BUMPENVMAT00), state.tssFloat(n, TSS_BUMPENVMAT01),
                                    state.tssFloat(n, TSS_BUMPENVMAT10), state.tssFloat(n, TSS_BUMPENVMAT11));
    c[kConstBumpEnv + 2 * n + 1] =
        Vec4(state.tssFloat(n, TSS_BUMPENVLSCALE), state.tssFloat(n, TSS_BUMPENVLOFFSET), 0, 0);
    c[kConstBumpEnvRows + 2 * n] = Vec4(state.tssFloat(n, TSS_BUMPENVMAT00), state.tssFloat(n, TSS_BUMPENVMAT01), 0, 0);
    c[kConstBumpEnvRows + 2 * n + 1] =
        Vec4(state.tssFloat(n, TSS_BUMPENVMAT10), state.tssFloat(n, TSS_BUMPENVMAT11), 0, 0);
    c[kConstStageConstant + n] = toVec4(colorFromD3D(state.tss(n, TSS_CONSTANT)));
  }
  c[kConstTextureFactor] = toVec4(colorFromD3D(state.rs(RS_TEXTUREFACTOR)));
  const float start = state.rsFloat(RS_FOGSTART), end = state.rsFloat(RS_FOGEND);
  const float density = state.rsFloat(RS_FOGDENSITY);
  const float log2e = 1.4426950408889634f;
  auto splat = [](float v) { return Vec4(v, v, v, v); };
  const float k = 1.0f / (end - start);  // unused (infinite) when end == start
  c[kConstPixelFog] = splat(-k);
  c[kConstPixelFog + 1] = splat(end * k);
  c[kConstPixelFog + 2] = splat(end);
  c[kConstPixelFog + 3] = splat(-density * log2e);
  c[kConstPixelFog + 4] = splat(density * std::sqrt(log2e));
  c[kConstPixelFog + 5] = toVec4(colorFromD3D(state.rs(RS_FOGCOLOR)));
}

}  // namespace refx::pipeline
