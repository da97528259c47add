#include "depth.h"

#include <cmath>

namespace refx::pipeline {

float projectionFarW(const Matrix& p) {
  const float m33 = p.m[2][2], m34 = p.m[2][3], m43 = p.m[3][2], m44 = p.m[3][3];
  if (m33 == m34) return 1.0f;
  const float farW = m34 * (m44 - m43) / (m33 - m34) + m44;
  return std::isfinite(farW) && farW > 0 ? farW : 1.0f;
}

}  // namespace refx::pipeline
