// Code generation for IR programs (x86-64, AsmJit's compiler): the 16 lanes of a
// batch are one zmm register (AVX-512) or two ymm registers (AVX2). Registers stay in
// memory between instructions, where the interpreter's routines find them: simple
// ops are emitted inline with the interpreter's exact operation sequence (no fused
// multiply-add: the interpreter is compiled with -ffp-contract=off), everything
// else calls the interpreter's routine for that one instruction.
#include <asmjit/x86.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <vector>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "exec/jit/jit.h"
#include "exec/lane_math.h"

namespace refx::exec::detail {

namespace {

using namespace asmjit;

constexpr int kRegisterBytes = int(sizeof(LaneVec4));
constexpr int kComponentBytes = kBatchLanes * int(sizeof(float));

JitRuntime& runtime() {
  static JitRuntime* rt = new JitRuntime;  // code lives as long as the process
  return *rt;
}

struct FailOnError : ErrorHandler {
  Error error = kErrorOk;
  void handleError(Error err, const char*, BaseEmitter*) override { error = err; }
};

// Called by generated code: one instruction run by the interpreter.
void callInstruction(JitFrame* f, uint32_t index) {
  executeInstruction(f->program->code[index], *f->program, *f->ctx, *f->regs);
}

// Called by generated code: source i of an instruction as the interpreter reads it.
void fetchSourceLanes(JitFrame* f, uint32_t index, uint32_t i, float* out) {
  fetchSource(f->program->code[index].src[i], *f->program, *f->ctx, *f->regs,
              reinterpret_cast<float (*)[kBatchLanes]>(out));
}

// Sources read through the interpreter's fetch: relative addressing, and the integer
// and boolean constant files.
bool fetchedByHelper(const Src& s) {
  return s.rel != RelMode::None || s.file == RegFile::ConstInt || s.file == RegFile::ConstBool;
}

bool isLaneFile(RegFile f) { return f == RegFile::Temp || f == RegFile::Input || f == RegFile::Output; }

// Ops the interpreter's prepared path runs with affine source modifiers (v * k + o);
// the others read sources through applySourceModifier.
bool affineModifierOp(Op op) {
  switch (op) {
    case Op::Mov: case Op::Add: case Op::Sub: case Op::Mul: case Op::Mad: case Op::Min:
    case Op::Max: case Op::Lrp: case Op::Cmp: case Op::Dp3: case Op::Dp4: return true;
    default: return false;
  }
}

// 16 lanes: one zmm, or two ymm (p[0] lanes 0..7, p[1] lanes 8..15).
struct V {
  x86::Vec p[2];
};

class Generator {
 public:
  // Instructions [begin, end) of `program`. `generic`: as the interpreter's
  // reference routine runs them (programs with flow control), else as its prepared
  // path does (they differ in how source modifiers round: applySourceModifier or v * k + o).
  Generator(x86::Compiler& cc, const Program& program, JitIsa isa, JitProgram& out, size_t begin, size_t end,
            bool generic)
      : cc_(cc), program_(program), wide_(isa == JitIsa::Avx512), parts_(wide_ ? 1 : 2), out_(out),
        begin_(begin), end_(end), generic_(generic) {}

  void run() {
    FuncNode* fn = cc_.addFunc(FuncSignatureT<void, JitFrame*>(CallConvId::kHost));
    fn->frame().setAvxEnabled();
    fn->frame().setAvxCleanup();
    if (wide_) fn->frame().setAvx512Enabled();
    frame_ = cc_.newIntPtr("frame");
    fn->setArg(0, frame_);
    // Base pointers of the files the program names (loaded once, before any branch).
    bool named[8] = {};
    for (size_t i = begin_; i < end_; ++i) {
      const Instr& in = program_.code[i];
      named[int(in.dst.file)] = true;
      for (const Src& src : in.src) {
        named[int(src.file)] = true;
        if (src.rel == RelMode::Temp) named[int(RegFile::Temp)] = true;  // the address register
      }
    }
    if (named[int(RegFile::Temp)]) temps_ = load(offsetof(JitFrame, temps));
    if (named[int(RegFile::Input)]) inputs_ = load(offsetof(JitFrame, inputs));
    if (named[int(RegFile::Output)]) outputs_ = load(offsetof(JitFrame, outputs));
    if (named[int(RegFile::Const)]) constants_ = load(offsetof(JitFrame, constants));
    if (named[int(RegFile::Imm)] || named[int(RegFile::Const)]) immediates_ = load(offsetof(JitFrame, immediates));
    findOverwrittenStores();
    for (size_t i = begin_; i < end_; ++i) {
      current_ = i;
      if (i + 1 < end_ && pairable(program_.code[i], program_.code[i + 1])) {
        emitTexPair(uint32_t(i), uint32_t(i + 1));
        ++i;
      } else {
        emitInstruction(uint32_t(i));
      }
    }
    cc_.endFunc();
  }

 private:
  x86::Gp load(size_t offset) {
    x86::Gp r = cc_.newIntPtr();
    cc_.mov(r, x86::ptr(frame_, int32_t(offset)));
    return r;
  }

  // ------------------------------------------------------------------ selection

  // Instructions whose code reads registers only through laneValue (the value this
  // code last stored, or a load): no call, no helper reading registers in place.
  bool readsThroughValues(const Instr& in) const {
    if (!inlined(in) || sampledDirectly(in)) return false;
    switch (in.op) {
      case Op::Kill: case Op::Exp2: case Op::Log2: case Op::Pow: case Op::Lit: case Op::ExpP: case Op::SinCos:
        return false;
      default: break;
    }
    for (int i = 0; i < sourceCount(in.op); ++i)
      if (fetchedByHelper(in.src[i])) return false;
    return true;
  }

  // The component stores that a later instruction of this code overwrites before
  // anything could read memory for them: only such instructions (readsThroughValues)
  // lie in between, and they read the value held, not memory. overwritten_[i - begin_]
  // bit c: instruction i's store of component c is left out. What a run leaves in every
  // register is unchanged (the last store of each stays).
  void findOverwrittenStores() {
    overwritten_.assign(end_ - begin_, 0);
    for (size_t i = begin_; i < end_; ++i) {
      const Instr& in = program_.code[i];
      if (!readsThroughValues(in) || in.op == Op::Kill || !isLaneFile(in.dst.file)) continue;
      for (int c = 0; c < 4; ++c) {
        if (!(in.dst.mask >> c & 1)) continue;
        for (size_t j = i + 1; j < end_; ++j) {
          const Instr& next = program_.code[j];
          if (!readsThroughValues(next)) break;
          // crs writes .xyz only (emitCrs)
          const uint8_t stored = next.op == Op::Crs ? next.dst.mask & 0x7 : next.dst.mask;
          if (next.dst.file == in.dst.file && next.dst.index == in.dst.index && (stored >> c & 1)) {
            overwritten_[i - begin_] |= uint8_t(1u << c);
            break;
          }
        }
      }
    }
  }

