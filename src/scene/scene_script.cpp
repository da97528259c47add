// Scene script parser: text -> typed commands with every name and value resolved.
#include "refx/scene/scene_script.h"
#include "refx/core/text.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/d3d9types.h"

namespace refx::scene {

namespace {

constexpr int kMaxTargetSize = 8192;
constexpr int kMaxTextureSize = 16384;  // Texture's own limit; caps are checked when run
constexpr int kMaxLights = 8;

struct Token {
  std::string_view text;
  int col = 0;  // 1-based
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string lower(std::string_view s) { return toLower(s); }

std::vector<Token> tokenize(std::string_view code) {
  std::vector<Token> out;
  size_t i = 0;
  while (i < code.size()) {
    while (i < code.size() && isBlank(code[i])) ++i;
    if (i >= code.size()) break;
    size_t start = i;
    while (i < code.size() && !isBlank(code[i])) ++i;
    out.push_back({code.substr(start, i - start), int(start) + 1});
  }
  return out;
}

std::optional<float> toFloat(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty() || s.front() == '+') return std::nullopt;
  float v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// Decimal or 0x hexadecimal, up to 64 bits.
std::optional<uint64_t> toUint(std::string_view s) { return parseUnsigned(s); }

std::optional<int64_t> toInt(std::string_view s) {
  bool neg = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    neg = s.front() == '-';
    s.remove_prefix(1);
  }
  auto u = toUint(s);
  if (!u || *u > uint64_t(1) << 40) return std::nullopt;
  return neg ? -int64_t(*u) : int64_t(*u);
}

// 0xAARRGGBB, or r,g,b[,a] floats (a defaults to 1).
std::optional<Color4> toColor(std::string_view s) {
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    if (s.size() > 10) return std::nullopt;
    auto v = toUint(s);
    if (!v) return std::nullopt;
    return colorFromD3D(D3DColor(*v));
  }
  float c[4] = {0, 0, 0, 1};
  int n = 0;
  while (true) {
    size_t comma = s.find(',');
    if (n == 4) return std::nullopt;
    auto v = toFloat(s.substr(0, comma));
    if (!v) return std::nullopt;
    c[n++] = *v;
    if (comma == std::string_view::npos) break;
    s.remove_prefix(comma + 1);
  }
  if (n < 3) return std::nullopt;
  return Color4{c[0], c[1], c[2], c[3]};
}

int fullChain(int w, int h, int d) {
  int m = std::max({w, h, d}), n = 1;
  while (m > 1) m >>= 1, ++n;
  return n;
}

// Names a D3D enumeration accepts, for "expected one of" messages.
std::string enumNames(d3d::EnumKind kind) {
  std::string out;
  auto add = [&](uint32_t v) {
    std::string_view n = d3d::enumName(kind, v);
    if (n.empty() || out.find(std::string(n) + ",") != std::string::npos) return;
    if (!out.empty()) out += ", ";
    out += n;
  };
  for (uint32_t v = 0; v <= 300; ++v) add(v);
  for (uint32_t v = 0x10000; v <= 0x40000; v += 0x10000) add(v);
  return out;
}

// fvf element order in a vertex: position, normal, psize, diffuse, specular, texcoords.
// `decl USAGE[N]:TYPE ...`: a vertex declaration on stream 0, elements packed in the
// order given; `v` lines give each element's values in that order.
struct DeclLayout {
  VertexDeclaration declaration;
  std::vector<uint8_t> types;  // d3d::DECLTYPE_* of each element
  std::string text;
  uint32_t stride = 0;
  size_t valueCount = 0;
};

struct FvfLayout {
  int positionFloats = 4;  // xyz 3, xyzrhw 4, xyzw 4, xyzbN 3 + N (betas included)
  uint32_t positionCode = d3d::FVF_XYZRHW;
  uint32_t lastBeta = 0;  // D3DFVF_LASTBETA_UBYTE4 / _D3DCOLOR: the last beta is a DWORD
  bool normal = false, psize = false, diffuse = true, specular = false;
  std::vector<int> texDims{2};
  std::string text = "xyzrhw diffuse tex 2";

  uint32_t code() const {
    uint32_t c = positionCode | lastBeta;
    if (normal) c |= d3d::FVF_NORMAL;
    if (psize) c |= d3d::FVF_PSIZE;
    if (diffuse) c |= d3d::FVF_DIFFUSE;
    if (specular) c |= d3d::FVF_SPECULAR;
    c |= uint32_t(texDims.size()) << d3d::FVF_TEXCOUNT_SHIFT;
    for (size_t i = 0; i < texDims.size(); ++i) c |= d3d::fvfTexCoordSize(texDims[i], int(i));
    return c;
  }
  uint32_t stride() const {
    uint32_t s = 4 * positionFloats + (normal ? 12 : 0) + (psize ? 4 : 0) + (diffuse ? 4 : 0) +
                 (specular ? 4 : 0);
    for (int d : texDims) s += 4 * d;
    return s;
  }
  size_t valueCount() const {
    size_t n = positionFloats + (normal ? 3 : 0) + (psize ? 1 : 0) + (diffuse ? 1 : 0) +
               (specular ? 1 : 0);
    for (int d : texDims) n += d;
    return n;
  }
};

class Parser {
 public:
  Parser(std::string_view text, const std::string& file) : text_(text) { script_.file = file; }

  SceneScript parse() {
    size_t pos = 0;
    int lineNo = 0;
    while (pos <= text_.size()) {
      std::string_view raw = nextLine(pos);
      ++lineNo;
      line_ = lineNo;
      size_t hash = raw.find('#');
      std::string_view code = raw.substr(0, hash);
      if (hash != std::string_view::npos) comment(raw.substr(hash + 1), int(hash) + 2);
      tok_ = tokenize(code);
      if (tok_.empty()) continue;
      std::string name = lower(tok_[0].text);
      cmd_ = name;
      if ((name == "vs" || name == "ps") && tok_.size() >= 2 && tok_[1].text.starts_with("<<")) {
        heredoc(name == "ps", pos, lineNo);
        line_ = lineNo;
      } else {
        dispatch(name);
      }
      first_ = false;
    }
    if (vertices_.size() || indices_.size()) {
      errIn("v", pendingLine_, 0, "vertices are never drawn (add a draw command)");
    }
    for (const Expectation& e : script_.expectations) {
      int w = script_.width, h = script_.height;
      if (e.target > 0) {
        const auto& size = targetSizes_[size_t(e.target)];
        if (!size)
          throw Error(SourceLocation{script_.file, e.line, 0},
                      fmt::format("expect@{}: no `rendertarget {} W H FORMAT` command creates "
                                  "render target {}", e.target, e.target, e.target));
        w = size->first, h = size->second;
      }
      if (e.x >= w || e.y >= h)
        throw Error(SourceLocation{script_.file, e.line, 0},
                    fmt::format("expect: pixel {},{} is outside the {}x{} render target", e.x,
                                e.y, w, h));
    }
    return std::move(script_);
  }

