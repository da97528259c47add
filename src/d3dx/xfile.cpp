// .x files: the data-object reader shared by the text and binary encodings, and the
// merge of all Mesh objects into one mesh (D3DXLoadMeshFromX).
//
// The reader knows the standard templates by name (Mesh, MeshNormals,
// MeshTextureCoords, MeshVertexColors, MeshMaterialList, Material, TextureFilename,
// Frame, FrameTransformMatrix, DeclData); every other data object and every template
// declaration is skipped by counting braces, without recursion.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <unordered_map>

#include <fmt/format.h>

#include "d3dx/xfile_internal.h"
#include "refx/core/diagnostics.h"
#include "refx/core/text.h"
#include "refx/d3dx/xfile.h"
#include "refx/resource/vertex_format.h"

namespace refx::d3dx {

namespace detail::xfile {

Header readHeader(std::span<const uint8_t> bytes, const std::string& name) {
  auto failHeader = [&](const std::string& msg) {
    throw Error(SourceLocation{name, 1, 1}, msg);
  };
  if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), "xof ", 4) != 0)
    failHeader("not a .x file (expected the header \"xof 0303txt 0032\")");
  std::string_view h(reinterpret_cast<const char*>(bytes.data()), kHeaderSize);
  for (int i = 4; i < 8; ++i)
    if (h[i] < '0' || h[i] > '9') failHeader(fmt::format("bad version '{}' in the .x header", h.substr(4, 4)));
  Header out;
  std::string_view format = h.substr(8, 4), floats = h.substr(12, 4);
  if (format == "txt ") {
    out.binary = false;
  } else if (format == "bin ") {
    out.binary = true;
  } else if (format == "tzip" || format == "bzip") {
    failHeader(fmt::format("compressed .x files ('{}', MSZIP) are not supported; save the file as "
                           "'txt ' or 'bin '", format));
  } else {
    failHeader("unknown .x format (expected 'txt ' or 'bin ' after the version)");
  }
  if (floats == "0032") {
    out.floatBits = 32;
  } else if (floats == "0064") {
    out.floatBits = 64;
  } else {
    failHeader("unknown float size in the .x header (expected 0032 or 0064)");
  }
  return out;
}

}  // namespace detail::xfile

namespace xfile = detail::xfile;

namespace {

using xfile::Lexer;
using xfile::Tok;
using xfile::Token;

constexpr int kMaxFrameDepth = 64;
constexpr size_t kMaxTextureName = 1024;
constexpr int kMaxTexSets = 8;


// One Mesh data object as the file describes it.
struct Part {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<uint32_t> polySizes;    // vertex count of each polygon
  std::vector<uint32_t> polyIndices;  // all polygons' position indices
  bool hasNormals = false;
  std::vector<Vec3> normals;
  std::vector<uint32_t> normalIndices;  // parallel to polyIndices
  int texDims[kMaxTexSets] = {};        // 0: set absent
  std::vector<Vec4> tex[kMaxTexSets];   // per position
  bool hasColors = false;
  std::vector<D3DColor> colors;         // per position
  std::vector<uint32_t> polyMaterial;   // empty: no MeshMaterialList
  std::vector<XMaterial> materials;
  Matrix world = Matrix::identity();
  bool transformed = false;
};

// What a value is, for messages; formatted only when an error is reported.
struct What {
  const char* text;  // fmt pattern with up to two {} for a and b
  uint32_t a = 0, b = 0;
  std::string str() const { return fmt::format(fmt::runtime(text), a, b); }
};

std::string printable(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40)) out += (uint8_t(c) >= 0x20 && uint8_t(c) < 0x7f) ? c : '?';
  if (s.size() > 40) out += "...";
  return out;
}

