// The built-in procedural textures and meshes of `refx asset`, by name, for the
// commands that bind them (`refx render --texture NAME=ASSET`, `--mesh`).
#pragma once
#include <optional>
#include <string>

#include "refx/d3dx/mesh.h"
#include "refx/resource/texture.h"

namespace refx::cli {

// nullptr / nullopt when `name` is not a built-in texture / mesh.
TexturePtr builtinTexture(const std::string& name);
std::optional<d3dx::Mesh> builtinMesh(const std::string& name);

}  // namespace refx::cli