 private:
  using Handler = void (Parser::*)();
  struct CommandEntry {
    std::string_view name;
    Handler handler;
  };

  std::string_view nextLine(size_t& pos) {
    size_t end = text_.find('\n', pos);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view l = text_.substr(pos, end - pos);
    pos = end + 1;
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    return l;
  }

  [[noreturn]] void err(int col, const std::string& msg) const { errIn(cmd_, line_, col, msg); }
  [[noreturn]] void errIn(std::string_view cmd, int line, int col, const std::string& msg) const {
    throw Error(SourceLocation{script_.file, line, col}, fmt::format("{}: {}", cmd, msg));
  }
  [[noreturn]] void errAt(size_t i, const std::string& msg) const { err(tok_[i].col, msg); }

  // Values after the command word.
  size_t argc() const { return tok_.size() - 1; }
  std::string_view arg(size_t i) const { return tok_[i].text; }

  void need(size_t min, size_t max, std::string_view usage) const {
    size_t n = argc();
    if (n >= min && n <= max) return;
    int col = n > max ? tok_[max + 1].col : 0;
    err(col, fmt::format("expected `{} {}`, got {} value{}", cmd_, usage, n, n == 1 ? "" : "s"));
  }

  float number(size_t i, std::string_view what) const {
    auto v = toFloat(arg(i));
    if (!v) errAt(i, fmt::format("expected a number for {}, got '{}'", what, arg(i)));
    return *v;
  }
  int integer(size_t i, std::string_view what, int64_t min, int64_t max) const {
    auto v = toInt(arg(i));
    if (!v) errAt(i, fmt::format("expected an integer for {}, got '{}'", what, arg(i)));
    if (*v < min || *v > max)
      errAt(i, fmt::format("{} {} is out of range ({} to {})", what, *v, min, max));
    return int(*v);
  }
  uint32_t uint32(size_t i, std::string_view what) const {
    auto v = toUint(arg(i));
    if (!v || *v > 0xffffffffull)
      errAt(i, fmt::format("expected an unsigned 32-bit number for {}, got '{}'", what, arg(i)));
    return uint32_t(*v);
  }
  Color4 color(size_t i, std::string_view what) const {
    auto c = toColor(arg(i));
    if (!c)
      errAt(i, fmt::format("expected a color (0xAARRGGBB or r,g,b[,a]) for {}, got '{}'", what,
                           arg(i)));
    return *c;
  }
  D3DColor d3dColor(size_t i, std::string_view what) const {
    auto s = arg(i);
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X') && s.size() <= 10)
      if (auto v = toUint(s)) return D3DColor(*v);
    return colorToD3D(color(i, what));
  }

  void add(Action action) {
    script_.commands.push_back(Command{line_, cmd_, std::move(action)});
  }

  // ---- comments: `# expect X Y r g b a [tolerance]`, `# expect@N ...` for target N
  void comment(std::string_view text, int col) {
    auto t = tokenize(text);
    if (t.empty() || !(t[0].text == "expect" || t[0].text.starts_with("expect@"))) return;
    for (Token& k : t) k.col += col - 1;
    Expectation e;
    e.line = line_;
    if (t[0].text != "expect") {
      const auto n = toInt(t[0].text.substr(7));
      if (!n || *n < 1 || *n > 3)
        errIn("expect", line_, t[0].col,
              fmt::format("expected expect@1, expect@2 or expect@3 (a render target), got '{}'",
                          t[0].text));
      e.target = int(*n);
    }
    if (t.size() != 7 && t.size() != 8)
      errIn("expect", line_, t[0].col,
            fmt::format("expected `# {} X Y r g b a [tolerance]`, got {} values", t[0].text,
                                t.size() - 1));
    auto val = [&](size_t i, std::string_view what, int max) {
      auto v = toInt(t[i].text);
      if (!v || *v < 0 || *v > max)
        errIn("expect", line_, t[i].col,
              fmt::format("expected {} from 0 to {}, got '{}'", what, max, t[i].text));
      return int(*v);
    };
    e.x = val(1, "X", kMaxTargetSize);
    e.y = val(2, "Y", kMaxTargetSize);
    for (int c = 0; c < 4; ++c) e.rgba[c] = val(3 + c, "a 0-255 channel value", 255);
    if (t.size() == 8) e.tolerance = val(7, "tolerance", 255);
    script_.expectations.push_back(e);
  }

  void dispatch(const std::string& name) {
    static constexpr CommandEntry kCommands[] = {
        {"size", &Parser::size},         {"clear", &Parser::clear},
        {"rs", &Parser::renderState},    {"tss", &Parser::stageState},
        {"samp", &Parser::samplerState}, {"texture", &Parser::texture},
        {"settex", &Parser::setTexture}, {"vs", &Parser::shader},
        {"ps", &Parser::shader},         {"vsconst", &Parser::constants},
        {"vsconsti", &Parser::constants}, {"vsconstb", &Parser::constants},
        {"psconst", &Parser::constants}, {"psconsti", &Parser::constants},
        {"psconstb", &Parser::constants}, {"fvf", &Parser::fvf},
        {"v", &Parser::vertex},          {"i", &Parser::index},
        {"draw", &Parser::draw},         {"transform", &Parser::transform},
        {"material", &Parser::material}, {"light", &Parser::light},
        {"viewport", &Parser::viewport}, {"scissor", &Parser::scissor},
        {"rendertarget", &Parser::renderTarget},
        {"clipplane", &Parser::clipPlane}, {"decl", &Parser::decl},
    };
    for (const CommandEntry& c : kCommands) {
      if (c.name == name) {
        (this->*c.handler)();
        return;
      }
    }
    throw Error(SourceLocation{script_.file, line_, tok_[0].col},
                fmt::format("unknown command '{}' (expected size, clear, rs, tss, samp, "
                            "texture, settex, vs, ps, vsconst, psconst, fvf, v, i, draw, "
                            "transform, material, light, viewport, scissor, rendertarget, clipplane or decl)",
                            tok_[0].text));
  }

  // A render target format: A8R8G8B8, X8R8G8B8 or A32B32G32R32F.
  Format targetFormat(size_t i) const {
    auto f = parseFormat(arg(i));
    if (!f || (*f != Format::A8R8G8B8 && *f != Format::X8R8G8B8 && *f != Format::A32B32G32R32F))
      errAt(i, fmt::format("render target format must be A8R8G8B8, X8R8G8B8 or A32B32G32R32F, "
                           "got '{}'", arg(i)));
    return *f;
  }

