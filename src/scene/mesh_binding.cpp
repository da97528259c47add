#include "refx/scene/mesh_binding.h"

#include <memory>

namespace refx::scene {

void bindMesh(Device& dev, const d3dx::Mesh& m) {
  dev.setFVF(m.fvf);
  auto vb = std::make_shared<VertexBuffer>();
  vb->data = m.vertices;
  dev.setStreamSource(0, vb, 0, m.stride);
  auto ib = std::make_shared<IndexBuffer>();
  ib->index32 = true;
  ib->data = m.indexBufferData(true);
  dev.setIndices(ib);
}

}  // namespace refx::scene
