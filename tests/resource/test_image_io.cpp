// Image files: write/read round trips (PNG, DDS, PPM, PAM), hand-built TGA/BMP/PNM/DDS
// byte arrays decoded to known texels, and corrupt files giving refx::Error that names
// the file.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/resource/image_io.h"

using namespace refx;
namespace fs = std::filesystem;

namespace {

using Bytes = std::vector<uint8_t>;

class ImageIO : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("refx_image_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& n) const { return (dir_ / n).string(); }
  fs::path dir_;
};

Bytes readAll(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), {});
}

// Raw bytes of an A8R8G8B8 texel: B, G, R, A.
uint32_t argbAt(const Texture& t, int x, int y, int face = 0, int level = 0) {
  const uint8_t* p = t.data(face, level) + (size_t(y) * t.width(level) + x) * 4;
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

void put16(Bytes& b, uint16_t v) { b.push_back(uint8_t(v)), b.push_back(uint8_t(v >> 8)); }
void put32(Bytes& b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(uint8_t(v >> (8 * i)));
}

// Expects loadTextureFromMemory to throw refx::Error mentioning `name` and `what`.
void expectLoadError(const Bytes& b, const std::string& name, const std::string& what = "") {
  try {
    loadTextureFromMemory(b, name);
    ADD_FAILURE() << name << ": no error";
  } catch (const Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find(name), std::string::npos) << m;
    EXPECT_NE(m.find(what), std::string::npos) << m;
  }
}

// DDS header for hand-built files (DDS_HEADER with a DDS_PIXELFORMAT).
Bytes ddsHeader(uint32_t w, uint32_t h, uint32_t depth, uint32_t mips, uint32_t pfFlags,
                uint32_t fourCC, uint32_t bits, uint32_t r, uint32_t g, uint32_t b, uint32_t a,
                uint32_t caps2 = 0) {
  Bytes o;
  put32(o, makeFourCC('D', 'D', 'S', ' '));
  put32(o, 124);
  put32(o, 0x1 | 0x2 | 0x4 | 0x1000 | (mips > 1 ? 0x20000 : 0));
  put32(o, h);
  put32(o, w);
  put32(o, 0);
  put32(o, depth);
  put32(o, mips);
  for (int i = 0; i < 11; ++i) put32(o, 0);
  for (uint32_t v : {32u, pfFlags, fourCC, bits, r, g, b, a}) put32(o, v);
  put32(o, 0x1000);
  put32(o, caps2);
  for (int i = 0; i < 3; ++i) put32(o, 0);
  return o;
}

uint32_t headerWord(const Bytes& dds, int index) {  // DWORD `index` after the magic
  size_t o = 4 + size_t(index) * 4;
  return uint32_t(dds[o]) | (uint32_t(dds[o + 1]) << 8) | (uint32_t(dds[o + 2]) << 16) |
         (uint32_t(dds[o + 3]) << 24);
}

void expectSameData(const Texture& a, const Texture& b) {
  ASSERT_EQ(a.format(), b.format());
  ASSERT_EQ(a.type(), b.type());
  ASSERT_EQ(a.levelCount(), b.levelCount());
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  ASSERT_EQ(a.depth(), b.depth());
  for (int f = 0; f < a.faceCount(); ++f)
    for (int l = 0; l < a.levelCount(); ++l) {
      ASSERT_EQ(a.dataSize(f, l), b.dataSize(f, l));
      EXPECT_EQ(std::memcmp(a.data(f, l), b.data(f, l), a.dataSize(f, l)), 0)
          << "face " << f << " level " << l;
    }
}

TexturePtr makeTestImage() {
  auto t = Texture::create2D(Format::A8R8G8B8, 3, 2);
  const Color4 c[6] = {{1, 0, 0, 1},       {0, 1, 0, 0.5f}, {0, 0, 1, 0},
                       {0.2f, 0.4f, 0.6f, 0.8f}, {1, 1, 1, 1},    {0, 0, 0, 1}};
  for (int i = 0; i < 6; ++i) t->setTexel(0, 0, i % 3, i / 3, 0, c[i]);
  return t;
}

}  // namespace

// ---- PNG --------------------------------------------------------------------------