  // ---- size W H [A8R8G8B8|X8R8G8B8|A32B32G32R32F]
  void size() {
    need(2, 3, "W H [A8R8G8B8|X8R8G8B8|A32B32G32R32F]");
    if (!first_ || sizeSeen_)
      err(tok_[0].col, "must be the first command (it creates the render target)");
    sizeSeen_ = true;
    script_.width = integer(1, "width", 1, kMaxTargetSize);
    script_.height = integer(2, "height", 1, kMaxTargetSize);
    if (argc() == 3) script_.targetFormat = targetFormat(3);
  }

  // ---- rendertarget N W H FORMAT | rendertarget N none
  void renderTarget() {
    if (argc() != 2) need(4, 4, "N W H FORMAT` or `rendertarget N none");
    SetRenderTarget r;
    r.index = integer(1, "the render target index (0 is `size`)", 1, 3);
    if (argc() == 2) {
      if (lower(arg(2)) != "none")
        errAt(2, fmt::format("expected `none` or `W H FORMAT` after the index, got '{}'", arg(2)));
      r.none = true;
      add(r);
      return;
    }
    r.width = integer(2, "width", 1, kMaxTargetSize);
    r.height = integer(3, "height", 1, kMaxTargetSize);
    r.format = targetFormat(4);
    targetSizes_[size_t(r.index)] = std::pair{r.width, r.height};
    add(r);
  }

  // ---- clear COLOR [Z [STENCIL]]
  void clear() {
    need(1, 3, "COLOR [Z [STENCIL]]");
    Clear c;
    c.color = d3dColor(1, "the clear color");
    if (argc() >= 2) {
      c.z = number(2, "Z");
      if (c.z < 0 || c.z > 1) errAt(2, fmt::format("Z {} is out of range (0 to 1)", c.z));
    }
    if (argc() >= 3) c.stencil = uint32_t(integer(3, "stencil", 0, 255));
    add(c);
  }

  // A state value as its StateValueInfo says; enum values may also be given as numbers.
  uint32_t stateValue(size_t i, d3d::StateValueInfo info, std::string_view stateName) const {
    std::string_view s = arg(i);
    std::string what = fmt::format("{}", stateName);
    switch (info.kind) {
      case d3d::ValueKind::Float: return floatBits(number(i, what));
      case d3d::ValueKind::Color: return d3dColor(i, what);
      case d3d::ValueKind::Uint:
        if (info.enumKind == d3d::EnumKind::TexCoordIndexFlags)
          if (auto v = d3d::parseEnum(info.enumKind, s)) return *v;
        if (auto v = toUint(s); v && *v <= 0xffffffffull) return uint32_t(*v);
        if (info.enumKind == d3d::EnumKind::TexCoordIndexFlags)
          errAt(i, fmt::format("expected N or N|{} for {}, got '{}'",
                               "CAMERASPACENORMAL|CAMERASPACEPOSITION|"
                               "CAMERASPACEREFLECTIONVECTOR|SPHEREMAP",
                               stateName, s));
        return uint32(i, what);
      case d3d::ValueKind::Enum:
      case d3d::ValueKind::Flags: {
        if (auto v = d3d::parseEnum(info.enumKind, s)) return *v;
        if (auto v = toUint(s); v && *v <= 0xffffffffull) return uint32_t(*v);
        const char* sep = info.kind == d3d::ValueKind::Flags ? " (combined with |)" : "";
        errAt(i, fmt::format("unknown value '{}' for {} (expected {}{})", s, stateName,
                             enumNames(info.enumKind), sep));
      }
    }
    errAt(i, "unknown value");
  }

  // ---- rs NAME VALUE
  void renderState() {
    need(2, 2, "NAME VALUE");
    auto st = d3d::parseEnum(d3d::EnumKind::RenderState, arg(1));
    if (!st) errAt(1, fmt::format("unknown render state '{}'", arg(1)));
    std::string_view name = d3d::enumName(d3d::EnumKind::RenderState, *st);
    add(SetRenderState{d3d::RenderState(*st), stateValue(2, d3d::renderStateValue(*st), name)});
  }

  // ---- tss STAGE NAME VALUE
  void stageState() {
    need(3, 3, "STAGE NAME VALUE");
    int stage = integer(1, "stage", 0, d3d::kMaxTextureStages - 1);
    auto st = d3d::parseEnum(d3d::EnumKind::TextureStageState, arg(2));
    if (!st) errAt(2, fmt::format("unknown texture stage state '{}'", arg(2)));
    std::string_view name = d3d::enumName(d3d::EnumKind::TextureStageState, *st);
    add(SetStageState{stage, d3d::TextureStageState(*st),
                      stateValue(3, d3d::textureStageStateValue(*st), name)});
  }

  // SAMPLER: 0-15 or vs0-vs3 (D3DVERTEXTEXTURESAMPLER0-3).
  int sampler(size_t i) const {
    std::string_view s = arg(i);
    if (s.size() == 3 && (s[0] == 'v' || s[0] == 'V') && (s[1] == 's' || s[1] == 'S') &&
        s[2] >= '0' && s[2] <= '3')
      return d3d::kVertexSampler0 + (s[2] - '0');
    auto v = toInt(s);
    if (!v || *v < 0 || *v >= d3d::kMaxPixelSamplers)
      errAt(i, fmt::format("expected a sampler 0-15 or vs0-vs3, got '{}'", s));
    return int(*v);
  }

  // ---- samp SAMPLER NAME VALUE
  void samplerState() {
    need(3, 3, "SAMPLER NAME VALUE");
    int s = sampler(1);
    auto st = d3d::parseEnum(d3d::EnumKind::SamplerState, arg(2));
    if (!st) errAt(2, fmt::format("unknown sampler state '{}'", arg(2)));
    std::string_view name = d3d::enumName(d3d::EnumKind::SamplerState, *st);
    add(SetSamplerState{s, d3d::SamplerStateType(*st),
                        stateValue(3, d3d::samplerStateValue(*st), name)});
  }

