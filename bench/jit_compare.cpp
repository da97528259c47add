// What compiling exec::Programs to native code with LLVM would buy: each straight-line
// program of the seeds (data/shaders, data/hlsl/point_light.hlsl compiled by refx, the
// fixed-function texture cascade of `refx bench`'s texture workload) is translated to
// LLVM IR on <16 x float> (one value per register component, a batch's 16 lanes) and
// compiled by ORC LLJIT at -O2 for the host CPU. Per program: instructions, LLVM's
// compile time (IR built, optimised, code generated; median of 5), the run time of one
// 16-lane batch compiled and through exec::prepare + exec::execute (and prepare's own
// time, the interpreter's "compile"), and whether the two
// give the same outputs on random inputs (every mismatch is reported).
//
// The translation follows the interpreter's arithmetic operation for operation (no
// fused multiply-add, no reassociation, D3D's special cases), so the outputs are
// expected to be bit-identical. Texture instructions call the SamplerBinding as the
// interpreter does; the stand-in sampler below only copies the coordinates, so the
// times are those of the shader arithmetic and the calls, not of filtering.
//
//   jit_compare [--filter SUBSTRING]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <llvm/ExecutionEngine/Orc/ExecutionUtils.h>
#include <llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h>
#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/ThreadSafeModule.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Intrinsics.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/IR/Verifier.h>
#include <llvm/Passes/PassBuilder.h>
#include <llvm/Support/Host.h>
#include <llvm/Support/TargetSelect.h>
#include <llvm/Target/TargetMachine.h>

#include "pipeline/ff_pixel.h"
#include "refx/core/diagnostics.h"
#include "refx/exec/interpreter.h"
#include "refx/exec/lower.h"
#include "refx/hlsl/compiler.h"
#include "refx/pipeline/device.h"
#include "refx/shader/assembler.h"
#include "refx/shader/bytecode.h"

namespace {

using namespace refx;
using namespace refx::exec;
constexpr int N = kBatchLanes;

// ---------------------------------------------------------------- the translation

// Why a program cannot be translated ("" when it can).
std::string unsupported(const Program& p) {
  if (p.flowControl) return "flow control";
  for (const Instr& in : p.code) {
    switch (in.op) {
      case Op::If: case Op::Else: case Op::EndIf: case Op::Rep: case Op::EndRep: case Op::Loop:
      case Op::EndLoop: case Op::Break: case Op::Call: case Op::Ret:
        return "flow control";
      case Op::TexGrad: case Op::Dsx: case Op::Dsy:
        return "derivatives";
      default: break;
    }
    if (in.dst.rel != RelMode::None) return "relative destination";
    for (int i = 0; i < sourceCount(in.op); ++i) {
      const Src& s = in.src[size_t(i)];
      if (s.rel != RelMode::None) return "relative addressing";
      if (s.file == RegFile::ConstInt || s.file == RegFile::ConstBool) return "integer / bool constants";
    }
  }
  return "";
}

// Arguments of the compiled function, in the interpreter's storage:
//   void f(LaneVec4* temps, const LaneVec4* inputs, LaneVec4* outputs,
//          const Vec4* constants, const SamplerBinding* samplers, uint16_t* laneMask)
class Translator {
 public:
  Translator(llvm::LLVMContext& ctx, llvm::Module& m, const Program& p, int constantCount)
      : ctx_(ctx), b_(ctx), p_(p), constantCount_(constantCount) {
    ptr_ = llvm::PointerType::get(ctx, 0);
    f32_ = b_.getFloatTy();
    vec_ = llvm::FixedVectorType::get(f32_, N);
    auto* fty = llvm::FunctionType::get(b_.getVoidTy(), {ptr_, ptr_, ptr_, ptr_, ptr_, ptr_}, false);
    fn_ = llvm::Function::Create(fty, llvm::Function::ExternalLinkage, "program", m);
    for (auto& a : fn_->args()) a.addAttr(llvm::Attribute::NoAlias);
    b_.SetInsertPoint(llvm::BasicBlock::Create(ctx, "entry", fn_));
    // sample(context, mode, coords, laneMask, out)
    sampleTy_ = llvm::FunctionType::get(b_.getVoidTy(), {ptr_, b_.getInt8Ty(), ptr_, b_.getInt16Ty(), ptr_}, false);
    coords_ = b_.CreateAlloca(llvm::ArrayType::get(f32_, 4 * N));
    coords_->setAlignment(llvm::Align(64));
    texOut_ = b_.CreateAlloca(llvm::ArrayType::get(f32_, 4 * N));
    texOut_->setAlignment(llvm::Align(64));
  }

