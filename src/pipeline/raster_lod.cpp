#include "raster_lod.h"

#include <algorithm>
#include <cmath>

namespace refx::pipeline {

namespace {

constexpr double kEps = 0x1p-24;  // a float operation's relative rounding error

struct Interval {
  double lo, hi;
};

// |a + b·t| over t in [t0, t1].
Interval absOfLinear(double a, double b, double t0, double t1) {
  const double p = a + b * t0, q = a + b * t1;
  const double hi = std::max(std::fabs(p), std::fabs(q));
  const bool crosses = (p <= 0 && q >= 0) || (p >= 0 && q <= 0);
  return {crosses ? 0.0 : std::min(std::fabs(p), std::fabs(q)), hi};
}

// What the region and 1/w give every coordinate's bounds.
struct Region {
  double x0, x1, y0, y1;  // lane positions from the plane origin
  double qMin, qMax;      // 1/w over the region (exact)
  double aw, bw, cw;      // the 1/w plane
  double wError;          // relative error bound of a lane's computed w = 1/(1/w)
  double maxX, maxY;      // the largest |x| and |y| of a lane (and its neighbour)
  // The terms' sizes |a| + |b|·|x| + |c|·|y| of a plane's value: what its roundings scale with.
  double size(double a, double b, double c) const { return std::fabs(a) + std::fabs(b) * maxX + std::fabs(c) * maxY; }
  // |value| of a plane over the region (a linear function: at the corners).
  double maxAbs(double a, double b, double c) const {
    double m = 0;
    for (double x : {x0, x1})
      for (double y : {y0, y1}) m = std::max(m, std::fabs(a + b * x + c * y));
    return m;
  }
};

// The bounds of |computed difference · scale| between a quad's lanes along x (`alongX`)
// or y, for one coordinate: the exact difference's range and the error of everything
// the lanes' values and the classification's subtraction and product add.
Interval scaledDifference(const Region& r, CoordinatePlane cp, double scale, bool alongX) {
  const double a = cp.plane[0], b = cp.plane[1], c = cp.plane[2];
  // The plane's value at a lane: the lane's position (two roundings of its offsets) and
  // three operations, each within kEps of the terms' sizes; 8 for a margin.
  const double planeError = 8 * kEps * r.size(a, b, c);
  Interval exact;
  double valueError;
  if (cp.flat) {
    exact = {std::fabs(alongX ? b : c), std::fabs(alongX ? b : c)};
    valueError = planeError;
  } else {
    // u = P/Q: u(x+1) - u(x) = (b·Q - bw·P) / (Q(x)·Q(x+1)), whose numerator depends on
    // y alone (and along y, on x alone).
    const Interval n = alongX ? absOfLinear(b * r.aw - r.bw * a, b * r.cw - r.bw * c, r.y0, r.y1)
                              : absOfLinear(c * r.aw - r.cw * a, c * r.bw - r.cw * b, r.x0, r.x1);
    exact = {n.lo / (r.qMax * r.qMax), n.hi / (r.qMin * r.qMin)};
    // Computed P·(1/Q), each of them off by its bound, and the product's rounding.
    const double pMax = r.maxAbs(a, b, c) + planeError;
    valueError = (planeError / r.qMin) * (1 + r.wError) * (1 + kEps) + (pMax / r.qMin) * (r.wError + 2 * kEps);
  }
  // Two lanes' errors, the subtraction's and the product's roundings.
  const double error = scale * (2.02 * valueError + 2.02 * kEps * exact.hi);
  return {std::max(0.0, exact.lo * scale - error), exact.hi * scale + error};
}

}  // namespace

ProvenRho provenQuadRho(const float* invW, CoordinatePlane u, CoordinatePlane v, float originX, float originY, int x0,
                       int y0, int x1, int y1, float width, float height) {
  Region r;
  r.x0 = double(x0) - double(originX), r.x1 = double(x1) - double(originX);
  r.y0 = double(y0) - double(originY), r.y1 = double(y1) - double(originY);
  r.maxX = std::max(std::fabs(r.x0), std::fabs(r.x1)) + 1;
  r.maxY = std::max(std::fabs(r.y0), std::fabs(r.y1)) + 1;
  r.aw = invW[0], r.bw = invW[1], r.cw = invW[2];
  r.qMin = HUGE_VAL, r.qMax = 0;
  for (double x : {r.x0, r.x1})
    for (double y : {r.y0, r.y1}) {
      const double q = r.aw + r.bw * x + r.cw * y;
      r.qMin = std::min(r.qMin, q), r.qMax = std::max(r.qMax, q);
    }
  const double qError = 8 * kEps * r.size(r.aw, r.bw, r.cw);
  if (!(r.qMin > 0) || !(qError < 0.5 * r.qMin) || !std::isfinite(r.qMax)) return {};
  // 1/Q computed from Q off by qError, then rounded.
  r.wError = 1.01 * (qError / (r.qMin - qError) + kEps);
  const Interval ux = scaledDifference(r, u, width, true), vx = scaledDifference(r, v, height, true);
  const Interval uy = scaledDifference(r, u, width, false), vy = scaledDifference(r, v, height, false);
  // The squares, their sums (three roundings) and the larger of the two.
  const double lo = std::max(ux.lo * ux.lo + vx.lo * vx.lo, uy.lo * uy.lo + vy.lo * vy.lo) * (1 - 4 * kEps);
  const double hi = std::max(ux.hi * ux.hi + vx.hi * vx.hi, uy.hi * uy.hi + vy.hi * vy.hi) * (1 + 4 * kEps);
  if (!(lo > 0x1p-126) || !(hi < 0x1p127)) return {};
  ProvenRho rho;
  std::frexp(lo, &rho.low);  // lo = m·2^low, m in [0.5, 1)
  std::frexp(hi, &rho.high);
  --rho.low, --rho.high;
  // Where the sampler's classification reads the exponent alone: mantissas in
  // [2^-11, 1 - 2^-11) of the binade (1e-6: beyond the bounds' own margins).
  rho.lowNearEdge = lo < std::ldexp(1 + 0x1p-11, rho.low) * (1 + 1e-6);
  rho.highNearEdge = hi >= std::ldexp(2 - 0x1p-11, rho.high) * (1 - 1e-6);
  return rho;
}

}  // namespace refx::pipeline
