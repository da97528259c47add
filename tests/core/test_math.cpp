// D3DX matrix conventions (row vectors, v * M, left-handed), worked out by hand from
// the D3DX documentation's formulas.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "refx/core/math.h"
#include "refx/core/text.h"
#include "refx/core/thread_pool.h"

using namespace refx;

namespace {

constexpr float kPi = 3.14159265358979f;

void expectVec(Vec4 got, Vec4 want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
  EXPECT_NEAR(got.w, want.w, tol);
}

TEST(Math, LookAtLHFromMinusZ) {
  // eye (0,0,-5) at origin, up +y: z = (0,0,1), x = up x z = (1,0,0), y = z x x = (0,1,0),
  // translation row = (-x.eye, -y.eye, -z.eye) = (0,0,5).
  Matrix m = matrixLookAtLH({0, 0, -5}, {0, 0, 0}, {0, 1, 0});
  expectVec(Vec4(0, 0, 0, 1) * m, {0, 0, 5, 1});
  expectVec(Vec4(1, 2, 0, 1) * m, {1, 2, 5, 1});
}

TEST(Math, LookAtLHFromPlusXPutsPlusZOnTheRight) {
  // eye (5,0,0): z = (-1,0,0), x = cross((0,1,0),(-1,0,0)) = (0,0,1), y = (0,1,0);
  // world (0,0,1) -> view x = 1 (right), z = -z.eye = 5.
  Matrix m = matrixLookAtLH({5, 0, 0}, {0, 0, 0}, {0, 1, 0});
  expectVec(Vec4(0, 0, 1, 1) * m, {1, 0, 5, 1});
}

TEST(Math, PerspectiveFovLHMapsNearToZeroAndFarToOne) {
  // fovy 90 deg, aspect 2, zn 1, zf 11: yscale = cot(45) = 1, xscale = 0.5,
  // _33 = zf/(zf-zn) = 1.1, _34 = 1, _43 = -zn*zf/(zf-zn) = -1.1.
  Matrix m = matrixPerspectiveFovLH(kPi / 2, 2.0f, 1.0f, 11.0f);
  EXPECT_NEAR(m.m[0][0], 0.5f, 1e-6f);
  EXPECT_NEAR(m.m[1][1], 1.0f, 1e-6f);
  EXPECT_NEAR(m.m[2][2], 1.1f, 1e-6f);
  EXPECT_EQ(m.m[2][3], 1.0f);
  EXPECT_NEAR(m.m[3][2], -1.1f, 1e-6f);
  EXPECT_NEAR(transformCoord({0, 0, 1}, m).z, 0.0f, 1e-6f);   // near plane
  EXPECT_NEAR(transformCoord({0, 0, 11}, m).z, 1.0f, 1e-6f);  // far plane
  // (2,1,2): x' = 2*0.5 = 1, y' = 1, w = 2 -> (0.5, 0.5).
  Vec3 p = transformCoord({2, 1, 2}, m);
  EXPECT_NEAR(p.x, 0.5f, 1e-6f);
  EXPECT_NEAR(p.y, 0.5f, 1e-6f);
}

TEST(Math, OrthoLH) {
  // w 4, h 2, zn 1, zf 5: _11 = 2/w = 0.5, _22 = 1, _33 = 1/(zf-zn) = 0.25,
  // _43 = zn/(zn-zf) = -0.25: (2, 1, 5) -> (1, 1, 1.25 - 0.25 = 1).
  Matrix m = matrixOrthoLH(4, 2, 1, 5);
  expectVec(Vec4(2, 1, 5, 1) * m, {1, 1, 1, 1});
  expectVec(Vec4(0, 0, 1, 1) * m, {0, 0, 0, 1});
}

TEST(Math, RotationsAreLeftHandedRowVector) {
  // RotationY(90): (1,0,0) -> (cos, 0, -sin) = (0,0,-1).
  expectVec(Vec4(1, 0, 0, 0) * matrixRotationY(kPi / 2), {0, 0, -1, 0});
  // RotationX(90): (0,1,0) -> (0, cos, sin) = (0,0,1).
  expectVec(Vec4(0, 1, 0, 0) * matrixRotationX(kPi / 2), {0, 0, 1, 0});
  // RotationZ(90): (1,0,0) -> (cos, sin, 0) = (0,1,0).
  expectVec(Vec4(1, 0, 0, 0) * matrixRotationZ(kPi / 2), {0, 1, 0, 0});
  // Axis (0,1,0) equals RotationY.
  Matrix a = matrixRotationAxis({0, 2, 0}, 0.7f), b = matrixRotationY(0.7f);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], 1e-6f);
}

