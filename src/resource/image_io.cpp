// Image file entry points: format detection by content, PNM reading/writing, and the
// helpers the per-format readers share.
#include "refx/resource/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "resource/image_io_internal.h"

namespace refx {

namespace resource::image {

void Reader::need(size_t n, const std::string& what) const {
  if (n > remaining())
    failFile(name_, "truncated: {} needs {} bytes, {} remain", what, n, remaining());
}
void Reader::seek(size_t pos, const std::string& what) {
  if (pos > bytes_.size())
    failFile(name_, "truncated: {} at offset {} is past the end of the file ({} bytes)", what,
             pos, bytes_.size());
  pos_ = pos;
}
void Reader::skip(size_t n, const std::string& what) {
  need(n, what);
  pos_ += n;
}
uint8_t Reader::u8(const char* what) {
  need(1, what);
  return bytes_[pos_++];
}
uint16_t Reader::u16(const char* what) {
  need(2, what);
  uint16_t v = uint16_t(bytes_[pos_] | (bytes_[pos_ + 1] << 8));
  pos_ += 2;
  return v;
}
uint32_t Reader::u32(const char* what) {
  need(4, what);
  uint32_t v = uint32_t(bytes_[pos_]) | (uint32_t(bytes_[pos_ + 1]) << 8) |
               (uint32_t(bytes_[pos_ + 2]) << 16) | (uint32_t(bytes_[pos_ + 3]) << 24);
  pos_ += 4;
  return v;
}
const uint8_t* Reader::take(size_t n, const std::string& what) {
  need(n, what);
  const uint8_t* p = here();
  pos_ += n;
  return p;
}

void checkImageSize(const std::string& name, int64_t width, int64_t height) {
  if (width <= 0 || height <= 0)
    failFile(name, "invalid image size {}x{}", width, height);
  if (width > kMaxImageDimension || height > kMaxImageDimension)
    failFile(name, "image size {}x{} exceeds the limit of {}x{}", width, height,
             kMaxImageDimension, kMaxImageDimension);
}

TexturePtr makeImageTexture(int width, int height, bool grey) {
  return Texture::create2D(grey ? Format::L8 : Format::A8R8G8B8, width, height, 1);
}

std::vector<uint8_t> toRGBA8(const Texture& tex, int face, int level) {
  int w = tex.width(level), h = tex.height(level), d = tex.depth(level);
  std::vector<uint8_t> out(size_t(w) * h * d * 4);
  const FormatInfo* info = formatInfo(tex.format());
  std::vector<Color4> row(static_cast<size_t>(w));
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < h; ++y) {
      if (info->compressed) {
        for (int x = 0; x < w; ++x) row[x] = tex.texel(face, level, x, y, z);
      } else {
        decodeRow(tex.format(),
                  tex.data(face, level) + size_t(z) * tex.slicePitch(level) +
                      size_t(y) * tex.rowPitch(level),
                  w, row.data());
      }
      uint8_t* o = &out[(size_t(z) * h + y) * w * 4];
      for (int x = 0; x < w; ++x) {
        o[4 * x + 0] = unorm8Safe(row[x].r);
        o[4 * x + 1] = unorm8Safe(row[x].g);
        o[4 * x + 2] = unorm8Safe(row[x].b);
        o[4 * x + 3] = unorm8Safe(row[x].a);
      }
    }
  return out;
}

void writeFile(const std::string& path, std::span<const uint8_t> bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) failFile(path, "cannot open for writing: {}", std::strerror(errno));
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  f.close();
  if (!f) failFile(path, "write failed: {}", std::strerror(errno));
}

// ---- PNM: P5 (PGM), P6 (PPM), P7 (PAM) -------------------------------------------