std::string describe(const Token& t) {
  switch (t.kind) {
    case Tok::End: return "the end of the file";
    case Tok::String: return "the string \"" + printable(t.text) + "\"";
    case Tok::Guid: return "<" + printable(t.text) + ">";
    case Tok::Integer:
    case Tok::Float:
      return t.text.empty() ? fmt::format("the number {}", t.number) : "'" + printable(t.text) + "'";
    default: return "'" + printable(t.text) + "'";
  }
}

class Parser {
 public:
  Parser(Lexer& lex, size_t fileSize) : lex_(lex), size_(fileSize) { cur_ = lex_.next(); }

  std::vector<Part> parseFile() {
    while (cur_.kind != Tok::End) {
      switch (cur_.kind) {
        case Tok::Template: skipTemplate(); break;
        case Tok::Name: dataObject(nullptr, 0); break;
        case Tok::OBrace: skipBlock(take(), "reference"); break;
        case Tok::Comma:
        case Tok::Semicolon: take(); break;
        default: error(cur_, "expected a template or a data object, got " + describe(cur_));
      }
    }
    if (parts_.empty()) error(cur_, "the file holds no Mesh object");
    return std::move(parts_);
  }

 private:
  Lexer& lex_;
  size_t size_;
  Token cur_;
  std::vector<Part> parts_;
  std::map<std::string, XMaterial> namedMaterials_;

  Token take() {
    Token t = std::move(cur_);
    cur_ = lex_.next();
    return t;
  }

  [[noreturn]] void error(const Token& at, const std::string& msg) const {
    throw Error(lex_.where(at) + ": error: " + msg);
  }

  // ---- values ----------------------------------------------------------------

  // Members end with ';' (array elements with ','); text files need at least one,
  // any run of them is accepted.
  void separator(const What& after) {
    if (cur_.kind != Tok::Semicolon && cur_.kind != Tok::Comma) {
      if (lex_.separatorsRequired())
        error(cur_, fmt::format("expected ';' after {}, got {}", after.str(), describe(cur_)));
      return;
    }
    while (cur_.kind == Tok::Semicolon || cur_.kind == Tok::Comma) take();
  }

  uint32_t readDWORD(const What& what) {
    if (cur_.kind != Tok::Integer)
      error(cur_, fmt::format("expected {} (an unsigned integer), got {}", what.str(), describe(cur_)));
    if (cur_.number > double(std::numeric_limits<uint32_t>::max()))
      error(cur_, fmt::format("{} {} does not fit in a DWORD", what.str(), describe(cur_)));
    uint32_t v = uint32_t(cur_.number);
    take();
    separator(what);
    return v;
  }

  // A count followed by `count` elements of `numbers` numbers each.
  uint32_t readCount(const What& what, uint32_t numbers) {
    Token at = cur_;
    uint32_t n = readDWORD(what);
    size_t left = cur_.offset < size_ ? size_ - cur_.offset : 0;
    if (uint64_t(n) * numbers * lex_.bytesPerNumber() > left)
      error(at, fmt::format("{} {} is larger than the rest of the file can hold", what.str(), n));
    return n;
  }

  float readFloat(const What& what) {
    if (cur_.kind != Tok::Integer && cur_.kind != Tok::Float)
      error(cur_, fmt::format("expected {} (a number), got {}", what.str(), describe(cur_)));
    float v;
    if (!cur_.text.empty()) {  // text: parsed once, as a float (no double rounding)
      const char* b = cur_.text.data() + (cur_.text[0] == '+' ? 1 : 0);
      auto r = std::from_chars(b, cur_.text.data() + cur_.text.size(), v);
      if (r.ec != std::errc())
        error(cur_, fmt::format("{} {} is out of the range of a float", what.str(), describe(cur_)));
    } else {
      v = float(cur_.number);
    }
    if (!std::isfinite(v))
      error(cur_, fmt::format("{} is not a finite float ({})", what.str(), describe(cur_)));
    take();
    separator(what);
    return v;
  }

