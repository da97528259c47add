// Native code against the interpreter, bit for bit: every shader file of the data
// and the tests, random IR programs over every op and modifier, and the switches
// that choose what runs a program.
#include "exec/jit_identity.h"

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <fstream>
#include <sstream>

#include "refx/core/cpu_features.h"
#include "refx/core/diagnostics.h"
#include "refx/exec/lower.h"
#include "refx/shader/assembler.h"

namespace {

using namespace jit_identity;
namespace fs = std::filesystem;

std::vector<fs::path> shaderFiles() {
  std::vector<fs::path> files;
  for (const char* root : {REFX_DATA_DIR, REFX_TEST_DIR})
    for (const auto& e : fs::recursive_directory_iterator(root)) {
      const auto ext = e.path().extension();
      if (ext == ".psh" || ext == ".vsh" || ext == ".asm") files.push_back(e.path());
    }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(JitIdentity, EveryShaderFileThatLowers) {
  const auto isas = availableIsas();
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU: the interpreter runs everything";
  struct Lowering {
    const char* name;
    ShaderLoweringOptions options;
  };
  ShaderLoweringOptions hardware;
  hardware.precision = Precision::Hardware;
  hardware.pixelShader1xMaxValue = 8.0f;
  const Lowering lowerings[] = {{"exact", {}}, {"hardware", hardware}};
  int files = 0, compiled = 0, interpreted = 0, runners = 0;
  CompileTimes times;
  for (const fs::path& path : shaderFiles()) {
    std::ifstream f(path);
    std::stringstream text;
    text << f.rdbuf();
    shader::Shader s;
    try {
      s = shader::assemble(text.str(), path.filename().string());
    } catch (const Error&) {
      continue;  // invalid on purpose, or a misprinted original
    }
    ++files;
    for (const Lowering& lowering : lowerings) {
      LoweredShader low;
      try {
        low = lowerShader(s, lowering.options);
      } catch (const Error&) {
        continue;
      }
      for (auto isa : isas) {
        const Outcome o = compare(low.program, isa, uint32_t(files), {}, kPixelInputRegisters);
        SCOPED_TRACE(path.string() + " (" + lowering.name + ", " + isaName(isa) + ")");
        EXPECT_EQ(o.mismatch, "");
        (o.backend == "interpreter" ? interpreted : compiled)++;
        runners += o.runner;
        times.add(o);
      }
    }
  }
  std::printf("shader files: %d assembled; program runs: %d on native code, %d on the interpreter\n", files,
              compiled, interpreted);
  std::printf("shader files: %s\n", times.summary().c_str());
  EXPECT_GT(files, 60);
  EXPECT_EQ(interpreted, 0);
  // The programs without flow control run through runnerFor's runner, as the rasterizer
  // runs them (ps_1_x and most others).
  EXPECT_GT(runners, compiled / 2);
}

// Random straight-line programs: every op, source file, swizzle, modifier, write
// mask and result modifier, with destinations that are also sources.
Instr randomInstruction(std::mt19937& rng) {
  static const Op kOps[] = {Op::Mov, Op::Add, Op::Sub, Op::Mul, Op::Mad, Op::Dp3, Op::Dp4, Op::Rcp,
                            Op::Rsq, Op::Min, Op::Max, Op::Slt, Op::Sge, Op::Frc, Op::Exp2, Op::Log2,
                            Op::Pow, Op::Lrp, Op::Cmp, Op::Cnd, Op::Abs, Op::Nrm, Op::Dp2Add, Op::Tex,
                            Op::TexProj, Op::TexBias, Op::TexLod, Op::Kill, Op::Floor, Op::Round,
                            Op::Lit, Op::Dist, Op::Crs, Op::Sgn, Op::SinCos, Op::ExpP, Op::Quot,
                            Op::SetP, Op::Dsx, Op::Dsy, Op::TexGrad};
  static const RegFile kFiles[] = {RegFile::Temp, RegFile::Temp, RegFile::Input, RegFile::Const,
                                   RegFile::Imm, RegFile::Output};
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  Instr in;
  in.op = kOps[pick(int(std::size(kOps)))];
  in.dst.file = pick(4) ? RegFile::Temp : RegFile::Output;
  in.dst.index = uint16_t(pick(in.dst.file == RegFile::Temp ? 4 : 2));
  in.dst.mask = uint8_t(1 + pick(15));
  for (Src& s : in.src) {
    s.file = kFiles[pick(int(std::size(kFiles)))];
    s.index = uint16_t(s.file == RegFile::Imm ? pick(7) : s.file == RegFile::Output ? pick(2) : pick(4));
    s.swizzle = pick(2) ? kSwzXYZW : uint8_t(rng());
    s.mod = pick(2) ? SrcMod::None : SrcMod(pick(int(SrcMod::AbsNeg) + 1));
    if (s.file == RegFile::Const && pick(3) == 0) s.flags = kSrcClampUnit;
  }
  switch (pick(6)) {
    case 0: in.saturate = true; break;
    case 1: in.clamp = true, in.clampLo = -8, in.clampHi = 8; break;
    case 2: in.shift = int8_t(pick(5) - 2); break;
    case 3: in.quantize = pick(4) == 0 ? 8 : 0; break;
    default: break;
  }
  in.sampler = uint8_t(pick(4));
  in.cmp = uint8_t(1 + pick(6));
  return in;
}

Program randomShell(std::mt19937& rng) {
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  Program p;
  p.tempCount = 4, p.inputCount = 4, p.outputCount = 2;
  for (int k = 0; k < 6; ++k) p.imm(Vec4(float(pick(9)) * 0.25f - 1, float(pick(9)) * 0.5f, -0.0f, float(pick(5))));
  p.localConstants = {-1, 2, -1, 0};  // c1, c3: local (def) constants
  return p;
}

// Random straight-line programs: every op, source file, swizzle, modifier, write
// mask and result modifier, with destinations that are also sources.
Program randomProgram(std::mt19937& rng) {
  Program p = randomShell(rng);
  const int count = 1 + int(rng() % 12);
  for (int k = 0; k < count; ++k) p.code.push_back(randomInstruction(rng));
  return p;
}

// Random straight-line blocks inside if/else/endif, rep (with a conditional break)
// and loop: per-lane conditions, so blocks run with every lane or with some.
Program randomFlowProgram(std::mt19937& rng) {
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  Program p = randomShell(rng);
  p.flowControl = true;
  auto block = [&] {
    for (int k = pick(4); k > 0; --k) p.code.push_back(randomInstruction(rng));
  };
  auto at = [&] { return int32_t(p.code.size()); };
  auto flow = [&](Op op, int cmp = 0) {
    Instr in;
    in.op = op;
    in.cmp = uint8_t(cmp);
    in.src[0] = reg(pick(2) ? RegFile::Temp : RegFile::Input, pick(4), kSwzXXXX);
    in.src[1] = reg(RegFile::Const, pick(4), kSwzYYYY);
    p.code.push_back(in);
    return at() - 1;
  };
  block();
  const int32_t ifAt = flow(Op::If, pick(7));  // 0: always
  block();
  const int32_t elseAt = flow(Op::Else);
  block();
  const int32_t endIf = flow(Op::EndIf);
  p.code[size_t(ifAt)].target = elseAt;
  p.code[size_t(elseAt)].target = endIf;
  block();
  const int32_t repAt = flow(Op::Rep);
  p.code[size_t(repAt)].src[0] = reg(RegFile::ConstInt, pick(4));
  block();
  flow(Op::Break, 1 + pick(6));
  block();
  const int32_t endRep = flow(Op::EndRep);
  p.code[size_t(repAt)].target = endRep;
  p.code[size_t(endRep)].target = repAt;
  const int32_t loopAt = flow(Op::Loop);
  p.code[size_t(loopAt)].src[0] = reg(RegFile::ConstInt, pick(4));
  block();
  const int32_t endLoop = flow(Op::EndLoop);
  p.code[size_t(loopAt)].target = endLoop;
  p.code[size_t(endLoop)].target = loopAt;
  block();
  return p;
}

TEST(JitIdentity, RandomPrograms) {
  const auto isas = availableIsas();
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937 rng(20261128);
  for (int n = 0; n < 1500; ++n) {
    const Program p = randomProgram(rng);
    for (auto isa : isas) {
      // Every third program with samplers 1 and 2 and up unbound.
      const Outcome o = compare(p, isa, uint32_t(n), {}, 0, n % 3 == 0 ? 1 : kSamplerCount);
      ASSERT_NE(o.backend, "interpreter");
      // Without flow control, with every constant set: a run is one call (runnerFor).
      ASSERT_TRUE(o.runner) << "program " << n;
      ASSERT_EQ(o.mismatch, "") << "program " << n << " (" << isaName(isa) << ")\n" << listProgram(p);
    }
  }
}

// Arithmetic chains whose clamped results feed later clamps (ps_1_x's range clamp,
// saturate): the code leaves out a clamp where the value's known range (from earlier
// clamps, constants and the ops between) proves it changes nothing. On special values
// (signed zeros, infinities, NaN, huge values) every such clamp must still give the
// interpreter's bits.
TEST(JitIdentity, ClampedArithmeticChainsOnSpecialValues) {
  const auto isas = availableIsas();
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  static const Op kOps[] = {Op::Mov, Op::Add, Op::Sub, Op::Mul, Op::Mad, Op::Dp3, Op::Dp4, Op::Lrp};
  std::mt19937 rng(1128);
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  for (int n = 0; n < 1500; ++n) {
    Program p = randomShell(rng);
    const int count = 2 + pick(10);
    for (int k = 0; k < count; ++k) {
      Instr in = randomInstruction(rng);
      in.op = kOps[pick(int(std::size(kOps)))];
      in.quantize = 0;
      switch (pick(4)) {
        case 0: in.saturate = true, in.clamp = false; break;
        case 1: in.saturate = false, in.clamp = true, in.clampLo = -1, in.clampHi = 1; break;
        case 2: in.saturate = false, in.clamp = true, in.clampLo = -8, in.clampHi = 8; break;
        default: break;
      }
      // Mostly temporaries, so clamped results feed the next instructions.
      for (Src& src : in.src)
        if (pick(3)) src.file = RegFile::Temp, src.index = uint16_t(pick(4)), src.flags = 0;
      p.code.push_back(in);
    }
    Ranges ranges;
    ranges.specialValues = n % 2 == 0;
    for (auto isa : isas) {
      const Outcome o = compare(p, isa, uint32_t(n), ranges);
      ASSERT_NE(o.backend, "interpreter");
      ASSERT_EQ(o.mismatch, "") << "program " << n << " (" << isaName(isa) << ")\n" << listProgram(p);
    }
  }
}

// The ops native code runs without the interpreter's routine, inline or through a
// lane helper sharing the interpreter's libm calls: random programs of them on
// special values (zeros of both signs, infinities, NaN, denormals, huge values,
// negative bases for pow), straight and inside flow control.
TEST(JitIdentity, RandomProgramsOfLaneOpsOnSpecialValues) {
  const auto isas = availableIsas();
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  static const Op kOps[] = {Op::Exp2, Op::Log2, Op::Pow,  Op::Lit,  Op::ExpP, Op::SinCos, Op::Round,
                            Op::Dist, Op::Crs,  Op::Sgn,  Op::Quot, Op::SetP, Op::Dsx,    Op::Dsy};
  std::mt19937 rng(4242);
  int perOp[std::size(kOps)] = {};
  for (int n = 0; n < 1200; ++n) {
    const bool flow = n % 4 == 3;
    Program p = flow ? randomFlowProgram(rng) : randomShell(rng);
    if (!flow) p.code.resize(1 + rng() % 8);
    for (Instr& in : p.code) {
      if (in.op >= Op::If) continue;
      if (!flow) in = randomInstruction(rng);
      const size_t k = rng() % std::size(kOps);
      in.op = kOps[k];
      ++perOp[k];
      in.cmp = uint8_t(rng() % 7);  // 0: always
    }
    Ranges ranges;
    ranges.specialValues = true;
    if (n % 2) ranges.lo = -300.0f, ranges.hi = 300.0f;
    for (auto isa : isas) {
      const Outcome o = compare(p, isa, uint32_t(n), ranges);
      ASSERT_NE(o.backend, "interpreter");
      ASSERT_EQ(o.interpretedInstructions, 0) << listProgram(p);
      ASSERT_EQ(o.mismatch, "") << "program " << n << " (" << isaName(isa) << ")\n" << listProgram(p);
    }
  }
  for (int count : perOp) EXPECT_GT(count, 100);
}

// Sources native code reads through the interpreter's fetch: c[a0.x + n] (a0 in a
// temp: truncated, negative, beyond the file, NaN), relative temps, inputs and outputs
// with their bounds, aL-relative sources inside loops, integer and boolean constants;
// the rest of the instruction runs inline.
TEST(JitIdentity, RandomProgramsWithRelativeAndIntegerSources) {
  const auto isas = availableIsas();
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937 rng(90210);
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  int relative = 0, integer = 0;
  for (int n = 0; n < 1200; ++n) {
    const bool flow = n % 3 == 2;
    Program p = flow ? randomFlowProgram(rng) : randomProgram(rng);
    if (n % 2 == 0) p.localConstants.clear();  // c[a0.x + n] gathered natively
    for (Instr& in : p.code) {
      if (in.op >= Op::If) continue;
      for (int i = 0; i < sourceCount(in.op); ++i) {
        Src& s = in.src[i];
        switch (pick(4)) {
          case 0:
            s.rel = flow && pick(2) ? RelMode::Loop : RelMode::Temp;
            s.relReg = uint16_t(pick(4)), s.relComp = uint8_t(pick(4));
            s.index = uint16_t(pick(s.file == RegFile::Const ? 40 : 4));
            s.relLo = 0, s.relHi = uint16_t(s.file == RegFile::Output ? 2 : 4);
            ++relative;
            break;
          case 1:
            s.file = pick(2) ? RegFile::ConstInt : RegFile::ConstBool;
            s.index = uint16_t(pick(18));  // two beyond the 16 set
            ++integer;
            break;
          default: break;
        }
      }
    }
    // Texture lookups with such coordinates are left to the interpreter's routine.
    int interpreted = 0;
    for (const Instr& in : p.code) {
      if (!(in.op >= Op::Tex && in.op <= Op::TexLod) && in.op != Op::TexGrad) continue;
      bool fetched = false;
      for (int i = 0; i < sourceCount(in.op); ++i)
        fetched |= in.src[i].rel != RelMode::None || in.src[i].file == RegFile::ConstInt ||
                   in.src[i].file == RegFile::ConstBool;
      interpreted += fetched;
    }
    Ranges ranges;
    ranges.specialValues = n % 2 == 1;
    if (n % 4 == 1) ranges.lo = -40.0f, ranges.hi = 40.0f;
    if (n % 8 == 2) ranges.lo = -400.0f, ranges.hi = 400.0f;  // beyond the constant file
    for (auto isa : isas) {
      const Outcome o = compare(p, isa, uint32_t(n), ranges, 0, n % 3 == 0 ? 1 : kSamplerCount);
      ASSERT_NE(o.backend, "interpreter") << "program " << n << " (" << isaName(isa) << ")\n" << listProgram(p);
      ASSERT_EQ(o.interpretedInstructions, interpreted) << listProgram(p);
      ASSERT_EQ(o.mismatch, "") << "program " << n << " (" << isaName(isa) << ")\n" << listProgram(p);
    }
  }
  EXPECT_GT(relative, 1000);
  EXPECT_GT(integer, 1000);
}

// rep 255 { rep 255 { add; mul } }: 255 * (1 + 255 * 3 + 1) instructions, more than
// kMaxExecutedInstructions, so the run stops inside a native block's range: it must
// stop where the interpreter stops.
TEST(JitIdentity, InstructionBudgetStopsWhereTheInterpreterStops) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  Program p;
  p.tempCount = 1, p.inputCount = 1, p.flowControl = true;
  auto flow = [&](Op op, int32_t target) {
    Instr in;
    in.op = op;
    in.src[0] = reg(RegFile::ConstInt, 0);
    in.target = target;
    p.code.push_back(in);
  };
  flow(Op::Rep, 6);
  flow(Op::Rep, 5);
  p.emit(Op::Add, dst(RegFile::Temp, 0), reg(RegFile::Temp, 0), reg(RegFile::Input, 0));
  p.emit(Op::Mul, dst(RegFile::Temp, 0, 0x3), reg(RegFile::Temp, 0), p.imm(Vec4(0.5f, 1.5f, 1, 1)));
  p.emit(Op::Add, dst(RegFile::Temp, 0, 0x4), reg(RegFile::Temp, 0, kSwzXXXX), reg(RegFile::Temp, 0, kSwzYYYY));
  flow(Op::EndRep, 1);
  flow(Op::EndRep, 0);
  const std::array<std::array<int, 4>, 1> ints{{{255, 0, 0, 0}}};
  std::atomic<uint32_t> stops{0};
  ExecContext ctx;
  ctx.intConstants = ints.data();
  ctx.intConstantCount = 1;
  ctx.boundStops = &stops;
  BatchRegisters ref, jit;
  for (BatchRegisters* r : {&ref, &jit}) {
    r->resize(p);
    for (int l = 0; l < kBatchLanes; ++l) r->inputs[0].c[0][l] = r->inputs[0].c[1][l] = 0.25f * float(l);
  }
  PrepareOptions interpreter;
  interpreter.jit = false;
  prepare(p, ctx, ref, interpreter);
  EXPECT_STRNE(prepare(p, ctx, jit).backend, "interpreter");
  execute(p, ctx, ref);
  execute(p, ctx, jit);
  EXPECT_EQ(ref.executedInstructions, kMaxExecutedInstructions);
  EXPECT_EQ(jit.executedInstructions, ref.executedInstructions);
  EXPECT_EQ(stops.load(), 2u);
  EXPECT_EQ(compareFile("r", ref.temps, jit.temps), "");
}

Program addProgram() {
  Program p;
  p.tempCount = 1, p.inputCount = 1;
  p.emit(Op::Add, dst(RegFile::Temp, 0), reg(RegFile::Input, 0), reg(RegFile::Const, 2));
  return p;
}

TEST(JitSwitches, EnvironmentAndOptionGiveTheInterpreter) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  const Program p = addProgram();
  BatchRegisters r;
  r.resize(p);
  EXPECT_STRNE(prepare(p, ExecContext{}, r).backend, "interpreter");
  PrepareOptions off;
  off.jit = false;
  EXPECT_STREQ(prepare(p, ExecContext{}, r, off).backend, "interpreter");
  setenv("REFX_JIT", "0", 1);
  EXPECT_STREQ(prepare(p, ExecContext{}, r).backend, "interpreter");
  unsetenv("REFX_JIT");
  const refx::CpuIsa previous = refx::setActiveIsa(refx::CpuIsa::Avx2);  // what REFX_ISA=avx2 sets
  EXPECT_STREQ(prepare(p, ExecContext{}, r).backend, "jit-avx2");
  refx::setActiveIsa(previous);
}