  bool inlined(const Instr& in) const {
    switch (in.op) {
      case Op::Mov: case Op::Add: case Op::Sub: case Op::Mul: case Op::Mad: case Op::Dp3:
      case Op::Dp4: case Op::Dp2Add: case Op::Min: case Op::Max: case Op::Slt: case Op::Sge:
      case Op::Lrp: case Op::Cmp: case Op::Cnd: case Op::Frc: case Op::Floor: case Op::Abs:
      case Op::Rcp: case Op::Rsq: case Op::Nrm: case Op::Kill: case Op::Round: case Op::Dist: case Op::Crs:
      case Op::Sgn: case Op::Quot: case Op::SetP: case Op::Dsx: case Op::Dsy: case Op::Exp2: case Op::Log2:
      case Op::Pow: case Op::Lit: case Op::ExpP: case Op::SinCos: break;
      default: return false;
    }
    if (in.op != Op::Kill && (in.dst.rel != RelMode::None || !isLaneFile(in.dst.file))) return false;
    for (int i = 0; i < sourceCount(in.op); ++i) {
      const Src& s = in.src[i];
      if (fetchedByHelper(s)) continue;
      if (!isLaneFile(s.file) && s.file != RegFile::Const && s.file != RegFile::Imm) return false;
    }
    return true;
  }

  static bool isTexture(Op op) {
    return op == Op::Tex || op == Op::TexProj || op == Op::TexBias || op == Op::TexLod || op == Op::TexGrad;
  }

  // Texture lookups with plain operands: the binding's sample() called directly.
  bool sampledDirectly(const Instr& in) const {
    if (!isTexture(in.op) || in.dst.rel != RelMode::None || !isLaneFile(in.dst.file)) return false;
    for (int i = 0; i < sourceCount(in.op); ++i) {
      const Src& s = in.src[i];
      if (s.rel != RelMode::None || !(isLaneFile(s.file) || s.file == RegFile::Const || s.file == RegFile::Imm))
        return false;
    }
    return true;
  }

  void emitInstruction(uint32_t index) {
    const Instr& in = program_.code[index];
    for (int i = 0; i < 3; ++i) fetched_[i] = gathered_[i] = false;
    if (sampledDirectly(in)) {
      emitTex(index);
      return;
    }
    if (!inlined(in)) {
      emitCall(index);
      return;
    }
    ++out_.inlineInstructions;
    affine_ = !generic_ && affineModifierOp(in.op);
    for (int i = 0; i < sourceCount(in.op); ++i) {
      const Src& s = in.src[i];
      if (fetchedByHelper(s)) {
        // The interpreter's routine runs such instructions: modifiers through applySourceModifier.
        affine_ = false;
        gathered_[i] = gatheredConstant(s);
        fetched_[i] = !gathered_[i];
        if (gathered_[i]) use(RegFile::Temp, s.relReg);
        else emitFetch(index, i);
        continue;
      }
      float k, o;
      if (isLaneFile(s.file) && s.mod != SrcMod::None && !affineSourceModifier(s.mod, k, o)) affine_ = false;
      if (isLaneFile(s.file)) use(s.file, s.index);
    }
    if (in.op != Op::Kill) use(in.dst.file, in.dst.index);
    switch (in.op) {
      case Op::Mov: emitMov(in); break;
      case Op::Add: emitAdd(in); break;
      case Op::Sub: emitSub(in); break;
      case Op::Mul: emitMul(in); break;
      case Op::Mad: emitMad(in); break;
      case Op::Dp3: case Op::Dp4: case Op::Dp2Add: emitDot(in); break;
      case Op::Min: emitMin(in); break;
      case Op::Max: emitMax(in); break;
      case Op::Slt: emitSlt(in); break;
      case Op::Sge: emitSge(in); break;
      case Op::Lrp: emitLrp(in); break;
      case Op::Cmp: emitCmp(in); break;
      case Op::Cnd: emitCnd(in); break;
      case Op::Frc: emitFrc(in); break;
      case Op::Floor: emitFloor(in); break;
      case Op::Abs: emitAbs(in); break;
      case Op::Rcp: emitRcp(in); break;
      case Op::Rsq: emitRsq(in); break;
      case Op::Nrm: emitNrm(in); break;
      case Op::Kill: emitKill(in); break;
      case Op::Round: emitRound(in); break;
      case Op::Dist: emitDist(in); break;
      case Op::Crs: emitCrs(in); break;
      case Op::Sgn: emitSgn(in); break;
      case Op::Quot: emitQuot(in); break;
      case Op::SetP: emitSetP(in); break;
      case Op::Dsx: case Op::Dsy: emitDerivative(in); break;
      case Op::Exp2: emitLaneHelper(in, exp2Lanes); break;
      case Op::Log2: emitLaneHelper(in, log2Lanes); break;
      case Op::Pow: emitLaneHelper(in, powLanes); break;
      case Op::Lit: emitLaneHelper(in, litLanes); break;
      case Op::ExpP: emitLaneHelper(in, expPLanes); break;
      case Op::SinCos: emitLaneHelper(in, sinCosLanes); break;
      default: break;
    }
  }

  // Source i of instruction `index` into a stack buffer by the interpreter's fetch
  // (before any result of the instruction is written).
  void emitFetch(uint32_t index, int i) {
    fetchedAt_[i] = cc_.newStack(4 * kComponentBytes, 64);
    forget();
    x86::Gp out = cc_.newIntPtr();
    cc_.lea(out, fetchedAt_[i]);
    InvokeNode* call;
    cc_.invoke(&call, imm(reinterpret_cast<void*>(&fetchSourceLanes)),
               FuncSignatureT<void, JitFrame*, uint32_t, uint32_t, float*>(CallConvId::kHost));
    call->setArg(0, frame_);
    call->setArg(1, imm(index));
    call->setArg(2, imm(i));
    call->setArg(3, out);
    forget();
  }

  // c[a0.x + n] (a0 in a temp) read natively when the program defines no local
  // constant (which would override the API's at some indices).
  bool gatheredConstant(const Src& s) const {
    if (s.rel != RelMode::Temp || s.file != RegFile::Const) return false;
    for (const auto local : program_.localConstants)
      if (local >= 0) return false;
    return true;
  }

  // Component `comp` of c[n + int(temp)] per lane, as the interpreter's uniformValue
  // reads it: indices truncated toward zero (cvttps2dq: NaN and huge values give
  // INT_MIN, as the interpreter's conversion), API constants below
  // ExecContext::constantCount, zero elsewhere.
  V gatherConstant(const Src& s, int comp) {
    const V address = laneValue(RegFile::Temp, s.relReg, s.relComp & 3);
    return memo({9, id(address), s.index, uint32_t(comp)}, [&] {
      x86::Gp ctx = load(offsetof(JitFrame, ctx));
      x86::Gp count = cc_.newInt32(), base = cc_.newIntPtr();
      cc_.mov(count, x86::dword_ptr(ctx, int32_t(offsetof(ExecContext, constantCount))));
      cc_.mov(base, x86::ptr(ctx, int32_t(offsetof(ExecContext, constants))));
      const V n = splatBits(s.index);  // the integer n
      V r = newV();
      for (int h = 0; h < parts_; ++h) {
        x86::Vec index = newVec(), limit = newVec(), offset = newVec();
        cc_.vcvttps2dq(index, address.p[h]);
        cc_.vpaddd(index, index, n.p[h]);
        cc_.vmovd(limit.xmm(), count);
        cc_.vpbroadcastd(limit, limit.xmm());
        // Byte offset index * 16 as (index * 4) scaled by 4: gathers scale by at most 8.
        cc_.vpslld(offset, index, imm(2));
        cc_.vxorps(r.p[h], r.p[h], r.p[h]);  // lanes out of range read zero
        const x86::Mem at = x86::ptr(base, offset, 2, comp * 4);
        if (wide_) {
          x86::KReg k = cc_.newKw();
          cc_.vpcmpud(k, index, limit, imm(1));  // unsigned <: negative indices are out too
          cc_.k(k).vgatherdps(r.p[h], at);
        } else {
          x86::Vec inside = newVec(), minusOne = newVec();
          cc_.vpcmpgtd(inside, limit, index);  // index < count
          cc_.vpcmpeqd(minusOne, minusOne, minusOne);
          cc_.vpcmpgtd(minusOne, index, minusOne);  // index > -1
          cc_.vpand(inside, inside, minusOne);
          cc_.vgatherdps(r.p[h], at, inside);
        }
      }
      return r;
    });
  }