  std::string readString(const What& what) {
    if (cur_.kind != Tok::String)
      error(cur_, fmt::format("expected {} (a quoted string), got {}", what.str(), describe(cur_)));
    std::string s = take().text;
    separator(what);
    return s;
  }

  Vec3 readVector(const char* x, const char* y, const char* z, uint32_t i) {
    float a = readFloat({x, i}), b = readFloat({y, i}), c = readFloat({z, i});
    return {a, b, c};
  }

  // ---- objects ---------------------------------------------------------------

  struct Head {
    Token type;
    std::string name;
  };

  // At the template name: Type [name] { [<guid>]
  Head openObject() {
    Head h{take(), {}};
    if (cur_.kind == Tok::Name) h.name = take().text;
    if (cur_.kind != Tok::OBrace)
      error(cur_, fmt::format("expected '{{' after '{}', got {}", printable(h.type.text), describe(cur_)));
    take();
    if (cur_.kind == Tok::Guid) take();
    return h;
  }

  // Skips to the '}' matching an already consumed '{'.
  void skipBlock(const Token& open, const std::string& what) {
    size_t depth = 1;
    while (depth > 0) {
      if (cur_.kind == Tok::End)
        error(cur_, fmt::format("expected '}}' to close the {} opened at {}, got the end of the file",
                                what, lex_.where(open)));
      if (cur_.kind == Tok::OBrace) ++depth;
      if (cur_.kind == Tok::CBrace) --depth;
      take();
    }
  }

  void skipTemplate() {
    take();
    if (cur_.kind != Tok::Name) error(cur_, "expected the template name after 'template', got " + describe(cur_));
    Token name = take();
    if (cur_.kind != Tok::OBrace)
      error(cur_, fmt::format("expected '{{' after 'template {}', got {}", printable(name.text), describe(cur_)));
    skipBlock(take(), fmt::format("template '{}'", printable(name.text)));
  }

  // Child objects until the object's '}'. `child` is called at the template name of
  // each child data object and returns false for those it does not know (skipped);
  // `reference` gets the name inside a {Name} reference.
  template <typename Child, typename Reference>
  void children(const Head& h, Child child, Reference reference) {
    for (;;) {
      switch (cur_.kind) {
        case Tok::CBrace: take(); return;
        case Tok::Comma:
        case Tok::Semicolon: take(); break;
        case Tok::Name:
          if (!child(std::string(cur_.text))) skipObject();
          break;
        case Tok::OBrace: {
          take();
          std::string name;
          Token at = cur_;
          while (cur_.kind == Tok::Name || cur_.kind == Tok::Guid) {
            if (cur_.kind == Tok::Name) name = cur_.text;
            take();
          }
          if (cur_.kind != Tok::CBrace)
            error(cur_, "expected '}' to end the reference, got " + describe(cur_));
          take();
          reference(name, at);
          break;
        }
        case Tok::End:
          error(cur_, fmt::format("expected '}}' to close '{}' opened at {}, got the end of the file",
                                  printable(h.type.text), lex_.where(h.type)));
        default:
          error(cur_, fmt::format("expected a child object or '}}' in '{}', got {}",
                                  printable(h.type.text), describe(cur_)));
      }
    }
  }
  static bool unknownChild(const std::string&) { return false; }
  static void ignoreReference(const std::string&, const Token&) {}
  // The end of an object whose members have been read; its children are skipped.
  void finish(const Head& h) { children(h, unknownChild, ignoreReference); }

  void skipObject() {
    Head h = openObject();
    skipBlock(h.type, fmt::format("'{}'", printable(h.type.text)));
  }

  // A data object where meshes may appear (top level, Frame). Collects the indices of
  // the meshes it adds into `meshes` (null at the top level).
  bool dataObject(std::vector<size_t>* meshes, int depth) {
    const std::string type = cur_.text;
    if (equalsNoCase(type, "Mesh")) {
      if (meshes) meshes->push_back(parts_.size());
      parts_.push_back(mesh());
    } else if (equalsNoCase(type, "Frame")) {
      std::vector<size_t> inner = frame(depth + 1);
      if (meshes) meshes->insert(meshes->end(), inner.begin(), inner.end());
    } else if (equalsNoCase(type, "Material")) {
      material();
    } else {
      skipObject();
    }
    return true;
  }