TEST_F(ImageIO, PngRgbaRoundTrip) {
  auto t = makeTestImage();
  savePNG(*t, path("a.png"), true);
  auto back = loadTexture(path("a.png"));
  ASSERT_EQ(back->format(), Format::A8R8G8B8);
  expectSameData(*t, *back);
}

TEST_F(ImageIO, PngRgbDropsAlpha) {
  auto t = makeTestImage();
  saveImage(*t, path("a.png"));  // alpha = false: RGB
  auto back = loadTexture(path("a.png"));
  // texel (1,0) = (0, 1, 0, 0.5) -> stored RGB, read back with A = 0xff: 0xff00ff00
  EXPECT_EQ(argbAt(*back, 1, 0), 0xff00ff00u);
  // texel (0,1) = (0.2, 0.4, 0.6): 51, 102, 153 -> 0xff336699
  EXPECT_EQ(argbAt(*back, 0, 1), 0xff336699u);
}

TEST_F(ImageIO, PngGreyPaletteAnd16Bit) {
  // Grey 8-bit -> L8.
  {
    png_image img{};
    img.version = PNG_IMAGE_VERSION;
    img.width = 2, img.height = 1, img.format = PNG_FORMAT_GRAY;
    uint8_t px[2] = {0x10, 0xf0};
    png_alloc_size_t size = 0;
    ASSERT_TRUE(png_image_write_to_memory(&img, nullptr, &size, 0, px, 0, nullptr));
    Bytes b(size);
    ASSERT_TRUE(png_image_write_to_memory(&img, b.data(), &size, 0, px, 0, nullptr));
    auto t = loadTextureFromMemory(b, "grey.png");
    ASSERT_EQ(t->format(), Format::L8);
    EXPECT_EQ(t->data(0, 0)[0], 0x10);
    EXPECT_EQ(t->data(0, 0)[1], 0xf0);
  }
  // Palette with transparency -> A8R8G8B8.
  {
    png_image img{};
    img.version = PNG_IMAGE_VERSION;
    img.width = 2, img.height = 1, img.format = PNG_FORMAT_RGBA_COLORMAP;
    img.colormap_entries = 2;
    uint8_t cmap[8] = {255, 0, 0, 255, 0, 0, 255, 128};  // red opaque, blue half
    uint8_t px[2] = {1, 0};
    png_alloc_size_t size = 0;
    ASSERT_TRUE(png_image_write_to_memory(&img, nullptr, &size, 0, px, 0, cmap));
    Bytes b(size);
    ASSERT_TRUE(png_image_write_to_memory(&img, b.data(), &size, 0, px, 0, cmap));
    ASSERT_EQ(b[25], 3) << "colour type: palette";
    auto t = loadTextureFromMemory(b, "pal.png");
    ASSERT_EQ(t->format(), Format::A8R8G8B8);
    EXPECT_EQ(argbAt(*t, 0, 0), 0x800000ffu);  // blue, alpha 128
    EXPECT_EQ(argbAt(*t, 1, 0), 0xffff0000u);  // red
  }
  // 16-bit grey: 0x8080 -> round(0x8080 / 257) = 128.
  {
    png_image img{};
    img.version = PNG_IMAGE_VERSION;
    img.width = 1, img.height = 1, img.format = PNG_FORMAT_LINEAR_Y;
    uint16_t px[1] = {0x8080};
    png_alloc_size_t size = 0;
    ASSERT_TRUE(png_image_write_to_memory(&img, nullptr, &size, 0, px, 0, nullptr));
    Bytes b(size);
    ASSERT_TRUE(png_image_write_to_memory(&img, b.data(), &size, 0, px, 0, nullptr));
    ASSERT_EQ(b[24], 16) << "bit depth";
    auto t = loadTextureFromMemory(b, "grey16.png");
    ASSERT_EQ(t->format(), Format::L8);
    EXPECT_EQ(t->data(0, 0)[0], 128);
  }
}

TEST_F(ImageIO, PngCorrupt) {
  auto t = makeTestImage();
  savePNG(*t, path("a.png"), true);
  Bytes b = readAll(path("a.png"));
  expectLoadError(Bytes(b.begin(), b.begin() + 40), "cut.png");
  Bytes bad = b;
  bad[30] ^= 0xff;  // inside IHDR: CRC mismatch
  expectLoadError(bad, "crc.png");
  Bytes noData(b.begin(), b.begin() + 8);
  expectLoadError(noData, "sig.png");
}