  // ---- texture NAME 2d|cube|volume FMT dims [levels N] GEN ARGS...
  void texture() {
    if (argc() < 2) need(5, 1000, "NAME 2d|cube|volume FMT W H [levels N] GEN...");
    TextureDef t;
    t.name = std::string(arg(1));
    if (equalsNoCase(t.name, "none")) errAt(1, "'none' cannot name a texture (settex uses it)");
    std::string type = lower(arg(2));
    int dims = 0;
    const char* usage = "";
    if (type == "2d") {
      t.type = TextureType::Texture2D, dims = 2, usage = "NAME 2d FMT W H [levels N] GEN...";
    } else if (type == "cube") {
      t.type = TextureType::Cube, dims = 1, usage = "NAME cube FMT SIZE [levels N] GEN...";
    } else if (type == "volume") {
      t.type = TextureType::Volume, dims = 3, usage = "NAME volume FMT W H D [levels N] GEN...";
    } else {
      errAt(2, fmt::format("expected a texture type 2d, cube or volume, got '{}'", arg(2)));
    }
    size_t genAt = 4 + size_t(dims);  // index of GEN (or `levels`)
    if (argc() < genAt) need(genAt, 1000, usage);
    auto f = parseFormat(arg(3));
    if (!f) errAt(3, fmt::format("unknown format '{}'", arg(3)));
    const FormatInfo* info = formatInfo(*f);
    if (!info || info->compressed || info->isDepth)
      errAt(3, fmt::format("format {} cannot be generated (expected an uncompressed color "
                           "format such as A8R8G8B8, V8U8 or A16B16G16R16F)",
                           arg(3)));
    t.format = *f;
    t.width = integer(4, "width", 1, kMaxTextureSize);
    t.height = dims == 1 ? t.width : integer(5, "height", 1, kMaxTextureSize);
    t.depth = dims == 3 ? integer(6, "depth", 1, kMaxTextureSize) : 1;
    int chain = fullChain(t.width, t.height, t.depth);
    if (argc() >= genAt && lower(arg(genAt)) == "levels") {
      if (argc() < genAt + 1) err(0, "expected a level count after `levels`");
      t.levels = integer(genAt + 1, "levels", 0, chain);
      genAt += 2;
    }
    if (argc() < genAt) need(genAt, 1000, usage);
    int levelCount = t.levels == 0 ? chain : t.levels;
    size_t first = genAt + 1;  // first generator argument
    size_t nargs = argc() - genAt;
    std::string gen = lower(arg(genAt));
    auto count = [&](size_t n, std::string_view genUsage) {
      if (nargs != n)
        err(nargs > n ? tok_[first + n].col : 0,
            fmt::format("expected `{}`, got {} value{}", genUsage, nargs,
                        nargs == 1 ? "" : "s"));
    };
    auto cubeOnly = [&] {
      if (t.type != TextureType::Cube)
        errAt(genAt, fmt::format("generator {} needs a cube texture", gen));
    };
    auto colors = [&](size_t n) {
      for (size_t k = 0; k < n; ++k) t.colors.push_back(color(first + k, "a texel color"));
    };
    if (gen == "solid") {
      t.generator = Generator::Solid, count(1, "solid COLOR"), colors(1);
    } else if (gen == "checker") {
      t.generator = Generator::Checker, count(3, "checker C0 C1 CELL"), colors(2);
      t.cell = integer(first + 2, "checker CELL", 1, kMaxTextureSize);
    } else if (gen == "gradient") {
      t.generator = Generator::Gradient, count(4, "gradient TL TR BL BR"), colors(4);
    } else if (gen == "coords") {
      t.generator = Generator::Coords, count(0, "coords");
    } else if (gen == "pixels") {
      t.generator = Generator::Pixels;
      uint64_t n = uint64_t(t.width) * t.height * t.depth * (t.type == TextureType::Cube ? 6 : 1);
      if (nargs != n)
        err(nargs > n ? tok_[first + n].col : 0,
            fmt::format("pixels: expected {} colors ({}x{}x{}{}), got {}", n, t.width, t.height,
                        t.depth, t.type == TextureType::Cube ? " x 6 faces" : "", nargs));
      colors(size_t(n));
    } else if (gen == "noise") {
      t.generator = Generator::Noise, count(1, "noise SEED");
      auto v = toUint(arg(first));
      if (!v) errAt(first, fmt::format("expected an unsigned seed, got '{}'", arg(first)));
      t.seed = *v;
    } else if (gen == "dome") {
      t.generator = Generator::Dome, count(0, "dome");
    } else if (gen == "normalize") {
      t.generator = Generator::Normalize, cubeOnly(), count(0, "normalize");
    } else if (gen == "faces") {
      t.generator = Generator::Faces, cubeOnly(), count(6, "faces C+X C-X C+Y C-Y C+Z C-Z");
      colors(6);
    } else if (gen == "mipcolors") {
      t.generator = Generator::MipColors;
      if (nargs != size_t(levelCount))
        err(nargs > size_t(levelCount) ? tok_[first + levelCount].col : 0,
            fmt::format("mipcolors: the texture has {} level{}, got {} color{}", levelCount,
                        levelCount == 1 ? "" : "s", nargs, nargs == 1 ? "" : "s"));
      colors(nargs);
    } else if (gen == "file") {
      t.generator = Generator::File, count(1, "file PATH");
      t.path = std::string(arg(first));
    } else {
      errAt(genAt, fmt::format("unknown generator '{}' (expected solid, checker, gradient, "
                               "coords, pixels, noise, dome, normalize, faces, mipcolors or "
                               "file)",
                               arg(genAt)));
    }
    textures_.insert(t.name);
    add(std::move(t));
  }

  // ---- settex SAMPLER NAME|none
  void setTexture() {
    need(2, 2, "SAMPLER NAME|none");
    SetTexture s{sampler(1), std::string(arg(2))};
    if (equalsNoCase(s.name, "none")) {
      s.name.clear();
    } else if (!textures_.count(s.name)) {
      errAt(2, fmt::format("unknown texture '{}' (define it with a texture command first)",
                           s.name));
    }
    add(std::move(s));
  }

  // ---- vs/ps file PATH | none   (heredoc blocks go through heredoc())
  void shader() {
    Shader s;
    s.pixel = lower(tok_[0].text) == "ps";
    std::string usage = "<<TAG ... TAG`, `" + cmd_ + " file PATH` or `" + cmd_ + " none";
    if (argc() == 1 && equalsNoCase(arg(1), "none")) {
      s.source = Shader::Source::None;
    } else if (argc() == 2 && equalsNoCase(arg(1), "file")) {
      s.source = Shader::Source::File;
      s.path = std::string(arg(2));
    } else {
      err(argc() ? tok_[1].col : 0, fmt::format("expected `{} {}`", cmd_, usage));
    }
    add(std::move(s));
  }

  void heredoc(bool pixel, size_t& pos, int& lineNo) {
    std::string_view tag = tok_[1].text.substr(2);
    size_t extra = 2;
    if (tag.empty() && tok_.size() >= 3) tag = tok_[2].text, extra = 3;
    if (tag.empty()) err(tok_[1].col, "expected an end marker after << (e.g. <<END)");
    if (tok_.size() > extra) err(tok_[extra].col, "unexpected text after the end marker");
    Shader s;
    s.pixel = pixel;
    s.source = Shader::Source::Inline;
    s.textLine = line_ + 1;
    int startLine = line_;
    bool closed = false;
    while (pos <= text_.size()) {
      std::string_view raw = nextLine(pos);
      ++lineNo;
      if (trim(raw) == tag) {
        closed = true;
        break;
      }
      s.text.append(raw);
      s.text.push_back('\n');
    }
    if (!closed) {
      line_ = startLine;
      err(tok_[1].col, fmt::format("no closing '{}' line for this shader block", tag));
    }
    line_ = startLine;
    add(std::move(s));
  }

