// Wavefront OBJ and MTL readers.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "refx/core/diagnostics.h"
#include "refx/core/text.h"
#include "refx/d3dx/obj.h"

namespace refx::d3dx {

namespace {

struct Word {
  std::string_view text;
  uint32_t column;  // 1-based
};

// One statement: its words (a '#' at the start of a word begins a comment) and the
// rest of the line after each word, for arguments that may hold spaces.
struct Statement {
  std::string_view line;
  uint32_t number = 0;
  std::vector<Word> words;
  std::string_view restAfter(size_t word) const {
    if (word + 1 >= words.size()) return {};
    size_t from = words[word + 1].column - 1;
    return trim(line.substr(from, lineEnd() - from));
  }
  size_t lineEnd() const {
    const Word& last = words.back();
    return last.column - 1 + last.text.size();
  }
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Calls `statement` for every non-empty line of `text`.
template <typename F>
void forEachStatement(std::string_view text, F statement) {
  Statement st;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++st.number;
    st.line = text.substr(pos, end - pos);
    st.words.clear();
    for (size_t i = 0; i < st.line.size();) {
      while (i < st.line.size() && isBlank(st.line[i])) ++i;
      if (i >= st.line.size() || st.line[i] == '#') break;
      size_t b = i;
      while (i < st.line.size() && !isBlank(st.line[i])) ++i;
      st.words.push_back({st.line.substr(b, i - b), uint32_t(b + 1)});
    }
    if (!st.words.empty()) statement(st);
    pos = end + 1;
  }
}

std::string quoted(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40)) out += (uint8_t(c) >= 0x20 && uint8_t(c) < 0x7f) ? c : '?';
  return "'" + out + (s.size() > 40 ? "...'" : "'");
}

class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void error(const Statement& st, uint32_t column, const std::string& msg) const {
    throw Error(SourceLocation{name_, int(st.number), int(column)}, msg);
  }
  uint32_t endColumn(const Statement& st) const { return uint32_t(st.lineEnd() + 1); }

  // Word i of the statement as a finite float.
  float number(const Statement& st, size_t i, const char* what) const {
    if (i >= st.words.size())
      error(st, endColumn(st), fmt::format("expected {} after {}", what, quoted(st.words[i - 1].text)));
    std::string_view w = st.words[i].text;
    const char* b = w.data() + (w[0] == '+' ? 1 : 0);
    float v = 0;
    auto r = std::from_chars(b, w.data() + w.size(), v);
    if (r.ptr != w.data() + w.size() || (r.ec != std::errc() && r.ec != std::errc::result_out_of_range))
      error(st, st.words[i].column, fmt::format("expected {} (a number), got {}", what, quoted(w)));
    if (r.ec != std::errc() || !std::isfinite(v))
      error(st, st.words[i].column, fmt::format("{} {} is not a finite float", what, quoted(w)));
    return v;
  }

 protected:
  std::string name_;
};

// MTL: newmtl, Kd, d, Tr, Ks, Ns, Ke, map_Kd.
class MtlReader : Reader {
 public:
  using Reader::Reader;

  void read(std::string_view text, std::map<std::string, XMaterial, std::less<>>& out) {
    XMaterial* m = nullptr;
    forEachStatement(text, [&](const Statement& st) {
      std::string_view key = st.words[0].text;
      if (key == "newmtl") {
        std::string_view name = st.restAfter(0);
        if (name.empty()) error(st, endColumn(st), "expected a material name after 'newmtl'");
        m = &out[std::string(name)];
        *m = XMaterial{};
        return;
      }
      bool known = key == "Kd" || key == "Ks" || key == "Ke" || key == "Ns" || key == "d" || key == "Tr" ||
                   key == "map_Kd";
      if (!known) return;  // Ka, illum, other maps: not part of the D3DX material
      if (!m) error(st, st.words[0].column, fmt::format("'{}' before the first 'newmtl'", key));
      if (key == "Kd" || key == "Ks" || key == "Ke") {
        // "Kd r g b", or "Kd r" for grey.
        float r = number(st, 1, "the red component");
        float g = st.words.size() > 2 ? number(st, 2, "the green component") : r;
        float b = st.words.size() > 2 ? number(st, 3, "the blue component") : r;
        if (key == "Kd") m->diffuse.r = r, m->diffuse.g = g, m->diffuse.b = b;
        if (key == "Ks") m->specular = {r, g, b};
        if (key == "Ke") m->emissive = {r, g, b};
      } else if (key == "Ns") {
        m->power = number(st, 1, "the specular exponent");
      } else if (key == "d") {
        size_t i = st.words.size() > 2 && st.words[1].text == "-halo" ? 2 : 1;
        m->diffuse.a = number(st, i, "the dissolve value");
      } else if (key == "Tr") {
        m->diffuse.a = 1.0f - number(st, 1, "the transparency");
      } else {
        m->textureFilename = mapFile(st);
      }
    });
  }

