// OBJ reader fuzz target: any text either loads or gives refx::Error.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> warnings;
  try {
    refx::d3dx::loadOBJFromMemory({reinterpret_cast<const char*>(data), size}, "fuzz.obj", &warnings);
  } catch (const refx::Error&) {
  }
  return 0;
}