  // ---- vsconst/vsconsti/vsconstb/psconst/psconsti/psconstb REG values...
  void constants() {
    std::string name = lower(tok_[0].text);
    SetConstants c;
    c.pixel = name[0] == 'p';
    char suffix = name.back();
    c.type = suffix == 'i' ? SetConstants::Type::Int
             : suffix == 'b' ? SetConstants::Type::Bool
                             : SetConstants::Type::Float;
    char prefix = suffix == 'i' ? 'i' : suffix == 'b' ? 'b' : 'c';
    int regs = c.type == SetConstants::Type::Float ? (c.pixel ? 224 : 256) : 16;
    bool isBool = c.type == SetConstants::Type::Bool;
    need(2, 100000, isBool ? "REG b [b...]" : "REG x y z w [x y z w...]");
    std::string_view r = arg(1);
    if (!r.empty() && std::tolower(static_cast<unsigned char>(r[0])) == prefix) r.remove_prefix(1);
    auto reg = toInt(r);
    if (!reg || *reg < 0 || *reg >= regs)
      errAt(1, fmt::format("expected a register {}0-{}{} (or its number), got '{}'", prefix,
                           prefix, regs - 1, arg(1)));
    c.reg = int(*reg);
    size_t n = argc() - 1;
    if (!isBool && n % 4 != 0)
      err(0, fmt::format("expected values in groups of 4 (x y z w per register), got {}", n));
    size_t count = isBool ? n : n / 4;
    if (c.reg + count > size_t(regs))
      err(0, fmt::format("{} register{} from {}{} run past the last register {}{}", count,
                         count == 1 ? "" : "s", prefix, c.reg, prefix, regs - 1));
    for (size_t k = 0; k < n; ++k) {
      size_t i = 2 + k;
      if (c.type == SetConstants::Type::Float) {
        c.floats.push_back(number(i, "a constant"));
      } else if (c.type == SetConstants::Type::Int) {
        c.ints.push_back(integer(i, "an integer constant", std::numeric_limits<int32_t>::min(),
                                 std::numeric_limits<int32_t>::max()));
      } else {
        auto b = d3d::parseEnum(d3d::EnumKind::Bool, arg(i));
        if (!b) errAt(i, fmt::format("expected TRUE, FALSE, 1 or 0, got '{}'", arg(i)));
        c.ints.push_back(int32_t(*b));
      }
    }
    add(std::move(c));
  }

  // ---- fvf ELEMENTS...
  void fvf() {
    need(1, 100, "xyz|xyzrhw|xyzw|xyzb1-5 [lastbeta_ubyte4|lastbeta_d3dcolor] [normal] [psize] "
                 "[diffuse] [specular] [tex D0 D1 ...]");
    if (!vertices_.empty() || !indices_.empty())
      err(tok_[0].col, "vertices are pending; draw them before changing the fvf");
    FvfLayout f;
    f.diffuse = false;
    f.texDims.clear();
    std::set<std::string> seen;
    bool position = false;
    for (size_t i = 1; i <= argc(); ++i) {
      std::string e = lower(arg(i));
      if (!seen.insert(e).second) errAt(i, fmt::format("'{}' is given twice", arg(i)));
      const bool blendPosition = e.size() == 5 && e.starts_with("xyzb");
      if (e == "xyz" || e == "xyzrhw" || e == "xyzw" || blendPosition) {
        if (position) errAt(i, "only one position element (xyz, xyzrhw, xyzw or xyzb1-5) is allowed");
        position = true;
        f.positionFloats = e == "xyz" ? 3 : 4;
        f.positionCode = e == "xyz" ? d3d::FVF_XYZ : e == "xyzw" ? d3d::FVF_XYZW : d3d::FVF_XYZRHW;
        if (blendPosition) {
          const int betas = e[4] - '0';
          if (betas < 1 || betas > 5)
            errAt(i, fmt::format("'{}': D3DFVF_XYZBn has 1 to 5 betas (xyzb1-xyzb5)", arg(i)));
          f.positionFloats = 3 + betas;
          f.positionCode = d3d::FVF_XYZB1 + 2 * uint32_t(betas - 1);  // 0x006, 0x008 ... 0x00e
        }
      } else if (e == "lastbeta_ubyte4" || e == "lastbeta_d3dcolor") {
        if (d3d::fvfBetaCount(f.positionCode) == 0)
          errAt(i, fmt::format("'{}' needs an xyzb1-xyzb5 position before it", arg(i)));
        if (f.lastBeta) errAt(i, "only one of lastbeta_ubyte4 and lastbeta_d3dcolor is allowed");
        f.lastBeta = e == "lastbeta_ubyte4" ? d3d::FVF_LASTBETA_UBYTE4 : d3d::FVF_LASTBETA_D3DCOLOR;
      } else if (e == "normal") {
        f.normal = true;
      } else if (e == "psize") {
        f.psize = true;
      } else if (e == "diffuse") {
        f.diffuse = true;
      } else if (e == "specular") {
        f.specular = true;
      } else if (e == "tex") {
        while (i + 1 <= argc() && toInt(arg(i + 1))) {
          ++i;
          if (f.texDims.size() == 8) errAt(i, "at most 8 texture coordinate sets");
          f.texDims.push_back(integer(i, "a texture coordinate dimension", 1, 4));
        }
        if (f.texDims.empty())
          errAt(i, "expected a dimension (1-4) for each texture coordinate set after tex");
      } else {
        errAt(i, fmt::format("unknown vertex element '{}' (expected xyz, xyzrhw, xyzw, xyzb1-5, "
                             "lastbeta_ubyte4, lastbeta_d3dcolor, normal, psize, diffuse, "
                             "specular or tex)",
                             arg(i)));
      }
    }
    if (!position)
      err(tok_[1].col, "expected a position element first (xyz, xyzrhw, xyzw or xyzb1-5)");
    if (f.normal && f.positionCode == d3d::FVF_XYZRHW)
      err(tok_[1].col, "normal cannot be used with xyzrhw (pretransformed vertices are not lit)");
    std::string text;
    for (size_t i = 1; i <= argc(); ++i) {
      if (i > 1) text.push_back(' ');
      text.append(arg(i));
    }
    f.text = text;
    fvf_ = f;
    decl_.reset();
  }