  void use(RegFile f, int index) {
    int& n = f == RegFile::Temp ? out_.tempsUsed : f == RegFile::Input ? out_.inputsUsed : out_.outputsUsed;
    n = std::max(n, index + 1);
  }

  void emitCall(uint32_t index) {
    ++out_.calledInstructions;
    forget();
    InvokeNode* call;
    cc_.invoke(&call, imm(reinterpret_cast<void*>(&callInstruction)),
               FuncSignatureT<void, JitFrame*, uint32_t>(CallConvId::kHost));
    call->setArg(0, frame_);
    call->setArg(1, imm(index));
  }

  // The binding's sample() called as the interpreter calls it: coordinates (and
  // gradients) read in place when they are one register's .xyzw, else computed into a
  // stack buffer (texldp divided by w first); the result written in place when all
  // four components go unmodified to a register that is not a source, else through a
  // buffer with the result modifiers. An unbound sampler takes the interpreter's
  // routine (which returns D3D's (0,0,0,1)).
  static bool coordsInPlace(const Instr& in) {
    const Src& coord = in.src[0];
    return (in.op == Op::Tex || in.op == Op::TexBias || in.op == Op::TexLod) && isLaneFile(coord.file) &&
           coord.swizzle == kSwzXYZW && coord.mod == SrcMod::None;
  }
  static bool resultInPlace(const Instr& in) {
    bool alias = false;
    for (int i = 0; i < sourceCount(in.op); ++i)
      alias |= in.src[i].file == in.dst.file && in.src[i].index == in.dst.index;
    return in.dst.mask == 0xF && in.shift == 0 && !in.saturate && !in.clamp && !in.quantize && !alias;
  }
  static bool sameRegister(const Src& s, const Dst& d) { return s.file == d.file && s.index == d.index; }

  // Two implicit lookups in a row that one samplePair call can make: both read their
  // coordinates and write all of their result in place, and the first one's result is
  // neither what the second reads nor where the second writes.
  bool pairable(const Instr& a, const Instr& b) const {
    return a.op == Op::Tex && b.op == Op::Tex && sampledDirectly(a) && sampledDirectly(b) && coordsInPlace(a) &&
           coordsInPlace(b) && resultInPlace(a) && resultInPlace(b) && !sameRegister(b.src[0], a.dst) &&
           !(a.dst.file == b.dst.file && a.dst.index == b.dst.index);
  }

  // The lanes a lookup produces: all four of every 2x2 quad with a live lane (quadLanes()).
  x86::Gp quadLanes() {
    x86::Gp lanes = cc_.newUInt32(), t = cc_.newUInt32();
    x86::Gp mask = load(offsetof(JitFrame, laneMask));
    cc_.movzx(lanes, x86::word_ptr(mask));
    cc_.mov(t, lanes), cc_.shr(t, 1), cc_.or_(lanes, t);
    cc_.mov(t, lanes), cc_.shr(t, 2), cc_.or_(lanes, t);
    cc_.and_(lanes, 0x1111);
    cc_.imul(lanes, lanes, 15);
    return lanes;
  }

  // A pairable a, b: one samplePair call where both bindings have the same one,
  // else the two lookups as emitTex makes them.
  void emitTexPair(uint32_t ia, uint32_t ib) {
    const Instr& a = program_.code[ia];
    const Instr& b = program_.code[ib];
    forget();
    Label separate = cc_.newLabel(), done = cc_.newLabel();
    x86::Gp ctx = load(offsetof(JitFrame, ctx));
    x86::Gp count = cc_.newInt32();
    cc_.mov(count, x86::dword_ptr(ctx, int32_t(offsetof(ExecContext, samplerCount))));
    cc_.cmp(count, std::max(a.sampler, b.sampler));
    cc_.jle(separate);
    x86::Gp binding = cc_.newIntPtr();
    cc_.mov(binding, x86::ptr(ctx, int32_t(offsetof(ExecContext, samplers))));
    const int32_t atA = int32_t(a.sampler * sizeof(SamplerBinding)), atB = int32_t(b.sampler * sizeof(SamplerBinding));
    const int32_t pairFn = int32_t(offsetof(SamplerBinding, samplePair));
    const int32_t pairContext = int32_t(offsetof(SamplerBinding, pairContext));
    x86::Gp fn = cc_.newIntPtr();
    cc_.mov(fn, x86::ptr(binding, atA + pairFn));
    cc_.test(fn, fn);
    cc_.jz(separate);
    cc_.cmp(fn, x86::ptr(binding, atB + pairFn));
    cc_.jne(separate);
    x86::Gp contextA = cc_.newIntPtr(), contextB = cc_.newIntPtr();
    cc_.mov(contextA, x86::ptr(binding, atA + pairContext));
    cc_.mov(contextB, x86::ptr(binding, atB + pairContext));
    x86::Gp coordsA = cc_.newIntPtr(), coordsB = cc_.newIntPtr(), outA = cc_.newIntPtr(), outB = cc_.newIntPtr();
    cc_.lea(coordsA, lane(a.src[0].file, a.src[0].index, 0, 0));
    cc_.lea(coordsB, lane(b.src[0].file, b.src[0].index, 0, 0));
    cc_.lea(outA, lane(a.dst.file, a.dst.index, 0, 0));
    cc_.lea(outB, lane(b.dst.file, b.dst.index, 0, 0));
    const x86::Gp lanes = quadLanes();
    InvokeNode* call;
    cc_.invoke(&call, fn,
               FuncSignatureT<void, const void*, const void*, const void*, const void*, uint16_t, void*, void*>(
                   CallConvId::kHost));
    call->setArg(0, contextA);
    call->setArg(1, contextB);
    call->setArg(2, coordsA);
    call->setArg(3, coordsB);
    call->setArg(4, lanes);
    call->setArg(5, outA);
    call->setArg(6, outB);
    cc_.jmp(done);
    cc_.bind(separate);
    emitTex(ia);
    emitTex(ib);
    cc_.bind(done);
    forget();  // values of one branch are not defined after the join
  }