TEST(JitSwitches, RegistersTheCodeWouldMissGiveTheInterpreter) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  Program p = addProgram();
  p.emit(Op::Mov, dst(RegFile::Output, 0), reg(RegFile::Input, 5));  // v5 beyond inputCount
  p.outputCount = 1;
  BatchRegisters r;
  r.resize(p);  // one input register: v5 reads as zero in the interpreter
  EXPECT_STREQ(prepare(p, ExecContext{}, r).backend, "interpreter");
  r.inputs.resize(6);
  EXPECT_STRNE(prepare(p, ExecContext{}, r).backend, "interpreter");
}

TEST(JitCache, ThreadsPreparingOneProgramCompileItOnce) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  Program p = addProgram();
  p.emit(Op::Mul, dst(RegFile::Temp, 0, 0x2), reg(RegFile::Temp, 0, kSwzWWWW), reg(RegFile::Input, 0));
  const JitCacheStats before = jitCacheStats();
  std::vector<std::thread> threads;
  std::atomic<int> compiles{0};
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&] {
      BatchRegisters r;
      r.resize(p);
      if (prepare(p, ExecContext{}, r).compileMicroseconds > 0) ++compiles;
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(compiles.load(), 1);
  EXPECT_EQ(jitCacheStats().compiled, before.compiled + 1);
  EXPECT_EQ(jitCacheStats().hits, before.hits + 7);
}