namespace {

// Reads one whitespace-separated header token of P5/P6, skipping '#' comments.
std::string pnmToken(Reader& r, const char* what) {
  for (;;) {
    if (r.remaining() == 0) failFile(r.name(), "truncated: header ends before the {}", what);
    uint8_t c = *r.here();
    if (c == '#') {
      while (r.remaining() && *r.here() != '\n') r.skip(1, "comment");
    } else if (std::isspace(c)) {
      r.skip(1, "header");
    } else {
      break;
    }
  }
  std::string t;
  while (r.remaining() && !std::isspace(*r.here()) && *r.here() != '#') {
    if (t.size() > 16) failFile(r.name(), "invalid header: {} is too long", what);
    t.push_back(char(r.u8(what)));
  }
  return t;
}

int64_t pnmNumber(const std::string& name, const std::string& t, const char* what) {
  if (t.empty() || t.size() > 9 || !std::all_of(t.begin(), t.end(), ::isdigit))
    failFile(name, "invalid header: expected a number for the {}, found '{}'", what, t);
  return std::stoll(t);
}

TexturePtr readPNMPixels(Reader& r, int64_t w, int64_t h, int channels, int maxval) {
  const std::string& name = r.name();
  checkImageSize(name, w, h);
  if (maxval < 1 || maxval > 255)
    failFile(name, "maxval {} is not supported (only 8-bit samples, maxval 1 to 255)", maxval);
  size_t bytes = size_t(w) * size_t(h) * size_t(channels);
  r.need(bytes, fmt::format("{}x{} pixel data", w, h));
  const uint8_t* p = r.take(bytes, "pixel data");
  bool grey = channels == 1;
  TexturePtr tex = makeImageTexture(int(w), int(h), grey);
  uint8_t* dst = tex->data(0, 0);
  auto scale = [maxval](uint8_t v) {
    v = std::min<uint8_t>(v, uint8_t(maxval));
    return uint8_t((v * 255 + maxval / 2) / maxval);
  };
  size_t n = size_t(w) * size_t(h);
  for (size_t i = 0; i < n; ++i, p += channels) {
    if (grey) {
      dst[i] = scale(p[0]);
      continue;
    }
    uint8_t r8, g8, b8, a8 = 255;
    if (channels <= 2) {
      r8 = g8 = b8 = scale(p[0]);
      if (channels == 2) a8 = scale(p[1]);
    } else {
      r8 = scale(p[0]), g8 = scale(p[1]), b8 = scale(p[2]);
      if (channels == 4) a8 = scale(p[3]);
    }
    uint8_t* q = dst + i * 4;
    q[0] = b8, q[1] = g8, q[2] = r8, q[3] = a8;
  }
  return tex;
}

TexturePtr loadPAM(Reader& r) {
  const std::string& name = r.name();
  r.skip(2, "magic");
  int64_t w = -1, h = -1, depth = -1, maxval = -1;
  std::string tupltype;
  // Line-based header: "KEY value" lines up to ENDHDR.
  for (int lines = 0;; ++lines) {
    if (lines > 1000) failFile(name, "invalid PAM header: no ENDHDR");
    std::string line;
    while (true) {
      if (r.remaining() == 0) failFile(name, "truncated: PAM header has no ENDHDR");
      char c = char(r.u8("header"));
      if (c == '\n') break;
      if (line.size() > 256) failFile(name, "invalid PAM header: line too long");
      line.push_back(c);
    }
    size_t s = line.find_first_not_of(" \t\r");
    if (s == std::string::npos || line[s] == '#') continue;
    line = line.substr(s);
    size_t sp = line.find_first_of(" \t");
    std::string key = line.substr(0, sp);
    std::string value;
    if (sp != std::string::npos) {
      size_t v = line.find_first_not_of(" \t", sp);
      if (v != std::string::npos) value = line.substr(v);
    }
    while (!value.empty() && std::isspace(uint8_t(value.back()))) value.pop_back();
    while (!key.empty() && std::isspace(uint8_t(key.back()))) key.pop_back();
    if (key == "ENDHDR") break;
    if (key == "WIDTH") w = pnmNumber(name, value, "width");
    else if (key == "HEIGHT") h = pnmNumber(name, value, "height");
    else if (key == "DEPTH") depth = pnmNumber(name, value, "depth");
    else if (key == "MAXVAL") maxval = pnmNumber(name, value, "maxval");
    else if (key == "TUPLTYPE") tupltype = value;
    else failFile(name, "invalid PAM header: unknown key '{}'", key);
  }
  if (w < 0 || h < 0 || depth < 0 || maxval < 0)
    failFile(name, "invalid PAM header: WIDTH, HEIGHT, DEPTH and MAXVAL are required");
  if (depth < 1 || depth > 4)
    failFile(name, "PAM depth {} is not supported (1 to 4 channels: {})", depth,
             tupltype.empty() ? "no TUPLTYPE" : tupltype);
  return readPNMPixels(r, w, h, int(depth), int(maxval));
}

}  // namespace