  llvm::Function* build() {
    for (const Instr& in : p_.code) instruction(in);
    // Outputs written by the program go back to the output registers.
    for (const auto& [key, v] : values_)
      if (key.file == RegFile::Output) b_.CreateAlignedStore(v, lanePtr(2, key.index, key.comp), llvm::Align(64));
    if (killMask_) b_.CreateStore(killMask_, arg(5));
    b_.CreateRetVoid();
    return fn_;
  }

 private:
  struct Key {
    RegFile file;
    int index, comp;
    bool operator<(const Key& o) const {
      return std::tie(file, index, comp) < std::tie(o.file, o.index, o.comp);
    }
  };

  llvm::Value* arg(int i) { return fn_->getArg(unsigned(i)); }
  llvm::Value* splat(float x) { return llvm::ConstantFP::get(vec_, x); }
  llvm::Value* lanePtr(int argIndex, int index, int comp) {
    return b_.CreateConstInBoundsGEP1_64(f32_, arg(argIndex), uint64_t((index * 4 + comp) * N));
  }
  llvm::Value* intrinsic(llvm::Intrinsic::ID id, llvm::Value* a, llvm::Value* c = nullptr) {
    if (c) return b_.CreateBinaryIntrinsic(id, a, c);
    return b_.CreateUnaryIntrinsic(id, a);
  }
  llvm::Value* fabs(llvm::Value* a) { return intrinsic(llvm::Intrinsic::fabs, a); }
  // The interpreter's min / max: a < b ? a : b, a > b ? a : b (NaN picks b).
  llvm::Value* vmin(llvm::Value* a, llvm::Value* c) { return b_.CreateSelect(b_.CreateFCmpOLT(a, c), a, c); }
  llvm::Value* vmax(llvm::Value* a, llvm::Value* c) { return b_.CreateSelect(b_.CreateFCmpOGT(a, c), a, c); }

  // Register component as the program last wrote it, or as the batch holds it.
  llvm::Value* laneValue(RegFile file, int index, int comp) {
    const Key k{file, index, comp};
    if (auto it = values_.find(k); it != values_.end()) return it->second;
    const int argIndex = file == RegFile::Temp ? 0 : file == RegFile::Input ? 1 : 2;
    llvm::Value* v = b_.CreateAlignedLoad(vec_, lanePtr(argIndex, index, comp), llvm::Align(64));
    values_[k] = v;
    return v;
  }

  float modify(float x, SrcMod m) { return applySourceModifier(x, m); }
  llvm::Value* modify(llvm::Value* x, SrcMod m) {
    switch (m) {
      case SrcMod::None: return x;
      case SrcMod::Neg: return b_.CreateFNeg(x);
      case SrcMod::Bias: return b_.CreateFSub(x, splat(0.5f));
      case SrcMod::BiasNeg: return b_.CreateFNeg(b_.CreateFSub(x, splat(0.5f)));
      case SrcMod::Sign: return b_.CreateFMul(splat(2.0f), b_.CreateFSub(x, splat(0.5f)));
      case SrcMod::SignNeg: return b_.CreateFMul(splat(-2.0f), b_.CreateFSub(x, splat(0.5f)));
      case SrcMod::Comp: return b_.CreateFSub(splat(1.0f), x);
      case SrcMod::X2: return b_.CreateFMul(splat(2.0f), x);
      case SrcMod::X2Neg: return b_.CreateFMul(splat(-2.0f), x);
      case SrcMod::Abs: return fabs(x);
      case SrcMod::AbsNeg: return b_.CreateFNeg(fabs(x));
    }
    return x;
  }

