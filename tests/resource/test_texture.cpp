// Texture storage, mip dimensions, box-filtered mips and the decoded sampling levels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/resource/texture.h"

using namespace refx;

namespace {
constexpr float kTol = 1.0f / 255.0f;
}

TEST(Texture, LevelDims) {
  // levels 0 = full chain: max(13, 5) = 13 -> 13, 6, 3, 1 : 4 levels.
  auto t = Texture::create2D(Format::A8R8G8B8, 13, 5, 0);
  ASSERT_EQ(t->levelCount(), 4);
  EXPECT_EQ(t->width(1), 6);   // 13 >> 1
  EXPECT_EQ(t->height(1), 2);  // 5 >> 1
  EXPECT_EQ(t->width(3), 1);
  EXPECT_EQ(t->height(3), 1);  // max(1, 5 >> 3)
  EXPECT_EQ(t->dataSize(0, 0), 13u * 5u * 4u);
  EXPECT_EQ(t->rowPitch(1), 6u * 4u);
}

TEST(Texture, SetTexelRoundTripA8R8G8B8) {
  auto t = Texture::create2D(Format::A8R8G8B8, 4, 4);
  t->setTexel(0, 0, 1, 2, 0, {1.0f, 0.5f, 0.0f, 0.25f});
  // Memory order B, G, R, A; 0.5*255 + 0.5 = 128, 0.25*255 + 0.5 = 64.
  const uint8_t* p = t->data(0, 0) + (2 * 4 + 1) * 4;
  EXPECT_EQ(p[0], 0);
  EXPECT_EQ(p[1], 128);
  EXPECT_EQ(p[2], 255);
  EXPECT_EQ(p[3], 64);
  Color4 c = t->texel(0, 0, 1, 2);
  EXPECT_NEAR(c.g, 128 / 255.0f, 1e-6);
}

TEST(Texture, SampleLevelPackingUnorm8) {
  auto t = Texture::create2D(Format::X8R8G8B8, 2, 1);
  uint8_t* p = t->data(0, 0);
  // texel 0: B=0x30 G=0x20 R=0x10 X=0x00 -> r | g<<8 | b<<16 | 0xff<<24 (X reads as A=1)
  p[0] = 0x30, p[1] = 0x20, p[2] = 0x10, p[3] = 0x00;
  t->markDirty();
  const SampleLevel& s = t->sampleLevel(0, 0);
  ASSERT_TRUE(s.unorm8);
  EXPECT_EQ(s.rgba8[0], 0xff302010u);
}

TEST(Texture, SampleLevelFloatFormat) {
  auto t = Texture::create2D(Format::A32B32G32R32F, 1, 1);
  t->setTexel(0, 0, 0, 0, 0, {2.0f, -1.0f, 0.5f, 3.0f});
  const SampleLevel& s = t->sampleLevel(0, 0);
  ASSERT_FALSE(s.unorm8);
  EXPECT_EQ(s.rgbaf[0], (Color4{2.0f, -1.0f, 0.5f, 3.0f}));  // float formats unclamped
}

TEST(Texture, SampleLevelL8A8) {
  auto l8 = Texture::create2D(Format::L8, 1, 1);
  l8->data(0, 0)[0] = 0x40;
  // L8 -> (L, L, L, 1)
  EXPECT_EQ(l8->sampleLevel(0, 0).rgba8[0], 0xff404040u);
  auto a8 = Texture::create2D(Format::A8, 1, 1);
  a8->data(0, 0)[0] = 0x40;
  // A8 -> (0, 0, 0, A)
  EXPECT_EQ(a8->sampleLevel(0, 0).rgba8[0], 0x40000000u);
}

TEST(Texture, MarkDirtyRedecodes) {
  auto t = Texture::create2D(Format::L8, 1, 1);
  EXPECT_EQ(t->sampleLevel(0, 0).rgba8[0], 0xff000000u);
  t->data(0, 0)[0] = 0xff;
  t->markDirty();
  EXPECT_EQ(t->sampleLevel(0, 0).rgba8[0], 0xffffffffu);
}

TEST(Texture, GenerateMipsBox2D) {
  auto t = Texture::create2D(Format::A8R8G8B8, 2, 2, 0);
  ASSERT_EQ(t->levelCount(), 2);
  t->setTexel(0, 0, 0, 0, 0, {1, 0, 0, 1});
  t->setTexel(0, 0, 1, 0, 0, {0, 1, 0, 1});
  t->setTexel(0, 0, 0, 1, 0, {0, 0, 1, 1});
  t->setTexel(0, 0, 1, 1, 0, {1, 1, 1, 0});
  t->generateMips();
  Color4 c = t->texel(0, 1, 0, 0);
  // average of the four: r = (1+0+0+1)/4, g = (0+1+0+1)/4, b = (0+0+1+1)/4, a = 3/4
  EXPECT_NEAR(c.r, 0.5f, kTol);
  EXPECT_NEAR(c.g, 0.5f, kTol);
  EXPECT_NEAR(c.b, 0.5f, kTol);
  EXPECT_NEAR(c.a, 0.75f, kTol);
}

