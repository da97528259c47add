// Caps profile fuzz target: any text either parses as a .caps file or gives
// refx::Error. A profile that parses is listed (`refx caps`), gives the shader
// validator its limits, and a device with it validates its state and draws a
// fixed-function triangle, however odd the limits.
#include <cstddef>
#include <cstdint>
#include <string>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/device.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx;
  const std::string text(reinterpret_cast<const char*>(data), size);
  CapsProfile caps;
  try {
    caps = parseCapsProfile(text, "fuzz.caps");
  } catch (const Error&) {
    return 0;
  }
  (void)describeCapsProfile(caps);
  DeviceOptions options;
  options.threads = 1;
  Device device(caps, options);
  (void)device.shaderValidationCaps();
  device.setRenderTarget(Texture::create2D(Format::A8R8G8B8, 8, 8));
  device.setDepthStencilSurface(std::make_shared<DepthStencilSurface>(8, 8));
  (void)device.validate();
  struct Vertex {
    float x, y, z, rhw;
    uint32_t color;
  };
  const Vertex triangle[3] = {{0, 0, 0.5f, 1, 0xffff0000}, {8, 0, 0.5f, 1, 0xff00ff00},
                              {0, 8, 0.5f, 1, 0xff0000ff}};
  try {
    device.setFVF(d3d::FVF_XYZRHW | d3d::FVF_DIFFUSE);
    device.drawPrimitiveUP(d3d::PT_TRIANGLELIST, 1, triangle, sizeof(Vertex));
  } catch (const Error&) {
  }
  return 0;
}