  std::vector<size_t> frame(int depth) {
    if (depth > kMaxFrameDepth) error(cur_, fmt::format("Frames nested deeper than {} levels", kMaxFrameDepth));
    Head h = openObject();
    std::vector<size_t> meshes;
    Matrix local = Matrix::identity();
    bool hasLocal = false;
    children(
        h,
        [&](const std::string& type) {
          if (equalsNoCase(type, "FrameTransformMatrix")) {
            Head m = openObject();
            for (int i = 0; i < 16; ++i)
              local.m[i / 4][i % 4] = readFloat({"element {} of the frame matrix", uint32_t(i)});
            hasLocal = true;
            finish(m);
            return true;
          }
          return dataObject(&meshes, depth);
        },
        ignoreReference);  // a {Mesh} reference would load a top-level mesh twice
    if (hasLocal && !(local == Matrix::identity()))
      for (size_t i : meshes) {
        parts_[i].world = parts_[i].world * local;  // child frame first, then this frame
        parts_[i].transformed = true;
      }
    return meshes;
  }

  XMaterial material() {
    Head h = openObject();
    XMaterial m;
    m.diffuse.r = readFloat({"the red of the face color"});
    m.diffuse.g = readFloat({"the green of the face color"});
    m.diffuse.b = readFloat({"the blue of the face color"});
    m.diffuse.a = readFloat({"the alpha of the face color"});
    m.power = readFloat({"the specular power"});
    m.specular = readVector("the red of the specular color", "the green of the specular color",
                            "the blue of the specular color", 0);
    m.emissive = readVector("the red of the emissive color", "the green of the emissive color",
                            "the blue of the emissive color", 0);
    children(
        h,
        [&](const std::string& type) {
          if (!equalsNoCase(type, "TextureFilename")) return false;
          Head t = openObject();
          Token at = cur_;
          m.textureFilename = readString({"the texture file name"});
          // Each {reference} copies the material: a bound keeps a small file from
          // growing into a huge mesh.
          if (m.textureFilename.size() > kMaxTextureName)
            error(at, fmt::format("the texture file name is {} bytes long, more than the {} accepted",
                                  m.textureFilename.size(), kMaxTextureName));
          finish(t);
          return true;
        },
        ignoreReference);
    if (!h.name.empty()) namedMaterials_[h.name] = m;
    return m;
  }

  Part mesh() {
    Head h = openObject();
    Part p;
    p.name = h.name;
    uint32_t nv = readCount({"the vertex count"}, 3);
    p.positions.resize(nv);
    for (uint32_t i = 0; i < nv; ++i)
      p.positions[i] = readVector("the x of vertex {}", "the y of vertex {}", "the z of vertex {}", i);
    uint32_t nf = readCount({"the face count"}, 4);
    p.polySizes.resize(nf);
    for (uint32_t f = 0; f < nf; ++f) {
      Token at = cur_;
      uint32_t n = readCount({"the index count of face {}", f}, 1);
      if (n < 3) error(at, fmt::format("face {} has {} indices; a face needs at least 3", f, n));
      p.polySizes[f] = n;
      for (uint32_t k = 0; k < n; ++k) {
        Token it = cur_;
        uint32_t v = readDWORD({"index {} of face {}", k, f});
        if (v >= nv)
          error(it, fmt::format("index {} of face {} is {}, but the mesh has {} vertices", k, f, v, nv));
        p.polyIndices.push_back(v);
      }
    }
    bool seen[5] = {};
    auto once = [&](int which, const Token& at) {
      if (seen[which]) error(at, fmt::format("a second '{}' in the same Mesh", printable(at.text)));
      seen[which] = true;
    };
    children(
        h,
        [&](const std::string& type) {
          Token at = cur_;
          if (equalsNoCase(type, "MeshNormals")) {
            once(0, at);
            meshNormals(p);
          } else if (equalsNoCase(type, "MeshTextureCoords")) {
            once(1, at);
            meshTextureCoords(p);
          } else if (equalsNoCase(type, "MeshVertexColors")) {
            once(2, at);
            meshVertexColors(p);
          } else if (equalsNoCase(type, "MeshMaterialList")) {
            once(3, at);
            meshMaterialList(p);
          } else if (equalsNoCase(type, "DeclData")) {
            once(4, at);
            declData(p);
          } else {
            return false;
          }
          return true;
        },
        ignoreReference);
    return p;
  }