  void emitTex(uint32_t index) {
    const Instr& in = program_.code[index];
    ++out_.inlineInstructions;
    affine_ = false;  // the interpreter reads texture operands through applySourceModifier
    const Src& coord = in.src[0];
    for (int i = 0; i < sourceCount(in.op); ++i)
      if (isLaneFile(in.src[i].file)) use(in.src[i].file, in.src[i].index);
    use(in.dst.file, in.dst.index);
    const bool coordsInPlace = this->coordsInPlace(in);
    const bool resultInPlace = this->resultInPlace(in);
    forget();
    Label unbound = cc_.newLabel(), done = cc_.newLabel();
    x86::Gp ctx = load(offsetof(JitFrame, ctx));
    x86::Gp count = cc_.newInt32();
    cc_.mov(count, x86::dword_ptr(ctx, int32_t(offsetof(ExecContext, samplerCount))));
    cc_.cmp(count, in.sampler);
    cc_.jle(unbound);
    x86::Gp binding = cc_.newIntPtr();
    cc_.mov(binding, x86::ptr(ctx, int32_t(offsetof(ExecContext, samplers))));
    const int32_t at = int32_t(in.sampler * sizeof(SamplerBinding));
    x86::Gp fn = cc_.newIntPtr();
    cc_.mov(fn, x86::ptr(binding, at + int32_t(offsetof(SamplerBinding, sample))));
    cc_.test(fn, fn);
    cc_.jz(unbound);

    x86::Gp coords = cc_.newIntPtr(), out = cc_.newIntPtr();
    if (coordsInPlace) {
      cc_.lea(coords, lane(coord.file, coord.index, 0, 0));
    } else {
      const x86::Mem buffer = cc_.newStack(12 * kComponentBytes, 64);
      V c[4];
      for (int k = 0; k < 4; ++k) c[k] = source(in, 0, k);
      if (in.op == Op::TexProj) {  // iw = 1 / w; xyz *= iw
        const V iw = div(splat(1.0f), c[3]);
        for (int k = 0; k < 3; ++k) c[k] = mul(c[k], iw);
      }
      for (int k = 0; k < 4; ++k) put(buffer, k, c[k]);
      if (in.op == Op::TexGrad)
        for (int k = 0; k < 4; ++k) put(buffer, 4 + k, source(in, 1, k)), put(buffer, 8 + k, source(in, 2, k));
      cc_.lea(coords, buffer);
    }
    const x86::Mem result = cc_.newStack(4 * kComponentBytes, 64);
    if (resultInPlace) cc_.lea(out, lane(in.dst.file, in.dst.index, 0, 0));
    else cc_.lea(out, result);
    x86::Gp context = cc_.newIntPtr();
    cc_.mov(context, x86::ptr(binding, at + int32_t(offsetof(SamplerBinding, context))));
    const x86::Gp lanes = quadLanes();
    const SampleMode mode = in.op == Op::TexBias  ? SampleMode::Bias
                            : in.op == Op::TexLod  ? SampleMode::Lod
                            : in.op == Op::TexGrad ? SampleMode::Grad
                                                   : SampleMode::Implicit;
    InvokeNode* call;
    cc_.invoke(&call, fn,
               FuncSignatureT<void, const void*, uint8_t, const void*, uint16_t, void*>(CallConvId::kHost));
    call->setArg(0, context);
    call->setArg(1, imm(int(mode)));
    call->setArg(2, coords);
    call->setArg(3, lanes);
    call->setArg(4, out);
    forget();
    if (!resultInPlace) {
      V r[4];
      for (int c = 0; c < 4; ++c)
        if (in.dst.mask >> c & 1) r[c] = loadLanes(result.cloneAdjusted(c * kComponentBytes));
      store(in, r);
    }
    cc_.jmp(done);
    cc_.bind(unbound);
    emitCall(index);
    --out_.calledInstructions;
    cc_.bind(done);
    forget();  // values of one branch are not defined after the join
  }

  void put(const x86::Mem& buffer, int row, const V& v) {
    for (int h = 0; h < parts_; ++h) cc_.vmovups(buffer.cloneAdjusted(row * kComponentBytes + h * 32), v.p[h]);
  }

  // ------------------------------------------------------------------ values

  x86::Vec newVec() { return wide_ ? x86::Vec(cc_.newZmmPs()) : x86::Vec(cc_.newYmmPs()); }
  V newV() {
    V v;
    for (int h = 0; h < parts_; ++h) v.p[h] = newVec();
    return v;
  }
  // Values are never modified once computed, so an op on the same operands gives
  // the same value: computed once (replicated results such as a dot product's, the
  // same modifier on each component, constants) while no call intervenes.
  using Key = std::array<uint32_t, 6>;
  static uint32_t id(const V& v) { return v.p[0].id(); }
  template <class F>
  V memo(const Key& key, F make) {
    auto it = values_.find(key);
    if (it != values_.end()) return it->second;
    const V v = make();
    values_.emplace(key, v);
    return v;
  }
  // Calls may write any register, and values kept across them would be spilled.
  void forget() {
    values_.clear();
    registers_.clear();
  }
  V splatBits(uint32_t bits) {
    return memo({1, bits}, [&] {
      V v;
      v.p[0] = v.p[1] = newVec();
      cc_.vbroadcastss(v.p[0], cc_.newDWordConst(ConstPoolScope::kLocal, bits));
      return v;
    });
  }
  V splat(float x) {
    uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const V v = splatBits(bits);
    if (std::isfinite(x)) ranges_.try_emplace(id(v), Range{double(x), double(x)});
    return v;
  }
  V op2(InstId inst, const V& a, const V& b) {
    return memo({2, inst, id(a), id(b)}, [&] {
      V r = newV();
      for (int h = 0; h < parts_; ++h) cc_.emit(inst, r.p[h], a.p[h], b.p[h]);
      noteRange(r, inst, a, b);
      return r;
    });
  }

  // ------------------------------------------------------------------ value ranges

