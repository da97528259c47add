// .x and OBJ mesh files: hand-written files whose contents are known, the binary
// encoding built token by token from the DirectX .x format, save/load round trips,
// and malformed inputs that must give refx::Error with a location.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"
#include "refx/d3dx/obj.h"
#include "refx/d3dx/xfile.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

// Flat normals of the octahedron: (±1, ±1, ±1) / sqrt(3), sqrt(1/3) = 0.57735026.
constexpr float kS = 0.57735026f;

// Octahedron: vertices +x 0, -x 1, +y 2, -y 3, +z 4, -z 5; one face per octant,
// wound clockwise seen from outside; face f has the flat normal kNormals[f].
// Faces 0-3 use the material "Red" (defined at the top level and referenced), faces
// 4-7 the inline material "Blue". Templates, a Header and a
// VertexDuplicationIndices object are there to be skipped.
const char* kOctahedron = R"(xof 0303txt 0032
// the DirectX templates a file may declare
template Vector {
 <3D82AB5E-62DA-11cf-AB39-0020AF71E433>
 FLOAT x;
 FLOAT y;
 FLOAT z;
}
template Mesh {
 <3D82AB44-62DA-11CF-AB39-0020AF71E433>
 DWORD nVertices;
 array Vector vertices[nVertices];
 DWORD nFaces;
 array MeshFace faces[nFaces];
 [...]
}
template MeshMaterialList {
 <F6F23F42-7686-11cf-8F52-0040333594A3>
 DWORD nMaterials;
 DWORD nFaceIndexes;
 array DWORD faceIndexes[nFaceIndexes];
 [Material <3D82AB4D-62DA-11CF-AB39-0020AF71E433>]
}
Header { 1; 0; 1; }
# a top-level material, referenced below
Material Red {
 1.0;0.0;0.0;1.0;;
 20.0;
 1.0;1.0;1.0;;
 0.0;0.0;0.0;;
 TextureFilename { "red.bmp"; }
}
Mesh octahedron {
 6;
 1.0;0.0;0.0;,
 -1.0;0.0;0.0;,
 0.0;1.0;0.0;,
 0.0;-1.0;0.0;,
 0.0;0.0;1.0;,
 0.0;0.0;-1.0;;
 8;
 3;2,4,0;,
 3;2,1,4;,
 3;3,0,4;,
 3;3,4,1;,
 3;2,0,5;,
 3;2,5,1;,
 3;3,5,0;,
 3;3,1,5;;
 VertexDuplicationIndices { 6; 6; 0, 1, 2, 3, 4, 5;; }
 MeshNormals {
  8;
  0.57735026;0.57735026;0.57735026;,
  -0.57735026;0.57735026;0.57735026;,
  0.57735026;-0.57735026;0.57735026;,
  -0.57735026;-0.57735026;0.57735026;,
  0.57735026;0.57735026;-0.57735026;,
  -0.57735026;0.57735026;-0.57735026;,
  0.57735026;-0.57735026;-0.57735026;,
  -0.57735026;-0.57735026;-0.57735026;;
  8;
  3;0,0,0;,
  3;1,1,1;,
  3;2,2,2;,
  3;3,3,3;,
  3;4,4,4;,
  3;5,5,5;,
  3;6,6,6;,
  3;7,7,7;;
 }
 MeshTextureCoords {
  6;
  0.0;0.5;,
  1.0;0.5;,
  0.5;0.0;,
  0.5;1.0;,
  0.25;0.25;,
  0.75;0.75;;
 }
 MeshMaterialList {
  2;
  8;
  0,0,0,0,1,1,1,1;;
  { Red }
  Material Blue {
   0.0;0.0;1.0;0.5;;
   5.0;
   0.5;0.5;0.5;;
   0.1;0.2;0.3;;
   TextureFilename { "textures\\blue.png"; }
  }
 }
}
)";