  void meshNormals(Part& p) {
    Head h = openObject();
    uint32_t nn = readCount({"the normal count"}, 3);
    std::vector<Vec3> normals(nn);
    for (uint32_t i = 0; i < nn; ++i)
      normals[i] = readVector("the x of normal {}", "the y of normal {}", "the z of normal {}", i);
    Token at = cur_;
    uint32_t nf = readCount({"the face count of MeshNormals"}, 4);
    if (nf != p.polySizes.size())
      error(at, fmt::format("MeshNormals has {} faces, the mesh has {}", nf, p.polySizes.size()));
    std::vector<uint32_t> indices;
    indices.reserve(p.polyIndices.size());
    for (uint32_t f = 0; f < nf; ++f) {
      Token ct = cur_;
      uint32_t n = readDWORD({"the index count of normal face {}", f});
      if (n != p.polySizes[f])
        error(ct, fmt::format("face {} of MeshNormals has {} indices, face {} of the mesh has {}", f, n, f,
                              p.polySizes[f]));
      for (uint32_t k = 0; k < n; ++k) {
        Token it = cur_;
        uint32_t v = readDWORD({"index {} of normal face {}", k, f});
        if (v >= nn)
          error(it, fmt::format("normal index {} of face {} is {}, but MeshNormals has {} normals", k, f, v, nn));
        indices.push_back(v);
      }
    }
    finish(h);
    p.hasNormals = true;
    p.normals = std::move(normals);
    p.normalIndices = std::move(indices);
  }

  void meshTextureCoords(Part& p) {
    Head h = openObject();
    Token at = cur_;
    uint32_t n = readCount({"the texture coordinate count"}, 2);
    if (n != p.positions.size())
      error(at, fmt::format("MeshTextureCoords has {} coordinates, the mesh has {} vertices", n,
                            p.positions.size()));
    std::vector<Vec4> uv(n);
    for (uint32_t i = 0; i < n; ++i) {
      uv[i].x = readFloat({"the u of texture coordinate {}", i});
      uv[i].y = readFloat({"the v of texture coordinate {}", i});
    }
    finish(h);
    p.tex[0] = std::move(uv);
    p.texDims[0] = 2;
  }

  void meshVertexColors(Part& p) {
    Head h = openObject();
    uint32_t n = readCount({"the vertex color count"}, 5);
    // Vertices the list leaves out are opaque white.
    std::vector<D3DColor> colors(p.positions.size(), 0xffffffffu);
    for (uint32_t i = 0; i < n; ++i) {
      Token at = cur_;
      uint32_t v = readDWORD({"the vertex index of vertex color {}", i});
      if (v >= p.positions.size())
        error(at, fmt::format("vertex color {} is for vertex {}, but the mesh has {} vertices", i, v,
                              p.positions.size()));
      Color4 c;
      c.r = readFloat({"the red of vertex color {}", i});
      c.g = readFloat({"the green of vertex color {}", i});
      c.b = readFloat({"the blue of vertex color {}", i});
      c.a = readFloat({"the alpha of vertex color {}", i});
      colors[v] = colorToD3D(c);
    }
    finish(h);
    p.hasColors = true;
    p.colors = std::move(colors);
  }