  // What is known of a value: every lane a number (no NaN) in [lo, hi], bounds on the
  // exact results of the operations that made it. The IEEE result of an operation on
  // such values lies within the rounded bounds (rounding is monotone), so a clamp to
  // float bounds that contain them changes no lane (storeClamped).
  struct Range {
    double lo, hi;
  };
  const Range* rangeOf(const V& v) const {
    const auto it = ranges_.find(id(v));
    return it == ranges_.end() ? nullptr : &it->second;
  }
  void setRange(const V& v, double lo, double hi) {
    if (std::fabs(lo) < 1e30 && std::fabs(hi) < 1e30) ranges_[id(v)] = {lo, hi};  // far from overflow
  }
  // a + b and a * b in double, rounded down or up where inexact (the error terms of
  // TwoSum and of an FMA), so the bounds hold for the exact results.
  static double sumBound(double a, double b, bool up) {
    const double s = a + b, bb = s - a, e = (a - (s - bb)) + (b - bb);
    return up ? (e > 0 ? std::nextafter(s, HUGE_VAL) : s) : (e < 0 ? std::nextafter(s, -HUGE_VAL) : s);
  }
  static double productBound(double a, double b, bool up) {
    const double p = a * b, e = std::fma(a, b, -p);
    return up ? (e > 0 ? std::nextafter(p, HUGE_VAL) : p) : (e < 0 ? std::nextafter(p, -HUGE_VAL) : p);
  }
  static Range productRange(const Range& a, const Range& b) {
    const double x[2] = {a.lo, a.hi}, y[2] = {b.lo, b.hi};
    Range r{HUGE_VAL, -HUGE_VAL};
    for (double u : x)
      for (double w : y) r.lo = std::min(r.lo, productBound(u, w, false)), r.hi = std::max(r.hi, productBound(u, w, true));
    return r;
  }
  void noteRange(const V& r, InstId inst, const V& a, const V& b) {
    const Range *ra = rangeOf(a), *rb = rangeOf(b);
    if (!ra || !rb) return;
    if (inst == x86::Inst::kIdVaddps) {
      setRange(r, sumBound(ra->lo, rb->lo, false), sumBound(ra->hi, rb->hi, true));
    } else if (inst == x86::Inst::kIdVsubps) {
      setRange(r, sumBound(ra->lo, -rb->hi, false), sumBound(ra->hi, -rb->lo, true));
    } else if (inst == x86::Inst::kIdVmulps) {
      const Range p = productRange(*ra, *rb);
      setRange(r, p.lo, p.hi);
    }
  }
  // Whether clamping v to [lo, hi] (vmaxps then vminps) gives v itself in every lane:
  // v has no NaN and lies within the bounds, and no bound is a zero a signed zero of
  // v could meet (vmaxps(-0, +0) gives +0).
  bool clampKeeps(const V& v, float lo, float hi) const {
    const Range* r = rangeOf(v);
    if (!r || r->lo < double(lo) || r->hi > double(hi)) return false;
    return !(lo == 0.0f && r->lo <= 0.0) && !(hi == 0.0f && r->hi >= 0.0);
  }
  V add(const V& a, const V& b) { return op2(x86::Inst::kIdVaddps, a, b); }
  V sub(const V& a, const V& b) { return op2(x86::Inst::kIdVsubps, a, b); }
  V mul(const V& a, const V& b) { return op2(x86::Inst::kIdVmulps, a, b); }
  V div(const V& a, const V& b) { return op2(x86::Inst::kIdVdivps, a, b); }
  // a * b + c in one rounding (vfmadd213ps). Only where a * b is exact, such as b = ±2,
  // is it the interpreter's product then sum.
  V mulAddExact(const V& a, const V& b, const V& c) {
    return memo({2, x86::Inst::kIdVfmadd213ps, id(a), id(b), id(c)}, [&] {
      V r = newV();
      for (int h = 0; h < parts_; ++h) {
        cc_.emit(x86::Inst::kIdVmovaps, r.p[h], a.p[h]);
        cc_.emit(x86::Inst::kIdVfmadd213ps, r.p[h], b.p[h], c.p[h]);
      }
      const Range *ra = rangeOf(a), *rb = rangeOf(b), *rc = rangeOf(c);
      if (ra && rb && rc) {
        const Range p = productRange(*ra, *rb);
        setRange(r, sumBound(p.lo, rc->lo, false), sumBound(p.hi, rc->hi, true));
      }
      return r;
    });
  }
  // a < b ? a : b and a > b ? a : b, as minps/maxps (NaN: b).
  V min(const V& a, const V& b) { return op2(x86::Inst::kIdVminps, a, b); }
  V max(const V& a, const V& b) { return op2(x86::Inst::kIdVmaxps, a, b); }
  V bitAnd(const V& a, uint32_t bits) { return op2(x86::Inst::kIdVandps, a, splatBits(bits)); }
  V bitOr(const V& a, uint32_t bits) { return op2(x86::Inst::kIdVorps, a, splatBits(bits)); }
  V bitXor(const V& a, uint32_t bits) { return op2(x86::Inst::kIdVxorps, a, splatBits(bits)); }
  // Rounding of roundps/rndscaleps: 1 = down (floor), 4 = the MXCSR mode; 8 = no
  // precision exception.
  V round(const V& a, int mode) {
    return memo({3, uint32_t(mode), id(a)}, [&] {
      V r = newV();
      for (int h = 0; h < parts_; ++h) {
        if (wide_) cc_.vrndscaleps(r.p[h], a.p[h], imm(mode | 8));
        else cc_.vroundps(r.p[h], a.p[h], imm(mode | 8));
      }
      return r;
    });
  }
  V sqrt(const V& a) {
    return memo({4, id(a)}, [&] {
      V r = newV();
      for (int h = 0; h < parts_; ++h) cc_.vsqrtps(r.p[h], a.p[h]);
      return r;
    });
  }
  // compare(a, b) ? t : f with a vcmpps predicate (ordered, NaN false).
  static constexpr int kEqual = 0x00, kLess = 0x01, kLessEqual = 0x02, kNotEqual = 0x04, kGreaterEqual = 0x0D,
                       kGreater = 0x0E;
  V select(int predicate, const V& a, const V& b, const V& t, const V& f) {
    return memo({5, uint32_t(predicate), id(a), id(b), id(t), id(f)}, [&] { return selectNew(predicate, a, b, t, f); });
  }
  V selectNew(int predicate, const V& a, const V& b, const V& t, const V& f) {
    V r = newV();
    for (int h = 0; h < parts_; ++h) {
      if (wide_) {
        x86::KReg k = cc_.newKw();
        cc_.vcmpps(k, a.p[h], b.p[h], imm(predicate));
        cc_.k(k).vblendmps(r.p[h], f.p[h], t.p[h]);
      } else {
        x86::Vec m = newVec();
        cc_.vcmpps(m, a.p[h], b.p[h], imm(predicate));
        cc_.vblendvps(r.p[h], f.p[h], t.p[h], m);
      }
    }
    return r;
  }

  // A register component: the value last stored there by this code, else loaded.
  V laneValue(RegFile f, int index, int c) {
    const std::array<int, 3> key{int(f), index, c};
    auto it = registers_.find(key);
    if (it != registers_.end()) return it->second;
    const V v = loadLanes(lane(f, index, c, 0));
    registers_.emplace(key, v);
    return v;
  }

  // 16 lanes from memory. AVX-512: one 64-byte load, as the AVX-512 producers of the
  // registers a program reads most (the interpolation, the group texture lookups)
  // store them: a load matching a recent store is forwarded from the store buffer.
  // (Two 32-byte loads suit the 8-lane producers better, but measured 2% slower on the
  // RacorX workloads.)
  V loadLanes(const x86::Mem& at) {
    V v = newV();
    if (wide_) {
      cc_.vmovups(v.p[0], at);
    } else {
      for (int h = 0; h < parts_; ++h) cc_.vmovups(v.p[h], at.cloneAdjusted(h * 32));
    }
    return v;
  }

  x86::Gp base(RegFile f) const { return f == RegFile::Temp ? temps_ : f == RegFile::Input ? inputs_ : outputs_; }
  x86::Mem lane(RegFile f, int index, int c, int h) const {
    return x86::ptr(base(f), index * kRegisterBytes + c * kComponentBytes + h * 32);
  }