const Vec3 kPositions[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const uint32_t kFaces[8][3] = {{2, 4, 0}, {2, 1, 4}, {3, 0, 4}, {3, 4, 1},
                               {2, 0, 5}, {2, 5, 1}, {3, 5, 0}, {3, 1, 5}};
const Vec3 kNormals[8] = {{kS, kS, kS},  {-kS, kS, kS},  {kS, -kS, kS},  {-kS, -kS, kS},
                          {kS, kS, -kS}, {-kS, kS, -kS}, {kS, -kS, -kS}, {-kS, -kS, -kS}};
const float kUV[6][2] = {{0, 0.5f}, {1, 0.5f}, {0.5f, 0}, {0.5f, 1}, {0.25f, 0.25f}, {0.75f, 0.75f}};

std::span<const uint8_t> bytesOf(const std::string& s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

Mesh loadText(const std::string& text, const std::string& name = "oct.x") {
  return loadXFileFromMemory(bytesOf(text), name);
}

void expectVec(Vec3 v, Vec3 e, float eps = 1e-6f) {
  EXPECT_NEAR(v.x, e.x, eps);
  EXPECT_NEAR(v.y, e.y, eps);
  EXPECT_NEAR(v.z, e.z, eps);
}

// The expected loaded octahedron: triangle f has the file's positions, face f's
// normal and each position's uv; vertices 0-5 are the file's vertices in order; a
// position with 4 different normals (each is used by 4 faces) becomes 4 vertices.
void expectOctahedron(const Mesh& m) {
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));  // 0x112
  ASSERT_EQ(m.vertexCount(), 24u);                            // 6 positions x 4 normals
  ASSERT_EQ(m.faceCount(), 8u);
  for (uint32_t i = 0; i < 6; ++i) expectVec(m.position(i), kPositions[i]);
  for (uint32_t f = 0; f < 8; ++f)
    for (int k = 0; k < 3; ++k) {
      uint32_t v = m.indices[3 * f + k], p = kFaces[f][k];
      SCOPED_TRACE(testing::Message() << "face " << f << " corner " << k);
      expectVec(m.position(v), kPositions[p]);
      expectVec(m.normal(v), kNormals[f]);
      EXPECT_EQ(m.texCoord(v, 0), Vec4(kUV[p][0], kUV[p][1], 0, 0));
    }
  // Vertex i < 6 keeps the normal of the first face using it: +x, +y, +z: face 0;
  // -x: face 1; -y: face 2; -z: face 4.
  const int firstFace[6] = {0, 1, 0, 2, 0, 4};
  for (uint32_t i = 0; i < 6; ++i) expectVec(m.normal(i), kNormals[firstFace[i]]);
  EXPECT_EQ(m.attributes, (std::vector<uint32_t>{0, 0, 0, 0, 1, 1, 1, 1}));
  ASSERT_EQ(m.materials.size(), 2u);
  const XMaterial& red = m.materials[0];
  EXPECT_EQ(red.diffuse, (Color4{1, 0, 0, 1}));
  EXPECT_EQ(red.power, 20.0f);
  EXPECT_EQ(red.specular, Vec3(1, 1, 1));
  EXPECT_EQ(red.emissive, Vec3(0, 0, 0));
  EXPECT_EQ(red.textureFilename, "red.bmp");
  const XMaterial& blue = m.materials[1];
  EXPECT_EQ(blue.diffuse, (Color4{0, 0, 1, 0.5f}));
  EXPECT_EQ(blue.power, 5.0f);
  EXPECT_EQ(blue.specular, Vec3(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(blue.emissive, Vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(blue.textureFilename, "textures\\\\blue.png");  // .x strings have no escapes
}

// Outward = cross(p1 - p0, p2 - p0) points away from the center (clockwise seen
// from outside in D3D's left-handed space).
void expectOutwardWinding(const Mesh& m, Vec3 center) {
  for (uint32_t f = 0; f < m.faceCount(); ++f) {
    Vec3 p0 = m.position(m.indices[3 * f]), p1 = m.position(m.indices[3 * f + 1]),
         p2 = m.position(m.indices[3 * f + 2]);
    Vec3 n = cross(p1 - p0, p2 - p0);
    EXPECT_GT(dot(n, (p0 + p1 + p2) * (1.0f / 3) - center), 0.0f) << "face " << f;
  }
}

// Bytes of a binary .x file, token by token (WORD token, then its data).
struct XBin {
  std::vector<uint8_t> b;
  explicit XBin(const char* header = "xof 0303bin 0032") { b.assign(header, header + 16); }
  XBin& word(uint16_t w) { return raw(&w, 2); }
  XBin& dword(uint32_t d) { return raw(&d, 4); }
  XBin& raw(const void* p, size_t n) {
    b.insert(b.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
    return *this;
  }
  XBin& name(const std::string& s) { return word(1).dword(uint32_t(s.size())).raw(s.data(), s.size()); }
  // TOKEN_STRING and its terminating TOKEN_SEMICOLON.
  XBin& str(const std::string& s) { return word(2).dword(uint32_t(s.size())).raw(s.data(), s.size()).word(20); }
  XBin& ints(std::initializer_list<uint32_t> v) {
    word(6).dword(uint32_t(v.size()));
    for (uint32_t x : v) dword(x);
    return *this;
  }
  XBin& floats(std::initializer_list<float> v) {
    word(7).dword(uint32_t(v.size()));
    for (float x : v) raw(&x, 4);
    return *this;
  }
  XBin& doubles(std::initializer_list<double> v) {
    word(7).dword(uint32_t(v.size()));
    for (double x : v) raw(&x, 8);
    return *this;
  }
  XBin& guid() {  // any 16 bytes
    word(5);
    for (int i = 0; i < 16; ++i) b.push_back(uint8_t(i * 17));
    return *this;
  }
  XBin& open() { return word(10); }
  XBin& close() { return word(11); }
  XBin& semicolon() { return word(20); }
};

// The octahedron of kOctahedron in the binary encoding; `doubles` for float size 0064.
std::vector<uint8_t> binaryOctahedron(bool doubles) {
  XBin x(doubles ? "xof 0303bin 0064" : "xof 0303bin 0032");
  auto fl = [&](std::initializer_list<float> v) -> XBin& {
    if (!doubles) return x.floats(v);
    x.word(7).dword(uint32_t(v.size()));
    for (float f : v) {
      double d = f;
      x.raw(&d, 8);
    }
    return x;
  };
  // template Vector { <guid> FLOAT x; FLOAT y; FLOAT z; }  (TEMPLATE 31, FLOAT 42)
  x.word(31).name("Vector").open().guid();
  for (const char* c : {"x", "y", "z"}) x.word(42).name(c).semicolon();
  x.close();
  // Header { 1; 0; 1; } is skipped as an unknown object.
  x.name("Header").open().ints({1, 0, 1}).close();
  x.name("Material").name("Red").open();
  fl({1, 0, 0, 1, 20, 1, 1, 1, 0, 0, 0});
  x.name("TextureFilename").open().str("red.bmp").close().close();
  x.name("Mesh").name("octahedron").open().ints({6});
  fl({1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1});
  x.ints({8, 3, 2, 4, 0, 3, 2, 1, 4, 3, 3, 0, 4, 3, 3, 4, 1, 3, 2, 0, 5, 3, 2, 5, 1, 3, 3, 5, 0, 3, 3, 1, 5});
  x.name("MeshNormals").open().ints({8});
  fl({kS, kS, kS, -kS, kS, kS, kS, -kS, kS, -kS, -kS, kS, kS, kS, -kS, -kS, kS, -kS, kS, -kS, -kS, -kS, -kS, -kS});
  x.ints({8, 3, 0, 0, 0, 3, 1, 1, 1, 3, 2, 2, 2, 3, 3, 3, 3, 3, 4, 4, 4, 3, 5, 5, 5, 3, 6, 6, 6, 3, 7, 7, 7});
  x.close();
  x.name("MeshTextureCoords").open().ints({6});
  fl({0, 0.5f, 1, 0.5f, 0.5f, 0, 0.5f, 1, 0.25f, 0.25f, 0.75f, 0.75f});
  x.close();
  x.name("MeshMaterialList").open().ints({2, 8, 0, 0, 0, 0, 1, 1, 1, 1});
  x.open().name("Red").close();  // reference {Red}
  x.name("Material").name("Blue").open();
  fl({0, 0, 1, 0.5f, 5, 0.5f, 0.5f, 0.5f, 0.1f, 0.2f, 0.3f});
  x.name("TextureFilename").open().str("textures\\\\blue.png").close().close();
  x.close();  // MeshMaterialList
  x.close();  // Mesh
  return x.b;
}

std::string tempPath(const std::string& file) {
  return (std::filesystem::path(testing::TempDir()) / ("refx_xfile_" + file)).string();
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

void expectSameMesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.fvf, b.fvf);
  EXPECT_EQ(a.stride, b.stride);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.attributes, b.attributes);
  EXPECT_EQ(a.materials, b.materials);
}

// The refx::Error message of loading `text` ("" when it loads).
std::string xError(const std::string& text, const std::string& name = "bad.x") {
  try {
    loadText(text, name);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
std::string binError(const std::vector<uint8_t>& bytes) {
  try {
    loadXFileFromMemory(bytes, "bad.x");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// ---- text .x ------------------------------------------------------------------

TEST(XFile, TextOctahedronCountsNormalsUVsMaterials) { expectOctahedron(loadText(kOctahedron)); }

TEST(XFile, OctahedronFacesAreWoundOutward) {
  // Checks the test data: faces clockwise seen from outside.
  expectOutwardWinding(loadText(kOctahedron), Vec3(0, 0, 0));
}

TEST(XFile, LoadFromFile) {
  std::string path = tempPath("octahedron.x");
  writeFile(path, kOctahedron);
  expectOctahedron(loadXFile(path));
}

TEST(XFile, MinimalExampleOfTheFormat) {
  // The format reference's example: one triangle, one normal for all corners.
  Mesh m = loadText(R"(xof 0303txt 0032
Mesh tri {
 3;
 0.0;0.0;0.0;,
 0.0;1.0;0.0;,
 1.0;0.0;0.0;;
 1;
 3;0,1,2;;
 MeshNormals { 1; 0.0;0.0;-1.0;; 1; 3;0,0,0;; }
 MeshTextureCoords { 3; 0.0;1.0;, 0.0;0.0;, 1.0;1.0;; }
 MeshMaterialList { 1; 1; 0;; Material { 1.0;1.0;1.0;1.0;; 0.0; 0.0;0.0;0.0;; 0.0;0.0;0.0;; } }
}
)");
  ASSERT_EQ(m.vertexCount(), 3u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
  for (uint32_t i = 0; i < 3; ++i) EXPECT_EQ(m.normal(i), Vec3(0, 0, -1));
  EXPECT_EQ(m.texCoord(2, 0), Vec4(1, 1, 0, 0));
  EXPECT_EQ(m.attributes, std::vector<uint32_t>{0});
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].diffuse, (Color4{1, 1, 1, 1}));
  EXPECT_EQ(m.materials[0].textureFilename, "");
}

TEST(XFile, PolygonsAreFannedAndMaterialIndexesRepeat) {
  // A pentagon and a quad; the material list gives one index for two faces, so
  // the last index (1) repeats. Fans: (0,1,2) (0,2,3) (0,3,4) and (5,6,7) (5,7,8).
  Mesh m = loadText(R"(xof 0302txt 0064
Mesh {
 9;
 0;0;0;, 1;0;0;, 2;1;0;, 1;2;0;, 0;1;0;,
 5;0;0;, 6;0;0;, 6;1;0;, 5;1;0;;
 2;
 5;0,1,2,3,4;,
 4;5,6,7,8;;
 MeshMaterialList { 2; 1; 1;; Material { 1;0;0;1;; 1; 0;0;0;; 0;0;0;; } Material { 0;1;0;1;; 1; 0;0;0;; 0;0;0;; } }
}
)");
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 5, 6, 7, 5, 7, 8}));
  EXPECT_EQ(m.attributes, (std::vector<uint32_t>{1, 1, 1, 1, 1}));
}

TEST(XFile, VertexColorsAndUnlistedVerticesWhite) {
  // ColorRGBA (r, g, b, a) -> D3DCOLOR 0xAARRGGBB; vertex 2 is not listed: opaque white.
  Mesh m = loadText(R"(xof 0303txt 0032
Mesh {
 3; 0;0;0;, 0;1;0;, 1;0;0;;
 1; 3;0,1,2;;
 MeshVertexColors { 2; 0;1.0;0.0;0.0;1.0;;, 1;0.0;0.5;1.0;0.0;;; }
}
)");
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_DIFFUSE);
  EXPECT_EQ(m.diffuse(0), 0xffff0000u);
  EXPECT_EQ(m.diffuse(1), 0x000080ffu);  // 0.5 * 255 + 0.5 = 128 = 0x80
  EXPECT_EQ(m.diffuse(2), 0xffffffffu);
  EXPECT_TRUE(m.attributes.empty());
  EXPECT_TRUE(m.materials.empty());
}

TEST(XFile, SeparatorsAreLenientAndNamesMayHoldDashes) {
  // ',' where ';' is usual, runs of separators, a name with '-' and '.', no GUID
  // spaces: D3DX accepts these.
  Mesh m = loadText(R"(xof 0303txt 0032
Mesh Box01-node.1 {
 3, 0,0,0,, 0,1,0;;; 1,0,0;
 1; 3;0;1;2;;;
}
)");
  ASSERT_EQ(m.vertexCount(), 3u);
  EXPECT_EQ(m.position(1), Vec3(0, 1, 0));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(XFile, FrameTransformsMoveVerticesAndNormals) {
  // Mesh A at the top level stays where it is. Mesh B sits in Child (scale (2,1,1))
  // inside Root (translation (10,20,30)): world = scale * translation, so
  // (1,0,0) -> (2,0,0) -> (12,20,30). Its normal (1,1,0)/sqrt(2) belongs to the
  // plane x + y = 1; scaled, the plane is x/2 + y = 1 with normal (1,2,0)/sqrt(5)
  // (inverse transpose diag(1/2, 1, 1)).
  Mesh m = loadText(R"(xof 0303txt 0032
Mesh A {
 3; 0;0;0;, 0;1;0;, 1;0;0;;
 1; 3;0,1,2;;
 MeshNormals { 1; 0;0;-1;; 1; 3;0,0,0;; }
}
Frame Root {
 FrameTransformMatrix {
  1.0,0.0,0.0,0.0,
  0.0,1.0,0.0,0.0,
  0.0,0.0,1.0,0.0,
  10.0,20.0,30.0,1.0;;
 }
 Frame Child {
  Mesh B {
   3; 1;0;0;, 0;1;0;, 1;0;1;;
   1; 3;0,1,2;;
   MeshNormals { 1; 0.70710678;0.70710678;0;; 1; 3;0,0,0;; }
   MeshMaterialList { 1; 1; 0;; Material { 0;1;0;1;; 8; 0;0;0;; 0;0;0;; } }
  }
  FrameTransformMatrix { 2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1;; }
 }
}
)");
  ASSERT_EQ(m.vertexCount(), 6u);
  ASSERT_EQ(m.faceCount(), 2u);
  expectVec(m.position(0), {0, 0, 0});
  expectVec(m.position(2), {1, 0, 0});
  expectVec(m.normal(0), {0, 0, -1});
  expectVec(m.position(3), {12, 20, 30});  // (1,0,0): 2*1 + 10, 0 + 20, 0 + 30
  expectVec(m.position(4), {10, 21, 30});  // (0,1,0)
  expectVec(m.position(5), {12, 20, 31});  // (1,0,1)
  const float r5 = 1.0f / std::sqrt(5.0f);
  for (uint32_t i = 3; i < 6; ++i) expectVec(m.normal(i), {r5, 2 * r5, 0}, 1e-5f);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  // A has no material list: it gets a default material of its own (id 0), B's is 1.
  EXPECT_EQ(m.attributes, (std::vector<uint32_t>{0, 1}));
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0], XMaterial{});
  EXPECT_EQ(m.materials[1].diffuse, (Color4{0, 1, 0, 1}));
}

