// The tile loop compiled for a draw's state (depth function and write, opaque store)
// against the one reading the state at run time, the reference: a ps_3_0 shader that
// reads vFace takes the latter. It writes the colour on both sides of its vFace test,
// so both shaders compute the same colour; every frame must leave the same bytes and
// depths.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "device_helpers.h"
#include "refx/pipeline/device.h"
#include "refx/shader/assembler.h"

namespace refx {
namespace {

using namespace d3d;

constexpr const char* kVS = "vs_3_0\ndcl_position v0\ndcl_color v1\ndcl_position o0\ndcl_color o1\n"
                            "mov o0, v0\nmov o1, v1\n";
constexpr const char* kPSDirect = "ps_3_0\ndcl_color v0\nmov oC0, v0\n";
constexpr const char* kPSWithFace = "ps_3_0\ndef c0, 0, 0, 0, 0\ndcl_color v0\ndcl vFace\n"
                                    "mov r0, v0\nif_gt vFace.x, c0.x\nmov r0, v0\nendif\nmov oC0, r0\n";

struct ClipVertex {  // D3DFVF_XYZ | D3DFVF_DIFFUSE in clip space (the shader passes it on)
  float x, y, z;
  uint32_t color;
};

std::unique_ptr<Device> shaderDevice(int w, int h, const char* ps, int threads) {
  auto dev = test::makeDevice(w, h, 0xff000000, threads);
  dev->setVertexShader(dev->createVertexShader(shader::assembleTokens(kVS, "t.vsh")));
  dev->setPixelShader(dev->createPixelShader(shader::assembleTokens(ps, "t.psh")));
  dev->setFVF(FVF_XYZ | FVF_DIFFUSE);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  return dev;
}

TEST(ShadePath, StateCompiledLoopMatchesTheRunTimeOne) {
  std::mt19937 rng(77);
  const uint32_t funcs[] = {CMP_NEVER, CMP_LESS, CMP_EQUAL, CMP_LESSEQUAL, CMP_GREATER, CMP_NOTEQUAL,
                            CMP_GREATEREQUAL, CMP_ALWAYS};
  for (auto [w, h] : {std::pair{70, 37}, {131, 67}}) {
    for (int threads : {1, 2}) {
      auto direct = shaderDevice(w, h, kPSDirect, threads);
      auto withFace = shaderDevice(w, h, kPSWithFace, threads);
      for (int frame = 0; frame < 48; ++frame) {
        const uint32_t func = funcs[frame % 8];
        const uint32_t zenable = frame % 16 < 14, zwrite = (frame / 8) % 2, blend = rng() % 4 == 0,
                       alphaTest = rng() % 4 == 0;
        const uint32_t clearFlags = rng() % 3 ? CLEAR_TARGET | CLEAR_ZBUFFER : CLEAR_ZBUFFER;
        const float clearZ = float(rng() % 5) / 4.0f;
        std::vector<ClipVertex> tris;
        for (int i = 0; i < 3 * (1 + int(rng() % 6)); ++i) {
          std::uniform_real_distribution<float> u(-1.5f, 1.5f);
          // z on the cleared values' grid (ties) or between.
          const float z = rng() % 2 ? float(rng() % 5) / 4.0f : float(rng() % 1000) / 1000.0f;
          tris.push_back({u(rng), u(rng), z, uint32_t(rng())});
        }
        for (Device* dev : {direct.get(), withFace.get()}) {
          dev->clear(clearFlags, 0xff203040, clearZ, 0);
          dev->setRenderState(RS_ZENABLE, zenable ? ZB_TRUE : ZB_FALSE);
          dev->setRenderState(RS_ZFUNC, func);
          dev->setRenderState(RS_ZWRITEENABLE, zwrite);
          dev->setRenderState(RS_ALPHABLENDENABLE, blend);
          dev->setRenderState(RS_SRCBLEND, BLEND_SRCALPHA);
          dev->setRenderState(RS_DESTBLEND, BLEND_INVSRCALPHA);
          dev->setRenderState(RS_ALPHATESTENABLE, alphaTest);
          dev->setRenderState(RS_ALPHAFUNC, CMP_GREATER);
          dev->setRenderState(RS_ALPHAREF, 0x80);
          // Two draws: the second tests against and blends over the first.
          const uint32_t half = uint32_t(tris.size() / 6) * 3;
          if (half) dev->drawPrimitiveUP(PT_TRIANGLELIST, half / 3, tris.data(), sizeof(ClipVertex));
          dev->drawPrimitiveUP(PT_TRIANGLELIST, uint32_t(tris.size() - half) / 3, tris.data() + half,
                               sizeof(ClipVertex));
        }
        const Texture& a = *direct->renderTarget();
        const Texture& b = *withFace->renderTarget();
        ASSERT_EQ(std::memcmp(a.data(0, 0), b.data(0, 0), size_t(h) * a.rowPitch(0)), 0)
            << w << "x" << h << " frame " << frame << " func " << func << " write " << zwrite;
        ASSERT_EQ(direct->depthStencilSurface()->depth, withFace->depthStencilSurface()->depth)
            << w << "x" << h << " frame " << frame << " func " << func << " write " << zwrite;
      }
    }
  }
}

}  // namespace
}  // namespace refx