  // Component c (after swizzle) of a source operand, modifier applied.
  llvm::Value* source(const Src& s, int c) {
    const int comp = (s.swizzle >> (2 * c)) & 3;
    if (s.file == RegFile::Imm || s.file == RegFile::Const) {
      // Immediates and local (def) constants are known; API constants are read from the
      // constant array and broadcast.
      const float* known = nullptr;
      if (s.file == RegFile::Imm && s.index < p_.immediates.size()) known = &p_.immediates[s.index].x;
      if (s.file == RegFile::Const && s.index < p_.localConstants.size() && p_.localConstants[s.index] >= 0)
        known = &p_.immediates[size_t(p_.localConstants[s.index])].x;
      if (known || s.file == RegFile::Imm || s.index >= constantCount_) {
        float x = known ? known[comp] : 0.0f;
        if (s.flags & kSrcClampUnit) x = std::min(std::max(x, -1.0f), 1.0f);
        return splat(modify(x, s.mod));
      }
      llvm::Value* x = b_.CreateAlignedLoad(
          f32_, b_.CreateConstInBoundsGEP1_64(f32_, arg(3), uint64_t(s.index * 4 + comp)), llvm::Align(4));
      if (s.flags & kSrcClampUnit) {
        // min(max(x, -1), 1) as std::min / std::max compute it.
        llvm::Value* lo = llvm::ConstantFP::get(f32_, -1.0), *hi = llvm::ConstantFP::get(f32_, 1.0);
        x = b_.CreateSelect(b_.CreateFCmpOLT(x, lo), lo, x);    // std::max(x, -1)
        x = b_.CreateSelect(b_.CreateFCmpOLT(hi, x), hi, x);    // std::min(x, 1)
      }
      return modify(b_.CreateVectorSplat(N, x), s.mod);
    }
    return modify(laneValue(s.file, s.index, comp), s.mod);
  }

  // Lanes a texture lookup computes: every lane of a 2x2 quad with a live lane.
  llvm::Value* quadLanes(llvm::Value* live) {
    llvm::Value* m = b_.getInt16(0);
    for (int q = 0; q < N / 4; ++q) {
      llvm::Value* any = b_.CreateICmpNE(b_.CreateAnd(live, b_.getInt16(uint16_t(0xF << (4 * q)))), b_.getInt16(0));
      m = b_.CreateOr(m, b_.CreateSelect(any, b_.getInt16(uint16_t(0xF << (4 * q))), b_.getInt16(0)));
    }
    return m;
  }

  void sample(const Instr& in, llvm::Value* (&res)[4]) {
    llvm::Value* co[4];
    for (int c = 0; c < 4; ++c) co[c] = source(in.src[0], c);
    uint8_t mode = 0;
    if (in.op == Op::TexProj) {
      llvm::Value* iw = b_.CreateFDiv(splat(1.0f), co[3]);
      for (int c = 0; c < 3; ++c) co[c] = b_.CreateFMul(co[c], iw);
    } else if (in.op == Op::TexBias) {
      mode = uint8_t(SampleMode::Bias);
    } else if (in.op == Op::TexLod) {
      mode = uint8_t(SampleMode::Lod);
    }
    for (int c = 0; c < 4; ++c)
      b_.CreateAlignedStore(co[c], b_.CreateConstInBoundsGEP1_64(f32_, coords_, uint64_t(c * N)), llvm::Align(64));
    // samplers[in.sampler] = {context, sample}
    llvm::Value* binding = b_.CreateConstInBoundsGEP1_64(ptr_, arg(4), uint64_t(2 * in.sampler));
    llvm::Value* context = b_.CreateLoad(ptr_, binding);
    llvm::Value* fnp = b_.CreateLoad(ptr_, b_.CreateConstInBoundsGEP1_64(ptr_, binding, 1));
    llvm::Value* live = killMask_ ? killMask_ : b_.getInt16(0xffff);
    b_.CreateCall(sampleTy_, fnp, {context, b_.getInt8(mode), coords_, quadLanes(live), texOut_});
    for (int c = 0; c < 4; ++c)
      res[c] = b_.CreateAlignedLoad(vec_, b_.CreateConstInBoundsGEP1_64(f32_, texOut_, uint64_t(c * N)),
                                    llvm::Align(64));
  }

