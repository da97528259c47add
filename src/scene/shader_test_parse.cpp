// .shader_test text → ShaderTestFile (docs/shader_test_format.md).
#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <fstream>
#include <sstream>

#include "refx/core/diagnostics.h"
#include "refx/scene/shader_test.h"
#include "scene/shader_test_text.h"

namespace refx::scene {

using detail::LineCursor;

namespace {

// Backend tags of vkd3d's runners. refx is a Direct3D 9 runner: only `d3d9` holds.
constexpr std::array<std::string_view, 17> kKnownTags = {
    "amd", "d3d9", "d3d11", "d3d12", "glsl", "intel", "llvm", "llvmpipe", "mesa",
    "msl", "mvk", "nvidia", "opengl", "radv", "vulkan", "warp", "windows"};

// "3", "3.0", "4.1" → 30, 30, 41.
std::optional<ShaderModel> parseModel(LineCursor& c) {
  c.skipSpace();
  std::string_view r = c.rest();
  if (r.empty() || !std::isdigit(static_cast<unsigned char>(r[0]))) return std::nullopt;
  int major = r[0] - '0', minor = 0;
  size_t used = 1;
  if (r.size() >= 3 && r[1] == '.' && std::isdigit(static_cast<unsigned char>(r[2]))) {
    minor = r[2] - '0';
    used = 3;
  }
  if (r.size() > used && std::isdigit(static_cast<unsigned char>(r[used]))) return std::nullopt;
  c.setPosition(c.position() + used);
  return major * 10 + minor;
}

}  // namespace

bool Condition::holds(ShaderModel model) const {
  if (anyOf.empty()) return true;
  for (const auto& all : anyOf) {
    bool ok = true;
    for (const Atom& a : all) {
      bool v = false;
      switch (a.kind) {
        case Atom::Kind::ModelAtLeast: v = model >= a.model; break;
        case Atom::Kind::ModelBelow: v = model < a.model; break;
        case Atom::Kind::Tag: v = a.tag == "d3d9"; break;
      }
      if (a.negate) v = !v;
      ok = ok && v;
    }
    if (ok) return true;
  }
  return false;
}

Condition parseCondition(std::string_view text) {
  Condition cond;
  LineCursor c(text);
  std::vector<Condition::Atom> all;
  for (;;) {
    Condition::Atom atom;
    atom.negate = c.ch('!');
    if (c.literal("sm>=") || c.literal("sm >=")) {
      atom.kind = Condition::Atom::Kind::ModelAtLeast;
    } else if (c.literal("sm<") || c.literal("sm <")) {
      atom.kind = Condition::Atom::Kind::ModelBelow;
    } else {
      std::string_view tag = c.name();
      if (std::find(kKnownTags.begin(), kKnownTags.end(), tag) == kKnownTags.end())
        fail("unknown qualifier '{}' (expected sm>=X, sm<X or a backend tag such as d3d9)",
             tag.empty() ? c.rest() : tag);
      atom.tag = std::string(tag);
      // A version comparison (mesa<23.3) only matters for a tag that holds; none of
      // refx's versioned tags does, so it is read and dropped.
      if (c.peek() == '<' || c.peek() == '>' || c.peek() == '=' || c.peek() == '!') {
        c.ch(c.peek());
        c.ch('=');
        if (c.name().empty()) fail("expected a version after '{}'", tag);
      }
    }
    if (atom.kind != Condition::Atom::Kind::Tag) {
      auto m = parseModel(c);
      if (!m) fail("expected a shader model such as 3.0 in '{}'", text);
      atom.model = *m;
    }
    all.push_back(std::move(atom));
    if (c.ch('&')) continue;
    cond.anyOf.push_back(std::move(all));
    all.clear();
    if (c.ch('|')) continue;
    if (!c.atEnd()) fail("unexpected '{}' in qualifier '{}'", c.rest(), text);
    return cond;
  }
}

// ---------------------------------------------------------------------------
// [test] lines

namespace {

// `(a, b, c, d)` with 1, 2 or 4 floats (or ints); the '(' is still to be read.
template <typename T, typename Read>
bool readTuple(LineCursor& c, T* out, int& count, Read read) {
  if (!c.ch('(')) return false;
  count = 0;
  for (;;) {
    if (count == 4) return false;
    auto v = read(c);
    if (!v) return false;
    out[count++] = T(*v);
    if (c.ch(')')) return count == 1 || count == 2 || count == 4;
    if (!c.ch(',')) return false;
  }
}

// The expected value of a probe: rgba(...), f32(...), r(...), u32/i32, rgbaui/rgbai, rui/ri.
bool readProbeValue(LineCursor& c, ProbeCommand& p, std::string& unsupported) {
  auto flt = [](LineCursor& cc) { return cc.number(); };
  auto itg = [](LineCursor& cc) { return cc.integer(); };
  if (c.word("rgba") || c.word("f32")) {
    p.kind = ProbeCommand::Kind::Float;
    return readTuple(c, p.floats, p.count, flt);
  }
  if (c.word("r")) {
    p.kind = ProbeCommand::Kind::Float;
    return readTuple(c, p.floats, p.count, flt) && p.count == 1;
  }
  const bool isUint = c.word("rgbaui") || c.word("u32") || c.word("rui");
  if (isUint || c.word("rgbai") || c.word("i32") || c.word("ri")) {
    p.kind = isUint ? ProbeCommand::Kind::Uint : ProbeCommand::Kind::Int;
    return readTuple(c, p.ints, p.count, itg);
  }
  for (std::string_view wide : {"rd", "f64", "u64", "i64", "rui64", "ri64"})
    if (c.word(wide)) {
      unsupported = fmt::format("{} probes need 64-bit targets", wide);
      return true;
    }
  return false;
}

TestCommandBody parseProbe(LineCursor& c) {
  ProbeCommand p;
  auto malformed = [&] { return MalformedCommand{"malformed probe: expected e.g. 'probe (x, y) rgba(r, g, b, a) [ulps]'"}; };
  // Resource reference: `rtv N` (older) or `rtv-N`; other resources are not D3D9's.
  if (c.word("rtv")) {
    auto slot = c.integer();
    if (!slot) return malformed();
    p.rtvSlot = int(*slot);
  } else {
    const size_t save = c.position();
    std::string_view ref = c.name();
    if (ref.starts_with("rtv-")) {
      p.rtvSlot = std::atoi(std::string(ref.substr(4)).c_str());
    } else if (ref.starts_with("uav") || ref.starts_with("dsv") || ref.starts_with("srv") ||
               ref.starts_with("cbv") || ref.starts_with("vb-")) {
      return UnknownCommand{fmt::format("probes of '{}' (D3D9 probes render targets only)", ref)};
    } else {
      c.setPosition(save);
    }
  }
  std::string unsupported;
  bool valueRead = false;
  auto floats = [](LineCursor& cc) { return cc.number(); };
  auto ints = [](LineCursor& cc) { return cc.integer(); };
  int64_t r[4];
  int n = 0;
  // Older forms: `probe all rgba (...)`, `probe rect rgba (x, y, w, h) (...)`, `probe rgba (x, y) (...)`.
  if (c.word("all")) {
    p.all = true;
  } else if (c.word("rect")) {
    if (!c.word("rgba") || !readTuple(c, r, n, ints) || n != 4) return malformed();
    p.left = int(r[0]), p.top = int(r[1]), p.right = int(r[0] + r[2]), p.bottom = int(r[1] + r[3]);
    if (!readTuple(c, p.floats, p.count, floats) || p.count != 4) return malformed();
    valueRead = true;
  } else if (c.word("rgba")) {
    if (!readTuple(c, r, n, ints) || n != 2) return malformed();
    p.left = int(r[0]), p.top = int(r[1]), p.right = p.left + 1, p.bottom = p.top + 1;
    if (!readTuple(c, p.floats, p.count, floats) || p.count != 4) return malformed();
    valueRead = true;
  } else if (c.ch('(')) {
    // Current forms: (x), (x, y), (x, y, layer), (left, top, right, bottom).
    for (;;) {
      auto v = c.integer();
      if (!v || n == 4) return malformed();
      r[n++] = *v;
      if (c.ch(')')) break;
      if (!c.ch(',')) return malformed();
    }
    if (n == 3 && r[2] != 0) return UnknownCommand{"probes of array layers (D3D9 targets have one layer)"};
    if (n == 4) {
      p.left = int(r[0]), p.top = int(r[1]), p.right = int(r[2]), p.bottom = int(r[3]);
    } else {
      p.left = int(r[0]), p.top = n == 1 ? 0 : int(r[1]);
      p.right = p.left + 1, p.bottom = p.top + 1;
    }
  } else {
    return malformed();
  }
  if (!valueRead) {
    if (!readProbeValue(c, p, unsupported)) return malformed();
    if (!unsupported.empty()) return UnknownCommand{unsupported};
  }
  if (!c.atEnd()) {
    auto ulps = c.integer();
    if (!ulps || *ulps < 0) return malformed();
    p.ulps = uint32_t(*ulps);
  }
  if (!c.atEnd()) return malformed();
  if (p.left < 0 || p.top < 0 || p.right <= p.left || p.bottom <= p.top)
    return MalformedCommand{fmt::format("probe rectangle ({}, {}, {}, {}) is empty or negative", p.left, p.top,
                                        p.right, p.bottom)};
  return p;
}

TestCommandBody parseUniform(LineCursor& c) {
  UniformCommand u;
  auto offset = c.integer();
  if (!offset || *offset < 0 || *offset > 1 << 20) return MalformedCommand{"malformed uniform: expected a word offset"};
  u.offset = int(*offset);
  using T = UniformCommand::Type;
  int count = 0;
  bool isFloat = true;
  if (c.word("float4")) u.type = T::Float4, count = 4;
  else if (c.word("float")) u.type = T::Float, count = 1;
  else if (c.word("int4")) u.type = T::Int4, count = 4, isFloat = false;
  else if (c.word("int")) u.type = T::Int, count = 1, isFloat = false;
  else if (c.word("uint4")) u.type = T::Uint4, count = 4, isFloat = false;
  else if (c.word("uint")) u.type = T::Uint, count = 1, isFloat = false;
  else return UnknownCommand{fmt::format("uniform type '{}' (D3D9 has float, int and uint uniforms)", c.name())};
  for (int i = 0; i < count; ++i) {
    if (isFloat) {
      auto v = c.number();
      if (!v) return MalformedCommand{fmt::format("malformed uniform: expected {} float values", count)};
      u.floats.push_back(*v);
    } else {
      auto v = c.integer();
      const bool isUint = u.type == T::Uint || u.type == T::Uint4;
      if (!v || (isUint && (*v < 0 || *v > int64_t(UINT32_MAX))) ||
          (!isUint && (*v < INT32_MIN || *v > INT32_MAX)))
        return MalformedCommand{fmt::format("malformed uniform: expected {} 32-bit integer values", count)};
      u.ints.push_back(*v);
    }
  }
  if (!c.atEnd()) return MalformedCommand{fmt::format("unexpected '{}' after the uniform values", c.rest())};
  return u;
}

std::optional<uint32_t> parseComparison(LineCursor& c) {
  static constexpr std::pair<std::string_view, uint32_t> kFuncs[] = {
      {"less equal", 4}, {"not equal", 6}, {"greater equal", 7}, {"never", 1},
      {"less", 2},       {"equal", 3},     {"greater", 5},       {"always", 8}};  // D3DCMP_*
  for (auto [name, func] : kFuncs)
    if (c.word(name)) return func;
  return std::nullopt;
}

TestCommandBody parseDirective(LineCursor& c) {
  if (c.word("draw quad")) {
    if (!c.atEnd()) return MalformedCommand{"unexpected text after 'draw quad'"};
    return DrawCommand{true, Topology::TriangleList, 3};
  }
  if (c.word("draw")) {
    DrawCommand d;
    if (c.word("triangle list")) d.topology = Topology::TriangleList;
    else if (c.word("triangle strip")) d.topology = Topology::TriangleStrip;
    else if (c.word("point list")) d.topology = Topology::PointList;
    else return UnknownCommand{fmt::format("topology '{}' (D3D9 runs triangle list, triangle strip and point list)",
                                           c.rest())};
    auto n = c.integer();
    if (!n || *n < 0 || *n > 1 << 24) return MalformedCommand{"malformed draw: expected a vertex count"};
    d.vertexCount = int(*n);
    if (!c.atEnd()) {
      auto instances = c.integer();
      if (!instances || !c.atEnd()) return MalformedCommand{"malformed draw: expected an instance count"};
      if (*instances != 1) return UnknownCommand{"instanced draws"};
    }
    return d;
  }
  if (c.word("clear")) {
    ClearCommand cl;
    if (c.word("rtv")) {  // older: clear rtv N r g b a
      auto slot = c.integer();
      if (!slot) return MalformedCommand{"malformed clear: expected 'clear rtv N r g b a'"};
      cl.slot = int(*slot);
      for (float& v : cl.color) {
        auto f = c.number();
        if (!f) return MalformedCommand{"malformed clear: expected 'clear rtv N r g b a'"};
        v = *f;
      }
    } else {
      std::string_view ref = c.name();
      if (!ref.starts_with("rtv-")) return UnknownCommand{fmt::format("clears of '{}' (D3D9 clears render targets)", ref)};
      cl.slot = std::atoi(std::string(ref.substr(4)).c_str());
      int n = 0;
      if (!(c.word("f32") || c.word("rgba")) ||
          !readTuple(c, cl.color, n, [](LineCursor& cc) { return cc.number(); }) || n != 4)
        return MalformedCommand{"malformed clear: expected 'clear rtv-N f32(r, g, b, a)'"};
    }
    if (!c.atEnd()) return MalformedCommand{fmt::format("unexpected '{}' after the clear color", c.rest())};
    return cl;
  }
  if (c.word("probe")) return parseProbe(c);
  if (c.word("uniform")) return parseUniform(c);
  if (c.word("alpha test")) {
    AlphaTestCommand a;
    auto func = parseComparison(c);
    auto ref = func ? c.number() : std::nullopt;
    if (!func || !ref || !c.atEnd()) return MalformedCommand{"malformed alpha test: expected 'alpha test FUNC REF'"};
    a.func = *func;
    a.reference = *ref;
    return a;
  }
  if (c.word("shade mode")) {
    ShadeModeCommand s;
    s.flat = c.word("flat");
    if (!s.flat && !c.word("gouraud") && !c.word("smooth") && !c.word("phong"))
      return MalformedCommand{"malformed shade mode: expected flat or gouraud"};
    return s;
  }
  if (c.word("fog")) {
    FogCommand f;
    using M = FogCommand::Mode;
    if (c.word("disable")) f.mode = M::Disable;
    else if (c.word("none")) f.mode = M::None;
    else if (c.word("linear")) f.mode = M::Linear;
    else if (c.word("exp2")) f.mode = M::Exp2;
    else if (c.word("exp")) f.mode = M::Exp;
    else return MalformedCommand{"malformed fog: expected disable, none, linear, exp or exp2"};
    if (c.word("ortho")) f.ortho = true;
    else if (c.word("non-ortho")) f.ortho = false;
    if (f.mode == M::Linear) {
      auto s = c.number(), e = s ? c.number() : std::nullopt;
      if (!s || !e) return MalformedCommand{"malformed fog: expected 'fog linear START END'"};
      f.start = *s, f.end = *e;
    } else if (f.mode == M::Exp || f.mode == M::Exp2) {
      auto d = c.number();
      if (!d) return MalformedCommand{"malformed fog: expected 'fog exp DENSITY'"};
      f.density = *d;
    }
    if (!c.atEnd()) return MalformedCommand{fmt::format("unexpected '{}' after the fog mode", c.rest())};
    return f;
  }
  if (c.word("fog-colour") || c.word("fog-color")) {
    FogColorCommand f;
    for (float& v : f.color) {
      auto n = c.number();
      if (!n) return MalformedCommand{"malformed fog-colour: expected four floats"};
      v = *n;
    }
    return f;
  }
  return UnknownCommand{std::string(c.rest())};
}

}  // namespace

TestCommand parseTestCommand(std::string_view text, int line) {
  TestCommand cmd;
  cmd.line = line;
  cmd.text = std::string(text);
  while (!cmd.text.empty() && std::isspace(static_cast<unsigned char>(cmd.text.back()))) cmd.text.pop_back();
  LineCursor c(cmd.text);
  try {
    // Prefixes: todo(q) bug(q) broken(q) winbug(q) if(q), in any order.
    for (;;) {
      const bool isTodo = c.word("todo"), isBug = !isTodo && (c.word("bug") || c.word("broken"));
      const bool isWinbug = !isTodo && !isBug && c.word("winbug");
      const bool isIf = !isTodo && !isBug && !isWinbug && c.word("if");
      if (!isTodo && !isBug && !isWinbug && !isIf) break;
      std::optional<Condition> q;
      if (c.ch('(')) {
        auto inside = c.parenthesized();
        if (!inside) fail("missing ')' after the qualifier");
        q = parseCondition(*inside);
      } else if (isIf) {
        fail("'if' needs a condition: if(sm>=3)");
      }
      if (isTodo) cmd.todo = true;
      if (isBug) cmd.bug = true;
      if (isIf) cmd.onlyIf.push_back(*q);
      // winbug: results that differ between Windows drivers; refx is not one of them.
    }
    cmd.body = parseDirective(c);
  } catch (const Error& e) {
    cmd.body = MalformedCommand{e.what()};
  }
  return cmd;
}

// ---------------------------------------------------------------------------
// Sections

namespace {

struct FormatName {
  std::string_view name;
  ElementFormat format;
};
// Current names first, then the older spelling with a space.
constexpr FormatName kFormats[] = {
    {"r32g32b32a32-float", ElementFormat::Float4}, {"r32g32b32-float", ElementFormat::Float3},
    {"r32g32-float", ElementFormat::Float2},       {"r32-float", ElementFormat::Float1},
    {"r32g32b32a32 float", ElementFormat::Float4}, {"r32g32 float", ElementFormat::Float2},
    {"r32 float", ElementFormat::Float1},
    {"r32g32b32a32-sint", ElementFormat::Unsupported}, {"r32g32b32a32-uint", ElementFormat::Unsupported},
    {"r32g32-sint", ElementFormat::Unsupported},   {"r32g32-uint", ElementFormat::Unsupported},
    {"r32-float-shadow", ElementFormat::Unsupported}, {"r32-sint", ElementFormat::Unsupported},
    {"r32-uint", ElementFormat::Unsupported},      {"r32-typeless", ElementFormat::Unsupported},
    {"r32g32b32a32 sint", ElementFormat::Unsupported}, {"r32g32b32a32 uint", ElementFormat::Unsupported},
    {"r32g32 int", ElementFormat::Unsupported},    {"r32g32 uint", ElementFormat::Unsupported},
    {"r32 float shadow", ElementFormat::Unsupported}, {"r32 sint", ElementFormat::Unsupported},
    {"r32 uint", ElementFormat::Unsupported},      {"unknown", ElementFormat::Unsupported},
};

std::optional<FormatName> parseFormat(LineCursor& c) {
  // Longest names first, so "r32-float-shadow" wins over "r32-float".
  const FormatName* best = nullptr;
  size_t bestEnd = 0;
  const size_t start = c.position();
  for (const FormatName& f : kFormats) {
    c.setPosition(start);
    if (c.word(f.name) && (!best || c.position() > bestEnd)) best = &f, bestEnd = c.position();
  }
  c.setPosition(best ? bestEnd : start);
  if (!best) return std::nullopt;
  return *best;
}

// Known caps of vkd3d's [require] sections; refx's device has fog (the D3D9
// fixed-function fog the `fog` test lines set). Every other cap is missing.
constexpr std::string_view kSupportedCaps[] = {"fog"};

// Numbers of a resource's data: floats are written with a '.', an exponent, inf or
// nan; other numbers are 32-bit words as they are (vkd3d's rule for [srv] data). The
// older [texture] sections read every number as a float.
bool parseDataWords(std::string_view line, bool allFloats, std::vector<uint32_t>& out) {
  LineCursor c(line);
  while (!c.atEnd()) {
    const size_t start = c.position();
    std::string_view tok = c.name();
    if (tok.empty() && (c.peek() == '-' || c.peek() == '+')) {
      c.ch(c.peek());
      tok = c.name();
    }
    c.setPosition(start);
    const bool isHex = tok.find("0x") != std::string_view::npos || tok.find("0X") != std::string_view::npos;
    const bool looksFloat = !isHex && (tok.find_first_of(".eE") != std::string_view::npos ||
                                       tok.find("inf") != std::string_view::npos ||
                                       tok.find("nan") != std::string_view::npos);
    if (allFloats || looksFloat) {
      auto f = c.number();
      if (!f) return false;
      out.push_back(std::bit_cast<uint32_t>(*f));
    } else {
      auto i = c.integer();
      if (!i || *i < INT32_MIN || *i > int64_t(UINT32_MAX)) return false;
      out.push_back(uint32_t(*i));
    }
    c.ch(',');
  }
  return true;
}

std::string trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  return std::string(s);
}

class FileParser {
 public:
  FileParser(std::string_view text, const std::string& path) : text_(text), path_(path) { file_.path = path; }

