// Drawing a d3dx::Mesh on a device: what the samples, the benchmark and the tests that
// render the samples' scenes do with their meshes.
#pragma once
#include "refx/d3dx/mesh.h"
#include "refx/pipeline/device.h"

namespace refx::scene {

// Sets the mesh's FVF, a vertex buffer on stream 0 and a 32-bit index buffer.
void bindMesh(Device& dev, const d3dx::Mesh& m);

}  // namespace refx::scene