  void instruction(const Instr& in) {
    uint8_t mask = in.dst.mask;
    llvm::Value* res[4] = {};
    auto src = [&](int i, int c) { return source(in.src[size_t(i)], c); };
    auto each = [&](auto&& f) {
      for (int c = 0; c < 4; ++c)
        if (mask & (1 << c)) res[c] = f(c);
    };
    const auto one = splat(1.0f), zero = splat(0.0f);
    switch (in.op) {
      case Op::Mov: each([&](int c) { return src(0, c); }); break;
      case Op::Add: each([&](int c) { return b_.CreateFAdd(src(0, c), src(1, c)); }); break;
      case Op::Sub: each([&](int c) { return b_.CreateFSub(src(0, c), src(1, c)); }); break;
      case Op::Mul: each([&](int c) { return b_.CreateFMul(src(0, c), src(1, c)); }); break;
      case Op::Mad:
        each([&](int c) { return b_.CreateFAdd(b_.CreateFMul(src(0, c), src(1, c)), src(2, c)); });
        break;
      case Op::Dp3:
      case Op::Dp4:
      case Op::Dp2Add: {
        llvm::Value* r = b_.CreateFAdd(b_.CreateFMul(src(0, 0), src(1, 0)), b_.CreateFMul(src(0, 1), src(1, 1)));
        if (in.op == Op::Dp2Add) {
          r = b_.CreateFAdd(r, src(2, 0));
        } else {
          r = b_.CreateFAdd(r, b_.CreateFMul(src(0, 2), src(1, 2)));
          if (in.op == Op::Dp4) r = b_.CreateFAdd(r, b_.CreateFMul(src(0, 3), src(1, 3)));
        }
        each([&](int) { return r; });
        break;
      }
      case Op::Rcp: each([&](int c) { return b_.CreateFDiv(one, src(0, c)); }); break;
      case Op::Rsq:
        each([&](int c) { return b_.CreateFDiv(one, intrinsic(llvm::Intrinsic::sqrt, fabs(src(0, c)))); });
        break;
      case Op::Min: each([&](int c) { return vmin(src(0, c), src(1, c)); }); break;
      case Op::Max: each([&](int c) { return vmax(src(0, c), src(1, c)); }); break;
      case Op::Slt:
        each([&](int c) { return b_.CreateSelect(b_.CreateFCmpOLT(src(0, c), src(1, c)), one, zero); });
        break;
      case Op::Sge:
        each([&](int c) { return b_.CreateSelect(b_.CreateFCmpOGE(src(0, c), src(1, c)), one, zero); });
        break;
      case Op::Frc:
        each([&](int c) {
          llvm::Value* a = src(0, c);
          return b_.CreateFSub(a, intrinsic(llvm::Intrinsic::floor, a));
        });
        break;
      case Op::Exp2: each([&](int c) { return intrinsic(llvm::Intrinsic::exp2, src(0, c)); }); break;
      case Op::Log2: each([&](int c) { return intrinsic(llvm::Intrinsic::log2, fabs(src(0, c))); }); break;
      case Op::Pow:
        each([&](int c) { return intrinsic(llvm::Intrinsic::pow, fabs(src(0, c)), src(1, c)); });
        break;
      case Op::Lrp:
        each([&](int c) {
          llvm::Value* d = src(2, c);
          return b_.CreateFAdd(b_.CreateFMul(src(0, c), b_.CreateFSub(src(1, c), d)), d);
        });
        break;
      case Op::Cmp:
        each([&](int c) { return b_.CreateSelect(b_.CreateFCmpOGE(src(0, c), zero), src(1, c), src(2, c)); });
        break;
      case Op::Cnd:
        each([&](int c) { return b_.CreateSelect(b_.CreateFCmpOGT(src(0, c), splat(0.5f)), src(1, c), src(2, c)); });
        break;
      case Op::Abs: each([&](int c) { return fabs(src(0, c)); }); break;
      case Op::Nrm: {
        llvm::Value* x = src(0, 0), *y = src(0, 1), *z = src(0, 2);
        llvm::Value* d = b_.CreateFAdd(b_.CreateFAdd(b_.CreateFMul(x, x), b_.CreateFMul(y, y)), b_.CreateFMul(z, z));
        llvm::Value* k = b_.CreateSelect(b_.CreateFCmpOEQ(d, zero), one,
                                         b_.CreateFDiv(one, intrinsic(llvm::Intrinsic::sqrt, d)));
        each([&](int c) { return b_.CreateFMul(src(0, c), k); });
        break;
      }
      case Op::Crs:
        mask &= 0x7;
        each([&](int c) {
          const int i = (c + 1) % 3, j = (c + 2) % 3;
          return b_.CreateFSub(b_.CreateFMul(src(0, i), src(1, j)), b_.CreateFMul(src(0, j), src(1, i)));
        });
        break;
      case Op::Floor: each([&](int c) { return intrinsic(llvm::Intrinsic::floor, src(0, c)); }); break;
      case Op::Round: each([&](int c) { return intrinsic(llvm::Intrinsic::nearbyint, src(0, c)); }); break;
      case Op::Sgn:
        each([&](int c) {
          llvm::Value* v = src(0, c);
          return b_.CreateSelect(b_.CreateFCmpOLT(v, zero), splat(-1.0f),
                                 b_.CreateSelect(b_.CreateFCmpOGT(v, zero), one, zero));
        });
        break;
      case Op::Quot:
        each([&](int c) {
          llvm::Value* d = src(1, c);
          return b_.CreateSelect(b_.CreateFCmpOEQ(d, zero), one, b_.CreateFDiv(src(0, c), d));
        });
        break;
      case Op::Dist:
        each([&](int c) -> llvm::Value* {
          return c == 0 ? one : c == 1 ? b_.CreateFMul(src(0, 1), src(1, 1)) : c == 2 ? src(0, 2) : src(1, 3);
        });
        break;
      case Op::SinCos:
        mask &= 0x3;
        each([&](int c) { return intrinsic(c == 0 ? llvm::Intrinsic::cos : llvm::Intrinsic::sin, src(0, 0)); });
        break;
      case Op::ExpP:
        each([&](int c) -> llvm::Value* {
          llvm::Value* v = src(0, 0);
          llvm::Value* f = intrinsic(llvm::Intrinsic::floor, v);
          return c == 0 ? intrinsic(llvm::Intrinsic::exp2, f)
                 : c == 1 ? b_.CreateFSub(v, f)
                 : c == 2 ? intrinsic(llvm::Intrinsic::exp2, v)
                          : one;
        });
        break;
      case Op::Lit:
        each([&](int c) -> llvm::Value* {
          if (c == 0 || c == 3) return one;
          llvm::Value* x = src(0, 0);
          llvm::Value* xPos = b_.CreateFCmpOGT(x, zero);
          if (c == 1) return b_.CreateSelect(xPos, x, zero);
          llvm::Value* y = src(0, 1);
          // std::min(std::max(w, -127.9961), 127.9961)
          llvm::Value* w = src(0, 3);
          w = b_.CreateSelect(b_.CreateFCmpOLT(w, splat(-127.9961f)), splat(-127.9961f), w);
          w = b_.CreateSelect(b_.CreateFCmpOLT(splat(127.9961f), w), splat(127.9961f), w);
          llvm::Value* lit = b_.CreateAnd(xPos, b_.CreateFCmpOGT(y, zero));
          return b_.CreateSelect(lit, intrinsic(llvm::Intrinsic::pow, y, w), zero);
        });
        break;
      case Op::SetP: {
        auto cmp = [&](llvm::Value* a, llvm::Value* c) -> llvm::Value* {
          switch (in.cmp) {
            case 1: return b_.CreateFCmpOGT(a, c);
            case 2: return b_.CreateFCmpOEQ(a, c);
            case 3: return b_.CreateFCmpOGE(a, c);
            case 4: return b_.CreateFCmpOLT(a, c);
            case 5: return b_.CreateFCmpUNE(a, c);
            case 6: return b_.CreateFCmpOLE(a, c);
            default: return llvm::ConstantInt::getTrue(llvm::FixedVectorType::get(b_.getInt1Ty(), N));
          }
        };
        each([&](int c) { return b_.CreateSelect(cmp(src(0, c), src(1, c)), one, zero); });
        break;
      }
      case Op::Tex:
      case Op::TexProj:
      case Op::TexBias:
      case Op::TexLod: {
        llvm::Value* all[4];
        sample(in, all);
        each([&](int c) { return all[c]; });
        break;
      }
      case Op::Kill: {
        // Lanes with a masked component < 0 are discarded.
        llvm::Value* neg = nullptr;
        for (int c = 0; c < 4; ++c) {
          if (!(mask & (1 << c))) continue;
          llvm::Value* n = b_.CreateFCmpOLT(src(0, c), zero);
          neg = neg ? b_.CreateOr(neg, n) : n;
        }
        if (neg) {
          llvm::Value* killed = b_.CreateBitCast(neg, b_.getInt16Ty());
          llvm::Value* live = killMask_ ? killMask_ : b_.CreateLoad(b_.getInt16Ty(), arg(5));
          killMask_ = b_.CreateAnd(live, b_.CreateNot(killed));
        }
        return;
      }
      default:
        return;  // not reached: unsupported() refuses the program
    }
    // Result modifiers: shift, then saturate or clamp (NaN -> lo), then fixed point.
    const bool clampResult = in.saturate || in.clamp;
    const float lo = in.saturate ? 0.0f : in.clampLo, hi = in.saturate ? 1.0f : in.clampHi;
    for (int c = 0; c < 4; ++c) {
      if (!(mask & (1 << c)) || !res[c]) continue;
      llvm::Value* r = res[c];
      if (in.shift != 0) r = b_.CreateFMul(r, splat(std::ldexp(1.0f, in.shift)));
      if (clampResult) r = vmin(vmax(r, splat(lo)), splat(hi));
      if (in.quantize) {
        r = intrinsic(llvm::Intrinsic::nearbyint, b_.CreateFMul(r, splat(std::ldexp(1.0f, in.quantize))));
        r = b_.CreateFMul(r, splat(std::ldexp(1.0f, -in.quantize)));
      }
      res[c] = r;
    }
    // All components are computed before any is written (a source may be the destination).
    for (int c = 0; c < 4; ++c)
      if ((mask & (1 << c)) && res[c]) values_[Key{in.dst.file, in.dst.index, c}] = res[c];
  }

