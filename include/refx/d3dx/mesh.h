// D3DX meshes: an indexed triangle list with an FVF vertex layout, and the D3DX
// shape generators (D3DXCreateSphere, Box, Cylinder, Torus) plus a textured sphere
// with tangents for per-pixel lighting samples.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "refx/core/color.h"
#include "refx/core/math.h"
#include "refx/resource/vertex_format.h"

namespace refx::d3dx {

// A material of the attribute table, as a .x file's Material template holds it
// (faceColor, power, specularColor, emissiveColor, TextureFilename).
struct XMaterial {
  Color4 diffuse{1, 1, 1, 1};
  float power = 0;
  Vec3 specular;
  Vec3 emissive;
  std::string textureFilename;  // empty: no texture
  bool operator==(const XMaterial&) const = default;
};

struct Mesh {
  uint32_t fvf = 0;
  uint32_t stride = 0;
  std::vector<uint8_t> vertices;   // vertexCount() * stride bytes
  std::vector<uint32_t> indices;   // triangle list, clockwise front faces
  // Attribute table: the attribute id (an index into `materials`) of each face;
  // empty means every face has attribute 0.
  std::vector<uint32_t> attributes;
  std::vector<XMaterial> materials;

  Mesh() = default;
  // Zeroed vertices and indices for the given counts.
  Mesh(uint32_t fvf, uint32_t vertexCount, uint32_t faceCount);

  uint32_t vertexCount() const { return stride ? uint32_t(vertices.size() / stride) : 0; }
  uint32_t faceCount() const { return uint32_t(indices.size() / 3); }
  FVFLayout layout() const { return FVFLayout::of(fvf); }
  uint32_t attribute(uint32_t face) const { return face < attributes.size() ? attributes[face] : 0; }

  // Index buffer bytes as D3DX stores them: 16-bit (the default) or 32-bit
  // (D3DXMESH_32BIT); 16-bit throws refx::Error when an index exceeds 65535.
  std::vector<uint8_t> indexBufferData(bool index32) const;
  // D3DXATTRIBUTERANGE: one entry per run of consecutive faces with the same attribute
  // (one per subset after sortFacesByAttribute), with the vertex range they use.
  struct AttributeRange {
    uint32_t attribId, faceStart, faceCount, vertexStart, vertexCount;
    bool operator==(const AttributeRange&) const = default;
  };
  std::vector<AttributeRange> attributeTable() const;
  // Stable sort of the faces by attribute id (OptimizeInplace(D3DXMESHOPT_ATTRSORT)),
  // so each subset is one contiguous range for DrawSubset.
  void sortFacesByAttribute();

  // Element access; throws refx::Error when the vertex or the element does not exist.
  Vec3 position(uint32_t i) const;
  void setPosition(uint32_t i, Vec3 p);
  Vec3 normal(uint32_t i) const;
  void setNormal(uint32_t i, Vec3 n);
  D3DColor diffuse(uint32_t i) const;
  void setDiffuse(uint32_t i, D3DColor c);
  // Components past the set's dimension read as 0 and are ignored when written.
  Vec4 texCoord(uint32_t i, int set = 0) const;
  void setTexCoord(uint32_t i, int set, Vec4 t);
  void setTexCoord(uint32_t i, int set, float u, float v) { setTexCoord(i, set, Vec4(u, v, 0, 0)); }

 private:
  uint8_t* element(uint32_t i, int offset, const char* what);
  const uint8_t* element(uint32_t i, int offset, const char* what) const;
};

// D3DXMESH::CloneMeshFVF: the same triangles with a new vertex layout. Elements
// present in both layouts are copied (texture sets by index, the common components);
// new elements are zero. The attribute table and the materials are kept.
Mesh cloneMeshFVF(const Mesh& mesh, uint32_t newFvf);

// D3DXCreateSphere: FVF XYZ | NORMAL, axis z (pole vertex (0,0,radius) first, then
// stacks-1 rings of `slices` vertices from +z to -z, then the -z pole).
// slices >= 2, stacks >= 2.
Mesh createSphere(float radius, uint32_t slices, uint32_t stacks);

// Sphere for texture-mapped samples (an earth globe): axis y with the north pole at +y,
// (stacks+1) rows of (slices+1) vertices, the u = 0 and u = 1 columns duplicated at
// the seam. u = slice / slices grows eastward, v = stack / stacks from the north pole.
// FVF XYZ | NORMAL | TEX2 | TEXCOORDSIZE3(1): set 0 = (u, v), set 1 = tangent
// = normalize(dP/du). Viewed from outside with north up, east (+u) is to the right.
// slices >= 3, stacks >= 2.
Mesh createTexturedSphere(float radius, uint32_t slices, uint32_t stacks);

// D3DXCreateBox: 24 vertices (4 per face, flat normals), 12 triangles; face order
// -x, +y, +x, -y, +z, -z.
Mesh createBox(float width, float height, float depth);

// D3DXCreateCylinder: axis z, radius1 at z = -length/2, radius2 at z = +length/2;
// -z cap (center + ring), stacks+1 side rings, +z cap (ring + center).
// slices >= 2, stacks >= 1.
Mesh createCylinder(float radius1, float radius2, float length, uint32_t slices, uint32_t stacks);

// D3DXCreateTorus: axis z; the tube of radius innerRadius circles the axis at
// distance outerRadius (as D3DX lays it out). sides >= 3 around the tube,
// rings >= 3 around the axis.
Mesh createTorus(float innerRadius, float outerRadius, uint32_t sides, uint32_t rings);

}  // namespace refx::d3dx
