// Expectations on D3DX math values, shared by the math and trackball tests.
#pragma once
#include <gtest/gtest.h>

#include "refx/core/math.h"

namespace refx::test {

constexpr float kPi = 3.14159265358979f;
constexpr float kEps = 1e-5f;

inline void expectQuat(Quaternion q, float x, float y, float z, float w, float eps = kEps) {
  EXPECT_NEAR(q.x, x, eps);
  EXPECT_NEAR(q.y, y, eps);
  EXPECT_NEAR(q.z, z, eps);
  EXPECT_NEAR(q.w, w, eps);
}

inline void expectVec(Vec3 v, float x, float y, float z, float eps = kEps) {
  EXPECT_NEAR(v.x, x, eps);
  EXPECT_NEAR(v.y, y, eps);
  EXPECT_NEAR(v.z, z, eps);
}

inline void expectMatrix(const Matrix& a, const Matrix& b, float eps = kEps) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], eps) << "m[" << i << "][" << j << "]";
}

// Row vector times matrix, w = 0 (a direction).
inline Vec3 rotate(Vec3 v, const Matrix& m) { return transformNormal(v, m); }

}  // namespace refx::test
