// Draws whose pixel program starts with texture lookups that read only interpolated
// inputs (exec::findTexturePrologue) make those lookups for groups of blocks at once,
// then run the rest of the program block by block (DrawStats::groupedLookupDraws).
// They must give exactly the pixels and depths of the same draw whose program keeps
// the lookups where they are: each pair of shaders below differs only in movs into
// the lookups' registers ahead of them (values the lookups overwrite), which stop the
// lookups from moving ahead and so from being grouped.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "device_helpers.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;

namespace {

// D3DTEXTUREFILTERTYPE and D3DTEXTUREADDRESS values.
constexpr uint32_t kNone = 0, kPoint = 1, kLinear = 2;
constexpr uint32_t kWrap = 1, kClamp = 3;

struct ShaderPair {
  const char* name;
  const char* grouped;
  const char* kept;
};

// Two lookups at the same coordinates (sampled as a pair), one lookup, and two at
// different coordinates (t0 and its own copy with a swizzle: not a plain lookup).
const ShaderPair kShaders[] = {
    {"two lookups",
     "ps_2_0\ndcl t0\ndcl v0\ndcl_2d s0\ndcl_2d s1\n"
     "texld r0, t0, s0\ntexld r1, t0, s1\nmul r0, r0, r1\nmad r0, r0, v0, c1\nmov oC0, r0\n",
     "ps_2_0\ndef c0, 0, 0, 0, 0\ndcl t0\ndcl v0\ndcl_2d s0\ndcl_2d s1\nmov r0, c0\nmov r1, c0\n"
     "texld r0, t0, s0\ntexld r1, t0, s1\nmul r0, r0, r1\nmad r0, r0, v0, c1\nmov oC0, r0\n"},
    {"one lookup",
     "ps_2_0\ndcl t0\ndcl_2d s1\ntexld r0, t0, s1\nmul r0, r0, c1\nmov oC0, r0\n",
     "ps_2_0\ndef c0, 0, 0, 0, 0\ndcl t0\ndcl_2d s1\nmov r0, c0\ntexld r0, t0, s1\nmul r0, r0, c1\nmov oC0, r0\n"},
    {"lookup then dependent lookup",
     "ps_2_0\ndcl t0\ndcl_2d s0\ndcl_2d s1\ntexld r0, t0, s0\ntexld r1, r0, s1\nlrp r0, c1, r0, r1\nmov oC0, r0\n",
     "ps_2_0\ndef c0, 0, 0, 0, 0\ndcl t0\ndcl_2d s0\ndcl_2d s1\nmov r0, c0\ntexld r0, t0, s0\ntexld r1, r0, s1\n"
     "lrp r0, c1, r0, r1\nmov oC0, r0\n"},
};

struct Config {
  uint32_t filter, mipFilter, address;
  bool depth, blend, sameSize;
};

struct Frame : FrameContents {
  uint64_t groupedDraws;
};

// Overlapping perspective triangles of many sizes (partial blocks, blocks of one
// primitive in several tiles, texture coordinates beyond [0, 1]) on a 150x90 target
// cleared to a colour; the last one half behind the others.
// secondSet: 0 the vertices have one texture coordinate set; 1 a second one equal to
// the first (interpolated once, RasterDraw::inputCopies); 2 a second one of other values.
Frame render(const Config& c, const char* ps, int secondSet = 0) {
  DeviceOptions opt;
  opt.threads = 2;
  Device dev(CapsProfile{}, opt);
  const int w = 150, h = 90;
  auto target = Texture::create2D(Format::A8R8G8B8, w, h);
  dev.setRenderTarget(target);
  auto ds = std::make_shared<DepthStencilSurface>(w, h);
  dev.setDepthStencilSurface(ds);
  dev.clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0x80402010, 1.0f, 0);
  dev.setRenderState(RS_ZENABLE, c.depth ? ZB_TRUE : ZB_FALSE);
  dev.setRenderState(RS_ZFUNC, CMP_LESS);
  dev.setRenderState(RS_CULLMODE, CULL_NONE);
  dev.setRenderState(RS_ALPHABLENDENABLE, c.blend ? 1 : 0);
  dev.setRenderState(RS_SRCBLEND, BLEND_SRCALPHA);
  dev.setRenderState(RS_DESTBLEND, BLEND_INVSRCALPHA);
  dev.setTexture(0, noiseTexture(64, 32, 12345));
  dev.setTexture(1, c.sameSize ? noiseTexture(64, 32, 777) : noiseTexture(32, 64, 777));
  for (uint32_t s : {0u, 1u}) setSampler(dev, s, c.filter, c.filter, c.mipFilter, c.address);
  const float k[4] = {0.75f, 0.5f, 0.25f, 0.625f};
  dev.setPixelShaderConstantF(1, k, 1);
  dev.setPixelShader(dev.createPixelShader(shader::assembleTokens(ps, "test.psh")));
  dev.resetStats();
  const std::vector<TLVertex> vertices = {{-3.5f, 1.25f, 0.5f, 1.0f, 0xff808080, -0.7f, -0.3f},
          {150.0f, 4.0f, 0.25f, 0.2f, 0xc0ff8040, 3.1f, 0.2f},
          {5.0f, 92.0f, 0.75f, 0.6f, 0x4020ff10, 0.4f, 2.6f},
          {140.0f, 88.0f, 0.6f, 1.0f, 0xffffffff, 1.5f, 1.5f},
          {10.0f, 3.0f, 0.6f, 0.5f, 0x80ff00ff, -0.2f, 0.9f},
          {146.0f, 40.0f, 0.6f, 0.8f, 0xff00ffff, 0.3f, -0.8f},
          {20.0f, 20.0f, 0.3f, 1.0f, 0xff102030, 0.1f, 0.1f},
          {27.0f, 22.0f, 0.3f, 1.0f, 0xff102030, 0.2f, 0.1f},
          {22.0f, 29.0f, 0.3f, 1.0f, 0xff102030, 0.1f, 0.2f},
          {60.0f, 10.0f, 0.55f, 0.9f, 0xffa0b0c0, 0.0f, 0.0f},
          {130.0f, 80.0f, 0.35f, 0.4f, 0xffa0b0c0, 1.0f, 1.0f},
          {61.0f, 80.0f, 0.45f, 0.7f, 0xffa0b0c0, 0.0f, 1.0f}};
  if (secondSet == 0) {
    drawTL(dev, PT_TRIANGLELIST, vertices);
  } else {
    struct TwoSetVertex {  // D3DFVF_XYZRHW | D3DFVF_DIFFUSE | D3DFVF_TEX2
      float x, y, z, rhw;
      uint32_t diffuse;
      float u0, v0, u1, v1;
    };
    std::vector<TwoSetVertex> two;
    for (const TLVertex& v : vertices) {
      const bool same = secondSet == 1;
      two.push_back(
          {v.x, v.y, v.z, v.rhw, v.diffuse, v.u, v.v, same ? v.u : 0.7f * v.v + 0.1f, same ? v.v : 1.3f * v.u});
    }
    dev.setFVF(FVF_XYZRHW | FVF_DIFFUSE | (2u << FVF_TEXCOUNT_SHIFT));
    dev.drawPrimitiveUP(PT_TRIANGLELIST, uint32_t(two.size() / 3), two.data(), sizeof(TwoSetVertex));
  }
  Frame f;
  static_cast<FrameContents&>(f) = readFrame(*target, *ds);
  f.groupedDraws = dev.stats().groupedLookupDraws;
  return f;
}