 private:
  // "map_Kd [-option args...] file name": options and their argument counts.
  std::string mapFile(const Statement& st) const {
    struct Option {
      const char* name;
      size_t minArgs, maxArgs;
    };
    static const Option kOptions[] = {
        {"-blendu", 1, 1}, {"-blendv", 1, 1}, {"-bm", 1, 1}, {"-boost", 1, 1}, {"-cc", 1, 1},
        {"-clamp", 1, 1},  {"-imfchan", 1, 1}, {"-mm", 2, 2}, {"-o", 1, 3},    {"-s", 1, 3},
        {"-t", 1, 3},      {"-texres", 1, 1}, {"-type", 1, 1}};
    size_t i = 1;
    while (i < st.words.size() && st.words[i].text.size() > 1 && st.words[i].text[0] == '-') {
      const Option* o = nullptr;
      for (const Option& k : kOptions)
        if (st.words[i].text == k.name) o = &k;
      if (!o) error(st, st.words[i].column, fmt::format("unknown map_Kd option {}", quoted(st.words[i].text)));
      ++i;
      for (size_t a = 0; a < o->maxArgs && i < st.words.size(); ++a, ++i) {
        float v;
        std::string_view w = st.words[i].text;
        bool numeric = std::from_chars(w.data(), w.data() + w.size(), v).ptr == w.data() + w.size();
        if (a >= o->minArgs && !numeric) break;  // -o/-s/-t take 1 to 3 numbers
      }
    }
    if (i >= st.words.size()) error(st, endColumn(st), "expected a file name after 'map_Kd'");
    return std::string(st.restAfter(i - 1));
  }
};

struct CornerKey {
  uint32_t v, vt, vn;  // vt, vn: index + 1, 0 = absent
  bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    return std::hash<uint64_t>()((uint64_t(k.v) << 32) ^ (uint64_t(k.vt) << 16) ^ k.vn);
  }
};

class ObjReader : Reader {
 public:
  ObjReader(std::string name, std::vector<std::string>* warnings, const std::string* dir)
      : Reader(std::move(name)), warnings_(warnings), dir_(dir) {}

  Mesh read(std::string_view text) {
    forEachStatement(text, [&](const Statement& st) { statement(st); });
    return finish();
  }

 private:
  std::vector<std::string>* warnings_;
  const std::string* dir_;  // null: mtllib is not read
  std::vector<Vec3> v_, vn_;
  std::vector<Vec2> vt_;
  std::unordered_map<CornerKey, uint32_t, CornerHash> vertexOf_;
  std::vector<CornerKey> vertices_;
  bool anyTex_ = false, anyNormal_ = false;
  std::vector<uint32_t> indices_;
  std::vector<int64_t> attributes_;  // material id per triangle, -1 before the first usemtl
  std::map<std::string, uint32_t, std::less<>> materialIds_;
  std::vector<std::pair<std::string, uint32_t>> materialUse_;  // name, line of first use
  std::map<std::string, XMaterial, std::less<>> library_;
  int64_t current_ = -1;

  void warn(uint32_t line, const std::string& msg) {
    std::string w = fmt::format("{}:{}: warning: {}", name_, line, msg);
    if (warnings_)
      warnings_->push_back(std::move(w));
    else
      std::fprintf(stderr, "%s\n", w.c_str());
  }

  void statement(const Statement& st) {
    std::string_view key = st.words[0].text;
    if (key == "v") {
      v_.push_back({number(st, 1, "the x coordinate"), number(st, 2, "the y coordinate"),
                    -number(st, 3, "the z coordinate")});
    } else if (key == "vt") {
      float u = number(st, 1, "the u coordinate");
      float v = st.words.size() > 2 ? number(st, 2, "the v coordinate") : 0.0f;
      vt_.push_back({u, 1.0f - v});
    } else if (key == "vn") {
      vn_.push_back({number(st, 1, "the x of the normal"), number(st, 2, "the y of the normal"),
                     -number(st, 3, "the z of the normal")});
    } else if (key == "f") {
      face(st);
    } else if (key == "usemtl") {
      std::string_view name = st.restAfter(0);
      if (name.empty()) error(st, endColumn(st), "expected a material name after 'usemtl'");
      current_ = materialId(name, st.number);
    } else if (key == "mtllib") {
      if (st.words.size() < 2) error(st, endColumn(st), "expected a file name after 'mtllib'");
      for (size_t i = 1; i < st.words.size(); ++i) library(st, std::string(st.words[i].text));
    }
  }

  uint32_t materialId(std::string_view name, uint32_t line) {
    auto it = materialIds_.find(name);
    if (it != materialIds_.end()) return it->second;
    uint32_t id = uint32_t(materialUse_.size());
    materialIds_.emplace(std::string(name), id);
    materialUse_.emplace_back(std::string(name), line);
    return id;
  }