  ShaderTestFile parse() {
    int lineNo = 0;
    size_t pos = 0;
    while (pos <= text_.size()) {
      size_t end = text_.find('\n', pos);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view line = text_.substr(pos, end - pos);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      ++lineNo;
      handleLine(line, lineNo);
      if (end == text_.size()) break;
      pos = end + 1;
    }
    return std::move(file_);
  }

 private:
  [[noreturn]] void error(int line, const std::string& message) {
    throw Error(SourceLocation{path_, line, 0}, message);
  }
  Section& current() { return file_.sections.back().section; }

  void handleLine(std::string_view line, int lineNo) {
    if (!line.empty() && line[0] == '[') {
      openSection(line, lineNo);
      return;
    }
    ShaderSection* shader = file_.sections.empty() ? nullptr : std::get_if<ShaderSection>(&current());
    if (shader) {
      // Shader text keeps its lines (comment lines become empty) so that compiler
      // diagnostics point at the right line of the test file.
      shader->text += (!line.empty() && line[0] == '%') ? std::string() : std::string(line);
      shader->text += '\n';
      return;
    }
    if (line.empty() || line[0] == '%' || trimmed(line).empty()) return;
    if (file_.sections.empty()) error(lineNo, fmt::format("'{}' before the first [section]", trimmed(line)));
    std::visit([&](auto& s) { sectionLine(s, trimmed(line), lineNo); }, current());
  }