TEST(XFile, DeclDataAddsTextureSets) {
  // TEXCOORD1 as FLOAT3 (type 2, usage 5, index 1); values as float bits:
  // 1.0f = 1065353216, 2.0f = 1073741824, 0.5f = 1056964608, 0 = 0.
  Mesh m = loadText(R"(xof 0303txt 0032
Mesh {
 3; 0;0;0;, 0;1;0;, 1;0;0;;
 1; 3;0,1,2;;
 MeshTextureCoords { 3; 0;0;, 0;1;, 1;0;; }
 DeclData { 1; 2;0;5;1;; 9; 1065353216,0,0, 0,1073741824,0, 0,0,1056964608;; }
}
)");
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::fvfTex(2) | d3d::fvfTexCoordSize(3, 1));
  EXPECT_EQ(m.texCoord(1, 0), Vec4(0, 1, 0, 0));
  EXPECT_EQ(m.texCoord(0, 1), Vec4(1, 0, 0, 0));
  EXPECT_EQ(m.texCoord(1, 1), Vec4(0, 2, 0, 0));
  EXPECT_EQ(m.texCoord(2, 1), Vec4(0, 0, 0.5f, 0));
}

// ---- binary .x ----------------------------------------------------------------

TEST(XFile, BinaryOctahedronLoadsLikeText) {
  Mesh bin = loadXFileFromMemory(binaryOctahedron(false), "oct-bin.x");
  expectOctahedron(bin);
  expectSameMesh(bin, loadText(kOctahedron));
}