  llvm::LLVMContext& ctx_;
  llvm::IRBuilder<> b_;
  const Program& p_;
  int constantCount_;
  llvm::PointerType* ptr_;
  llvm::Type* f32_;
  llvm::FixedVectorType* vec_;
  llvm::Function* fn_;
  llvm::FunctionType* sampleTy_;
  llvm::AllocaInst *coords_, *texOut_;
  llvm::Value* killMask_ = nullptr;  // live lanes after the last texkill (i16)
  std::map<Key, llvm::Value*> values_;
};

using CompiledFn = void (*)(LaneVec4*, const LaneVec4*, LaneVec4*, const Vec4*, const SamplerBinding*, uint16_t*);

class Jit {
 public:
  Jit() {
    auto jtmb = llvm::orc::JITTargetMachineBuilder::detectHost();
    if (!jtmb) fail("LLVM: {}", llvm::toString(jtmb.takeError()));
    jtmb->setCodeGenOptLevel(llvm::CodeGenOpt::Default);  // -O2
    cpu_ = jtmb->getCPU();
    const std::string features = jtmb->getFeatures().getString();
    isa_ = features.find("+avx512f") != std::string::npos ? "AVX-512"
           : features.find("+avx2") != std::string::npos  ? "AVX2"
                                                          : "SSE";
    auto tm = jtmb->createTargetMachine();
    if (!tm) fail("LLVM: {}", llvm::toString(tm.takeError()));
    tm_ = std::move(*tm);
    auto jit = llvm::orc::LLJITBuilder().setJITTargetMachineBuilder(std::move(*jtmb)).create();
    if (!jit) fail("LLVM: {}", llvm::toString(jit.takeError()));
    jit_ = std::move(*jit);
    // exp2f, log2f, powf … of the lanes LLVM does not expand come from the C library.
    auto process = llvm::orc::DynamicLibrarySearchGenerator::GetForCurrentProcess(
        jit_->getDataLayout().getGlobalPrefix());
    if (!process) fail("LLVM: {}", llvm::toString(process.takeError()));
    jit_->getMainJITDylib().addGenerator(std::move(*process));
  }
  const std::string& cpu() const { return cpu_; }
  const char* isa() const { return isa_; }