TEST_F(ImageIO, PngHugeDimensionsRejected) {
  // IHDR claiming 16384 x 16384 (within the limits) but no image data: must be an
  // error about the size, not an attempt to allocate 1 GiB.
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  img.width = 1, img.height = 1, img.format = PNG_FORMAT_GRAY;
  uint8_t px[1] = {0};
  png_alloc_size_t size = 0;
  ASSERT_TRUE(png_image_write_to_memory(&img, nullptr, &size, 0, px, 0, nullptr));
  Bytes b(size);
  ASSERT_TRUE(png_image_write_to_memory(&img, b.data(), &size, 0, px, 0, nullptr));
  // IHDR data at 16..28, CRC at 29..32 over bytes 12..28.
  for (int o : {16, 20}) b[o] = 0, b[o + 1] = 0, b[o + 2] = 0x40, b[o + 3] = 0;
  uint32_t crc = uint32_t(crc32(0, b.data() + 12, 17));
  for (int i = 0; i < 4; ++i) b[29 + i] = uint8_t(crc >> (24 - 8 * i));
  expectLoadError(b, "huge.png", "16384x16384");
}

TEST_F(ImageIO, PngFromFloatTextureClampsAndMapsNaN) {
  auto t = Texture::create2D(Format::A32B32G32R32F, 2, 1);
  t->setTexel(0, 0, 0, 0, 0, {2.0f, -1.0f, 0.5f, 1});
  t->setTexel(0, 0, 1, 0, 0, {std::nanf(""), 0, 0, 1});
  savePNG(*t, path("f.png"));
  auto back = loadTexture(path("f.png"));
  // (2, -1, 0.5) clamps to (1, 0, 0.5): 255, 0, 128.
  EXPECT_EQ(argbAt(*back, 0, 0), 0xffff0080u);
  EXPECT_EQ(argbAt(*back, 1, 0), 0xff000000u);  // NaN -> 0
}

// ---- DDS --------------------------------------------------------------------------

TEST_F(ImageIO, Dds2DWithMips) {
  auto t = Texture::create2D(Format::A8R8G8B8, 4, 2, 0);
  ASSERT_EQ(t->levelCount(), 3);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) t->setTexel(0, 0, x, y, 0, {x / 3.0f, y * 1.0f, 0.5f, 1});
  t->generateMips();
  saveDDS(*t, path("m.dds"));
  Bytes b = readAll(path("m.dds"));
  // flags: CAPS|HEIGHT|WIDTH|PITCH|PIXELFORMAT|MIPMAPCOUNT = 0x1|0x2|0x4|0x8|0x1000|0x20000
  EXPECT_EQ(headerWord(b, 1), 0x2100Fu);
  EXPECT_EQ(headerWord(b, 4), 16u);   // pitch = 4 * 4 bytes
  EXPECT_EQ(headerWord(b, 6), 3u);    // mip count
  // caps: TEXTURE|COMPLEX|MIPMAP = 0x1000|0x8|0x400000
  EXPECT_EQ(headerWord(b, 26), 0x401008u);
  // pixel format: RGB|ALPHAPIXELS, 32 bits, A8R8G8B8 masks
  EXPECT_EQ(headerWord(b, 19), 0x41u);
  EXPECT_EQ(headerWord(b, 21), 32u);
  EXPECT_EQ(headerWord(b, 22), 0xff0000u);
  EXPECT_EQ(headerWord(b, 25), 0xff000000u);
  // 128 header bytes + 32 + 8 + 4 data bytes
  EXPECT_EQ(b.size(), 128u + 4 * 2 * 4 + 2 * 1 * 4 + 1 * 1 * 4);
  auto back = loadTexture(path("m.dds"));
  expectSameData(*t, *back);
}