TEST(XFile, BinaryWith64BitFloats) {
  Mesh bin = loadXFileFromMemory(binaryOctahedron(true), "oct-bin64.x");
  expectOctahedron(bin);
  expectSameMesh(bin, loadText(kOctahedron));
}

TEST(XFile, BinaryIntegerTokensAndSeparators) {
  // TOKEN_INTEGER (3) members and explicit separators instead of lists.
  XBin x;
  x.name("Mesh").open().word(3).dword(3).semicolon();
  x.floats({0, 0, 0, 0, 1, 0, 1, 0, 0}).semicolon();
  x.word(3).dword(1).semicolon().ints({3, 0, 1, 2}).semicolon().semicolon().close();
  Mesh m = loadXFileFromMemory(x.b, "ints.x");
  ASSERT_EQ(m.vertexCount(), 3u);
  EXPECT_EQ(m.position(2), Vec3(1, 0, 0));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
}

// ---- writing ------------------------------------------------------------------

TEST(XFile, TexturedSphereRoundTrip) {
  // XYZ | NORMAL | TEX2 with a 3-component set 1 (MeshTextureCoords + DeclData).
  Mesh m = createTexturedSphere(1.5f, 12, 6);
  m.materials = {XMaterial{{1, 0.5f, 0.25f, 1}, 16, {1, 1, 1}, {0, 0, 0.125f}, "earth.png"},
                 XMaterial{{0.2f, 0.3f, 0.4f, 0.75f}, 0, {}, {}, ""},
                 XMaterial{{0, 0, 0, 0}, 100, {0.1f, 0.2f, 0.3f}, {}, "sub dir/clouds.dds"}};
  for (uint32_t f = 0; f < m.faceCount(); ++f) m.attributes.push_back(f % 3);
  std::string path = tempPath("sphere.x");
  saveXFileText(m, path);
  expectSameMesh(loadXFile(path), m);
}