  void openSection(std::string_view line, int lineNo) {
    std::string header = trimmed(line);
    if (header.size() < 2 || header.back() != ']') error(lineNo, fmt::format("expected ']' to close '{}'", header));
    const std::string inside = header.substr(1, header.size() - 2);
    LineCursor c(inside);
    auto slotOf = [&](std::string_view what) {
      auto n = c.integer();
      if (!n || *n < 0 || *n > 255 || !c.atEnd()) error(lineNo, fmt::format("expected '[{} N]'", what));
      return int(*n);
    };
    auto add = [&](Section s) { file_.sections.push_back({lineNo, std::move(s)}); };
    if (c.word("require") && c.atEnd()) return add(RequireSection{});
    c.setPosition(0);
    if (c.word("test") && c.atEnd()) return add(TestSection{});
    c.setPosition(0);
    if (c.word("input layout") && c.atEnd()) return add(InputLayoutSection{});
    c.setPosition(0);
    if (c.word("sampler")) {
      SamplerSection s;
      s.slot = slotOf("sampler");
      return add(s);
    }
    using RK = ResourceSection::Kind;
    const std::pair<std::string_view, RK> kResources[] = {
        {"srv", RK::Texture},           {"texture", RK::Texture},          {"rtv", RK::RenderTarget},
        {"render target", RK::RenderTarget}, {"vb", RK::VertexBuffer}, {"vertex buffer", RK::VertexBuffer},
        {"uav", RK::Unsupported}};
    for (auto [name, kind] : kResources) {
      c.setPosition(0);
      if (!c.word(name)) continue;
      ResourceSection r;
      r.kind = kind;
      r.slot = slotOf(name);
      oldTexture_ = name == "texture";
      if (kind == RK::VertexBuffer) r.dimension = ResourceSection::Dimension::Buffer;
      if (kind == RK::Unsupported) r.unsupported = "UAVs need a D3D11 device";
      return add(r);
    }
    for (std::string_view name : {"dsv", "descriptors", "preproc", "preproc fail", "buffer"}) {
      c.setPosition(0);
      if (c.word(name)) return add(UnsupportedSection{std::string(name)});
    }
    const std::pair<std::string_view, ShaderStage> kStages[] = {
        {"pixel shader", ShaderStage::Pixel},           {"vertex shader", ShaderStage::Vertex},
        {"effect", ShaderStage::Effect},                {"compute shader", ShaderStage::Unsupported},
        {"hull shader", ShaderStage::Unsupported},      {"domain shader", ShaderStage::Unsupported},
        {"geometry shader", ShaderStage::Unsupported}};
    for (auto [name, stage] : kStages) {
      c.setPosition(0);
      if (!c.word(name)) continue;
      ShaderSection s;
      s.stage = stage;
      s.stageName = std::string(name);
      s.bodyLine = lineNo + 1;
      while (!c.atEnd()) {
        std::optional<Condition>* slot = nullptr;
        if (c.word("fail")) slot = &s.fail;
        else if (c.word("notimpl")) slot = &s.notimpl;
        else if (c.word("todo")) slot = &s.todo;
        else if (c.word("d3dbc-hex")) s.source = ShaderSource::D3dbcHex;
        else if (c.word("dxbc-tpf-hex") || c.word("dxbc-dxil-hex")) s.source = ShaderSource::OtherHex;
        else error(lineNo, fmt::format("unknown shader section qualifier '{}' in '{}'", c.rest(), header));
        if (!slot) continue;
        Condition q;
        if (c.ch('(')) {
          auto text = c.parenthesized();
          if (!text) error(lineNo, fmt::format("missing ')' in '{}'", header));
          try {
            q = parseCondition(*text);
          } catch (const Error& e) {
            error(lineNo, e.what());
          }
        }
        *slot = std::move(q);
      }
      return add(std::move(s));
    }
    error(lineNo, fmt::format("unknown section '{}'", header));
  }

