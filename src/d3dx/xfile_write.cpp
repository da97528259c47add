// Text .x writer (D3DXSaveMeshToX with D3DXF_FILEFORMAT_TEXT). Floats are written in
// their shortest form that reads back as the same float, so a saved mesh loads
// back bit for bit.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/xfile.h"
#include "refx/resource/vertex_format.h"

namespace refx::d3dx {

namespace {

// "a;b;c;" members of one element; elements separated by ",\n", the list ended by ";".
template <typename Element>
void list(std::string& out, const char* indent, uint32_t count, Element element) {
  for (uint32_t i = 0; i < count; ++i) {
    out += indent;
    element(i);
    out += i + 1 < count ? ",\n" : ";\n";
  }
}

void floats(std::string& out, std::initializer_list<float> values) {
  for (float v : values) fmt::format_to(std::back_inserter(out), "{};", v);
}

void material(std::string& out, const XMaterial& m) {
  out += "  Material {\n   ";
  floats(out, {m.diffuse.r, m.diffuse.g, m.diffuse.b, m.diffuse.a});
  out += ";\n   ";
  floats(out, {m.power});
  out += "\n   ";
  floats(out, {m.specular.x, m.specular.y, m.specular.z});
  out += ";\n   ";
  floats(out, {m.emissive.x, m.emissive.y, m.emissive.z});
  out += ";\n";
  if (!m.textureFilename.empty()) {
    // .x strings have no escapes.
    if (m.textureFilename.find_first_of("\"\n\r") != std::string::npos)
      fail("xfile: the texture file name '{}' cannot be written in a .x string (it holds a quote or a line "
           "break)", m.textureFilename);
    fmt::format_to(std::back_inserter(out), "   TextureFilename {{\n    \"{}\";\n   }}\n", m.textureFilename);
  }
  out += "  }\n";
}

void checkFinite(float v, const char* what, uint32_t i) {
  if (!std::isfinite(v)) fail("xfile: the {} of vertex {} is not a finite number; a .x file cannot hold it", what, i);
}

}  // namespace

std::string xFileText(const Mesh& mesh) {
  FVFLayout l = mesh.layout();
  if (l.position < 0) fail("xfile: a mesh without positions (FVF 0x{:x}) cannot be written", mesh.fvf);
  uint32_t nv = mesh.vertexCount(), nf = mesh.faceCount();
  if (mesh.indices.size() % 3) fail("xfile: the mesh has {} indices, not a whole number of triangles", mesh.indices.size());
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= nv) fail("xfile: index {} is {}, but the mesh has {} vertices", i, mesh.indices[i], nv);
  if (!mesh.attributes.empty() && mesh.attributes.size() != nf)
    fail("xfile: the attribute table has {} entries for {} faces", mesh.attributes.size(), nf);
  for (uint32_t f = 0; f < mesh.attributes.size(); ++f)
    if (mesh.attributes[f] >= std::max<size_t>(mesh.materials.size(), 1))
      fail("xfile: face {} has attribute {}, but the mesh has {} materials", f, mesh.attributes[f],
           mesh.materials.size());

  std::string out = "xof 0303txt 0032\n\nMesh {\n";
  auto faceList = [&](const char* indent) {
    fmt::format_to(std::back_inserter(out), "{}{};\n", indent, nf);
    list(out, indent, nf, [&](uint32_t f) {
      const uint32_t* t = &mesh.indices[3 * size_t(f)];
      fmt::format_to(std::back_inserter(out), "3;{},{},{};", t[0], t[1], t[2]);
    });
  };
  auto vec3List = [&](const char* indent, const char* what, Vec3 (Mesh::*get)(uint32_t) const) {
    fmt::format_to(std::back_inserter(out), "{}{};\n", indent, nv);
    list(out, indent, nv, [&](uint32_t i) {
      Vec3 v = (mesh.*get)(i);
      checkFinite(v.x, what, i), checkFinite(v.y, what, i), checkFinite(v.z, what, i);
      floats(out, {v.x, v.y, v.z});
    });
  };

  vec3List(" ", "position", &Mesh::position);
  faceList(" ");

  if (l.normal >= 0) {
    out += " MeshNormals {\n";
    vec3List("  ", "normal", &Mesh::normal);
    faceList("  ");
    out += " }\n";
  }

  int sets = d3d::fvfTexCount(mesh.fvf);
  bool set0Standard = sets > 0 && l.texDims[0] == 2;
  if (set0Standard) {
    fmt::format_to(std::back_inserter(out), " MeshTextureCoords {{\n  {};\n", nv);
    list(out, "  ", nv, [&](uint32_t i) {
      Vec4 t = mesh.texCoord(i, 0);
      checkFinite(t.x, "texture coordinate", i), checkFinite(t.y, "texture coordinate", i);
      floats(out, {t.x, t.y});
    });
    out += " }\n";
  }

  if (l.diffuse >= 0) {
    fmt::format_to(std::back_inserter(out), " MeshVertexColors {{\n  {};\n", nv);
    list(out, "  ", nv, [&](uint32_t i) {
      // Written as c/255, which reads back to the same byte.
      Color4 c = colorFromD3D(mesh.diffuse(i));
      fmt::format_to(std::back_inserter(out), "{};", i);
      floats(out, {c.r, c.g, c.b, c.a});
      out += ";";
    });
    out += " }\n";
  }

  if (!mesh.materials.empty()) {
    fmt::format_to(std::back_inserter(out), " MeshMaterialList {{\n  {};\n  {};\n", mesh.materials.size(), nf);
    list(out, "  ", nf, [&](uint32_t f) { fmt::format_to(std::back_inserter(out), "{}", mesh.attribute(f)); });
    for (const XMaterial& m : mesh.materials) material(out, m);
    out += " }\n";
  }

  // The texture sets MeshTextureCoords cannot hold, as D3DVERTEXELEMENT9 FLOATn
  // TEXCOORDn elements and their values' bits.
  int first = set0Standard ? 1 : 0;
  if (sets > first) {
    uint32_t perVertex = 0;
    for (int s = first; s < sets; ++s) perVertex += uint32_t(l.texDims[s]);
    fmt::format_to(std::back_inserter(out), " DeclData {{\n  {};\n", sets - first);
    list(out, "  ", uint32_t(sets - first), [&](uint32_t e) {
      int s = first + int(e);
      fmt::format_to(std::back_inserter(out), "{};0;{};{};", d3d::DECLTYPE_FLOAT1 + l.texDims[s] - 1,
                     uint32_t(d3d::DECLUSAGE_TEXCOORD), s);
    });
    fmt::format_to(std::back_inserter(out), "  {};\n", uint64_t(perVertex) * nv);
    list(out, "  ", nv, [&](uint32_t i) {
      bool firstValue = true;
      for (int s = first; s < sets; ++s) {
        Vec4 t = mesh.texCoord(i, s);
        for (int c = 0; c < l.texDims[s]; ++c) {
          uint32_t bits;
          float v = t[c];
          std::memcpy(&bits, &v, 4);
          fmt::format_to(std::back_inserter(out), "{}{}", firstValue ? "" : ",", bits);
          firstValue = false;
        }
      }
    });
    out += " }\n";
  }
  out += "}\n";
  return out;
}

void saveXFileText(const Mesh& mesh, const std::string& path) {
  std::string text = xFileText(mesh);
  std::ofstream f(path, std::ios::binary);
  if (!f) fail("{}: error: cannot create: {}", path, std::strerror(errno));
  f.write(text.data(), std::streamsize(text.size()));
  if (!f) fail("{}: error: write failed", path);
}

}  // namespace refx::d3dx