TEST(JitIdentity, RandomProgramsWithFlowControl) {
  const auto isas = availableIsas();
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937 rng(1128);
  for (int n = 0; n < 600; ++n) {
    const Program p = randomFlowProgram(rng);
    for (auto isa : isas) {
      const Outcome o = compare(p, isa, uint32_t(n), {}, 0, n % 3 == 0 ? 1 : kSamplerCount);
      ASSERT_NE(o.backend, "interpreter");
      ASSERT_EQ(o.runner, !p.flowControl) << "program " << n;  // flow control runs through execute()
      ASSERT_EQ(o.mismatch, "") << "program " << n << " (" << isaName(isa) << ")\n" << listProgram(p);
    }
  }
}

TEST(JitCache, CompilesOncePerContentAndReadsConstantsWhenRunning) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  Program a = addProgram();
  // An instruction no other test has: r0.w = v0.z + imm0.y.
  Src imm0y = a.imm(Vec4(0.25f, 0.5f, 0, 0));
  imm0y.swizzle = kSwzYYYY;
  a.emit(Op::Add, dst(RegFile::Temp, 0, 0x8), reg(RegFile::Input, 0, kSwzZZZZ), imm0y);
  Program b = a;  // same content, another object
  std::vector<Vec4> constants(3, Vec4(0, 0, 0, 0));
  ExecContext ctx;
  ctx.constants = constants.data();
  ctx.constantCount = 3;
  BatchRegisters ra, rb;
  ra.resize(a), rb.resize(b);
  const JitCacheStats before = jitCacheStats();
  const ProgramBuildInfo first = prepare(a, ctx, ra);
  const ProgramBuildInfo second = prepare(b, ctx, rb);
  const JitCacheStats after = jitCacheStats();
  EXPECT_EQ(first.instructions, 2);
  EXPECT_GT(first.compileMicroseconds, 0.0);
  EXPECT_EQ(second.compileMicroseconds, 0.0);
  EXPECT_EQ(after.compiled, before.compiled + 1);
  EXPECT_EQ(after.hits, before.hits + 1);
  // A new constant value is read by the same code: v0 + c2 = 1.5 + 2.25.
  constants[2] = Vec4(2.25f, -1, 0, 4);
  for (int l = 0; l < kBatchLanes; ++l) rb.inputs[0].c[0][l] = 1.5f;
  execute(b, ctx, rb);
  EXPECT_EQ(rb.temps[0].c[0][7], 3.75f);
  // Constants the API did not set read as zero: c2 beyond a count of 2.
  ctx.constantCount = 2;
  execute(b, ctx, rb);
  EXPECT_EQ(rb.temps[0].c[0][7], 1.5f);
  // New immediates are read by the same code too: v0.z + imm0.y = 2 + 0.75.
  b.immediates[0] = Vec4(0, 0.75f, 0, 0);
  for (int l = 0; l < kBatchLanes; ++l) rb.inputs[0].c[2][l] = 2.0f;
  EXPECT_EQ(prepare(b, ctx, rb).compileMicroseconds, 0.0);
  execute(b, ctx, rb);
  EXPECT_EQ(rb.temps[0].c[3][7], 2.75f);
  EXPECT_EQ(jitCacheStats().compiled, after.compiled);
}

}  // namespace