  // IR built, optimised at -O2 and compiled; the function's address.
  CompiledFn compile(const Program& p, int constantCount) {
    auto ctx = std::make_unique<llvm::LLVMContext>();
    auto m = std::make_unique<llvm::Module>("refx", *ctx);
    m->setDataLayout(jit_->getDataLayout());
    m->setTargetTriple(jit_->getTargetTriple().str());
    llvm::Function* f = Translator(*ctx, *m, p, constantCount).build();
    const std::string name = "program" + std::to_string(next_++);
    f->setName(name);
    if (llvm::verifyModule(*m, &llvm::errs())) fail("{}: LLVM IR does not verify", p.name);
    {
      llvm::LoopAnalysisManager lam;
      llvm::FunctionAnalysisManager fam;
      llvm::CGSCCAnalysisManager cgam;
      llvm::ModuleAnalysisManager mam;
      llvm::PassBuilder pb(tm_.get());
      pb.registerModuleAnalyses(mam);
      pb.registerCGSCCAnalyses(cgam);
      pb.registerFunctionAnalyses(fam);
      pb.registerLoopAnalyses(lam);
      pb.crossRegisterProxies(lam, fam, cgam, mam);
      pb.buildPerModuleDefaultPipeline(llvm::OptimizationLevel::O2).run(*m, mam);
    }
    if (auto err = jit_->addIRModule(llvm::orc::ThreadSafeModule(std::move(m), std::move(ctx))))
      fail("LLVM: {}", llvm::toString(std::move(err)));
    auto sym = jit_->lookup(name);
    if (!sym) fail("LLVM: {}", llvm::toString(sym.takeError()));
    return sym->toPtr<CompiledFn>();
  }

