// Wavefront OBJ meshes (with their MTL material libraries).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "refx/d3dx/mesh.h"

namespace refx::d3dx {

// Reads v, vt, vn and f (v, v/vt, v//vn, v/vt/vn; negative indices count back from
// the last element read); polygons are triangulated as fans (v0, vk, vk+1). One
// vertex per distinct (v, vt, vn) triple, in the order faces first use them.
//
// OBJ is right-handed with counter-clockwise front faces and v = 0 at the bottom of
// the image; the mesh is converted to Direct3D's conventions as D3D content tools do:
// z negated (positions and normals), triangles wound clockwise, v' = 1 - v. A model
// looks the same through a left-handed camera as through the mirrored right-handed one.
//
// FVF: XYZ | NORMAL (when faces use vn) | TEX1 (when faces use vt); corners without
// one of them get zeros. usemtl names give the attribute ids in the order of their
// first use; their materials come from the mtllib files (Kd, d / Tr, Ks, Ns, Ke,
// map_Kd), read relative to the OBJ file. A missing .mtl or an unknown material name
// is a warning: the material keeps the defaults (white, no texture). Faces before
// the first usemtl use a default material; a file without usemtl has no attribute
// table. Other statements (o, g, s, l, p, …) are ignored.
//
// Warnings ("file:line: warning: ...") go to `warnings`, or to stderr when it is null.
// Errors throw refx::Error "file:line:col: error: ...".
Mesh loadOBJ(const std::string& path, std::vector<std::string>* warnings = nullptr);
// Same from memory; mtllib statements are reported as warnings and not read.
Mesh loadOBJFromMemory(std::string_view text, const std::string& name,
                       std::vector<std::string>* warnings = nullptr);

}  // namespace refx::d3dx