TEST_F(ImageIO, DdsCube) {
  auto t = Texture::createCube(Format::R5G6B5, 2, 2);
  for (int f = 0; f < 6; ++f)
    for (int l = 0; l < 2; ++l)
      for (size_t i = 0; i < t->dataSize(f, l); ++i) t->data(f, l)[i] = uint8_t(f * 16 + l * 4 + i);
  saveDDS(*t, path("c.dds"));
  Bytes b = readAll(path("c.dds"));
  EXPECT_EQ(headerWord(b, 27), 0x200u | 0xFC00u);  // caps2: CUBEMAP | all faces
  EXPECT_EQ(headerWord(b, 19), 0x40u);             // DDPF_RGB
  auto back = loadTexture(path("c.dds"));
  expectSameData(*t, *back);
  // Dropping a face bit: refused.
  b[4 + 27 * 4 + 1] &= ~0x04;  // clear +X (0x400)
  expectLoadError(b, "cube5.dds", "six faces");
}

TEST_F(ImageIO, DdsVolume) {
  auto t = Texture::createVolume(Format::L8, 4, 4, 2, 0);
  ASSERT_EQ(t->levelCount(), 3);
  for (int l = 0; l < 3; ++l)
    for (size_t i = 0; i < t->dataSize(0, l); ++i) t->data(0, l)[i] = uint8_t(l * 50 + i);
  saveDDS(*t, path("v.dds"));
  Bytes b = readAll(path("v.dds"));
  EXPECT_EQ(headerWord(b, 5), 2u);           // depth
  EXPECT_EQ(headerWord(b, 27), 0x200000u);   // VOLUME
  EXPECT_EQ(headerWord(b, 1) & 0x800000u, 0x800000u);  // DDSD_DEPTH
  EXPECT_EQ(headerWord(b, 19), 0x20000u);    // LUMINANCE
  auto back = loadTexture(path("v.dds"));
  expectSameData(*t, *back);
  // 16*2 + 4*1 + 1 = 37 data bytes
  EXPECT_EQ(b.size(), 128u + 37u);
}

TEST_F(ImageIO, DdsDxt1RawBlocks) {
  auto t = Texture::create2D(Format::DXT1, 8, 4);
  // Block 0 solid red (c0 = 0xF800, indices 0), block 1 solid blue.
  const uint8_t blocks[16] = {0x00, 0xF8, 0, 0, 0, 0, 0, 0, 0x1F, 0x00, 0, 0, 0, 0, 0, 0};
  ASSERT_EQ(t->dataSize(0, 0), 16u);
  std::memcpy(t->data(0, 0), blocks, 16);
  saveDDS(*t, path("d.dds"));
  Bytes b = readAll(path("d.dds"));
  EXPECT_EQ(headerWord(b, 19), 0x4u);  // FOURCC
  EXPECT_EQ(headerWord(b, 20), makeFourCC('D', 'X', 'T', '1'));
  EXPECT_EQ(headerWord(b, 4), 16u);    // linear size of level 0
  EXPECT_EQ(headerWord(b, 1) & 0x80000u, 0x80000u);  // DDSD_LINEARSIZE
  auto back = loadTexture(path("d.dds"));
  expectSameData(*t, *back);
  Color4 c = back->texel(0, 0, 5, 2);  // block 1
  EXPECT_EQ(c, (Color4{0, 0, 1, 1}));
}

TEST_F(ImageIO, DdsOtherFormatsRoundTrip) {
  for (Format f : {Format::A16B16G16R16F, Format::A32B32G32R32F, Format::R16F, Format::R32F,
                   Format::V8U8, Format::Q8W8V8U8, Format::X8L8V8U8, Format::L6V5U5,
                   Format::A8L8, Format::A8, Format::A4R4G4B4, Format::A1R5G5B5,
                   Format::X8R8G8B8, Format::R8G8B8, Format::G16R16, Format::V16U16,
                   Format::A8B8G8R8, Format::L16, Format::DXT3, Format::DXT5}) {
    SCOPED_TRACE(std::string(formatName(f)));
    auto t = Texture::create2D(f, 4, 4);
    for (size_t i = 0; i < t->dataSize(0, 0); ++i) t->data(0, 0)[i] = uint8_t(i * 7 + 3);
    saveDDS(*t, path("f.dds"));
    auto back = loadTexture(path("f.dds"));
    expectSameData(*t, *back);
  }
}

