// The AVX-512 variant of the block walk (raster_coverage.h): the same walk as the
// AVX2 variant (raster_coverage_walk.h), its 16 lanes in one register. Compiled with
// AVX-512 flags (CMakeLists.txt: sources named *_avx512.cpp) and called only where the
// CPU has them (chooseCoverBlocks).
#include "raster_coverage_walk.h"

namespace refx::pipeline {

int coverBlocksAvx512(const Primitive& p, int minX, int minY, int maxX, int maxY, CoveredBlock* out) {
  if (p.kind != PrimKind::Triangle) return coverBlocksAvx2(p, minX, minY, maxX, maxY, out);
  return walkTriangle(p, minX, minY, maxX, maxY, out);
}

}  // namespace refx::pipeline