  // ---- section bodies ----
  void sectionLine(RequireSection& r, const std::string& line, int lineNo) {
    LineCursor c(line);
    const bool atLeast = c.word("shader model >=");
    const bool below = !atLeast && c.word("shader model <");
    const bool equal = !atLeast && !below && c.word("shader model =");
    if (atLeast || below || equal) {
      auto m = parseModel(c);
      if (!m || !c.atEnd()) error(lineNo, fmt::format("expected a shader model such as 3.0 in '{}'", line));
      if (atLeast || equal) r.minModel = std::max(r.minModel, *m);
      if (below) r.belowModel = std::min(r.belowModel, *m);
      if (equal) r.belowModel = std::min(r.belowModel, *m + 1);
      return;
    }
    c.setPosition(0);
    if (c.word("options:")) {
      while (!c.atEnd()) {
        std::string_view o = c.name();
        if (o == "row-major") r.rowMajor = true;
        else if (o == "column-major") r.rowMajor = false;
        else if (o == "backcompat") r.backCompat = true;
        else if (o == "none") {
        } else if (o == "unbounded-descriptor-arrays") {
          r.missingCaps.push_back(std::string(o));
        } else {
          error(lineNo, fmt::format("unknown option '{}' (expected row-major, column-major or backcompat)",
                                    o.empty() ? c.rest() : o));
        }
      }
      return;
    }
    if (std::find(std::begin(kSupportedCaps), std::end(kSupportedCaps), line) != std::end(kSupportedCaps)) return;
    // A backend tag expression (`d3d9`, `!glsl`) holds or not; anything else is a
    // cap refx does not have.
    try {
      if (parseCondition(line).holds(kLowestShaderModel)) return;
    } catch (const Error&) {
    }
    r.missingCaps.push_back(line);
  }

