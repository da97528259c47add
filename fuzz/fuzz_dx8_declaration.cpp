// DirectX 8 vertex declaration fuzz target. The first byte picks the form of the rest:
// bit 0 clear: text (D3DVSD_* token macros or an effect `decl` block, parsed by
// parseVsDeclaration); bit 0 set: D3DVSD tokens (decodeVsDeclaration). A declaration
// that parses encodes to tokens that decode and encode to the same tokens, becomes a
// D3D9 vertex declaration (vertexDeclarationFromVsd) whose D3DVSD_CONST data loads
// into the vertex shader constants, and a triangle of stream 0 vertices in its layout
// is drawn, by the fixed-function pipeline (bit 1 clear) or by a vs_1_1 shader without
// dcl (bit 1 set). Never a crash: anything the device cannot draw gives refx::Error.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/device.h"
#include "refx/pipeline/dx8_declaration.h"
#include "refx/shader/assembler.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/vs_declaration.h"

namespace {

using namespace refx;

// Vertices larger than this are not drawn (D3D8's largest vertex is far smaller).
constexpr uint32_t kMaxStride = 1024;

void draw(const shader::VsDeclaration& vsd, bool withShader) {
  static const CapsProfile caps = loadCapsProfile("ref");
  static const std::vector<uint32_t> shaderTokens =
      shader::assembleTokens("vs_1_1\nmov oPos, v0\nmad oD0, v5, c4, v3\nmov oT0, v7\n");
  DeviceOptions options;
  options.threads = 1;
  Device device(caps, options);
  device.setRenderTarget(Texture::create2D(Format::A8R8G8B8, 8, 8));
  device.setDepthStencilSurface(std::make_shared<DepthStencilSurface>(8, 8));
  device.setVertexDeclaration(vertexDeclarationFromVsd(vsd));
  setVsdConstants(device, vsd);
  if (withShader) device.setVertexShader(device.createVertexShader(shaderTokens));
  const uint32_t stride = shader::vsdStreamSize(vsd, 0);
  if (stride == 0 || stride > kMaxStride) return;
  // Three vertices of small floats (read as colors, bytes and shorts where the layout
  // says so), most positions inside the clip volume.
  std::vector<uint8_t> vertices(size_t(stride) * 3);
  static constexpr float kValues[] = {0.5f, -0.25f, 0.75f, 1.0f, -0.5f, 0.25f, 0.0f};
  for (size_t i = 0; i + 4 <= vertices.size(); i += 4)
    std::memcpy(&vertices[i], &kValues[(i / 4) % std::size(kValues)], 4);
  device.drawPrimitiveUP(d3d::PT_TRIANGLELIST, 1, vertices.data(), stride);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t select = data[0];
  const std::span<const uint8_t> rest(data + 1, size - 1);
  shader::VsDeclaration vsd;
  try {
    if (select & 1) {
      vsd = shader::decodeVsDeclaration(shader::tokensFromBytes(rest.first(rest.size() & ~size_t(3))));
    } else {
      vsd = shader::parseVsDeclaration(
          std::string_view(reinterpret_cast<const char*>(rest.data()), rest.size()), "fuzz.decl");
    }
  } catch (const Error&) {
    return 0;
  }
  const std::vector<uint32_t> tokens = shader::encodeVsDeclaration(vsd);
  try {
    if (shader::encodeVsDeclaration(shader::decodeVsDeclaration(tokens)) != tokens) std::abort();
  } catch (const Error&) {
    std::abort();  // what the encoder writes must decode
  }
  (void)shader::vsdElements(vsd);
  try {
    draw(vsd, select & 2);
  } catch (const Error&) {
  }
  return 0;
}