TEST_F(ImageIO, DdsHandBuilt) {
  // V8U8 by DDPF_BUMPDUDV masks: one texel {U = 0x81, V = 0x7F} -> (-1, 1, 1, 1).
  Bytes b = ddsHeader(1, 1, 0, 1, 0x80000, 0, 16, 0xff, 0xff00, 0, 0);
  b.push_back(0x81), b.push_back(0x7F);
  auto t = loadTextureFromMemory(b, "v8u8.dds");
  ASSERT_EQ(t->format(), Format::V8U8);
  EXPECT_EQ(t->texel(0, 0, 0, 0), (Color4{-1, 1, 1, 1}));
  // FourCC 113 = A16B16G16R16F: halves 1, -2, 0.5, 0 (0x3C00, 0xC000, 0x3800, 0x0000).
  Bytes h = ddsHeader(1, 1, 0, 1, 0x4, 113, 0, 0, 0, 0, 0);
  for (uint16_t v : {0x3C00, 0xC000, 0x3800, 0x0000}) put16(h, v);
  auto th = loadTextureFromMemory(h, "half.dds");
  ASSERT_EQ(th->format(), Format::A16B16G16R16F);
  EXPECT_EQ(th->texel(0, 0, 0, 0), (Color4{1, -2, 0.5f, 0}));
  // X8R8G8B8: RGB flag without ALPHAPIXELS. Texel bytes B=1, G=2, R=3, X=0.
  Bytes x = ddsHeader(1, 1, 0, 1, 0x40, 0, 32, 0xff0000, 0xff00, 0xff, 0);
  for (uint8_t v : {1, 2, 3, 0}) x.push_back(v);
  EXPECT_EQ(loadTextureFromMemory(x, "x.dds")->format(), Format::X8R8G8B8);
}

TEST_F(ImageIO, DdsErrors) {
  // DX10 extended header.
  expectLoadError(ddsHeader(4, 4, 0, 1, 0x4, makeFourCC('D', 'X', '1', '0'), 0, 0, 0, 0, 0),
                  "dx10.dds", "DX10");
  // Truncated mip level: 4x4 A8R8G8B8 with 3 levels needs 64 + 16 + 4 bytes.
  Bytes t = ddsHeader(4, 4, 0, 3, 0x41, 0, 32, 0xff0000, 0xff00, 0xff, 0xff000000);
  t.resize(t.size() + 64 + 10);
  expectLoadError(t, "earth.dds", "truncated: mip level 1 needs 16 bytes, 10 remain");
  // Hostile sizes: refused before any allocation.
  expectLoadError(ddsHeader(0x7fffffff, 0x7fffffff, 0, 1, 0x41, 0, 32, 0xff0000, 0xff00, 0xff,
                            0xff000000),
                  "huge.dds", "exceeds");
  expectLoadError(ddsHeader(16384, 16384, 16384, 1, 0x40, 0, 32, 0xff0000, 0xff00, 0xff, 0,
                            0x200000),
                  "vol.dds", "truncated");
  expectLoadError(ddsHeader(4, 4, 0, 40, 0x41, 0, 32, 0xff0000, 0xff00, 0xff, 0xff000000),
                  "mips.dds", "mip levels");
  expectLoadError(ddsHeader(4, 4, 0, 1, 0x40, 0, 32, 0x1234, 0, 0, 0), "masks.dds",
                  "unsupported pixel format");
  expectLoadError(ddsHeader(4, 4, 0, 1, 0x4, makeFourCC('A', 'T', 'I', '2'), 0, 0, 0, 0, 0),
                  "ati2.dds", "ATI2");
  Bytes cut = ddsHeader(1, 1, 0, 1, 0x40, 0, 32, 0xff0000, 0xff00, 0xff, 0);
  cut.resize(60);
  expectLoadError(cut, "cut.dds", "truncated");
}

// ---- PNM --------------------------------------------------------------------------