TEST(XFile, ColorsAndBoxRoundTrip) {
  Mesh m = cloneMeshFVF(createBox(1, 2, 3), d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::FVF_DIFFUSE | d3d::fvfTex(1));
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    m.setDiffuse(i, 0x01020304u * i + 0x80000000u);
    m.setTexCoord(i, 0, float(i) / 7, 1.0f / float(i + 1));
  }
  Mesh back = loadText(xFileText(m), "box.x");
  expectSameMesh(back, m);
}

TEST(XFile, CloneKeepsTheAttributeTable) {
  Mesh box = createBox(1, 1, 1);
  box.materials = {XMaterial{}, XMaterial{{0, 1, 0, 1}, 4, {}, {}, "green.png"}};
  box.attributes.assign(12, 1);
  box.attributes[0] = 0;
  Mesh c = cloneMeshFVF(box, d3d::FVF_XYZ | d3d::fvfTex(1));
  EXPECT_EQ(c.attributes, box.attributes);
  EXPECT_EQ(c.materials, box.materials);
  EXPECT_EQ(c.attribute(0), 0u);
  EXPECT_EQ(c.attribute(11), 1u);
}

TEST(XFile, SavedTextIsTheDocumentedLayout) {
  // One triangle: the members and separators of the Mesh template as written by hand.
  Mesh m(d3d::FVF_XYZ, 3, 1);
  m.setPosition(1, {0, 1, 0});
  m.setPosition(2, {1, 0.5f, 0});
  m.indices = {0, 1, 2};
  EXPECT_EQ(xFileText(m),
            "xof 0303txt 0032\n\nMesh {\n 3;\n 0;0;0;,\n 0;1;0;,\n 1;0.5;0;;\n 1;\n 3;0,1,2;;\n}\n");
}

// ---- OBJ ----------------------------------------------------------------------