  // ---- decl USAGE[N]:TYPE ...  (stream 0, packed in order)
  void decl() {
    need(1, 32, "USAGE[N]:TYPE ... (e.g. position0:float3 position1:float3 normal0:float3 "
                "color0:d3dcolor)");
    if (!vertices_.empty() || !indices_.empty())
      err(tok_[0].col, "vertices are pending; draw them before changing the declaration");
    struct Named {
      std::string_view name;
      uint8_t value;
    };
    static constexpr Named kUsages[] = {
        {"position", d3d::DECLUSAGE_POSITION}, {"blendweight", d3d::DECLUSAGE_BLENDWEIGHT},
        {"blendindices", d3d::DECLUSAGE_BLENDINDICES}, {"normal", d3d::DECLUSAGE_NORMAL},
        {"psize", d3d::DECLUSAGE_PSIZE}, {"texcoord", d3d::DECLUSAGE_TEXCOORD},
        {"tangent", d3d::DECLUSAGE_TANGENT}, {"binormal", d3d::DECLUSAGE_BINORMAL},
        {"positiont", d3d::DECLUSAGE_POSITIONT}, {"color", d3d::DECLUSAGE_COLOR},
        {"fog", d3d::DECLUSAGE_FOG}};
    // Types a `v` line can spell: floats, a D3DCOLOR, or four bytes 0-255.
    struct TypeInfo {
      std::string_view name;
      uint8_t type;
      uint32_t values;
    };
    static constexpr TypeInfo kTypes[] = {
        {"float1", d3d::DECLTYPE_FLOAT1, 1}, {"float2", d3d::DECLTYPE_FLOAT2, 2},
        {"float3", d3d::DECLTYPE_FLOAT3, 3}, {"float4", d3d::DECLTYPE_FLOAT4, 4},
        {"d3dcolor", d3d::DECLTYPE_D3DCOLOR, 1}, {"ubyte4", d3d::DECLTYPE_UBYTE4, 4}};
    DeclLayout d;
    for (size_t i = 1; i <= argc(); ++i) {
      const std::string e = lower(arg(i));
      const size_t colon = e.find(':');
      const std::string usageText = e.substr(0, colon);
      const std::string typeText = colon == std::string::npos ? "" : e.substr(colon + 1);
      size_t digits = usageText.size();
      while (digits > 0 && std::isdigit(static_cast<unsigned char>(usageText[digits - 1]))) --digits;
      const Named* usage = nullptr;
      for (const Named& u : kUsages)
        if (u.name == usageText.substr(0, digits)) usage = &u;
      const TypeInfo* type = nullptr;
      for (const TypeInfo& t : kTypes)
        if (t.name == typeText) type = &t;
      const std::string indexText = usageText.substr(digits);
      if (!usage || !type || indexText.size() > 2)
        errAt(i, fmt::format("expected USAGE[N]:TYPE with a usage of position, blendweight, "
                             "blendindices, normal, psize, texcoord, tangent, binormal, "
                             "positiont, color or fog, N 0-15 and a type of float1-4, d3dcolor "
                             "or ubyte4, got '{}'",
                             arg(i)));
      const int index = indexText.empty() ? 0 : std::stoi(indexText);
      if (index > 15) errAt(i, fmt::format("usage index {} is out of range (0-15)", index));
      if (d.declaration.find(usage->value, uint8_t(index)))
        errAt(i, fmt::format("'{}' is given twice", arg(i)));
      VertexElement el;
      el.stream = 0;
      el.offset = uint16_t(d.stride);
      el.type = type->type;
      el.usage = usage->value;
      el.usageIndex = uint8_t(index);
      d.declaration.elements.push_back(el);
      d.types.push_back(type->type);
      d.stride += declTypeSize(type->type);
      d.valueCount += type->values;
    }
    if (!d.declaration.find(d3d::DECLUSAGE_POSITION, 0) && !d.declaration.find(d3d::DECLUSAGE_POSITIONT, 0))
      err(tok_[1].col, "expected a position0 or positiont0 element");
    for (size_t i = 1; i <= argc(); ++i) {
      if (i > 1) d.text.push_back(' ');
      d.text.append(arg(i));
    }
    decl_ = std::move(d);
  }

  // ---- v VALUES... with a `decl` layout
  void declVertex() {
    const DeclLayout& d = *decl_;
    if (argc() != d.valueCount)
      err(argc() > d.valueCount ? tok_[d.valueCount + 1].col : 0,
          fmt::format("expected {} values for decl `{}`, got {}", d.valueCount, d.text, argc()));
    size_t at = 1;
    for (uint8_t type : d.types) {
      if (type == d3d::DECLTYPE_D3DCOLOR) {
        const uint32_t c = d3dColor(at++, "a color");
        const uint8_t* b = reinterpret_cast<const uint8_t*>(&c);
        vertices_.insert(vertices_.end(), b, b + 4);
      } else if (type == d3d::DECLTYPE_UBYTE4) {
        for (int k = 0; k < 4; ++k) vertices_.push_back(uint8_t(integer(at++, "a byte", 0, 255)));
      } else {
        for (int k = 0; k <= type - d3d::DECLTYPE_FLOAT1; ++k) {
          const float f = number(at++, "a float");
          const uint8_t* b = reinterpret_cast<const uint8_t*>(&f);
          vertices_.insert(vertices_.end(), b, b + 4);
        }
      }
    }
  }

  // ---- v VALUES...
  void vertex() {
    if (decl_) {
      declVertex();
      if (vertexCount_ == 0 && indices_.empty()) pendingLine_ = line_;
      ++vertexCount_;
      if (vertexCount_ > 65536 * 16) err(0, "too many vertices for one draw");
      return;
    }
    size_t n = fvf_.valueCount();
    if (argc() != n)
      err(argc() > n ? tok_[n + 1].col : 0,
          fmt::format("expected {} values for fvf `{}`, got {}", n, fvf_.text, argc()));
    size_t at = 1;
    auto putFloat = [&](float f) {
      uint8_t b[4];
      std::memcpy(b, &f, 4);
      vertices_.insert(vertices_.end(), b, b + 4);
    };
    auto putU32 = [&](uint32_t u) {
      uint8_t b[4];
      std::memcpy(b, &u, 4);
      vertices_.insert(vertices_.end(), b, b + 4);
    };
    const int positionFloats = fvf_.positionFloats - (fvf_.lastBeta ? 1 : 0);
    for (int k = 0; k < positionFloats; ++k)
      putFloat(number(at++, k < 3 ? "the position" : "a blend weight"));
    if (fvf_.lastBeta) {
      // Four matrix indices packed in a DWORD, stored as written (little endian).
      auto v = toInt(arg(at));
      if (!v || *v < 0 || *v > 0xffffffffll)
        errAt(at, fmt::format("expected the packed matrix indices as a DWORD (e.g. 0x00000301), "
                              "got '{}'",
                              arg(at)));
      putU32(uint32_t(*v));
      ++at;
    }
    if (fvf_.normal)
      for (int k = 0; k < 3; ++k) putFloat(number(at++, "the normal"));
    if (fvf_.psize) putFloat(number(at++, "the point size"));
    if (fvf_.diffuse) putU32(d3dColor(at++, "the diffuse color"));
    if (fvf_.specular) putU32(d3dColor(at++, "the specular color"));
    for (size_t t = 0; t < fvf_.texDims.size(); ++t)
      for (int k = 0; k < fvf_.texDims[t]; ++k)
        putFloat(number(at++, fmt::format("texture coordinate set {}", t)));
    if (vertexCount_ == 0 && indices_.empty()) pendingLine_ = line_;
    ++vertexCount_;
    if (vertexCount_ > 65536 * 16) err(0, "too many vertices for one draw");
  }