  void sectionLine(ShaderSection&, const std::string&, int) {}  // handled in handleLine
  void sectionLine(TestSection& t, const std::string& line, int lineNo) {
    t.commands.push_back(parseTestCommand(line, lineNo));
  }
  void sectionLine(UnsupportedSection&, const std::string&, int) {}

  void sectionLine(SamplerSection& s, const std::string& line, int lineNo) {
    LineCursor c(line);
    if (c.word("address")) {
      for (AddressMode& a : s.address) {
        if (c.word("border")) a = AddressMode::Border;
        else if (c.word("clamp")) a = AddressMode::Clamp;
        else if (c.word("mirror_once")) a = AddressMode::MirrorOnce;
        else if (c.word("mirror")) a = AddressMode::Mirror;
        else if (c.word("wrap")) a = AddressMode::Wrap;
        else error(lineNo, fmt::format("expected 'address U V W' with clamp, wrap, mirror, mirror_once or border"));
      }
    } else if (c.word("filter")) {
      if (c.word("minimum") || c.word("maximum")) s.unsupported = "min/max filtering";
      FilterMode* modes[] = {&s.minFilter, &s.magFilter, &s.mipFilter};
      for (FilterMode* m : modes) {
        if (c.word("point")) *m = FilterMode::Point;
        else if (c.word("linear")) *m = FilterMode::Linear;
        else error(lineNo, "expected 'filter MIN MAG MIP' with point or linear");
      }
    } else if (c.word("comparison")) {
      s.unsupported = "comparison samplers";
      return;
    } else {
      error(lineNo, fmt::format("unknown sampler line '{}' (expected filter or address)", line));
    }
    if (!c.atEnd()) error(lineNo, fmt::format("unexpected '{}'", c.rest()));
  }