namespace {

// A cube (RH, counter-clockwise seen from outside), faces -z, +z, -x, +x (material
// "wood") then -y, +y (material "metal"). Positions: 1 (-1,-1,-1) 2 (1,-1,-1)
// 3 (1,1,-1) 4 (-1,1,-1) 5 (-1,-1,1) 6 (1,-1,1) 7 (1,1,1) 8 (-1,1,1).
const char* kCubeObj = R"(# cube
mtllib cube.mtl
o Cube
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
vn -1 0 0
vn 1 0 0
vn 0 -1 0
vn 0 1 0
usemtl wood
f 1/1/1 4/4/1 3/3/1 2/2/1
f 5/1/2 6/2/2 7/3/2 8/4/2
f 1/1/3 5/2/3 8/3/3 4/4/3
f -7/1/-3 -6/2/-3 -2/3/-3 -3/4/-3
usemtl metal
s off
f 1/1/5 2/2/5 6/3/5 5/4/5
f 4/1/6 8/2/6 7/3/6 3/4/6
)";

const char* kCubeMtl = R"(newmtl wood
Ka 0.1 0.1 0.1
Kd 0.6 0.4 0.2
Ks 0.5 0.5 0.5
Ns 32
map_Kd -s 2 2 1 wood grain.png

newmtl metal
Kd 0.8
d 0.25
Ke 0 0 0.5
)";

}  // namespace

TEST(OBJ, CubeWithTwoMaterials) {
  std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "refx_obj_cube";
  std::filesystem::create_directories(dir);
  writeFile((dir / "cube.obj").string(), kCubeObj);
  writeFile((dir / "cube.mtl").string(), kCubeMtl);
  std::vector<std::string> warnings;
  Mesh m = loadOBJ((dir / "cube.obj").string(), &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
  // Every corner has its own (v, vt, vn): 6 faces x 4 corners, 2 triangles a face.
  ASSERT_EQ(m.vertexCount(), 24u);
  ASSERT_EQ(m.faceCount(), 12u);
  // Face "1/1/1 4/4/1 3/3/1 2/2/1" gives vertices 0..3; fan (0,1,2) (0,2,3) wound
  // the other way: (0,2,1) (0,3,2).
  EXPECT_EQ(std::vector<uint32_t>(m.indices.begin(), m.indices.begin() + 6),
            (std::vector<uint32_t>{0, 2, 1, 0, 3, 2}));
  // Vertex 1 = "4/4/1": v 4 (-1,1,-1) with z negated, vt (0,1) with v' = 1 - 1 = 0,
  // vn (0,0,-1) with z negated.
  EXPECT_EQ(m.position(1), Vec3(-1, 1, 1));
  EXPECT_EQ(m.texCoord(1, 0), Vec4(0, 0, 0, 0));
  EXPECT_EQ(m.normal(1), Vec3(0, 0, 1));
  // Negative indices: face 4 "-7/1/-3 ..." is "2/1/4 3/2/4 7/3/4 6/4/4" (+x face):
  // its first corner is vertex 12, position 2 = (1,-1,-1) -> (1,-1,1), normal (1,0,0).
  EXPECT_EQ(m.indices[18], 12u);
  EXPECT_EQ(m.position(12), Vec3(1, -1, 1));
  EXPECT_EQ(m.normal(12), Vec3(1, 0, 0));
  EXPECT_EQ(m.texCoord(12, 0), Vec4(0, 1, 0, 0));  // vt 1 (0,0): v' = 1
  // Each normal points out of the cube and the triangles are clockwise from outside.
  for (uint32_t i = 0; i < m.vertexCount(); ++i) EXPECT_GT(dot(m.normal(i), m.position(i)), 0.0f);
  expectOutwardWinding(m, Vec3(0, 0, 0));
  EXPECT_EQ(m.attributes, (std::vector<uint32_t>{0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1}));
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].diffuse, (Color4{0.6f, 0.4f, 0.2f, 1}));
  EXPECT_EQ(m.materials[0].specular, Vec3(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(m.materials[0].power, 32.0f);
  EXPECT_EQ(m.materials[0].textureFilename, "wood grain.png");  // after the -s option
  EXPECT_EQ(m.materials[1].diffuse, (Color4{0.8f, 0.8f, 0.8f, 0.25f}));  // "Kd 0.8" is grey
  EXPECT_EQ(m.materials[1].emissive, Vec3(0, 0, 0.5f));
  EXPECT_EQ(m.materials[1].textureFilename, "");
}

TEST(OBJ, MissingMaterialLibraryIsAWarning) {
  std::string path = tempPath("nomtl.obj");
  writeFile(path, "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  std::vector<std::string> warnings;
  Mesh m = loadOBJ(path, &warnings);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find(":1: warning: material library"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find(":5: warning: material 'red'"), std::string::npos) << warnings[1];
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 2, 1}));
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0], XMaterial{});
}

TEST(OBJ, SharedCornersAndFacesBeforeUsemtl) {
  // "v//vn" corners; the quad's corners 1 and 3 are shared with the triangle, with
  // the same (v, vt, vn), so 4 vertices. Faces before usemtl get a default material
  // after the named ones.
  Mesh m = loadOBJFromMemory(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
      "f 1//1 2//1 3//1\nusemtl a\nf 1//1 3//1 4//1\n",
      "shared.obj");
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL);
  ASSERT_EQ(m.vertexCount(), 4u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 2, 1, 0, 3, 2}));
  EXPECT_EQ(m.normal(3), Vec3(0, 0, -1));
  EXPECT_EQ(m.attributes, (std::vector<uint32_t>{1, 0}));
  EXPECT_EQ(m.materials.size(), 2u);
}