 private:
  std::unique_ptr<llvm::TargetMachine> tm_;
  std::unique_ptr<llvm::orc::LLJIT> jit_;
  std::string cpu_;
  const char* isa_ = "";
  int next_ = 0;
};

// ---------------------------------------------------------------- the programs

struct Candidate {
  std::string name;
  Program program;
  std::string skipped;  // why it is not measured
};

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Candidate lowered(const std::string& name, std::span<const uint32_t> tokens) {
  Candidate c{name, {}, ""};
  try {
    ShaderLoweringOptions o;  // exact precision, a DirectX 8 part's ps.1.x range
    c.program = lowerShader(shader::decode(tokens), o).program;
    c.skipped = unsupported(c.program);
  } catch (const Error& e) {
    c.skipped = e.what();
  }
  return c;
}

std::vector<Candidate> candidates() {
  std::vector<Candidate> r;
  const std::string data = REFX_DATA_DIR;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(data + "/shaders"))
    if (e.path().extension() == ".psh" || e.path().extension() == ".vsh") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    try {
      const auto tokens = shader::assembleTokens(readText(f.string()), f.filename().string());
      r.push_back(lowered(f.filename().string(), tokens));
    } catch (const Error& e) {
      std::string why = e.what();
      r.push_back({f.filename().string(), {}, why.substr(0, why.find('\n'))});
    }
  }
  // The HLSL point light as `refx bench --workload phong` compiles it.
  const std::string hlslPath = data + "/hlsl/point_light.hlsl";
  const std::string source = readText(hlslPath);
  for (const auto& [profile, entry] : {std::pair{"vs_1_1", "VS"}, std::pair{"ps_2_0", "PS"}}) {
    hlsl::CompileOptions o;
    o.profile = profile;
    o.entry = entry;
    const hlsl::CompileResult cr = hlsl::compile(source, hlslPath, o);
    const std::string name = std::string("point_light.hlsl ") + entry + " " + profile;
    if (!cr.ok()) r.push_back({name, {}, cr.messages()});
    else r.push_back(lowered(name, cr.tokens));
  }
  // The fixed-function cascade of the texture workload: texture x diffuse in stage 0.
  Device dev(CapsProfile{});
  auto tex = Texture::create2D(Format::A8R8G8B8, 4, 4, 1);
  dev.setTexture(0, tex);
  dev.setTextureStageState(0, d3d::TSS_COLOROP, d3d::TOP_MODULATE);
  dev.setTextureStageState(0, d3d::TSS_COLORARG1, d3d::TA_TEXTURE);
  dev.setTextureStageState(0, d3d::TSS_COLORARG2, d3d::TA_DIFFUSE);
  pipeline::FixedFunctionPixelConfig cfg;
  cfg.textures[0] = tex.get();
  Candidate ff{"fixed-function texture x diffuse", pipeline::buildFixedFunctionPixelProgram(dev.state(), cfg), ""};
  ff.skipped = unsupported(ff.program);
  r.push_back(std::move(ff));
  return r;
}

// ---------------------------------------------------------------- running

// The stand-in texture: the coordinates (u, v, u, v) copied out, as cheap as a call
// can be, the same for both paths.
void standInSample(const void*, SampleMode, const float (*co)[N], uint16_t, float (*out)[N]) {
  for (int c = 0; c < 4; ++c) std::memcpy(out[c], co[c & 1], sizeof out[c]);
}

struct Batch {
  BatchRegisters regs;
  std::vector<Vec4> constants;
};

constexpr int kConstants = kConstBumpEnv + kConstBumpEnvCount;

void randomize(Batch& b, const Program& p, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  b.regs.resize(p);
  for (auto* file : {&b.regs.temps, &b.regs.inputs, &b.regs.outputs})
    for (LaneVec4& r : *file)
      for (auto& comp : r.c)
        for (float& x : comp) x = file == &b.regs.inputs ? u(rng) : 0.0f;
  b.constants.resize(kConstants);
  for (Vec4& v : b.constants) v = Vec4(u(rng), u(rng), u(rng), u(rng));
  b.regs.laneMask = 0xffff;
}

template <class F>
double nsPerCall(F&& f) {
  // Calibrated to about 20 ms per measurement; the best of 3 measurements.
  int iters = 1000;
  for (;;) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) f();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (s > 0.02 || iters > (1 << 26)) break;
    iters *= 4;
  }
  double best = 1e30;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / iters);
  }
  return best * 1e9;
}

}  // namespace