  // Source i of `in`, component c: swizzle, unit clamp and modifier as the
  // interpreter applies them.
  V source(const Instr& in, int i, int c) {
    const Src& s = in.src[i];
    if (fetched_[i]) return loadLanes(fetchedAt_[i].cloneAdjusted(c * kComponentBytes));  // swizzled, modified
    const int comp = (s.swizzle >> (2 * c)) & 3;
    if (gathered_[i]) {
      V v = gatherConstant(s, comp);
      if (s.flags & kSrcClampUnit) v = min(splat(1.0f), max(splat(-1.0f), v));
      return modify(v, s.mod);
    }
    if (isLaneFile(s.file)) {
      V v = laneValue(s.file, s.index, comp);
      if (s.mod == SrcMod::None) return v;
      float k, o;
      if (affine_ && affineSourceModifier(s.mod, k, o)) {
        // The prepared path: v * k + o (o = -0 adds nothing; so does * 1 before an
        // add, which quiets a signalling NaN as the multiplication would).
        // v * ±2 is exact (a change of exponent; overflow gives the same infinity
        // either way), so one fused rounding is the same as the two.
        if ((k == 2.0f || k == -2.0f) && o != 0.0f) return mulAddExact(v, splat(k), splat(o));
        if (k != 1.0f) v = mul(v, splat(k));
        return o == 0.0f ? v : add(v, splat(o));
      }
      return modify(v, s.mod);
    }
    const bool local = s.file == RegFile::Const && size_t(s.index) < program_.localConstants.size() &&
                       program_.localConstants[s.index] >= 0;
    V v;
    if (s.file == RegFile::Imm || local) {
      // Immediates are read when the code runs too, so programs that differ only in
      // them (fixed-function state: matrices, lights, colours) share one compiled form.
      const int immediate = local ? program_.localConstants[s.index] : s.index;
      if (size_t(immediate) >= program_.immediates.size()) {  // reads as zero
        const Vec4 zero = uniformRegisterValue(s, s.index, ExecContext{}, program_);
        return splat(applySourceModifier(zero[comp], s.mod));
      }
      v = memo({7, uint32_t(immediate), uint32_t(comp)}, [&] {
        V b;
        b.p[0] = b.p[1] = newVec();
        cc_.vbroadcastss(b.p[0], x86::dword_ptr(immediates_, immediate * int(sizeof(Vec4)) + comp * 4));
        return b;
      });
    } else {  // an API constant
      out_.constantsRead = std::max(out_.constantsRead, int(s.index) + 1);
      v = memo({6, s.index, uint32_t(comp)}, [&] {
        V b;
        b.p[0] = b.p[1] = newVec();
        cc_.vbroadcastss(b.p[0], x86::dword_ptr(constants_, int(s.index) * int(sizeof(Vec4)) + comp * 4));
        return b;
      });
    }
    if (s.flags & kSrcClampUnit) v = min(splat(1.0f), max(splat(-1.0f), v));  // std::min(std::max(v, -1), 1)
    return modify(v, s.mod);
  }

  // applySourceModifier, lane by lane.
  V modify(const V& v, SrcMod m) {
    constexpr uint32_t kSign = 0x80000000u, kMagnitude = 0x7fffffffu;
    switch (m) {
      case SrcMod::None: return v;
      case SrcMod::Neg: return bitXor(v, kSign);
      case SrcMod::Bias: return sub(v, splat(0.5f));
      case SrcMod::BiasNeg: return bitXor(sub(v, splat(0.5f)), kSign);
      case SrcMod::Sign: return mul(splat(2.0f), sub(v, splat(0.5f)));
      case SrcMod::SignNeg: return mul(splat(-2.0f), sub(v, splat(0.5f)));
      case SrcMod::Comp: return sub(splat(1.0f), v);
      case SrcMod::X2: return mul(splat(2.0f), v);
      case SrcMod::X2Neg: return mul(splat(-2.0f), v);
      case SrcMod::Abs: return bitAnd(v, kMagnitude);
      case SrcMod::AbsNeg: return bitOr(v, kSign);
    }
    return v;
  }

  // Stores the written components with the result modifiers: shift, then saturate or
  // clamp (vmin(vmax(r, lo), hi): NaN becomes lo), then the fixed-point grid. Every
  // source is read before.
  void store(const Instr& in, const V* r) {
    const bool clamp = in.saturate || in.clamp;
    for (int c = 0; c < 4; ++c) {
      if (!(in.dst.mask >> c & 1)) continue;
      V v = r[c];
      if (in.shift != 0) v = mul(v, splat(std::ldexp(1.0f, in.shift)));
      if (clamp) {
        const float lo = in.saturate ? 0.0f : in.clampLo, hi = in.saturate ? 1.0f : in.clampHi;
        if (!clampKeeps(v, lo, hi)) {
          v = min(max(v, splat(lo)), splat(hi));
          setRange(v, lo, hi);  // NaN becomes lo
        }
      }
      // Fixed point of `quantize` fractional bits: nearbyint(v * 2^q) * 2^-q.
      if (in.quantize)
        v = mul(round(mul(v, splat(std::ldexp(1.0f, in.quantize))), 4), splat(std::ldexp(1.0f, -in.quantize)));
      const bool overwritten = &in == &program_.code[current_] && (overwritten_[current_ - begin_] >> c & 1);
      if (!overwritten)
        for (int h = 0; h < parts_; ++h) cc_.vmovups(lane(in.dst.file, in.dst.index, c, h), v.p[h]);
      registers_[{int(in.dst.file), int(in.dst.index), c}] = v;
    }
  }

  // Per-component ops: f(sources of component c) for each written component.
  template <class F>
  void perComponent(const Instr& in, F f) {
    const int n = sourceCount(in.op);
    V r[4];
    for (int c = 0; c < 4; ++c) {
      if (!(in.dst.mask >> c & 1)) continue;
      V s[3];
      for (int i = 0; i < n; ++i) s[i] = source(in, i, c);
      r[c] = f(s);
    }
    store(in, r);
  }

  // ------------------------------------------------------------------ one emitter per op

