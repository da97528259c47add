// DirectX .x mesh files (D3DXLoadMeshFromX / D3DXSaveMeshToX): text and binary
// encodings, 32- and 64-bit floats. The compressed variants (tzip, bzip) are rejected.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "refx/d3dx/mesh.h"

namespace refx::d3dx {

// Every Mesh data object of the file merged into one mesh, as D3DXLoadMeshFromX does:
// meshes nested in Frames are moved by the frames' FrameTransformMatrix (world =
// local * parent), normals by its inverse transpose. Polygons are triangulated as
// fans (v0, vk, vk+1). Where MeshNormals gives one position different normals, the
// vertex is split: vertex i of the file stays vertex i, the copies follow the
// file's vertices.
//
// FVF of the result: XYZ | NORMAL (MeshNormals) | DIFFUSE (MeshVertexColors) |
// TEXn (MeshTextureCoords is set 0; DeclData TEXCOORDn elements add set n).
// MeshMaterialList gives `materials` and the attribute id of every triangle; a
// file without materials gives an empty attribute table.
//
// Limits against hostile files: Frames nest at most 64 deep, texture file names are
// at most 1024 bytes, and a count larger than the rest of the file can hold is an
// error before anything is allocated.
//
// Errors: refx::Error "file:line:col: error: ..." (text) or "file:byte N: error:
// ..." (binary).
Mesh loadXFile(const std::string& path);
// Same from memory; `name` is used in error messages.
Mesh loadXFileFromMemory(std::span<const uint8_t> bytes, const std::string& name);

// Text .x (xof 0303txt 0032) with Mesh, MeshNormals, MeshTextureCoords (set 0 when it
// has 2 components), MeshVertexColors, MeshMaterialList / Material / TextureFilename
// and, for the other texture coordinate sets, DeclData. Loading the result gives
// the same vertices, indices, attributes and materials. The w / rhw of the position,
// blend weights, point size and specular colors are not written; a mesh without a
// position or with non-finite values throws refx::Error.
std::string xFileText(const Mesh& mesh);
void saveXFileText(const Mesh& mesh, const std::string& path);

}  // namespace refx::d3dx