  void meshMaterialList(Part& p) {
    Head h = openObject();
    uint32_t nm = readDWORD({"the material count"});
    Token at = cur_;
    uint32_t ni = readCount({"the face index count"}, 1);
    uint32_t nf = uint32_t(p.polySizes.size());
    if (ni > nf) error(at, fmt::format("MeshMaterialList has {} face indexes, the mesh has {} faces", ni, nf));
    std::vector<uint32_t> ids(nf, 0);
    for (uint32_t f = 0; f < ni; ++f) {
      Token it = cur_;
      ids[f] = readDWORD({"the material of face {}", f});
      if (ids[f] >= nm)
        error(it, fmt::format("face {} uses material {}, but the list has {} materials", f, ids[f], nm));
    }
    // Fewer indexes than faces: the last one repeats.
    for (uint32_t f = ni; f < nf && ni > 0; ++f) ids[f] = ids[ni - 1];
    std::vector<XMaterial> materials;
    auto tooMany = [&](const Token& t) {
      if (materials.size() >= nm)
        error(t, fmt::format("MeshMaterialList declares {} materials but holds more", nm));
    };
    children(
        h,
        [&](const std::string& type) {
          if (!equalsNoCase(type, "Material")) return false;
          tooMany(cur_);
          materials.push_back(material());
          return true;
        },
        [&](const std::string& name, const Token& t) {
          auto it = namedMaterials_.find(name);
          if (it == namedMaterials_.end())
            error(t, fmt::format("material '{}' is not defined before this reference", printable(name)));
          tooMany(t);
          materials.push_back(it->second);
        });
    if (materials.size() != nm)
      error(h.type, fmt::format("MeshMaterialList declares {} materials but holds {}", nm, materials.size()));
    p.polyMaterial = std::move(ids);
    p.materials = std::move(materials);
  }

  // DeclData: D3DVERTEXELEMENT9 (Type, Method, Usage, UsageIndex) list and the vertex
  // data as DWORDs. TEXCOORDn (FLOAT1..4) becomes texture set n, NORMAL (FLOAT3) the
  // normals when there is no MeshNormals, COLOR0 (D3DCOLOR) the vertex colors.
  void declData(Part& p) {
    Head h = openObject();
    uint32_t ne = readCount({"the vertex element count"}, 4);
    struct Element {
      uint32_t type, usage, index;
    };
    std::vector<Element> elements(ne);
    uint64_t dwordsPerVertex = 0;
    for (uint32_t i = 0; i < ne; ++i) {
      Token at = cur_;
      elements[i].type = readDWORD({"the type of vertex element {}", i});
      readDWORD({"the method of vertex element {}", i});
      elements[i].usage = readDWORD({"the usage of vertex element {}", i});
      elements[i].index = readDWORD({"the usage index of vertex element {}", i});
      if (elements[i].type > d3d::DECLTYPE_FLOAT16_4)
        error(at, fmt::format("vertex element {} has the unknown D3DDECLTYPE {}", i, elements[i].type));
      dwordsPerVertex += declTypeSize(uint8_t(elements[i].type)) / 4;
    }
    Token at = cur_;
    uint32_t nd = readCount({"the DWORD count of the vertex data"}, 1);
    uint64_t nv = p.positions.size();
    if (nd != dwordsPerVertex * nv)
      error(at, fmt::format("DeclData holds {} DWORDs; {} vertices of {} DWORDs need {}", nd, nv,
                            dwordsPerVertex, dwordsPerVertex * nv));
    std::vector<uint32_t> data(nd);
    for (uint32_t i = 0; i < nd; ++i) data[i] = readDWORD({"DWORD {} of the vertex data", i});
    finish(h);

    auto floatAt = [&](size_t i, uint32_t v) {
      float f;
      std::memcpy(&f, &data[i], 4);
      if (!std::isfinite(f)) error(at, fmt::format("DeclData vertex {} holds a value that is not a finite float", v));
      return f;
    };
    uint32_t off = 0;
    for (const Element& e : elements) {
      if (e.usage == d3d::DECLUSAGE_TEXCOORD && e.type <= d3d::DECLTYPE_FLOAT4 && e.index < kMaxTexSets) {
        int dims = int(e.type) + 1;
        p.texDims[e.index] = dims;
        p.tex[e.index].assign(nv, Vec4());
        for (uint32_t v = 0; v < nv; ++v)
          for (int c = 0; c < dims; ++c) p.tex[e.index][v][c] = floatAt(v * dwordsPerVertex + off + c, v);
      } else if (e.usage == d3d::DECLUSAGE_NORMAL && e.type == d3d::DECLTYPE_FLOAT3 && !p.hasNormals) {
        p.normals.resize(nv);
        for (uint32_t v = 0; v < nv; ++v) {
          size_t b = v * dwordsPerVertex + off;
          p.normals[v] = {floatAt(b, v), floatAt(b + 1, v), floatAt(b + 2, v)};
        }
        p.normalIndices = p.polyIndices;
        p.hasNormals = true;
      } else if (e.usage == d3d::DECLUSAGE_COLOR && e.type == d3d::DECLTYPE_D3DCOLOR && e.index == 0) {
        p.colors.resize(nv);
        for (uint32_t v = 0; v < nv; ++v) p.colors[v] = data[v * dwordsPerVertex + off];
        p.hasColors = true;
      }
      off += declTypeSize(uint8_t(e.type)) / 4;
    }
  }
};

