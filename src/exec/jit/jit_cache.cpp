// The process-wide cache of native code: one compiled function per program content
// and instruction set, shared by every thread and draw.
#include <asmjit/core.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <unordered_map>

#include "exec/jit/jit.h"
#include "refx/core/cpu_features.h"

namespace refx::exec::detail {

namespace {

struct HostIsa {
  bool avx2 = false, avx512 = false;
};

const HostIsa& hostIsa() {
  static const HostIsa isa = [] {
    HostIsa h;
    const auto& f = asmjit::CpuInfo::host().features().x86();
    h.avx2 = f.hasAVX2() && f.hasFMA();
    h.avx512 = h.avx2 && f.hasAVX512_F() && f.hasAVX512_BW() && f.hasAVX512_DQ() && f.hasAVX512_VL();
    return h;
  }();
  return isa;
}

template <class T>
void put(std::string& key, const T& v) {
  key.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// Everything that decides the generated code (field by field: no padding). The
// values of the immediates do not: the code reads them, as it reads constants, when
// it runs; only their count matters.
std::string contentKey(const Program& p, JitIsa isa) {
  std::string key;
  key.reserve(p.code.size() * 64 + p.immediates.size() * 16 + 32);
  put(key, isa);
  put(key, p.tempCount), put(key, p.inputCount), put(key, p.outputCount);
  put(key, p.flowControl);
  put(key, p.code.size());
  for (const Instr& in : p.code) {
    put(key, in.op);
    put(key, in.dst.file), put(key, in.dst.index), put(key, in.dst.mask), put(key, in.dst.rel);
    put(key, in.dst.relLo), put(key, in.dst.relHi);
    for (const Src& s : in.src) {
      put(key, s.file), put(key, s.index), put(key, s.swizzle), put(key, s.mod), put(key, s.rel);
      put(key, s.relComp), put(key, s.flags), put(key, s.relReg), put(key, s.relLo), put(key, s.relHi);
    }
    put(key, in.shift), put(key, in.saturate), put(key, in.clamp), put(key, in.clampLo), put(key, in.clampHi);
    put(key, in.sampler), put(key, in.cmp), put(key, in.quantize), put(key, in.target);
  }
  put(key, p.immediates.size());
  put(key, p.localConstants.size());
  for (int32_t l : p.localConstants) put(key, l);
  return key;
}

struct Cache {
  std::mutex mutex;
  std::unordered_map<std::string, std::shared_ptr<const JitProgram>> programs;  // null: unsupported
  JitCacheStats stats;
};

Cache& cache() {
  static Cache* c = new Cache;  // lives as long as the code it holds
  return *c;
}

}  // namespace

bool chooseJitIsa(const PrepareOptions& options, JitIsa& isa) {
  if (const char* e = std::getenv("REFX_JIT"); e && std::strcmp(e, "0") == 0) return false;
  const HostIsa& host = hostIsa();
  switch (options.isa) {
    case PrepareOptions::Isa::Avx2:
      isa = JitIsa::Avx2;
      return host.avx2;
    case PrepareOptions::Isa::Avx512:
      isa = JitIsa::Avx512;
      return host.avx512;
    case PrepareOptions::Isa::Auto: break;
  }
  // The level the rest of refx runs at (REFX_ISA=avx2 lowers it for everything).
  if (host.avx512 && activeIsa() == CpuIsa::Avx512) {
    isa = JitIsa::Avx512;
    return true;
  }
  isa = JitIsa::Avx2;
  return host.avx2;
}

std::shared_ptr<const JitProgram> jitProgram(const Program& program, JitIsa isa, bool& compiled) {
  compiled = false;
  std::string key = contentKey(program, isa);
  Cache& c = cache();
  // Compiling under the lock: each program is compiled once, whichever thread
  // asks first, and the others wait for it.
  std::lock_guard<std::mutex> lock(c.mutex);
  auto it = c.programs.find(key);
  if (it != c.programs.end()) {
    if (it->second) ++c.stats.hits;
    return it->second;
  }
  const auto start = std::chrono::steady_clock::now();
  std::shared_ptr<JitProgram> jit = compileProgram(program, isa);
  if (jit) {
    jit->compileMicroseconds =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    ++c.stats.compiled;
    c.stats.compileMicroseconds += jit->compileMicroseconds;
    compiled = true;
  } else {
    ++c.stats.unsupported;
  }
  c.programs.emplace(std::move(key), jit);
  return jit;
}

JitFrame jitFrame(const Program& program, BatchRegisters& regs) {
  JitFrame f{};
  f.temps = regs.temps[0].c[0];
  f.inputs = regs.inputs[0].c[0];
  f.outputs = regs.outputs[0].c[0];
  f.immediates = program.immediates.data();
  f.laneMask = &regs.laneMask;
  f.program = &program;
  f.regs = &regs;
  return f;
}

void runJit(const JitProgram& jit, JitFunction fn, JitFrame& f, const ExecContext& ctx) {
  f.ctx = &ctx;
  f.constants = ctx.constants;
  if (constantsToPad(jit, ctx)) {
    // Constants the API did not set read as zero, as in the interpreter.
    thread_local std::vector<Vec4> padded;
    padded.assign(size_t(jit.constantsRead), Vec4(0, 0, 0, 0));
    if (ctx.constants)
      std::copy(ctx.constants, ctx.constants + std::max(0, std::min(ctx.constantCount, jit.constantsRead)),
                padded.begin());
    f.constants = padded.data();
  }
  fn(&f);
}

}  // namespace refx::exec::detail

namespace refx::exec {

JitCacheStats jitCacheStats() {
  auto& c = detail::cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  return c.stats;
}

}  // namespace refx::exec