  void sectionLine(ResourceSection& r, const std::string& line, int lineNo) {
    LineCursor c(line);
    using D = ResourceSection::Dimension;
    if (c.word("format")) {
      auto f = parseFormat(c);
      if (!f || !c.atEnd()) error(lineNo, fmt::format("unknown format '{}'", c.rest()));
      r.format = f->format;
      r.formatName = std::string(f->name);
      return;
    }
    c.setPosition(0);
    if (c.word("size")) {
      if (!c.ch('(')) error(lineNo, "expected 'size (2d, W, H)'");
      auto dims = [&](int n) {
        int v[3] = {1, 1, 1};
        for (int i = 0; i < n; ++i) {
          if (i && !c.ch(',')) error(lineNo, fmt::format("malformed size '{}'", line));
          auto x = c.integer();
          if (!x || *x < 1 || *x > 8192) error(lineNo, fmt::format("malformed size '{}' (1 to 8192 each)", line));
          v[i] = int(*x);
        }
        if (!c.ch(')') || !c.atEnd()) error(lineNo, fmt::format("malformed size '{}'", line));
        r.width = v[0], r.height = v[1], r.depth = v[2];
      };
      if (c.word("2d") && c.ch(',')) r.dimension = D::Tex2D, dims(2);
      else if (c.word("3d") && c.ch(',')) r.dimension = D::Tex3D, dims(3);
      else if (c.word("cube") && c.ch(',')) r.dimension = D::Cube, dims(1), r.height = r.width;
      else if ((c.word("buffer") || c.word("raw_buffer") || c.word("counter_buffer")) && c.ch(',')) {
        r.dimension = D::Buffer, dims(1);
        if (r.kind != ResourceSection::Kind::VertexBuffer) r.unsupported = "buffer views need a D3D10 device";
      } else if ((c.word("2darray") || c.word("2dms")) && c.ch(',')) {
        dims(3);
        r.unsupported = "array and multisampled textures need a D3D10 device";
      } else {
        dims(2);  // the older `size (W, H)`
        r.dimension = D::Tex2D;
      }
      return;
    }
    c.setPosition(0);
    if (c.word("levels")) {
      auto n = c.integer();
      if (!n || *n < 1 || *n > 14 || !c.atEnd()) error(lineNo, "expected 'levels N' (1 to 14)");
      r.levels = int(*n);
      return;
    }
    c.setPosition(0);
    if (c.word("stride")) {
      r.unsupported = "structured buffers need a D3D11 device";
      return;
    }
    if (!parseDataWords(line, oldTexture_, r.data))
      error(lineNo, fmt::format("unknown resource line '{}' (expected format, size, levels or data)", line));
  }