TEST_F(ImageIO, PpmPamRoundTrip) {
  auto t = makeTestImage();
  savePNM(*t, path("a.ppm"));
  auto p = loadTexture(path("a.ppm"));
  ASSERT_EQ(p->format(), Format::A8R8G8B8);
  EXPECT_EQ(argbAt(*p, 0, 1), 0xff336699u);  // (0.2, 0.4, 0.6) -> 51, 102, 153, alpha dropped
  EXPECT_EQ(argbAt(*p, 2, 0), 0xff0000ffu);
  saveImage(*t, path("a.pam"));
  auto q = loadTexture(path("a.pam"));
  expectSameData(*t, *q);
  Bytes b = readAll(path("a.ppm"));
  EXPECT_EQ(std::string(b.begin(), b.begin() + 11), "P6\n3 2\n255\n");
}

TEST_F(ImageIO, PgmAndPamHandBuilt) {
  std::string pgm = "P5\n# comment\n2 1\n255\n";
  Bytes b(pgm.begin(), pgm.end());
  b.push_back(0x00), b.push_back(0xC0);
  auto t = loadTextureFromMemory(b, "g.pgm");
  ASSERT_EQ(t->format(), Format::L8);
  EXPECT_EQ(t->data(0, 0)[1], 0xC0);
  std::string pam = "P7\nWIDTH 1\nHEIGHT 1\nDEPTH 2\nMAXVAL 255\nTUPLTYPE GRAYSCALE_ALPHA\nENDHDR\n";
  Bytes c(pam.begin(), pam.end());
  c.push_back(0x40), c.push_back(0x80);
  auto u = loadTextureFromMemory(c, "ga.pam");
  EXPECT_EQ(argbAt(*u, 0, 0), 0x80404040u);  // grey 0x40 replicated, alpha 0x80
  expectLoadError(Bytes(b.begin(), b.end() - 1), "short.pgm", "truncated");
  std::string p16 = "P6\n1 1\n65535\n";
  expectLoadError(Bytes(p16.begin(), p16.end()), "deep.ppm", "maxval");
  std::string huge = "P6\n99999999 99999999\n255\n";
  expectLoadError(Bytes(huge.begin(), huge.end()), "huge.ppm", "exceeds");
  std::string noend = "P7\nWIDTH 1\n";
  expectLoadError(Bytes(noend.begin(), noend.end()), "noend.pam", "ENDHDR");
}

// ---- TGA --------------------------------------------------------------------------

namespace {
Bytes tgaHeader(uint8_t type, uint16_t w, uint16_t h, uint8_t bits, uint8_t desc,
                uint8_t cmType = 0, uint16_t cmLen = 0, uint8_t cmBits = 0) {
  Bytes b = {0, cmType, type, 0, 0};
  put16(b, cmLen);
  b.push_back(cmBits);
  put16(b, 0), put16(b, 0), put16(b, w), put16(b, h);
  b.push_back(bits), b.push_back(desc);
  return b;
}
}  // namespace

TEST_F(ImageIO, TgaUncompressed24BottomUp) {
  // 2x2, origin bottom-left (descriptor bit 5 clear): first row in the file is y = 1.
  Bytes b = tgaHeader(2, 2, 2, 24, 0);
  for (uint8_t v : {0, 0, 255, /**/ 0, 255, 0,     // bottom row: red, green (B, G, R)
                    255, 0, 0, /**/ 10, 20, 30})  // top row: blue, (R=30, G=20, B=10)
    b.push_back(v);
  auto t = loadTextureFromMemory(b, "a.tga");
  ASSERT_EQ(t->format(), Format::A8R8G8B8);
  EXPECT_EQ(argbAt(*t, 0, 1), 0xffff0000u);
  EXPECT_EQ(argbAt(*t, 1, 1), 0xff00ff00u);
  EXPECT_EQ(argbAt(*t, 0, 0), 0xff0000ffu);
  EXPECT_EQ(argbAt(*t, 1, 0), 0xff1e140au);
}

TEST_F(ImageIO, TgaRle32TopDown) {
  // 3x1, top-left origin (bit 5), 8 alpha bits. Run packet of 2 (0x81) + raw packet of 1.
  Bytes b = tgaHeader(10, 3, 1, 32, 0x28);
  for (uint8_t v : {0x81, 1, 2, 3, 4, /**/ 0x00, 5, 6, 7, 8}) b.push_back(v);
  auto t = loadTextureFromMemory(b, "rle.tga");
  EXPECT_EQ(argbAt(*t, 0, 0), 0x04030201u);  // bytes B=1 G=2 R=3 A=4 = A8R8G8B8 order
  EXPECT_EQ(argbAt(*t, 1, 0), 0x04030201u);
  EXPECT_EQ(argbAt(*t, 2, 0), 0x08070605u);
  // Run longer than the image.
  Bytes bad = tgaHeader(10, 3, 1, 32, 0x28);
  for (uint8_t v : {0x85, 1, 2, 3, 4}) bad.push_back(v);
  expectLoadError(bad, "long.tga", "past the end");
  Bytes cut(b.begin(), b.end() - 2);
  expectLoadError(cut, "cut.tga", "truncated");
}

