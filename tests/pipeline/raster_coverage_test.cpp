// The block walk of the tile loop (raster_coverage.h) against the scalar coverage
// reference, in both instruction-set variants: random triangles of every size and
// winding, in scissor rectangles, walked tile by tile as the rasterizer does; the
// top-left rule on shared edges; lines and points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "pipeline/output_merger.h"
#include "pipeline/raster_coverage.h"
#include "refx/core/cpu_features.h"

namespace refx::pipeline {
namespace {

constexpr int64_t kOne = int64_t(1) << kSubPixelBits;

// A triangle with subpixel vertices (X, Y): the device's edge functions
// (setTriangleEdges; the shared-edge test below checks their top-left rule). Bounds: the
// vertices' pixel bounding box within `clip` (inclusive). False: degenerate or empty.
bool makeTriangle(const int64_t (&X)[3], const int64_t (&Y)[3], int clipX0, int clipY0, int clipX1,
                  int clipY1, Primitive& p) {
  const int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
  if (area == 0) return false;
  p = Primitive{};
  setTriangleEdges(X, Y, area < 0, p);
  auto ceilPixel = [](int64_t v) { return int(std::ceil(double(v) / kOne)); };
  auto floorPixel = [](int64_t v) { return int(std::floor(double(v) / kOne)); };
  p.minX = std::max(clipX0, ceilPixel(std::min({X[0], X[1], X[2]})));
  p.maxX = std::min(clipX1, floorPixel(std::max({X[0], X[1], X[2]})));
  p.minY = std::max(clipY0, ceilPixel(std::min({Y[0], Y[1], Y[2]})));
  p.maxY = std::min(clipY1, floorPixel(std::max({Y[0], Y[1], Y[2]})));
  return p.minX <= p.maxX && p.minY <= p.maxY;
}

std::vector<CoverBlocksFn> variants() {
  std::vector<CoverBlocksFn> v = {coverBlocksAvx2};
  if (detectedIsa() == CpuIsa::Avx512) v.push_back(coverBlocksAvx512);
  return v;
}

// Walks p tile by tile as the tile loop does and checks every variant's blocks against
// referenceCoverage over each tile's rectangle; returns the blocks compared.
int checkAgainstReference(const Primitive& p, const char* what) {
  int compared = 0;
  for (int ty = p.minY / kTileSize; ty <= p.maxY / kTileSize; ++ty)
    for (int tx = p.minX / kTileSize; tx <= p.maxX / kTileSize; ++tx) {
      const int x0 = tx * kTileSize, y0 = ty * kTileSize;
      const int minX = std::max(p.minX, x0) & ~3, minY = std::max(p.minY, y0) & ~3;
      const int maxX = std::min(p.maxX, x0 + kTileSize - 1), maxY = std::min(p.maxY, y0 + kTileSize - 1);
      std::vector<CoveredBlock> expected;
      for (int by = minY; by <= maxY; by += 4)
        for (int bx = minX; bx <= maxX; bx += 4)
          if (const uint16_t mask = referenceCoverage(p, bx, by)) expected.push_back({bx, by, mask});
      for (CoverBlocksFn cover : variants()) {
        CoveredBlock out[kMaxTileBlocks];
        const int n = cover(p, minX, minY, maxX, maxY, out);
        EXPECT_EQ(n, int(expected.size())) << what << " tile " << tx << "," << ty;
        for (int i = 0; i < std::min(n, int(expected.size())); ++i) {
          EXPECT_EQ(out[i].bx, expected[i].bx) << what << " block " << i;
          EXPECT_EQ(out[i].by, expected[i].by) << what << " block " << i;
          EXPECT_EQ(out[i].mask, expected[i].mask) << what << " block " << i << " at " << out[i].bx << ","
                                                   << out[i].by;
        }
        if (::testing::Test::HasFailure()) return compared;
      }
      compared += int(expected.size());
    }
  return compared;
}

TEST(RasterCoverage, RandomTrianglesMatchTheReference) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Sizes in pixels: tiny, small (the sphere's), tile-sized, large, the guard band's
  // 16384 and beyond (edge offsets past the int32 range), each with a sliver variant.
  const double sizes[] = {0.7, 3, 12, 40, 150, 700, 3000, 16384, 200000};
  int triangles = 0, blocks = 0;
  for (double size : sizes)
    for (int n = 0; n < (size < 1000 ? 300 : 60); ++n) {  // large ones cover the whole target
      const bool sliver = n % 3 == 0, onCentres = n % 5 == 0;
      int64_t X[3], Y[3];
      const double cx = unit(rng) * 300 - 20, cy = unit(rng) * 300 - 20;
      const double angle = unit(rng) * 6.283185307179586;
      for (int i = 0; i < 3; ++i) {
        double ox = (unit(rng) - 0.5) * size, oy = (unit(rng) - 0.5) * size;
        if (sliver) oy *= 0.01;  // thin along a random direction
        const double x = cx + ox * std::cos(angle) - oy * std::sin(angle);
        const double y = cy + ox * std::sin(angle) + oy * std::cos(angle);
        // On pixel centres some of the time: edges through centres test the top-left rule.
        X[i] = onCentres ? int64_t(std::llround(x)) * kOne : int64_t(std::llround(x * kOne));
        Y[i] = onCentres ? int64_t(std::llround(y)) * kOne : int64_t(std::llround(y * kOne));
      }
      if (onCentres && size > 1000) {
        // Large edges rarely meet a pixel centre inside the target: put the first one
        // through a centre, vertices far out on both sides along a small integer step.
        const int64_t px = int64_t(unit(rng) * 300), py = int64_t(unit(rng) * 280);
        const int64_t sx = int64_t(unit(rng) * 9) - 4, sy = int64_t(unit(rng) * 9) - 4;
        const int64_t t = int64_t(size / 8);
        X[0] = (px - t * sx) * kOne, Y[0] = (py - t * sy) * kOne;
        X[1] = (px + t * sx) * kOne, Y[1] = (py + t * sy) * kOne;
      }
      // A scissor rectangle inside a 320x300 target, sometimes cutting the triangle.
      const int sx0 = n % 4 == 1 ? int(unit(rng) * 100) : 0, sy0 = n % 4 == 1 ? int(unit(rng) * 100) : 0;
      const int sx1 = n % 4 == 1 ? 150 + int(unit(rng) * 170) : 319, sy1 = n % 4 == 1 ? 150 + int(unit(rng) * 150) : 299;
      for (bool swapWinding : {false, true}) {
        if (swapWinding) {
          std::swap(X[1], X[2]);
          std::swap(Y[1], Y[2]);
        }
        Primitive p;
        if (!makeTriangle(X, Y, sx0, sy0, sx1, sy1, p)) continue;
        ++triangles;
        blocks += checkAgainstReference(p, "triangle");
        if (HasFailure()) {
          ADD_FAILURE() << "size " << size << " n " << n << " vertices (" << X[0] << "," << Y[0] << ") (" << X[1]
                        << "," << Y[1] << ") (" << X[2] << "," << Y[2] << ")";
          return;
        }
      }
    }
  // The sample covered every kind: thousands of triangles, many covered blocks.
  EXPECT_GT(triangles, 2000);
  EXPECT_GT(blocks, 100000);
}

// Pixels of a 128x128 target covered by each triangle, counted through the block walk.
void countCoverage(const Primitive& p, CoverBlocksFn cover, std::vector<int>& counts) {
  for (int ty = p.minY / kTileSize; ty <= p.maxY / kTileSize; ++ty)
    for (int tx = p.minX / kTileSize; tx <= p.maxX / kTileSize; ++tx) {
      const int x0 = tx * kTileSize, y0 = ty * kTileSize;
      CoveredBlock out[kMaxTileBlocks];
      const int n = cover(p, std::max(p.minX, x0) & ~3, std::max(p.minY, y0) & ~3,
                          std::min(p.maxX, x0 + kTileSize - 1), std::min(p.maxY, y0 + kTileSize - 1), out);
      for (int i = 0; i < n; ++i)
        for (int l = 0; l < kBatchLanes; ++l)
          if (out[i].mask >> l & 1) ++counts[size_t(out[i].by + kLaneY[l]) * 128 + (out[i].bx + kLaneX[l])];
    }
}

TEST(RasterCoverage, TwoTrianglesSharingAnEdgeCoverEachPixelOnce) {
  // A convex quad split along a diagonal: every pixel centre strictly inside the quad
  // (its four edges' E > 0), the diagonal's included, is covered by exactly one of the
  // two triangles, and no pixel by both (the top-left rule).
  std::mt19937 rng(99);
  std::uniform_int_distribution<int> coord(0, 127 * 4);  // quarter pixels, often on centres
  int quads = 0, insidePixels = 0;
  for (int n = 0; n < 1000; ++n) {
    int64_t X[4], Y[4];
    for (int i = 0; i < 4; ++i) {
      X[i] = int64_t(coord(rng)) * kOne / 4;
      Y[i] = int64_t(coord(rng)) * kOne / 4;
    }
    // Convex and clockwise on screen (y down): each turn has positive cross product.
    bool convex = true;
    for (int i = 0; i < 4; ++i) {
      const int a = i, b = (i + 1) % 4, c = (i + 2) % 4;
      convex &= (X[b] - X[a]) * (Y[c] - Y[b]) - (Y[b] - Y[a]) * (X[c] - X[b]) > 0;
    }
    if (!convex) continue;
    ++quads;
    for (CoverBlocksFn cover : variants()) {
      std::vector<int> counts(128 * 128, 0);
      const int64_t tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
      for (const auto& t : tri) {
        const int64_t tx[3] = {X[t[0]], X[t[1]], X[t[2]]}, ty[3] = {Y[t[0]], Y[t[1]], Y[t[2]]};
        Primitive p;
        if (makeTriangle(tx, ty, 0, 0, 127, 127, p)) countCoverage(p, cover, counts);
      }
      for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
          bool strictlyInside = true;  // E > 0 for the quad's four clockwise edges
          for (int i = 0; i < 4; ++i) {
            const int a = i, b = (i + 1) % 4;
            strictlyInside &= (y * kOne - Y[a]) * (X[b] - X[a]) - (x * kOne - X[a]) * (Y[b] - Y[a]) > 0;
          }
          const int c = counts[size_t(y) * 128 + x];
          ASSERT_LE(c, 1) << "quad " << n << " pixel " << x << "," << y;
          if (strictlyInside) {
            ASSERT_EQ(c, 1) << "quad " << n << " pixel " << x << "," << y;
            ++insidePixels;
          }
        }
    }
  }
  EXPECT_GT(quads, 50);
  EXPECT_GT(insidePixels, 10000);
}

TEST(RasterCoverage, ChosenVariantFollowsTheActiveIsa) {
  const CpuIsa previous = activeIsa();
  setActiveIsa(CpuIsa::Avx2);
  EXPECT_EQ(chooseCoverBlocks(), &coverBlocksAvx2);
  if (detectedIsa() == CpuIsa::Avx512) {
    setActiveIsa(CpuIsa::Avx512);
    EXPECT_EQ(chooseCoverBlocks(), &coverBlocksAvx512);
  }
  setActiveIsa(previous);
}

TEST(RasterCoverage, LinesAndPointsMatchTheReference) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-10.0f, 200.0f);
  for (int n = 0; n < 500; ++n) {
    Primitive p{};
    if (n % 2) {
      // A line from a to b: y = m x + q along x (or x = m y + q along y), bounds one
      // pixel around it.
      const float ax = pos(rng), ay = pos(rng), bx = pos(rng), by = pos(rng);
      p.kind = PrimKind::Line;
      p.xMajor = std::fabs(bx - ax) >= std::fabs(by - ay);
      const float amaj = p.xMajor ? ax : ay, bmaj = p.xMajor ? bx : by;
      const float amin = p.xMajor ? ay : ax, bmin = p.xMajor ? by : bx;
      if (amaj == bmaj) continue;
      p.lineM = (bmin - amin) / (bmaj - amaj);
      p.lineQ = amin - p.lineM * amaj;
      p.minX = std::max(0, int(std::floor(std::min(ax, bx))) - 1);
      p.maxX = std::min(190, int(std::ceil(std::max(ax, bx))) + 1);
      p.minY = std::max(0, int(std::floor(std::min(ay, by))) - 1);
      p.maxY = std::min(190, int(std::ceil(std::max(ay, by))) + 1);
    } else {
      p.kind = PrimKind::Point;
      const float x = pos(rng), y = pos(rng), h = 0.5f + float(n % 9);
      p.minX = std::max(0, int(std::ceil(x - h)));
      p.maxX = std::min(190, int(std::ceil(x + h)) - 1);
      p.minY = std::max(0, int(std::ceil(y - h)));
      p.maxY = std::min(190, int(std::ceil(y + h)) - 1);
    }
    if (p.minX > p.maxX || p.minY > p.maxY) continue;
    checkAgainstReference(p, n % 2 ? "line" : "point");
    if (HasFailure()) return;
  }
}

}  // namespace
}  // namespace refx::pipeline