// A part as an indexed triangle list: vertex i is position i with the first normal a
// face gives it; a position that faces give other normals too gets copies after the
// file's vertices.
struct Built {
  std::vector<uint32_t> source;  // position index of each vertex
  std::vector<Vec3> normals;     // each vertex's normal (hasNormals)
  std::vector<uint32_t> triangles;
  std::vector<uint32_t> triangleMaterial;
};

Built build(const Part& p) {
  Built b;
  uint32_t nv = uint32_t(p.positions.size());
  b.source.resize(nv);
  for (uint32_t i = 0; i < nv; ++i) b.source[i] = i;
  std::vector<uint32_t> corner(p.polyIndices.size());
  if (p.hasNormals) {
    // Unused positions keep the normal of the same index when there is one.
    b.normals.resize(nv);
    for (uint32_t i = 0; i < nv && i < p.normals.size(); ++i) b.normals[i] = p.normals[i];
    std::vector<int64_t> firstNormal(nv, -1);
    std::unordered_map<uint64_t, uint32_t> copies;
    for (size_t c = 0; c < corner.size(); ++c) {
      uint32_t v = p.polyIndices[c], n = p.normalIndices[c];
      if (firstNormal[v] < 0) {
        firstNormal[v] = n;
        b.normals[v] = p.normals[n];
        corner[c] = v;
      } else if (uint32_t(firstNormal[v]) == n) {
        corner[c] = v;
      } else {
        auto [it, added] = copies.try_emplace((uint64_t(v) << 32) | n, uint32_t(b.source.size()));
        if (added) {
          b.source.push_back(v);
          b.normals.push_back(p.normals[n]);
        }
        corner[c] = it->second;
      }
    }
  } else {
    corner = p.polyIndices;
  }
  size_t c = 0;
  for (size_t f = 0; f < p.polySizes.size(); ++f) {
    uint32_t n = p.polySizes[f];
    for (uint32_t k = 1; k + 1 < n; ++k) {  // fan around the first corner
      b.triangles.insert(b.triangles.end(), {corner[c], corner[c + k], corner[c + k + 1]});
      if (!p.polyMaterial.empty()) b.triangleMaterial.push_back(p.polyMaterial[f]);
    }
    c += n;
  }
  return b;
}