int main(int argc, char** argv) {
  std::string filter;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--filter") == 0 && i + 1 < argc) filter = argv[++i];
    else {
      std::fprintf(stderr, "usage: jit_compare [--filter SUBSTRING]\n");
      return 2;
    }
  }
  try {
    llvm::InitializeNativeTarget();
    llvm::InitializeNativeTargetAsmPrinter();
    Jit jit;
    SamplerBinding samplers[kSamplerCount];
    for (auto& s : samplers) s = {nullptr, standInSample};
    std::printf("LLVM %s ORC LLJIT, -O2, CPU %s (%s); tex = a call to a stand-in SamplerBinding\n",
                LLVM_VERSION_STRING, jit.cpu().c_str(), jit.isa());
    std::printf("%-36s %6s %13s %10s %12s %17s %8s  %s\n", "program", "instrs", "llvm-compile", "prepare", "llvm",
                "exec::prepare path", "speedup", "check (random inputs)");
    std::printf("%-36s %6s %13s %10s %12s %17s %8s\n", "", "", "us (med of 5)", "us (med)", "ns/batch", "ns/batch",
                "");
    int mismatches = 0;
    for (Candidate& c : candidates()) {
      if (!filter.empty() && c.name.find(filter) == std::string::npos) continue;
      if (!c.skipped.empty()) {
        std::printf("%-36s skipped: %s\n", c.name.c_str(), c.skipped.c_str());
        continue;
      }
      const Program& p = c.program;
      std::vector<double> compileUs;
      CompiledFn fn = nullptr;
      for (int i = 0; i < 5; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        fn = jit.compile(p, kConstants);
        compileUs.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
      }
      std::sort(compileUs.begin(), compileUs.end());

      // The same random batches through both; outputs and the live-lane mask compared bit for bit.
      std::mt19937 rng(12345);
      long lanesDiffer = 0, lanesTotal = 0;
      float maxDiff = 0;
      Batch a, b;
      for (int trial = 0; trial < 64; ++trial) {
        randomize(a, p, rng);
        b.regs.resize(p);
        b.regs.inputs = a.regs.inputs, b.regs.temps = a.regs.temps, b.regs.outputs = a.regs.outputs;
        b.constants = a.constants;
        b.regs.laneMask = 0xffff;
        ExecContext ctx{a.constants.data(), kConstants, samplers, kSamplerCount};
        prepare(p, ctx, a.regs);
        execute(p, ctx, a.regs);
        fn(b.regs.temps.data(), b.regs.inputs.data(), b.regs.outputs.data(), b.constants.data(), samplers,
           &b.regs.laneMask);
        for (size_t o = 0; o < a.regs.outputs.size(); ++o)
          for (int comp = 0; comp < 4; ++comp)
            for (int l = 0; l < N; ++l) {
              const float x = a.regs.outputs[o].c[comp][l], y = b.regs.outputs[o].c[comp][l];
              ++lanesTotal;
              if (std::memcmp(&x, &y, 4) != 0 && !(std::isnan(x) && std::isnan(y))) {
                ++lanesDiffer;
                maxDiff = std::max(maxDiff, std::fabs(x - y));
              }
            }
        if (a.regs.laneMask != b.regs.laneMask) ++lanesDiffer;
      }
      std::string check = lanesDiffer == 0
                              ? fmt::format("identical ({} values)", lanesTotal)
                              : fmt::format("MISMATCH: {} of {} values differ, max |diff| {:g}", lanesDiffer,
                                            lanesTotal, maxDiff);
      mismatches += lanesDiffer != 0;

      randomize(a, p, rng);
      ExecContext ctx{a.constants.data(), kConstants, samplers, kSamplerCount};
      std::vector<double> prepareUs;
      for (int i = 0; i < 5; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        prepare(p, ctx, a.regs);
        prepareUs.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
      }
      std::sort(prepareUs.begin(), prepareUs.end());
      const double interp = nsPerCall([&] {
        a.regs.laneMask = 0xffff;
        execute(p, ctx, a.regs);
      });
      b.regs.resize(p);
      const double compiled = nsPerCall([&] {
        b.regs.laneMask = 0xffff;
        fn(b.regs.temps.data(), b.regs.inputs.data(), b.regs.outputs.data(), a.constants.data(), samplers,
           &b.regs.laneMask);
      });
      std::printf("%-36s %6zu %13.0f %10.1f %12.1f %17.1f %7.1fx  %s\n", c.name.c_str(), p.code.size(),
                  compileUs[2], prepareUs[2], compiled, interp, interp / compiled, check.c_str());
      std::fflush(stdout);
    }
    return mismatches ? 1 : 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "jit_compare: %s\n", e.what());
    return 1;
  }
}