TexturePtr loadPNM(std::span<const uint8_t> bytes, const std::string& name) {
  Reader r(bytes, name);
  if (bytes.size() < 2 || bytes[0] != 'P') failFile(name, "not a PNM file");
  char kind = char(bytes[1]);
  if (kind == '7') return loadPAM(r);
  if (kind != '5' && kind != '6')
    failFile(name, "PNM type P{} is not supported (P5, P6 and P7 are)", kind);
  r.skip(2, "magic");
  int64_t w = pnmNumber(name, pnmToken(r, "width"), "width");
  int64_t h = pnmNumber(name, pnmToken(r, "height"), "height");
  int64_t maxval = pnmNumber(name, pnmToken(r, "maxval"), "maxval");
  // Exactly one whitespace byte separates the header from the samples.
  if (r.remaining() == 0 || !std::isspace(*r.here()))
    failFile(name, "truncated: no whitespace after the maxval");
  r.skip(1, "header");
  if (maxval > 255) failFile(name, "maxval {} is not supported (only 8-bit samples)", maxval);
  return readPNMPixels(r, w, h, kind == '5' ? 1 : 3, int(maxval));
}

}  // namespace resource::image

namespace image = resource::image;

TexturePtr loadTextureFromMemory(std::span<const uint8_t> bytes, const std::string& name) {
  using namespace image;
  auto starts = [&](std::string_view magic) {
    return bytes.size() >= magic.size() && std::memcmp(bytes.data(), magic.data(), magic.size()) == 0;
  };
  if (starts("\x89PNG\r\n\x1a\n")) return loadPNG(bytes, name);
  if (starts("DDS ")) return loadDDS(bytes, name);
  if (starts("BM")) return loadBMP(bytes, name);
  if (starts("P5") || starts("P6") || starts("P7")) return loadPNM(bytes, name);
  if (looksLikeTGA(bytes)) return loadTGA(bytes, name);
  failFile(name, "unknown image format (expected PNG, DDS, BMP, TGA, PPM, PGM or PAM)");
}

TexturePtr loadTexture(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) image::failFile(path, "cannot open: {}", std::strerror(errno));
  f.seekg(0, std::ios::end);
  std::streamoff size = f.tellg();
  if (size < 0) image::failFile(path, "cannot read");
  if (uint64_t(size) > (uint64_t(1) << 32)) image::failFile(path, "file is too large ({} bytes)", size);
  f.seekg(0);
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  f.read(reinterpret_cast<char*>(bytes.data()), size);
  if (!f) image::failFile(path, "read failed");
  return loadTextureFromMemory(bytes, path);
}

void savePNG(const Texture& tex, const std::string& path, bool alpha, int face, int level) {
  image::writeFile(path, image::encodePNG(tex, alpha, face, level, path));
}

void saveDDS(const Texture& tex, const std::string& path) {
  image::writeFile(path, image::encodeDDS(tex, path));
}

void savePNM(const Texture& tex, const std::string& path, bool alpha, int face, int level) {
  if (face < 0 || face >= tex.faceCount() || level < 0 || level >= tex.levelCount())
    image::failFile(path, "texture has no face {} level {}", face, level);
  std::vector<uint8_t> rgba = image::toRGBA8(tex, face, level);
  int w = tex.width(level), h = tex.height(level) * tex.depth(level);
  std::string header = alpha ? fmt::format("P7\nWIDTH {}\nHEIGHT {}\nDEPTH 4\nMAXVAL 255\n"
                                           "TUPLTYPE RGB_ALPHA\nENDHDR\n", w, h)
                             : fmt::format("P6\n{} {}\n255\n", w, h);
  std::vector<uint8_t> out(header.begin(), header.end());
  size_t n = size_t(w) * size_t(h);
  out.reserve(out.size() + n * (alpha ? 4 : 3));
  for (size_t i = 0; i < n; ++i)
    out.insert(out.end(), rgba.begin() + i * 4, rgba.begin() + i * 4 + (alpha ? 4 : 3));
  image::writeFile(path, out);
}

void saveImage(const Texture& tex, const std::string& path, bool alpha) {
  std::string ext;
  if (size_t dot = path.rfind('.'); dot != std::string::npos) ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == "png") return savePNG(tex, path, alpha);
  if (ext == "dds") return saveDDS(tex, path);
  if (ext == "ppm") return savePNM(tex, path, false);
  if (ext == "pam") return savePNM(tex, path, true);
  image::failFile(path, "cannot tell the image format from the extension '.{}' "
                        "(use .png, .dds, .ppm or .pam)", ext);
}

}  // namespace refx