TEST_F(ImageIO, TgaGreyColormapAnd16) {
  Bytes g = tgaHeader(3, 2, 1, 8, 0x20);
  g.push_back(0x11), g.push_back(0xEE);
  auto tg = loadTextureFromMemory(g, "g.tga");
  ASSERT_EQ(tg->format(), Format::L8);
  EXPECT_EQ(tg->data(0, 0)[0], 0x11);
  EXPECT_EQ(tg->data(0, 0)[1], 0xEE);
  // Colour-mapped: 2 entries of 24 bits (B, G, R), indices 1, 0.
  Bytes c = tgaHeader(1, 2, 1, 8, 0x20, 1, 2, 24);
  for (uint8_t v : {255, 0, 0, /**/ 0, 128, 255, /**/ 1, 0}) c.push_back(v);
  auto tc = loadTextureFromMemory(c, "cm.tga");
  EXPECT_EQ(argbAt(*tc, 0, 0), 0xffff8000u);  // entry 1: R=255 G=128 B=0
  EXPECT_EQ(argbAt(*tc, 1, 0), 0xff0000ffu);
  c[c.size() - 2] = 7;
  expectLoadError(c, "cmbad.tga", "outside the colour map");
  // 16-bit A1R5G5B5 with 1 alpha bit: 0x7C00 = red, alpha 0; 0x801F = blue, alpha 1.
  Bytes s = tgaHeader(2, 2, 1, 16, 0x21);
  put16(s, 0x7C00), put16(s, 0x801F);
  auto ts = loadTextureFromMemory(s, "s.tga");
  EXPECT_EQ(argbAt(*ts, 0, 0), 0x00ff0000u);
  EXPECT_EQ(argbAt(*ts, 1, 0), 0xff0000ffu);
  // 65535 x 65535 with no data: size error, no allocation.
  expectLoadError(tgaHeader(2, 65535, 65535, 24, 0), "big.tga", "exceeds");
  expectLoadError(tgaHeader(2, 16000, 16000, 24, 0), "short.tga", "truncated");
}

// ---- BMP --------------------------------------------------------------------------

namespace {
Bytes bmpHeaders(int32_t w, int32_t h, uint16_t bits, uint32_t compression, uint32_t paletteBytes,
                 uint32_t extra = 0, uint32_t colorsUsed = 0) {
  Bytes b = {'B', 'M'};
  put32(b, 0);
  put32(b, 0);
  put32(b, 14 + 40 + extra + paletteBytes);
  put32(b, 40);
  put32(b, uint32_t(w));
  put32(b, uint32_t(h));
  put16(b, 1);
  put16(b, bits);
  put32(b, compression);
  put32(b, 0), put32(b, 0), put32(b, 0);
  put32(b, colorsUsed), put32(b, 0);
  return b;
}
}  // namespace

TEST_F(ImageIO, Bmp24BottomUpPadded) {
  // 2x2, rows 6 bytes padded to 8, bottom row first.
  Bytes b = bmpHeaders(2, 2, 24, 0, 0);
  for (uint8_t v : {0, 0, 255, 0, 255, 0, 0, 0,        // y = 1: red, green, pad
                    255, 0, 0, 10, 20, 30, 0, 0})      // y = 0: blue, (R30 G20 B10), pad
    b.push_back(v);
  auto t = loadTextureFromMemory(b, "a.bmp");
  EXPECT_EQ(argbAt(*t, 0, 1), 0xffff0000u);
  EXPECT_EQ(argbAt(*t, 1, 1), 0xff00ff00u);
  EXPECT_EQ(argbAt(*t, 0, 0), 0xff0000ffu);
  EXPECT_EQ(argbAt(*t, 1, 0), 0xff1e140au);
}