  // ---- i N N N...
  void index() {
    need(1, 100000, "N [N...]");
    if (vertexCount_ == 0 && indices_.empty()) pendingLine_ = line_;
    for (size_t i = 1; i <= argc(); ++i) {
      indices_.push_back(uint16_t(integer(i, "an index", 0, 65535)));
      indexLines_.push_back(line_);
    }
    if (indices_.size() > 65536 * 16) err(0, "too many indices for one draw");
  }

  // ---- draw trilist|tristrip|trifan|linelist|linestrip|pointlist
  void draw() {
    need(1, 1, "trilist|tristrip|trifan|linelist|linestrip|pointlist");
    struct Prim {
      std::string_view name;
      d3d::PrimitiveType type;
      uint32_t min, multiple, subtract;  // count = (n - subtract) / multiple
    };
    static constexpr Prim kPrims[] = {
        {"pointlist", d3d::PT_POINTLIST, 1, 1, 0}, {"linelist", d3d::PT_LINELIST, 2, 2, 0},
        {"linestrip", d3d::PT_LINESTRIP, 2, 1, 1}, {"trilist", d3d::PT_TRIANGLELIST, 3, 3, 0},
        {"tristrip", d3d::PT_TRIANGLESTRIP, 3, 1, 2}, {"trifan", d3d::PT_TRIANGLEFAN, 3, 1, 2},
    };
    const Prim* prim = nullptr;
    std::string name = lower(arg(1));
    auto pt = d3d::parseEnum(d3d::EnumKind::PrimitiveType, arg(1));
    for (const Prim& p : kPrims)
      if (p.name == name || (pt && p.type == *pt)) prim = &p;
    if (!prim)
      errAt(1, fmt::format("unknown primitive type '{}' (expected trilist, tristrip, trifan, "
                           "linelist, linestrip or pointlist)",
                           arg(1)));
    if (vertexCount_ == 0) err(tok_[0].col, "no vertices to draw (add v lines first)");
    Draw d;
    d.type = prim->type;
    d.fvf = fvf_.code();
    d.stride = fvf_.stride();
    if (decl_) {
      d.fvf = 0;
      d.stride = decl_->stride;
      d.declaration = decl_->declaration;
    }
    d.vertexCount = vertexCount_;
    bool indexed = !indices_.empty();
    uint32_t n = indexed ? uint32_t(indices_.size()) : vertexCount_;
    const char* what = indexed ? "indices" : "vertices";
    if (n < prim->min)
      errAt(1, fmt::format("{} needs at least {} {}, got {}", prim->name, prim->min, what, n));
    if ((n - prim->subtract) % prim->multiple != 0)
      errAt(1, fmt::format("{} needs a multiple of {} {}, got {}", prim->name, prim->multiple,
                           what, n));
    d.primitiveCount = (n - prim->subtract) / prim->multiple;
    for (size_t k = 0; k < indices_.size(); ++k) {
      if (indices_[k] >= vertexCount_) {
        errIn("i", indexLines_[k], 0, fmt::format("index {} is out of range: the draw has {} vertices", indices_[k],
                           vertexCount_));
      }
    }
    d.vertices = std::move(vertices_);
    d.indices = std::move(indices_);
    vertices_.clear();
    indices_.clear();
    indexLines_.clear();
    vertexCount_ = 0;
    add(std::move(d));
  }

  // ---- transform WORLD|VIEW|PROJECTION|TEXTUREn m11 ... m44
  void transform() {
    need(17, 17, "WORLD|VIEW|PROJECTION|TEXTUREn|WORLDn m11 m12 ... m44 (16 numbers)");
    auto type = d3d::parseEnum(d3d::EnumKind::TransformType, arg(1));
    if (!type) {
      // WORLDn (D3DTS_WORLDMATRIX(n)), n = 0-255.
      std::string name = lower(arg(1));
      if (name.starts_with("d3dts_")) name.erase(0, 6);
      const std::string_view digits = std::string_view(name).substr(std::min<size_t>(name.size(), 5));
      if (name.starts_with("world") && !digits.empty() &&
          digits.find_first_not_of("0123456789") == std::string_view::npos) {
        auto n = toInt(digits);
        if (n) {
          if (*n > 255)
            errAt(1, fmt::format("world matrix index {} is out of range (WORLD0-WORLD255)", *n));
          type = d3d::worldMatrix(int(*n));
        }
      }
    }
    if (!type)
      errAt(1, fmt::format("unknown transform '{}' (expected WORLD, VIEW, PROJECTION, "
                           "TEXTURE0-7 or WORLD0-255)",
                           arg(1)));
    SetTransform t{*type, {}};
    for (int k = 0; k < 16; ++k)
      t.matrix.m[k / 4][k % 4] = number(2 + size_t(k), fmt::format("m{}{}", k / 4 + 1, k % 4 + 1));
    add(t);
  }

  // ---- material DIFFUSE AMBIENT SPECULAR EMISSIVE POWER
  void material() {
    need(5, 5, "DIFFUSE AMBIENT SPECULAR EMISSIVE POWER");
    SetMaterial m;
    m.material.diffuse = color(1, "DIFFUSE");
    m.material.ambient = color(2, "AMBIENT");
    m.material.specular = color(3, "SPECULAR");
    m.material.emissive = color(4, "EMISSIVE");
    m.material.power = number(5, "POWER");
    add(m);
  }