Mesh merge(const std::vector<Part>& parts, const std::string& name) {
  bool normals = false, colors = false, materials = false;
  int dims[kMaxTexSets] = {}, sets = 0;
  for (const Part& p : parts) {
    normals = normals || p.hasNormals;
    colors = colors || p.hasColors;
    materials = materials || !p.materials.empty();
    for (int s = 0; s < kMaxTexSets; ++s)
      if (p.texDims[s]) {
        dims[s] = std::max(dims[s], p.texDims[s]);
        sets = std::max(sets, s + 1);
      }
  }
  uint32_t code = d3d::FVF_XYZ | (normals ? d3d::FVF_NORMAL : 0) | (colors ? d3d::FVF_DIFFUSE : 0) | d3d::fvfTex(sets);
  for (int s = 0; s < sets; ++s) code |= d3d::fvfTexCoordSize(dims[s] ? dims[s] : 2, s);

  std::vector<Built> built;
  uint64_t vertexCount = 0, indexCount = 0;
  for (const Part& p : parts) {
    built.push_back(build(p));
    vertexCount += built.back().source.size();
    indexCount += built.back().triangles.size();
  }
  if (vertexCount > std::numeric_limits<uint32_t>::max() / 2)
    fail("{}: error: {} vertices are more than a mesh can index", name, vertexCount);
  Mesh out(code, uint32_t(vertexCount), 0);
  out.indices.reserve(indexCount);
  uint32_t base = 0;
  for (size_t pi = 0; pi < parts.size(); ++pi) {
    const Part& p = parts[pi];
    const Built& b = built[pi];
    Matrix normalMatrix = p.world;
    Matrix inv;
    if (p.transformed && inverse(p.world, inv)) normalMatrix = transpose(inv);
    for (uint32_t v = 0; v < b.source.size(); ++v) {
      uint32_t src = b.source[v], dst = base + v;
      Vec3 pos = p.positions[src];
      if (p.transformed) pos = transformCoord(pos, p.world);
      if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(pos.z))
        fail("{}: error: the frame transforms move vertex {} of mesh '{}' to infinity", name, src,
             printable(p.name));
      out.setPosition(dst, pos);
      if (p.hasNormals) {
        Vec3 n = b.normals[v];
        if (p.transformed) {
          n = normalize(transformNormal(n, normalMatrix));
          if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) n = Vec3();
        }
        out.setNormal(dst, n);
      }
      if (p.hasColors) out.setDiffuse(dst, p.colors[src]);
      for (int s = 0; s < sets; ++s)
        if (p.texDims[s]) out.setTexCoord(dst, s, p.tex[s][src]);
    }
    for (uint32_t i : b.triangles) out.indices.push_back(base + i);
    if (materials) {
      // A mesh without a material list gets a default material of its own.
      uint32_t first = uint32_t(out.materials.size());
      if (p.materials.empty()) {
        out.materials.push_back(XMaterial{});
        out.attributes.insert(out.attributes.end(), b.triangles.size() / 3, first);
      } else {
        out.materials.insert(out.materials.end(), p.materials.begin(), p.materials.end());
        for (uint32_t m : b.triangleMaterial) out.attributes.push_back(first + m);
      }
    }
    base += uint32_t(b.source.size());
  }
  return out;
}

}  // namespace

Mesh loadXFileFromMemory(std::span<const uint8_t> bytes, const std::string& name) {
  xfile::Header header = xfile::readHeader(bytes, name);
  std::unique_ptr<Lexer> lex = header.binary ? xfile::makeBinaryLexer(bytes, name, header.floatBits)
                                             : xfile::makeTextLexer(bytes, name);
  Parser parser(*lex, bytes.size());
  return merge(parser.parseFile(), name);
}

Mesh loadXFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) fail("{}: error: cannot open: {}", path, std::strerror(errno));
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) fail("{}: error: read failed", path);
  return loadXFileFromMemory(bytes, path);
}

}  // namespace refx::d3dx