TEST_F(ImageIO, Bmp8BitPaletteTopDown) {
  // Negative height = top-down. Palette entries B, G, R, 0. 3x1 -> 3 bytes + 1 pad.
  Bytes b = bmpHeaders(3, -2, 8, 0, 2 * 4, 0, 2);
  for (uint8_t v : {0, 0, 255, 0, /**/ 255, 255, 255, 0}) b.push_back(v);
  for (uint8_t v : {0, 1, 0, 0, /**/ 1, 1, 1, 0}) b.push_back(v);
  auto t = loadTextureFromMemory(b, "p.bmp");
  EXPECT_EQ(argbAt(*t, 0, 0), 0xffff0000u);
  EXPECT_EQ(argbAt(*t, 1, 0), 0xffffffffu);
  EXPECT_EQ(argbAt(*t, 2, 1), 0xffffffffu);
  b[b.size() - 2] = 5;  // index past the 2-entry palette
  expectLoadError(b, "pbad.bmp", "outside the palette");
}

TEST_F(ImageIO, BmpBitfields) {
  // 16-bit R5G6B5 masks after the 40-byte header; 2x1 = 4 bytes, no padding.
  Bytes b = bmpHeaders(2, 1, 16, 3, 0, 12);
  put32(b, 0xF800), put32(b, 0x07E0), put32(b, 0x001F);
  put16(b, 0xF800), put16(b, 0x0400);  // red; G = 0x0400 >> 5 = 32 -> round(32*255/63) = 130
  auto t = loadTextureFromMemory(b, "bf.bmp");
  EXPECT_EQ(argbAt(*t, 0, 0), 0xffff0000u);
  EXPECT_EQ(argbAt(*t, 1, 0), 0xff008200u);
  // 32-bit BI_RGB: X8R8G8B8, the high byte ignored.
  Bytes x = bmpHeaders(1, 1, 32, 0, 0);
  for (uint8_t v : {1, 2, 3, 9}) x.push_back(v);
  EXPECT_EQ(argbAt(*loadTextureFromMemory(x, "x.bmp"), 0, 0), 0xff030201u);
  // ALPHABITFIELDS (6): four masks, alpha used.
  Bytes a = bmpHeaders(1, 1, 32, 6, 0, 16);
  put32(a, 0xff0000), put32(a, 0xff00), put32(a, 0xff), put32(a, 0xff000000);
  for (uint8_t v : {1, 2, 3, 9}) a.push_back(v);
  EXPECT_EQ(argbAt(*loadTextureFromMemory(a, "al.bmp"), 0, 0), 0x09030201u);
}

TEST_F(ImageIO, BmpErrors) {
  Bytes b = bmpHeaders(2, 2, 24, 0, 0);
  b.resize(b.size() + 10);
  expectLoadError(b, "cut.bmp", "truncated");
  expectLoadError(bmpHeaders(100000, 1, 24, 0, 0), "wide.bmp", "exceeds");
  expectLoadError(bmpHeaders(2, 2, 8, 1, 0), "rle.bmp", "RLE");
  expectLoadError(bmpHeaders(2, 2, 7, 0, 0), "bits.bmp", "bit count");
  expectLoadError(Bytes{'B', 'M', 0}, "tiny.bmp", "truncated");
}

// ---- Detection and files ------------------------------------------------------------

TEST_F(ImageIO, DetectionByContentNotExtension) {
  auto t = makeTestImage();
  savePNG(*t, path("a.png"), true);
  fs::rename(path("a.png"), path("a.dds"));
  auto back = loadTexture(path("a.dds"));  // PNG content despite the extension
  expectSameData(*t, *back);
  expectLoadError(Bytes{1, 2, 3, 4, 5}, "junk.bin", "unknown image format");
  expectLoadError(Bytes{}, "empty.bin", "unknown image format");
}

TEST_F(ImageIO, FileErrors) {
  try {
    loadTexture(path("missing.png"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos);
  }
  auto t = makeTestImage();
  EXPECT_THROW(saveImage(*t, path("a.xyz")), Error);
  EXPECT_THROW(savePNG(*t, path("no/such/dir/a.png")), Error);
}