  // ---- light N directional|point DIFFUSE SPECULAR AMBIENT X Y Z [RANGE A0 A1 A2]
  //      light N spot DIFFUSE SPECULAR AMBIENT X Y Z DX DY DZ RANGE A0 A1 A2 FALLOFF THETA PHI
  //      light N off
  void light() {
    const char* usage =
        "N directional|point DIFFUSE SPECULAR AMBIENT X Y Z [RANGE A0 A1 A2]`, `light N spot "
        "DIFFUSE SPECULAR AMBIENT X Y Z DX DY DZ RANGE A0 A1 A2 FALLOFF THETA PHI` or `light "
        "N off";
    need(2, 18, usage);
    SetLight l;
    l.index = integer(1, "the light index", 0, kMaxLights - 1);
    std::string type = lower(arg(2));
    if (type == "off") {
      need(2, 2, usage);
      l.enable = false;
      add(l);
      return;
    }
    auto lt = d3d::parseEnum(d3d::EnumKind::LightType, arg(2));
    if (!lt)
      errAt(2, fmt::format("unknown light type '{}' (expected directional, point, spot or off)",
                           arg(2)));
    Light& L = l.light;
    L.type = *lt;
    if (L.type == d3d::LIGHT_SPOT) {
      need(18, 18, usage);
    } else if (argc() != 8 && argc() != 12) {
      need(8, 8, usage);
    }
    L.diffuse = color(3, "DIFFUSE");
    L.specular = color(4, "SPECULAR");
    L.ambient = color(5, "AMBIENT");
    Vec3 xyz{number(6, "X"), number(7, "Y"), number(8, "Z")};
    // Without RANGE: the largest range D3D allows and no attenuation (A0 = 1).
    L.range = std::sqrt(std::numeric_limits<float>::max());
    L.attenuation0 = 1;
    if (L.type == d3d::LIGHT_DIRECTIONAL) {
      if (xyz == Vec3{0, 0, 0}) errAt(6, "a directional light needs a nonzero direction");
      L.direction = xyz;
    } else {
      L.position = xyz;
    }
    size_t at = 9;
    if (L.type == d3d::LIGHT_SPOT) {
      L.direction = {number(9, "DX"), number(10, "DY"), number(11, "DZ")};
      if (L.direction == Vec3{0, 0, 0}) errAt(9, "a spot light needs a nonzero direction");
      at = 12;
    }
    if (argc() >= at + 3) {
      L.range = number(at, "RANGE");
      if (L.range < 0 || L.range > std::sqrt(std::numeric_limits<float>::max()))
        errAt(at, fmt::format("RANGE {} is out of range (0 to sqrt(FLT_MAX))", L.range));
      L.attenuation0 = number(at + 1, "A0");
      L.attenuation1 = number(at + 2, "A1");
      L.attenuation2 = number(at + 3, "A2");
      if (L.attenuation0 < 0 || L.attenuation1 < 0 || L.attenuation2 < 0)
        errAt(at + 1, "attenuation factors must not be negative");
    }
    if (L.type == d3d::LIGHT_SPOT) {
      L.falloff = number(16, "FALLOFF");
      L.theta = number(17, "THETA");
      L.phi = number(18, "PHI");
      // D3DLIGHT9: 0 <= Theta <= Phi <= pi (radians).
      if (L.phi < 0 || L.phi > std::numbers::pi_v<float>)
        errAt(18, fmt::format("PHI {} is out of range (0 to pi radians)", L.phi));
      if (L.theta < 0 || L.theta > L.phi)
        errAt(17, fmt::format("THETA {} is out of range (0 to PHI)", L.theta));
    }
    add(l);
  }

  // ---- viewport X Y W H [MINZ MAXZ]
  void viewport() {
    need(4, 6, "X Y W H [MINZ MAXZ]");
    if (argc() == 5) need(4, 4, "X Y W H [MINZ MAXZ]");
    Viewport v;
    v.x = integer(1, "X", 0, kMaxTargetSize);
    v.y = integer(2, "Y", 0, kMaxTargetSize);
    v.width = integer(3, "W", 1, kMaxTargetSize);
    v.height = integer(4, "H", 1, kMaxTargetSize);
    if (argc() == 6) {
      v.minZ = number(5, "MINZ");
      v.maxZ = number(6, "MAXZ");
      if (v.minZ < 0 || v.minZ > 1 || v.maxZ < 0 || v.maxZ > 1)
        errAt(5, "MINZ and MAXZ must be in 0 to 1");
    }
    // SetViewport fails for a viewport outside the render target.
    if (v.x + v.width > script_.width || v.y + v.height > script_.height)
      err(tok_[1].col, fmt::format("{},{} {}x{} does not fit the {}x{} render target", v.x, v.y,
                                   v.width, v.height, script_.width, script_.height));
    add(SetViewport{v});
  }

  // ---- scissor L T R B
  void scissor() {
    need(4, 4, "L T R B");
    Rect r;
    r.left = integer(1, "L", 0, kMaxTargetSize);
    r.top = integer(2, "T", 0, kMaxTargetSize);
    r.right = integer(3, "R", r.left, kMaxTargetSize);
    r.bottom = integer(4, "B", r.top, kMaxTargetSize);
    add(SetScissor{r});
  }

  // ---- clipplane N A B C D
  void clipPlane() {
    need(5, 5, "N A B C D");
    SetClipPlane c;
    c.index = integer(1, "N", 0, kMaxUserClipPlanes - 1);
    for (int k = 0; k < 4; ++k) c.plane[k] = number(2 + size_t(k), std::string(1, "ABCD"[k]));
    add(c);
  }

  std::string_view text_;
  SceneScript script_;
  std::vector<Token> tok_;
  std::string cmd_;
  int line_ = 0;
  bool first_ = true, sizeSeen_ = false;
  std::set<std::string> textures_;
  std::array<std::optional<std::pair<int, int>>, 4> targetSizes_;  // rendertarget N W H
  FvfLayout fvf_;
  std::optional<DeclLayout> decl_;  // `decl` replaces the FVF until the next `fvf`
  std::vector<uint8_t> vertices_;
  uint32_t vertexCount_ = 0;
  std::vector<uint16_t> indices_;
  std::vector<int> indexLines_;
  int pendingLine_ = 0;
};

}  // namespace

SceneScript parseSceneScript(std::string_view text, const std::string& file) {
  return Parser(text, file).parse();
}

SceneScript loadSceneScript(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) failAt(SourceLocation{path}, "cannot open the scene script: {}", std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) failAt(SourceLocation{path}, "cannot read the scene script");
  return parseSceneScript(ss.str(), path);
}

void readTargetPixel(const Texture& target, int x, int y, int rgba[4]) {
  Color4 c = target.texel(0, 0, x, y);
  rgba[0] = unorm8(c.r);
  rgba[1] = unorm8(c.g);
  rgba[2] = unorm8(c.b);
  rgba[3] = unorm8(c.a);
}

std::vector<std::string> checkSceneExpectations(const SceneScript& script, const SceneOutput& output) {
  std::vector<std::string> out;
  for (const Expectation& e : script.expectations) {
    const std::string what =
        e.target ? fmt::format("target {} {},{}", e.target, e.x, e.y) : fmt::format("{},{}", e.x, e.y);
    const Texture* target = output.targets[size_t(e.target)].get();
    if (e.target == 0 && output.target) target = output.target.get();
    if (!target) {
      out.push_back(fmt::format("{}:{}: expected {}, but render target {} was never created",
                                script.file, e.line, what, e.target));
      continue;
    }
    int got[4];
    readTargetPixel(*target, e.x, e.y, got);
    bool ok = true;
    for (int c = 0; c < 4; ++c) ok = ok && std::abs(got[c] - e.rgba[c]) <= e.tolerance;
    if (!ok)
      out.push_back(fmt::format("{}:{}: expected {} = {} {} {} {}, got {} {} {} {}",
                                script.file, e.line, what, e.rgba[0], e.rgba[1], e.rgba[2],
                                e.rgba[3], got[0], got[1], got[2], got[3]));
  }
  return out;
}

}  // namespace refx::scene
