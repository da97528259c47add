// Texture storage, mip dimensions, box-filtered mips and the decoded sampling levels.
#include <gtest/gtest.h>

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
