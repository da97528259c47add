// D3DX quaternion helpers, checked against rotations worked out by hand in D3DX's
// row-vector, left-handed convention (d3dx-utilities.md §7).
#include <gtest/gtest.h>

#include <cmath>

#include "core/math_expect.h"
#include "refx/core/math.h"

using namespace refx;

using namespace refx::test;

TEST(Quaternion, RotationAxisIsHalfAngleSineAndCosine) {
  // 90 degrees about y: (0, sin 45, 0, cos 45).
  Quaternion q = quaternionRotationAxis({0, 2, 0}, kPi / 2);  // the axis is normalized
  expectQuat(q, 0, 0.70710678f, 0, 0.70710678f);
}

TEST(Quaternion, NinetyDegreesAboutYTurnsXIntoMinusZ) {
  // D3DX: row vector times matrix, left-handed. Row 1 of the quaternion matrix is
  // (1 - 2(y²+z²), 2(xy + zw), 2(xz - yw)) = (1 - 1, 0, -2 * 0.5) = (0, 0, -1),
  // so (1,0,0) -> (0,0,-1), the same as D3DXMatrixRotationY(90°) whose first row
  // is (cos, 0, -sin).
  Matrix m = matrixRotationQuaternion(quaternionRotationAxis({0, 1, 0}, kPi / 2));
  expectVec(rotate({1, 0, 0}, m), 0, 0, -1);
  expectMatrix(m, matrixRotationY(kPi / 2));
}

TEST(Quaternion, MatrixMatchesRotationAxis) {
  Vec3 axis{1, -2, 0.5f};
  for (float angle : {0.3f, 1.7f, -2.5f, 3.0f})
    expectMatrix(matrixRotationQuaternion(quaternionRotationAxis(axis, angle)),
                 matrixRotationAxis(axis, angle));
}

TEST(Quaternion, MultiplyAppliesTheFirstRotationFirst) {
  // q1 = 90° about y, q2 = 90° about x; s = c = sqrt(1/2).
  // multiply(q1, q2) = q2 * q1 (Hamilton):
  //   x = w2 x1 + x2 w1 + y2 z1 - z2 y1 = s c = 1/2
  //   y = w2 y1 - x2 z1 + y2 w1 + z2 x1 = c s = 1/2
  //   z = w2 z1 + x2 y1 - y2 x1 + z2 w1 = s s = 1/2
  //   w = w2 w1 - x2 x1 - y2 y1 - z2 z1 = c c = 1/2
  Quaternion q1 = quaternionRotationAxis({0, 1, 0}, kPi / 2);
  Quaternion q2 = quaternionRotationAxis({1, 0, 0}, kPi / 2);
  Quaternion q = multiply(q1, q2);
  expectQuat(q, 0.5f, 0.5f, 0.5f, 0.5f);
  // (1,0,0) -> (0,0,-1) by q1, then by RotationX(90°) (rows (1,0,0), (0,c,s), (0,-s,c))
  // (0,0,-1) -> -(row 3) = (0, s, -c) = (0, 1, 0).
  expectVec(rotate({1, 0, 0}, matrixRotationQuaternion(q)), 0, 1, 0);
  expectMatrix(matrixRotationQuaternion(q), matrixRotationQuaternion(q1) * matrixRotationQuaternion(q2));
}

TEST(Quaternion, NormalizeAndConjugate) {
  expectQuat(normalize(Quaternion{0, 3, 0, 4}), 0, 0.6f, 0, 0.8f);  // |q| = 5
  Quaternion q = quaternionRotationAxis({0, 0, 1}, 0.8f);
  expectQuat(multiply(q, conjugate(q)), 0, 0, 0, 1);
}

TEST(Quaternion, SlerpHalfway) {
  // Halfway from identity to 90° about y is 45° about y: (0, sin 22.5°, 0, cos 22.5°).
  Quaternion a = Quaternion::identity(), b = quaternionRotationAxis({0, 1, 0}, kPi / 2);
  expectQuat(slerp(a, b, 0.5f), 0, 0.38268343f, 0, 0.92387953f);
  expectQuat(slerp(a, b, 0), 0, 0, 0, 1);
  expectQuat(slerp(a, b, 1), b.x, b.y, b.z, b.w);
  // -b is the same rotation; slerp takes the shorter arc and gives the same result.
  Quaternion nb{-b.x, -b.y, -b.z, -b.w};
  expectQuat(slerp(a, nb, 0.5f), 0, 0.38268343f, 0, 0.92387953f);
  // A quarter of the way: 22.5° about y.
  expectQuat(slerp(a, b, 0.25f), 0, std::sin(kPi / 16), 0, std::cos(kPi / 16));
}

TEST(Quaternion, MatrixRoundTrip) {
  const Vec3 axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {-0.3f, 0.8f, 0.2f}, {2, -1, 3}};
  const float angles[] = {0.1f, 1.0f, 2.0f, 3.1f, kPi, -1.2f};
  for (Vec3 axis : axes)
    for (float angle : angles) {
      Quaternion q = quaternionRotationAxis(axis, angle);
      Quaternion r = quaternionRotationMatrix(matrixRotationQuaternion(q));
      // q and -q are the same rotation.
      float sign = dot(q, r) < 0 ? -1.0f : 1.0f;
      expectQuat(r, sign * q.x, sign * q.y, sign * q.z, sign * q.w, 1e-4f);
    }
  // 180° about x: matrix diag(1, -1, -1); trace + 1 = 0 takes the largest-diagonal branch.
  expectQuat(quaternionRotationMatrix(matrixRotationX(kPi)), 1, 0, 0, 0, 1e-4f);
  // A matrix from the other helpers.
  Matrix m = matrixRotationYawPitchRoll(0.4f, -0.7f, 1.1f);
  expectMatrix(matrixRotationQuaternion(quaternionRotationMatrix(m)), m, 1e-5f);
}