  void sectionLine(InputLayoutSection& l, const std::string& line, int lineNo) {
    LineCursor c(line);
    InputElement e;
    auto slot = c.integer();
    if (!slot || *slot < 0 || *slot > 15) error(lineNo, "expected 'SLOT FORMAT SEMANTIC [INDEX]'");
    e.slot = int(*slot);
    auto f = parseFormat(c);
    if (!f) error(lineNo, fmt::format("unknown format in '{}'", line));
    e.format = f->format;
    e.formatName = std::string(f->name);
    e.semantic = std::string(c.name());
    if (e.semantic.empty()) error(lineNo, "expected a semantic name after the format");
    if (!c.atEnd()) {
      auto idx = c.integer();
      if (!idx || *idx < 0 || *idx > 15 || !c.atEnd()) error(lineNo, "expected a semantic index 0-15");
      e.semanticIndex = int(*idx);
    }
    l.elements.push_back(std::move(e));
  }

  std::string_view text_;
  std::string path_;
  ShaderTestFile file_;
  bool oldTexture_ = false;
};

}  // namespace

ShaderTestFile parseShaderTest(std::string_view text, const std::string& path) {
  return FileParser(text, path).parse();
}

ShaderTestFile loadShaderTest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: error: cannot open the file", path);
  std::stringstream ss;
  ss << in.rdbuf();
  return parseShaderTest(ss.str(), path);
}

std::optional<ShaderModel> chooseShaderModel(const ShaderTestFile& file) {
  std::vector<const RequireSection*> requires_;
  bool runsBeforeFirstRequire = false;
  for (const auto& e : file.sections) {
    if (auto* r = std::get_if<RequireSection>(&e.section)) requires_.push_back(r);
    else if (requires_.empty() && !std::holds_alternative<UnsupportedSection>(e.section))
      runsBeforeFirstRequire = true;
  }
  for (ShaderModel m : {20, 30}) {
    if (requires_.empty() || runsBeforeFirstRequire) return m;
    for (const RequireSection* r : requires_)
      if (m >= r->minModel && m < r->belowModel) return m;
  }
  return std::nullopt;
}

}  // namespace refx::scene
