// .x file reader fuzz target: any bytes either load or give refx::Error, and a mesh
// that loads is saved as text and must load back identical.
#include <cstddef>
#include <cstdint>
#include <string>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/xfile.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx::d3dx;
  Mesh mesh;
  try {
    mesh = loadXFileFromMemory({data, size}, "fuzz.x");
  } catch (const refx::Error&) {
    return 0;
  }
  std::string text;
  try {
    text = xFileText(mesh);
  } catch (const refx::Error&) {
    return 0;  // a texture name a .x string cannot hold (quote, line break)
  }
  Mesh back = loadXFileFromMemory({reinterpret_cast<const uint8_t*>(text.data()), text.size()}, "saved.x");
  if (back.fvf != mesh.fvf || back.vertices != mesh.vertices || back.indices != mesh.indices ||
      back.attributes != mesh.attributes || back.materials != mesh.materials)
    __builtin_trap();
  return 0;
}
