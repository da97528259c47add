#pragma once

namespace refx {

// Pixels and vertices are processed in SoA batches of this many lanes. For pixels a
// batch is a 4x4 block made of four 2x2 quads: lane = quad*4 + (y&1)*2 + (x&1),
// quads ordered (0,0) (2,0) (0,2) (2,2). Quads give the derivatives for mip selection.
constexpr int kBatchLanes = 16;

}  // namespace refx