  void emitMov(const Instr& in) { perComponent(in, [&](const V* s) { return s[0]; }); }
  void emitAdd(const Instr& in) { perComponent(in, [&](const V* s) { return add(s[0], s[1]); }); }
  void emitSub(const Instr& in) { perComponent(in, [&](const V* s) { return sub(s[0], s[1]); }); }
  void emitMul(const Instr& in) { perComponent(in, [&](const V* s) { return mul(s[0], s[1]); }); }
  void emitMad(const Instr& in) { perComponent(in, [&](const V* s) { return add(mul(s[0], s[1]), s[2]); }); }
  void emitMin(const Instr& in) { perComponent(in, [&](const V* s) { return min(s[0], s[1]); }); }
  void emitMax(const Instr& in) { perComponent(in, [&](const V* s) { return max(s[0], s[1]); }); }
  void emitSlt(const Instr& in) {
    perComponent(in, [&](const V* s) { return select(kLess, s[0], s[1], splat(1.0f), splat(0.0f)); });
  }
  void emitSge(const Instr& in) {
    perComponent(in, [&](const V* s) { return select(kGreaterEqual, s[0], s[1], splat(1.0f), splat(0.0f)); });
  }
  // s0 * (s1 - s2) + s2
  void emitLrp(const Instr& in) {
    perComponent(in, [&](const V* s) { return add(mul(s[0], sub(s[1], s[2])), s[2]); });
  }
  void emitCmp(const Instr& in) {
    perComponent(in, [&](const V* s) { return select(kGreaterEqual, s[0], splat(0.0f), s[1], s[2]); });
  }
  void emitCnd(const Instr& in) {
    perComponent(in, [&](const V* s) { return select(kGreater, s[0], splat(0.5f), s[1], s[2]); });
  }
  void emitFrc(const Instr& in) { perComponent(in, [&](const V* s) { return sub(s[0], round(s[0], 1)); }); }
  void emitFloor(const Instr& in) { perComponent(in, [&](const V* s) { return round(s[0], 1); }); }
  void emitAbs(const Instr& in) { perComponent(in, [&](const V* s) { return bitAnd(s[0], 0x7fffffffu); }); }
  // D3D rcp(0) = +inf: 1 / x.
  void emitRcp(const Instr& in) { perComponent(in, [&](const V* s) { return div(splat(1.0f), s[0]); }); }
  // 1 / sqrt(|x|), both correctly rounded as in the interpreter.
  void emitRsq(const Instr& in) {
    perComponent(in, [&](const V* s) {
      const V a = bitAnd(s[0], 0x7fffffffu);
      return div(splat(1.0f), sqrt(a));
    });
  }
  // dp2add: s0.x*s1.x + s0.y*s1.y + s2.x; dp3/dp4 add the next products in order.
  void emitDot(const Instr& in) {
    const int n = in.op == Op::Dp4 ? 4 : in.op == Op::Dp3 ? 3 : 2;
    V a[4], b[4];
    for (int k = 0; k < n; ++k) a[k] = source(in, 0, k), b[k] = source(in, 1, k);
    V r = add(mul(a[0], b[0]), mul(a[1], b[1]));
    if (in.op == Op::Dp2Add) r = add(r, source(in, 2, 0));
    for (int k = 2; k < n; ++k) r = add(r, mul(a[k], b[k]));
    const V all[4] = {r, r, r, r};
    store(in, all);
  }
  // All four components scaled by 1 / |xyz| (x*x + y*y + z*z in that order); a
  // zero vector is kept as it is.
  void emitNrm(const Instr& in) {
    const V x = source(in, 0, 0), y = source(in, 0, 1), z = source(in, 0, 2);
    const V d = add(add(mul(x, x), mul(y, y)), mul(z, z));
    const V one = splat(1.0f);
    const V k = select(kEqual, d, splat(0.0f), one, div(one, sqrt(d)));
    V r[4];
    for (int c = 0; c < 4; ++c)
      if (in.dst.mask >> c & 1) r[c] = mul(source(in, 0, c), k);
    store(in, r);
  }
  // nearbyint: the MXCSR rounding mode, as the interpreter's.
  void emitRound(const Instr& in) { perComponent(in, [&](const V* s) { return round(s[0], 4); }); }
  // (1, s0.y * s1.y, s0.z, s1.w)
  void emitDist(const Instr& in) {
    V r[4];
    if (in.dst.mask & 1) r[0] = splat(1.0f);
    if (in.dst.mask & 2) r[1] = mul(source(in, 0, 1), source(in, 1, 1));
    if (in.dst.mask & 4) r[2] = source(in, 0, 2);
    if (in.dst.mask & 8) r[3] = source(in, 1, 3);
    store(in, r);
  }
  // xyz only: s0[i] * s1[j] - s0[j] * s1[i] with i, j the next two components.
  void emitCrs(const Instr& in) {
    Instr xyz = in;
    xyz.dst.mask &= 0x7;
    V r[4];
    for (int c = 0; c < 3; ++c) {
      if (!(xyz.dst.mask >> c & 1)) continue;
      const int i = (c + 1) % 3, j = (c + 2) % 3;
      r[c] = sub(mul(source(in, 0, i), source(in, 1, j)), mul(source(in, 0, j), source(in, 1, i)));
    }
    store(xyz, r);
  }
  // v < 0 ? -1 : v > 0 ? 1 : 0 (NaN and -0: 0).
  void emitSgn(const Instr& in) {
    perComponent(in, [&](const V* s) {
      const V zero = splat(0.0f);
      return select(kLess, s[0], zero, splat(-1.0f), select(kGreater, s[0], zero, splat(1.0f), zero));
    });
  }
  // s1 == 0 ? 1 : s0 / s1
  void emitQuot(const Instr& in) {
    perComponent(in, [&](const V* s) {
      return select(kEqual, s[1], splat(0.0f), splat(1.0f), div(s[0], s[1]));
    });
  }
  // (s0 CMP s1) ? 1 : 0 with compare()'s predicates: != is true for NaN, the others false.
  void emitSetP(const Instr& in) {
    static constexpr int kPredicate[] = {-1, kGreater, kEqual, kGreaterEqual, kLess, kNotEqual, kLessEqual};
    const int predicate = size_t(in.cmp) < std::size(kPredicate) ? kPredicate[in.cmp] : -1;
    perComponent(in, [&](const V* s) {
      if (predicate < 0) return splat(1.0f);  // always
      return select(predicate, s[0], s[1], splat(1.0f), splat(0.0f));
    });
  }
  // Lane l = quad * 4 + (y & 1) * 2 + (x & 1): s0[l | bit] - s0[l & ~bit], lanes
  // permuted within each quad (a 128-bit lane), bit 1 for dsx, 2 for dsy.
  void emitDerivative(const Instr& in) {
    const bool x = in.op == Op::Dsx;
    const uint32_t high = x ? 0xF5 : 0xEE, low = x ? 0xA0 : 0x44;  // [1,1,3,3] [0,0,2,2] / [2,3,2,3] [0,1,0,1]
    perComponent(in, [&](const V* s) { return sub(permute(s[0], high), permute(s[0], low)); });
  }
  V permute(const V& a, uint32_t pattern) {
    return memo({8, pattern, id(a)}, [&] {
      V r = newV();
      for (int h = 0; h < parts_; ++h) cc_.vpermilps(r.p[h], a.p[h], imm(pattern));
      return r;
    });
  }

