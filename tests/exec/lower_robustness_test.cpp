// Lowering and running arbitrary decoded shaders: every input either lowers and runs
// (bounded) or is rejected with refx::Error; nothing crashes or hangs.
#include <random>

#include "shader_probe.h"

using namespace probe;

namespace {

TEST(LowerRobustness, RandomInstructionStreams) {
  std::mt19937 rng(12345);
  const sh::Opcode opcodes[] = {
      sh::Opcode::Mov, sh::Opcode::Add, sh::Opcode::Mad, sh::Opcode::Dp3, sh::Opcode::M4x4,
      sh::Opcode::M3x2, sh::Opcode::Rcp, sh::Opcode::Lit, sh::Opcode::Dst, sh::Opcode::Call,
      sh::Opcode::CallNZ, sh::Opcode::Loop, sh::Opcode::Ret, sh::Opcode::EndLoop, sh::Opcode::Label,
      sh::Opcode::Rep, sh::Opcode::EndRep, sh::Opcode::If, sh::Opcode::IfC, sh::Opcode::Else,
      sh::Opcode::EndIf, sh::Opcode::Break, sh::Opcode::BreakC, sh::Opcode::MovA, sh::Opcode::TexCoord,
      sh::Opcode::TexKill, sh::Opcode::Tex, sh::Opcode::TexBem, sh::Opcode::TexBemL,
      sh::Opcode::TexReg2AR, sh::Opcode::TexM3x2Pad, sh::Opcode::TexM3x2Tex, sh::Opcode::TexM3x3Pad,
      sh::Opcode::TexM3x3Spec, sh::Opcode::TexM3x3VSpec, sh::Opcode::ExpP, sh::Opcode::LogP,
      sh::Opcode::Cnd, sh::Opcode::Def, sh::Opcode::TexDP3Tex, sh::Opcode::TexM3x2Depth,
      sh::Opcode::TexDepth, sh::Opcode::Cmp, sh::Opcode::Bem, sh::Opcode::Dp2Add, sh::Opcode::Dsx,
      sh::Opcode::TexLdd, sh::Opcode::SetP, sh::Opcode::TexLdl, sh::Opcode::BreakP, sh::Opcode::Nrm,
      sh::Opcode::SinCos, sh::Opcode::Crs, sh::Opcode::Sgn, sh::Opcode::Pow, sh::Opcode::DefI,
      sh::Opcode::DefB, sh::Opcode::Dcl, sh::Opcode::Phase,
  };
  const sh::Version versions[] = {
      {sh::ShaderType::Vertex, 1, 1}, {sh::ShaderType::Vertex, 2, 0}, {sh::ShaderType::Vertex, 3, 0},
      {sh::ShaderType::Pixel, 1, 1},  {sh::ShaderType::Pixel, 1, 3},  {sh::ShaderType::Pixel, 1, 4},
      {sh::ShaderType::Pixel, 2, 0},  {sh::ShaderType::Pixel, 2, 1},  {sh::ShaderType::Pixel, 3, 0},
  };
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  // Mostly plausible register types, sometimes anything.
  const sh::RegType common[] = {sh::RegType::Temp, sh::RegType::Input, sh::RegType::Const,
                                sh::RegType::Texture, sh::RegType::Temp};
  auto regType = [&] { return pick(5) ? common[pick(5)] : sh::RegType(pick(20)); };
  int lowered = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    sh::Shader s;
    s.version = versions[pick(9)];
    const int count = 1 + pick(10);
    for (int k = 0; k < count; ++k) {
      sh::Instruction in;
      in.opcode = opcodes[pick(int(std::size(opcodes)))];
      in.hasDst = pick(4) != 0;
      in.dst.type = pick(3) ? sh::RegType::Temp : regType();
      in.dst.index = uint16_t(pick(20) == 0 ? pick(3000) : pick(4));
      in.dst.writeMask = uint8_t(1 + pick(15));
      in.dst.shift = int8_t(pick(5) - 2);
      in.dst.resultMod = uint8_t(pick(2));
      in.dst.relative = pick(20) == 0;
      in.srcCount = uint8_t(pick(5));
      for (int i = 0; i < in.srcCount; ++i) {
        sh::SrcParam& p = in.src[size_t(i)];
        p.type = regType();
        p.index = uint16_t(pick(20) == 0 ? pick(3000) : pick(4));
        p.swizzle = uint8_t(rng());
        p.mod = pick(3) ? sh::SrcMod::None : sh::SrcMod(pick(14));
        p.relative = pick(10) == 0;
        p.rel.type = pick(2) ? sh::RegType::Addr : sh::RegType::Loop;
        p.rel.component = uint8_t(pick(4));
      }
      in.control = uint8_t(pick(8));
      in.predicated = pick(10) == 0;
      in.predicateNot = pick(2) == 0;
      in.coissue = pick(8) == 0;
      in.literal = {uint32_t(rng()), uint32_t(rng()), uint32_t(pick(300)), uint32_t(rng())};
      in.usage = sh::DeclUsage(pick(14));
      in.usageIndex = uint8_t(pick(10));
      in.textureType = sh::TextureType(pick(5));
      s.instructions.push_back(in);
    }
    try {
      ShaderRun r(s);
      ++lowered;
      for (int v = 0; v < 13; ++v) r.input(v, {float(pick(5)) - 2, 0.5f, -0.25f, 1});
      for (auto& i : r.ints) i = {pick(300), pick(300), pick(9) - 4, 0};
      r.execute();
    } catch (const refx::Error&) {
    }
  }
  // A fair share of the random streams is runnable (registers beyond the version's
  // register files, r2 in ps_1_1 say, are rejected).
  EXPECT_GT(lowered, 900);
}

}  // namespace