TEST(Math, YawPitchRollAppliesRollThenPitchThenYaw) {
  // Roll 90 first takes (1,0,0) to (0,1,0); yaw about y then leaves it there.
  // (Yaw first would give (0,0,-1), which roll keeps.)
  expectVec(Vec4(1, 0, 0, 0) * matrixRotationYawPitchRoll(kPi / 2, 0, kPi / 2), {0, 1, 0, 0});
}

TEST(Math, InverseTransposeAndTransforms) {
  Matrix m = matrixScaling(2, 4, 8) * matrixTranslation(1, 2, 3);
  Matrix inv;
  ASSERT_TRUE(inverse(m, inv));
  // m maps (1,1,1) -> (2+1, 4+2, 8+3) = (3,6,11); the inverse maps it back.
  expectVec(Vec4(3, 6, 11, 1) * inv, {1, 1, 1, 1});
  Matrix id = m * inv;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(id.m[i][j], i == j ? 1.0f : 0.0f, 1e-6f);
  EXPECT_FALSE(inverse(matrixScaling(1, 0, 1), inv));
  Matrix t = transpose(matrixTranslation(1, 2, 3));
  EXPECT_EQ(t.m[0][3], 1.0f);
  EXPECT_EQ(t.m[2][3], 3.0f);
  // transformNormal ignores translation; transformCoord divides by w.
  Vec3 n = transformNormal({0, 1, 0}, m);
  EXPECT_EQ(n, Vec3(0, 4, 0));
  Matrix w2 = Matrix::identity();
  w2.m[3][3] = 2;
  EXPECT_EQ(transformCoord({2, 4, 6}, w2), Vec3(1, 2, 3));
}

TEST(ThreadPool, EveryIndexRunsOnceOnEveryPoolSize) {
  for (int threads : {1, 2, 8}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.threadCount(), threads);
    for (int round = 0; round < 20; ++round) {
      std::vector<std::atomic<int>> hits(257);
      std::atomic<bool> badThread{false};
      pool.parallelFor(hits.size(), [&](size_t i, int t) {
        hits[i].fetch_add(1);
        if (t < 0 || t >= threads) badThread = true;
      });
      for (auto& h : hits) EXPECT_EQ(h.load(), 1);
      EXPECT_FALSE(badThread.load());
    }
  }
}

TEST(Text, HelpersTrimCompareAndParse) {
  EXPECT_EQ(trim("  a b \t"), "a b");
  EXPECT_TRUE(equalsNoCase("D3DRS_ZENABLE", "d3drs_zenable"));
  EXPECT_FALSE(equalsNoCase("ZENABLE", "ZENABLED"));
  EXPECT_TRUE(startsWithNoCase("d3dtop_add", "D3DTOP_"));
  EXPECT_EQ(parseUnsigned("0x1F"), 31u);
  EXPECT_EQ(parseUnsigned("42"), 42u);
  EXPECT_FALSE(parseUnsigned("4 2").has_value());
  EXPECT_FALSE(parseUnsigned("0x").has_value());
  EXPECT_FALSE(parseUnsigned("-1").has_value());
}

}  // namespace
