// Binding a d3dx::Mesh to a device, shared by the samples, the benchmark and the tests
// that render the samples' scenes.
#pragma once
#include <memory>

#include "refx/d3dx/mesh.h"
#include "refx/pipeline/device.h"

namespace refx::samples {

// Sets the mesh's FVF, a vertex buffer on stream 0 and a 32-bit index buffer.
inline void bindMesh(Device& dev, const d3dx::Mesh& m) {
  dev.setFVF(m.fvf);
  auto vb = std::make_shared<VertexBuffer>();
  vb->data = m.vertices;
  dev.setStreamSource(0, vb, 0, m.stride);
  auto ib = std::make_shared<IndexBuffer>();
  ib->index32 = true;
  ib->data = m.indexBufferData(true);
  dev.setIndices(ib);
}

}  // namespace refx::samples