// ---- malformed input ----------------------------------------------------------

TEST(XFileErrors, MissingSeparatorNamesLineAndColumn) {
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3\n}\n"),
            "bad.x:4:1: error: expected ';' after the vertex count, got '}'");
}

TEST(XFileErrors, BadNumber) {
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3;\n 0.0;abc;0.0;,\n 0;1;0;, 1;0;0;;\n"),
            "bad.x:4:6: error: expected the y of vertex 0 (a number), got 'abc'");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 1;\n 1e39;0;0;;\n"),
            "bad.x:4:2: error: the x of vertex 0 '1e39' is out of the range of a float");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n -3;\n"),
            "bad.x:3:2: error: expected the vertex count (an unsigned integer), got '-3'");
}

TEST(XFileErrors, WrongCounts) {
  // The face list ends early: 2 faces declared, a child object where face 1 should be.
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 2;\n 3;0,1,2;;\n"
                   " MeshNormals { 1; 0;0;1;; 1; 3;0,0,0;; }\n}\n"),
            "bad.x:6:2: error: expected the index count of face 1 (an unsigned integer), got 'MeshNormals'");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 1;\n 3;0,1,3;;\n}\n"),
            "bad.x:5:8: error: index 2 of face 0 is 3, but the mesh has 3 vertices");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 1;\n 3;0,1,2;;\n"
                   " MeshTextureCoords { 2; 0;0;, 1;1;; }\n}\n"),
            "bad.x:6:22: error: MeshTextureCoords has 2 coordinates, the mesh has 3 vertices");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 1;\n 3;0,1,2;;\n"
                   " MeshNormals { 1; 0;0;1;; 1; 4;0,0,0,0;; }\n}\n"),
            "bad.x:6:30: error: face 0 of MeshNormals has 4 indices, face 0 of the mesh has 3");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 1;\n 2;0,1;;\n}\n"),
            "bad.x:5:2: error: face 0 has 2 indices; a face needs at least 3");
  std::string twoMaterialsOneGiven =
      "xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 1;\n 3;0,1,2;;\n"
      " MeshMaterialList { 2; 1; 0;; Material { 1;1;1;1;; 0; 0;0;0;; 0;0;0;; } }\n}\n";
  EXPECT_EQ(xError(twoMaterialsOneGiven),
            "bad.x:6:2: error: MeshMaterialList declares 2 materials but holds 1");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 1;\n 3;0,1,2;;\n"
                   " MeshMaterialList { 1; 1; 0;; { Nowhere } }\n}\n"),
            "bad.x:6:33: error: material 'Nowhere' is not defined before this reference");
}

TEST(XFileErrors, UnbalancedBraces) {
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 3; 0;0;0;, 0;1;0;, 1;0;0;;\n 1;\n 3;0,1,2;;\n"),
            "bad.x:6:1: error: expected '}' to close 'Mesh' opened at bad.x:2:1, got the end of the file");
  EXPECT_EQ(xError("xof 0303txt 0032\nHeader { 1; 0; { 1; }\n"),
            "bad.x:3:1: error: expected '}' to close the 'Header' opened at bad.x:2:1, got the end of the file");
  EXPECT_EQ(xError("xof 0303txt 0032\n}\n"), "bad.x:2:1: error: expected a template or a data object, got '}'");
  EXPECT_EQ(xError("xof 0303txt 0032\ntemplate Foo { <12345678-0000-0000-0000-000000000000>\n"),
            "bad.x:3:1: error: expected '}' to close the template 'Foo' opened at bad.x:2:14, got the end of the file");
}

TEST(XFileErrors, TruncatedFiles) {
  // Every proper prefix of the octahedron (past the header) fails cleanly, with a
  // location in the file.
  std::string text = kOctahedron;
  for (size_t n = 16; n < text.rfind('}'); n += 7) {
    std::string e = xError(text.substr(0, n), "cut.x");
    ASSERT_EQ(e.rfind("cut.x:", 0), 0u) << "prefix " << n << ": " << e;
  }
  std::vector<uint8_t> bin = binaryOctahedron(false);
  for (size_t n = 16; n < bin.size(); n += 3) {
    std::string e = binError(std::vector<uint8_t>(bin.begin(), bin.begin() + long(n)));
    ASSERT_EQ(e.rfind("bad.x:byte ", 0), 0u) << "prefix " << n << ": " << e;
  }
}

