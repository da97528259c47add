// PNG through libpng. libpng reports errors by longjmp, so every function that calls
// into it with setjmp armed holds only plain C data; C++ objects live in the callers.
#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "resource/image_io_internal.h"

namespace refx::resource::image {

namespace {

struct PngContext {
  const uint8_t* data = nullptr;
  size_t size = 0;
  size_t pos = 0;
  char message[256] = {};
  // Writing: output grows here (plain realloc'd buffer, freed by the caller).
  uint8_t* out = nullptr;
  size_t outSize = 0, outCap = 0;
  bool outOfMemory = false;
};

extern "C" void pngError(png_structp png, png_const_charp msg) {
  auto* ctx = static_cast<PngContext*>(png_get_error_ptr(png));
  std::snprintf(ctx->message, sizeof ctx->message, "%s", msg ? msg : "unknown error");
  png_longjmp(png, 1);
}

extern "C" void pngWarning(png_structp, png_const_charp) {}

extern "C" void pngRead(png_structp png, png_bytep dst, png_size_t n) {
  auto* ctx = static_cast<PngContext*>(png_get_io_ptr(png));
  if (n > ctx->size - ctx->pos) png_error(png, "truncated: the file ends inside a chunk");
  std::memcpy(dst, ctx->data + ctx->pos, n);
  ctx->pos += n;
}

extern "C" void pngWrite(png_structp png, png_bytep src, png_size_t n) {
  auto* ctx = static_cast<PngContext*>(png_get_io_ptr(png));
  if (n > ctx->outCap - ctx->outSize) {
    size_t cap = std::max(ctx->outCap * 2, ctx->outSize + n + 4096);
    auto* p = static_cast<uint8_t*>(std::realloc(ctx->out, cap));
    if (!p) {
      ctx->outOfMemory = true;
      png_error(png, "out of memory");
    }
    ctx->out = p, ctx->outCap = cap;
  }
  std::memcpy(ctx->out + ctx->outSize, src, n);
  ctx->outSize += n;
}

extern "C" void pngFlush(png_structp) {}

struct PngHeader {
  png_uint_32 width, height;
  int bitDepth, colorType, interlace;
  bool hasTrns;
};

// Reads the header and sets up the transforms to 8-bit grey or BGRA. False on error.
bool readHeader(png_structp png, png_infop info, PngHeader* h, bool* grey) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_user_limits(png, kMaxImageDimension, kMaxImageDimension);
  png_read_info(png, info);
  png_get_IHDR(png, info, &h->width, &h->height, &h->bitDepth, &h->colorType, &h->interlace,
               nullptr, nullptr);
  h->hasTrns = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
  *grey = (h->colorType == PNG_COLOR_TYPE_GRAY) && !h->hasTrns;
  if (h->bitDepth == 16) png_set_scale_16(png);  // round to 8 bits
  if (h->colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (h->colorType == PNG_COLOR_TYPE_GRAY && h->bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (h->hasTrns) png_set_tRNS_to_alpha(png);
  if (!*grey) {
    if (h->colorType == PNG_COLOR_TYPE_GRAY || h->colorType == PNG_COLOR_TYPE_GRAY_ALPHA)
      png_set_gray_to_rgb(png);
    png_set_bgr(png);  // memory order B, G, R, A = A8R8G8B8
    png_set_filler(png, 0xff, PNG_FILLER_AFTER);  // opaque alpha where there is none
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != size_t(h->width) * (*grey ? 1 : 4))
    png_error(png, "unexpected row size after conversion");
  return true;
}

bool readRows(png_structp png, png_infop info, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

bool writeImage(png_structp png, png_infop info, png_uint_32 w, png_uint_32 h, bool alpha,
                png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, png_get_io_ptr(png), pngWrite, pngFlush);
  png_set_IHDR(png, info, w, h, 8, alpha ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

struct ReadGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~ReadGuard() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

struct WriteGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  PngContext* ctx = nullptr;
  ~WriteGuard() {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    std::free(ctx->out);
  }
};

}  // namespace

TexturePtr loadPNG(std::span<const uint8_t> bytes, const std::string& name) {
  PngContext ctx;
  ctx.data = bytes.data();
  ctx.size = bytes.size();
  ReadGuard g;
  g.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, pngError, pngWarning);
  if (!g.png) failFile(name, "cannot initialise the PNG reader");
  g.info = png_create_info_struct(g.png);
  if (!g.info) failFile(name, "cannot initialise the PNG reader");
  png_set_read_fn(g.png, &ctx, pngRead);

  PngHeader h{};
  bool grey = false;
  if (!readHeader(g.png, g.info, &h, &grey)) failFile(name, "invalid PNG: {}", ctx.message);
  checkImageSize(name, h.width, h.height);
  // Deflate expands at most about 1032:1; a header claiming more pixels than the
  // remaining data could hold is corrupt (and must not make us allocate gigabytes).
  uint64_t rawBytes = uint64_t(h.height) * ((uint64_t(h.width) + 7) / 8 + 1);  // >= 1 bit/pixel
  if (rawBytes > uint64_t(bytes.size()) * 1040 + 1024)
    failFile(name, "truncated: a {}x{} image cannot fit in {} bytes", h.width, h.height,
             bytes.size());

  TexturePtr tex = makeImageTexture(int(h.width), int(h.height), grey);
  std::vector<png_bytep> rows(h.height);
  size_t pitch = tex->rowPitch(0);
  for (png_uint_32 y = 0; y < h.height; ++y) rows[y] = tex->data(0, 0) + y * pitch;
  if (!readRows(g.png, g.info, rows.data())) failFile(name, "invalid PNG: {}", ctx.message);
  tex->markDirty();
  return tex;
}

std::vector<uint8_t> encodePNG(const Texture& tex, bool alpha, int face, int level,
                               const std::string& name) {
  if (face < 0 || face >= tex.faceCount() || level < 0 || level >= tex.levelCount())
    failFile(name, "texture has no face {} level {}", face, level);
  std::vector<uint8_t> rgba = toRGBA8(tex, face, level);
  png_uint_32 w = png_uint_32(tex.width(level));
  png_uint_32 h = png_uint_32(tex.height(level) * tex.depth(level));  // volume slices stacked
  if (!alpha) {  // pack to RGB in place
    size_t n = size_t(w) * h;
    for (size_t i = 0; i < n; ++i) std::memmove(&rgba[i * 3], &rgba[i * 4], 3);
  }
  std::vector<png_bytep> rows(h);
  for (png_uint_32 y = 0; y < h; ++y) rows[y] = &rgba[size_t(y) * w * (alpha ? 4 : 3)];

  PngContext ctx;
  WriteGuard g;
  g.ctx = &ctx;
  g.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, pngError, pngWarning);
  if (!g.png) failFile(name, "cannot initialise the PNG writer");
  g.info = png_create_info_struct(g.png);
  if (!g.info) failFile(name, "cannot initialise the PNG writer");
  png_set_write_fn(g.png, &ctx, pngWrite, pngFlush);
  if (!writeImage(g.png, g.info, w, h, alpha, rows.data()))
    failFile(name, "cannot write PNG: {}", ctx.message);
  return std::vector<uint8_t>(ctx.out, ctx.out + ctx.outSize);
}

}  // namespace refx::resource::image