TEST(Texture, BadArguments) {
  EXPECT_THROW(Texture::create2D(Format::A8R8G8B8, 0, 4), Error);
  EXPECT_THROW(Texture::create2D(Format::A8R8G8B8, 16385, 4), Error);
  EXPECT_THROW(Texture::create2D(Format::A8R8G8B8, 4, 4, 4), Error);  // chain is 3 levels
  EXPECT_THROW(Texture(TextureType::Cube, Format::A8R8G8B8, 4, 8, 1, 1), Error);
  EXPECT_THROW(Texture::create2D(Format::Unknown, 4, 4), Error);
}

TEST(Texture, GenerateMipsVolumeAndOddSizes) {
  auto v = Texture::createVolume(Format::L8, 2, 2, 2, 0);
  ASSERT_EQ(v->levelCount(), 2);
  // Eight texels 0, 1/7, ..., 7/7 stored as round(i/7*255): box average of all eight.
  float sum = 0;
  for (int i = 0; i < 8; ++i) {
    v->setTexel(0, 0, i & 1, (i >> 1) & 1, i >> 2, {i / 7.0f, 0, 0, 1});
    sum += std::round(i / 7.0f * 255) / 255;
  }
  v->generateMips();
  EXPECT_NEAR(v->texel(0, 1, 0, 0, 0).r, sum / 8, kTol);  // = 0.5 within one step
  // 3x1: level 1 is 1x1 from texels 0 and 1 (a plain 2x box: the odd last column
  // does not contribute).
  auto o = Texture::create2D(Format::A8, 3, 1, 0);
  ASSERT_EQ(o->levelCount(), 2);
  o->setTexel(0, 0, 0, 0, 0, {0, 0, 0, 0.2f});
  o->setTexel(0, 0, 1, 0, 0, {0, 0, 0, 0.6f});
  o->setTexel(0, 0, 2, 0, 0, {0, 0, 0, 1.0f});
  o->generateMips();
  EXPECT_NEAR(o->texel(0, 1, 0, 0).a, 0.4f, kTol);  // (0.2 + 0.6) / 2
}

TEST(Texture, GenerateMipsCubeFaces) {
  auto c = Texture::createCube(Format::X8R8G8B8, 2, 0);
  for (int f = 0; f < 6; ++f)
    for (int i = 0; i < 4; ++i) c->setTexel(f, 0, i & 1, i >> 1, 0, {f / 5.0f, i / 3.0f, 0, 1});
  c->generateMips();
  for (int f = 0; f < 6; ++f) {
    Color4 t = c->texel(f, 1, 0, 0);
    EXPECT_NEAR(t.r, f / 5.0f, kTol);
    EXPECT_NEAR(t.g, 0.5f, kTol);  // (0 + 1/3 + 2/3 + 1) / 4
    EXPECT_EQ(t.a, 1.0f);
  }
}

TEST(Texture, CompressedTexelsAndMips) {
  auto t = Texture::create2D(Format::DXT1, 8, 8, 0);
  // Block (1, 0): c0 = 0xF800 red > c1 = 0x001F blue; all indices 1 (0x55) -> blue.
  uint8_t* b = t->data(0, 0) + 8;
  const uint8_t block[8] = {0x00, 0xF8, 0x1F, 0x00, 0x55, 0x55, 0x55, 0x55};
  std::copy(block, block + 8, b);
  t->markDirty();
  EXPECT_EQ(t->texel(0, 0, 5, 3), (Color4{0, 0, 1, 1}));
  // Sample level is 8-bit: blue = 0xff0000 | alpha 0xff000000.
  EXPECT_EQ(t->sampleLevel(0, 0).rgba8[3 * 8 + 5], 0xffff0000u);
  EXPECT_THROW(t->generateMips(), Error);
  EXPECT_THROW(t->setTexel(0, 0, 0, 0, 0, {}), Error);
  EXPECT_EQ(t->dataSize(0, 3), 8u);  // 1x1 level still one block
}

TEST(Texture, SampleLevelFromManyThreads) {
  auto t = Texture::create2D(Format::R5G6B5, 64, 64, 0);
  std::vector<const SampleLevel*> seen(8);
  std::vector<std::thread> threads;
  for (int i = 0; i < 8; ++i)
    threads.emplace_back([&, i] { seen[i] = &t->sampleLevel(0, i % 2); });
  for (auto& th : threads) th.join();
  for (int i = 2; i < 8; ++i) EXPECT_EQ(seen[i], seen[i % 2]);
  EXPECT_EQ(seen[0]->width, 64);
  EXPECT_EQ(seen[1]->width, 32);
  EXPECT_TRUE(seen[0]->unorm8);  // packed 16-bit unorm fits 8 bits
}

TEST(Texture, SignedFormatSampleLevelIsFloat) {
  auto t = Texture::create2D(Format::V8U8, 1, 1);
  t->data(0, 0)[0] = 0x81;  // U = -127/127 = -1
  t->data(0, 0)[1] = 0x40;  // V = 64/127
  t->markDirty();
  const SampleLevel& s = t->sampleLevel(0, 0);
  ASSERT_FALSE(s.unorm8);
  EXPECT_EQ(s.rgbaf[0].r, -1.0f);
  EXPECT_NEAR(s.rgbaf[0].g, 64 / 127.0f, 1e-6f);
  EXPECT_EQ(s.rgbaf[0].b, 1.0f);
}