TEST(XFileErrors, HugeCountsFailBeforeAllocating) {
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 4000000000;\n 0;0;0;;\n}\n"),
            "bad.x:3:2: error: the vertex count 4000000000 is larger than the rest of the file can hold");
  EXPECT_EQ(xError("xof 0303txt 0032\nMesh {\n 99999999999;\n"),
            "bad.x:3:2: error: the vertex count '99999999999' does not fit in a DWORD");
  // Binary: an INTEGER_LIST claiming 0x7fffffff elements, at byte 16 (header) + 10
  // (NAME "Mesh": WORD, DWORD length, 4 bytes) + 2 (OBRACE) = 28.
  XBin x;
  x.name("Mesh").open().word(6).dword(0x7fffffff).dword(3);
  EXPECT_EQ(binError(x.b), "bad.x:byte 28: error: a list of 2147483647 integers runs past the end of the file");
  // Binary: a vertex count of 1000000 with three floats behind it; the count is the
  // list's first element: 28 + 2 (TOKEN_INTEGER_LIST) + 4 (element count) = 34.
  XBin y;
  y.name("Mesh").open().ints({1000000}).floats({0, 0, 0}).close();
  EXPECT_EQ(binError(y.b), "bad.x:byte 34: error: the vertex count 1000000 is larger than the rest of the file can hold");
}

TEST(XFileErrors, HeaderAndCompressedFormats) {
  EXPECT_EQ(xError("xof 0303tzip0032\n"),
            "bad.x:1:1: error: compressed .x files ('tzip', MSZIP) are not supported; save the file as 'txt ' or 'bin '");
  EXPECT_NE(xError("xof 0303bzip0064").find("compressed .x files ('bzip'"), std::string::npos);
  EXPECT_EQ(xError("Mesh {}"), "bad.x:1:1: error: not a .x file (expected the header \"xof 0303txt 0032\")");
  EXPECT_EQ(xError("xof 0303txt 0016\n"),
            "bad.x:1:1: error: unknown float size in the .x header (expected 0032 or 0064)");
  EXPECT_EQ(xError("xof 0303txt 0032\n// nothing\n"), "bad.x:3:1: error: the file holds no Mesh object");
}

TEST(XFileErrors, DeepNesting) {
  std::string frames = "xof 0303txt 0032\n";
  for (int i = 0; i < 100; ++i) frames += "Frame {\n";
  EXPECT_EQ(xError(frames), "bad.x:66:1: error: Frames nested deeper than 64 levels");
  // Unknown objects are skipped by counting braces: deep nesting costs no stack.
  std::string deep = "xof 0303txt 0032\nFoo {";
  for (int i = 0; i < 200000; ++i) deep += " {";
  EXPECT_NE(xError(deep).find("bad.x:2:"), std::string::npos);
}

TEST(XFileErrors, OverlongTextureName) {
  std::string text = "xof 0303txt 0032\nMaterial M { 1;1;1;1;; 0; 0;0;0;; 0;0;0;;\n TextureFilename { \"" +
                     std::string(1025, 'a') + "\"; } }\n";
  EXPECT_EQ(xError(text), "bad.x:3:20: error: the texture file name is 1025 bytes long, more than the 1024 accepted");
}

TEST(XFileErrors, BinaryUnknownTokenAndBadString) {
  XBin x;
  x.name("Mesh").open().word(99);
  EXPECT_EQ(binError(x.b), "bad.x:byte 28: error: unknown token 99");
  XBin y;
  y.word(2).dword(1000).raw("abc", 3);
  EXPECT_EQ(binError(y.b), "bad.x:byte 16: error: the string runs past the end of the file");
}

TEST(XFileErrors, SaveRejectsWhatTheFormatCannotHold) {
  Mesh m(d3d::FVF_XYZ, 3, 1);
  m.setPosition(0, {std::nanf(""), 0, 0});
  EXPECT_THROW(xFileText(m), Error);
  Mesh q(d3d::FVF_XYZ, 3, 1);
  q.materials = {XMaterial{}};
  q.materials[0].textureFilename = "a\"b.png";
  EXPECT_THROW(xFileText(q), Error);
  q.materials[0].textureFilename = "ok.png";
  q.attributes = {1};  // only one material
  EXPECT_THROW(xFileText(q), Error);
}

TEST(OBJErrors, LocationsOfBadStatements) {
  auto objError = [](const std::string& text) -> std::string {
    try {
      loadOBJFromMemory(text, "bad.obj");
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(objError("v 0 0 0\nv 1 x 0\n"), "bad.obj:2:5: error: expected the y coordinate (a number), got 'x'");
  EXPECT_EQ(objError("v 0 0\n"), "bad.obj:1:6: error: expected the z coordinate after '0'");
  EXPECT_EQ(objError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
            "bad.obj:4:7: error: vertex index 4 in '4' refers to none of the 3 vertices read so far");
  EXPECT_EQ(objError("v 0 0 0\nf 0 1 1\n"), "bad.obj:2:3: error: vertex index 0 in '0': OBJ indices start at 1");
  EXPECT_EQ(objError("v 0 0 0\nf 1 1\n"), "bad.obj:2:6: error: a face needs at least 3 corners, this one has 2");
  EXPECT_EQ(objError("v 0 0 0\nf 1/2 1 1\n"),
            "bad.obj:2:3: error: texture coordinate index 2 in '1/2' refers to none of the 0 texture coordinates read "
            "so far");
  EXPECT_EQ(objError("v 0 0 0\nf 1/a 1 1\n"),
            "bad.obj:2:3: error: expected a texture coordinate index in '1/a', got 'a'");
}