  void library(const Statement& st, const std::string& file) {
    if (!dir_) {
      warn(st.number, fmt::format("material library '{}' not read (mesh read from memory)", file));
      return;
    }
    std::string path = dir_->empty() ? file : *dir_ + "/" + file;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      warn(st.number, fmt::format("material library '{}' cannot be opened: {}", path, std::strerror(errno)));
      return;
    }
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    MtlReader(path).read(text, library_);
  }

  // One corner "v", "v/vt", "v//vn" or "v/vt/vn".
  uint32_t corner(const Statement& st, const Word& w) {
    CornerKey key{0, 0, 0};
    std::string_view parts[3];
    size_t n = 0, from = 0;
    for (size_t i = 0; i <= w.text.size(); ++i)
      if (i == w.text.size() || w.text[i] == '/') {
        if (n == 3) error(st, w.column, fmt::format("expected v, v/vt, v//vn or v/vt/vn, got {}", quoted(w.text)));
        parts[n++] = w.text.substr(from, i - from);
        from = i + 1;
      }
    static const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    static const char* kPlural[3] = {"vertices", "texture coordinates", "normals"};
    size_t counts[3] = {v_.size(), vt_.size(), vn_.size()};
    uint32_t* out[3] = {&key.v, &key.vt, &key.vn};
    for (size_t k = 0; k < n; ++k) {
      if (parts[k].empty() && k > 0) continue;  // v//vn, or a trailing '/'
      int64_t i = 0;
      auto r = std::from_chars(parts[k].data(), parts[k].data() + parts[k].size(), i);
      if (parts[k].empty() || r.ptr != parts[k].data() + parts[k].size() || r.ec != std::errc())
        error(st, w.column, fmt::format("expected a {} index in {}, got {}", kWhat[k], quoted(w.text),
                                        quoted(parts[k])));
      int64_t count = int64_t(counts[k]);
      if (i == 0) error(st, w.column, fmt::format("{} index 0 in {}: OBJ indices start at 1", kWhat[k], quoted(w.text)));
      int64_t index = i > 0 ? i - 1 : count + i;  // negative: relative to the end
      if (index < 0 || index >= count)
        error(st, w.column, fmt::format("{} index {} in {} refers to none of the {} {} read so far", kWhat[k], i,
                                        quoted(w.text), count, kPlural[k]));
      *out[k] = uint32_t(index) + (k > 0 ? 1 : 0);
    }
    anyTex_ = anyTex_ || key.vt;
    anyNormal_ = anyNormal_ || key.vn;
    auto [it, added] = vertexOf_.try_emplace(key, uint32_t(vertices_.size()));
    if (added) vertices_.push_back(key);
    return it->second;
  }

  void face(const Statement& st) {
    if (st.words.size() < 4)
      error(st, endColumn(st), fmt::format("a face needs at least 3 corners, this one has {}", st.words.size() - 1));
    std::vector<uint32_t> c;
    c.reserve(st.words.size() - 1);
    for (size_t i = 1; i < st.words.size(); ++i) c.push_back(corner(st, st.words[i]));
    // Fan (c0, ck, ck+1), wound the other way for Direct3D's clockwise front faces.
    for (size_t k = 1; k + 1 < c.size(); ++k) {
      indices_.insert(indices_.end(), {c[0], c[k + 1], c[k]});
      attributes_.push_back(current_);
    }
  }

  Mesh finish() {
    uint32_t code = d3d::FVF_XYZ | (anyNormal_ ? d3d::FVF_NORMAL : 0) | (anyTex_ ? d3d::fvfTex(1) : 0);
    Mesh m(code, uint32_t(vertices_.size()), 0);
    for (uint32_t i = 0; i < vertices_.size(); ++i) {
      const CornerKey& k = vertices_[i];
      m.setPosition(i, v_[k.v]);
      if (anyNormal_) m.setNormal(i, k.vn ? vn_[k.vn - 1] : Vec3());
      if (anyTex_) m.setTexCoord(i, 0, k.vt ? vt_[k.vt - 1].x : 0.0f, k.vt ? vt_[k.vt - 1].y : 0.0f);
    }
    m.indices = std::move(indices_);
    if (!materialUse_.empty()) {
      for (const auto& [name, line] : materialUse_) {
        auto it = library_.find(name);
        if (it != library_.end()) {
          m.materials.push_back(it->second);
        } else {
          if (dir_) warn(line, fmt::format("material '{}' is not defined in a material library", name));
          m.materials.push_back(XMaterial{});
        }
      }
      // Faces before the first usemtl: a default material after the named ones.
      uint32_t fallback = uint32_t(m.materials.size());
      bool fallbackUsed = false;
      m.attributes.resize(attributes_.size());
      for (size_t f = 0; f < attributes_.size(); ++f) {
        fallbackUsed = fallbackUsed || attributes_[f] < 0;
        m.attributes[f] = attributes_[f] < 0 ? fallback : uint32_t(attributes_[f]);
      }
      if (fallbackUsed) m.materials.push_back(XMaterial{});
    }
    return m;
  }
};

std::string directoryOf(const std::string& path) {
  size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

}  // namespace

Mesh loadOBJFromMemory(std::string_view text, const std::string& name, std::vector<std::string>* warnings) {
  return ObjReader(name, warnings, nullptr).read(text);
}

Mesh loadOBJ(const std::string& path, std::vector<std::string>* warnings) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: error: cannot open: {}", path, std::strerror(errno));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail("{}: error: read failed", path);
  std::string dir = directoryOf(path);
  return ObjReader(path, warnings, &dir).read(text);
}

}  // namespace refx::d3dx