// The grouped draw made its lookups for groups, the other in place, with the same pixels
// and depths.
void expectSameFrames(const Frame& grouped, const Frame& kept) {
  EXPECT_EQ(grouped.groupedDraws, 1u);
  EXPECT_EQ(kept.groupedDraws, 0u);
  EXPECT_EQ(grouped.color, kept.color);
  EXPECT_EQ(grouped.depth, kept.depth);
}

TEST(GroupedLookups, SamePixelsAsTheLookupsInPlace) {
  int configs = 0;
  for (const ShaderPair& shaders : kShaders)
    for (uint32_t filter : {kPoint, kLinear})
      for (uint32_t mip : {kNone, kPoint, kLinear})
        for (uint32_t address : {kWrap, kClamp})
          for (bool depth : {false, true})
            for (bool blend : {false, true})
              for (bool sameSize : {false, true}) {
                const Config c{filter, mip, address, depth, blend, sameSize};
                SCOPED_TRACE(testing::Message() << shaders.name << ": filter " << filter << " mip " << mip
                                                << " address " << address << " depth " << depth << " blend "
                                                << blend << " same size " << sameSize);
                expectSameFrames(render(c, shaders.grouped), render(c, shaders.kept));
                ++configs;
              }
  EXPECT_EQ(configs, 3 * 96);
}

// Two lookups at the coordinate sets t0 and t1: where the vertices give both the same
// values the second lookup reads the first one's coordinates
// (RasterDraw::PrologueLookup::coordinates), where they differ each reads its own.
// Either way the pixels are those of the lookups kept in place.
TEST(GroupedLookups, TwoCoordinateSetsSameOrDifferent) {
  const char* grouped = "ps_2_0\ndcl t0\ndcl t1\ndcl v0\ndcl_2d s0\ndcl_2d s1\n"
                        "texld r0, t0, s0\ntexld r1, t1, s1\nmul r0, r0, r1\nmad r0, r0, v0, c1\nmov oC0, r0\n";
  const char* kept = "ps_2_0\ndef c0, 0, 0, 0, 0\ndcl t0\ndcl t1\ndcl v0\ndcl_2d s0\ndcl_2d s1\nmov r0, c0\n"
                     "mov r1, c0\ntexld r0, t0, s0\ntexld r1, t1, s1\nmul r0, r0, r1\nmad r0, r0, v0, c1\nmov oC0, r0\n";
  int configs = 0;
  for (int secondSet : {1, 2})
    for (uint32_t mip : {kNone, kPoint})
      for (bool sameSize : {false, true}) {
        const Config c{kLinear, mip, kWrap, true, false, sameSize};
        SCOPED_TRACE(testing::Message() << "second set " << secondSet << " mip " << mip << " same size " << sameSize);
        expectSameFrames(render(c, grouped, secondSet), render(c, kept, secondSet));
        ++configs;
      }
  EXPECT_EQ(configs, 8);
}

}  // namespace