  // Ops computed with libm (exp2, log2, pow, lit, expp, sincos): the lane helper of
  // lane_math.cpp, called with pointers to its operands (a register read in place
  // when unmodified, else the source computed into a stack buffer) and to its result
  // (the destination component itself for per-component ops without result
  // modifiers that write no source, else a buffer stored with the modifiers).
  void emitLaneHelper(const Instr& in, LaneHelper fn) {
    const bool perComp = in.op == Op::Exp2 || in.op == Op::Log2 || in.op == Op::Pow;
    const uint8_t mask = in.op == Op::SinCos ? in.dst.mask & 0x3 : in.dst.mask;
    if (mask == 0) return;
    const int nsrc = sourceCount(in.op);
    bool alias = false;
    for (int i = 0; i < nsrc; ++i) alias |= in.src[i].file == in.dst.file && in.src[i].index == in.dst.index;
    const bool direct = perComp && !alias && in.shift == 0 && !in.saturate && !in.clamp && !in.quantize;
    // The (source, component) operands of each call: one call per written component
    // or one for the instruction.
    struct Call {
      int operand[3][2];  // source, component (-1: none)
      int component;      // result component (-1: all of mask)
    };
    std::vector<Call> calls;
    if (perComp) {
      for (int c = 0; c < 4; ++c)
        if (mask >> c & 1) calls.push_back({{{0, c}, {nsrc > 1 ? 1 : -1, c}, {-1, 0}}, c});
    } else if (in.op == Op::Lit) {
      calls.push_back({{{0, 0}, {0, 1}, {0, 3}}, -1});
    } else {
      calls.push_back({{{0, 0}, {-1, 0}, {-1, 0}}, -1});
    }
    const x86::Mem operands = cc_.newStack(12 * kComponentBytes, 64);
    const x86::Mem result = cc_.newStack(4 * kComponentBytes, 64);
    bool buffered[3][4] = {};
    for (const Call& call : calls)  // every source read before a result is written
      for (const auto& o : call.operand) {
        if (o[0] < 0) continue;
        const Src& s = in.src[o[0]];
        if ((isLaneFile(s.file) && s.mod == SrcMod::None && !fetched_[o[0]]) || buffered[o[0]][o[1]]) continue;
        put(operands, o[0] * 4 + o[1], source(in, o[0], o[1]));
        buffered[o[0]][o[1]] = true;
      }
    forget();
    for (const Call& call : calls) {
      x86::Gp args[4];
      for (int k = 0; k < 3; ++k) {
        const auto& o = call.operand[k];
        args[k] = cc_.newIntPtr();
        if (o[0] < 0) {
          cc_.xor_(args[k], args[k]);
          continue;
        }
        const Src& s = in.src[o[0]];
        if (buffered[o[0]][o[1]]) cc_.lea(args[k], operands.cloneAdjusted((o[0] * 4 + o[1]) * kComponentBytes));
        else cc_.lea(args[k], lane(s.file, s.index, (s.swizzle >> (2 * o[1])) & 3, 0));
      }
      args[3] = cc_.newIntPtr();
      if (direct) cc_.lea(args[3], lane(in.dst.file, in.dst.index, call.component, 0));
      else cc_.lea(args[3], result.cloneAdjusted(std::max(call.component, 0) * kComponentBytes));
      InvokeNode* node;
      cc_.invoke(&node, imm(reinterpret_cast<void*>(fn)),
                 FuncSignatureT<void, const float*, const float*, const float*, float*, uint32_t>(CallConvId::kHost));
      for (int k = 0; k < 4; ++k) node->setArg(uint32_t(k), args[k]);
      node->setArg(4, imm(mask));
    }
    forget();
    if (direct) return;
    Instr written = in;
    written.dst.mask = mask;
    V r[4];
    for (int c = 0; c < 4; ++c)
      if (mask >> c & 1) r[c] = loadLanes(result.cloneAdjusted(c * kComponentBytes));
    store(written, r);
  }

  // Lanes with a masked component below zero leave laneMask.
  void emitKill(const Instr& in) {
    x86::Gp killed = cc_.newUInt32();
    cc_.xor_(killed, killed);
    const V zero = splat(0.0f);
    for (int c = 0; c < 4; ++c) {
      if (!(in.dst.mask >> c & 1)) continue;
      const V v = source(in, 0, c);
      for (int h = 0; h < parts_; ++h) {
        x86::Gp bits = cc_.newUInt32();
        if (wide_) {
          x86::KReg k = cc_.newKw();
          cc_.vcmpps(k, v.p[h], zero.p[h], imm(kLess));
          cc_.kmovw(bits, k);
        } else {
          x86::Vec m = newVec();
          cc_.vcmpps(m, v.p[h], zero.p[h], imm(kLess));
          cc_.vmovmskps(bits, m);
          if (h) cc_.shl(bits, 8);
        }
        cc_.or_(killed, bits);
      }
    }
    cc_.not_(killed);
    x86::Gp mask = load(offsetof(JitFrame, laneMask));
    cc_.and_(x86::word_ptr(mask), killed.r16());
  }

  x86::Compiler& cc_;
  const Program& program_;
  const bool wide_;
  const int parts_;
  JitProgram& out_;
  const size_t begin_, end_;
  const bool generic_;
  bool affine_ = false;  // the current instruction's lane sources use affine modifiers
  bool fetched_[3] = {};  // the current instruction's sources read by emitFetch, into:
  x86::Mem fetchedAt_[3];
  bool gathered_[3] = {};  // … and those gathered natively (gatheredConstant)
  std::map<Key, V> values_;                   // see memo()
  std::map<std::array<int, 3>, V> registers_;  // (file, index, component) → value held
  std::map<uint32_t, Range> ranges_;           // by value id: see Range
  size_t current_ = 0;                  // the instruction being emitted
  std::vector<uint8_t> overwritten_;    // see findOverwrittenStores()
  x86::Gp frame_, temps_, inputs_, outputs_, constants_, immediates_;
};

}  // namespace

namespace {

bool isFlow(Op op) { return op >= Op::If && op <= Op::Ret; }

// One function for instructions [begin, end); null on failure.
JitFunction compileRange(const Program& program, JitIsa isa, JitProgram& out, size_t begin, size_t end) {
  CodeHolder code;
  code.init(runtime().environment());
  FailOnError errors;
  code.setErrorHandler(&errors);
  // REFX_JIT_LOG=1: the generated code of each compiled program on stderr.
  FileLogger logger(stderr);
  if (const char* log = std::getenv("REFX_JIT_LOG"); log && std::strcmp(log, "1") == 0) {
    std::fprintf(stderr, "; %s [%zu, %zu)\n", program.name.c_str(), begin, end);
    code.setLogger(&logger);
  }
  x86::Compiler cc(&code);
  Generator(cc, program, isa, out, begin, end, program.flowControl).run();
  JitFunction fn = nullptr;
  if (errors.error != kErrorOk || cc.finalize() != kErrorOk || errors.error != kErrorOk) return nullptr;
  if (runtime().add(&fn, &code) != kErrorOk) return nullptr;
  return fn;
}

}  // namespace

std::unique_ptr<JitProgram> compileProgram(const Program& program, JitIsa isa) {
  auto out = std::make_unique<JitProgram>();
  out->isa = isa;
  if (!program.flowControl) {
    out->run = compileRange(program, isa, *out, 0, program.code.size());
    if (!out->run) return nullptr;
    return out;
  }
  // Flow control stays with the interpreter; each run of straight-line instructions
  // between flow-control instructions is one function it calls while every lane runs.
  out->blocks.resize(program.code.size());
  for (size_t b = 0; b < program.code.size();) {
    if (isFlow(program.code[b].op)) {
      ++b;
      continue;
    }
    size_t e = b;
    while (e < program.code.size() && !isFlow(program.code[e].op)) ++e;
    out->blocks[b].run = compileRange(program, isa, *out, b, e);
    if (!out->blocks[b].run) return nullptr;
    out->blocks[b].length = int32_t(e - b);
    b = e;
  }
  return out;
}

}  // namespace refx::exec::detail
