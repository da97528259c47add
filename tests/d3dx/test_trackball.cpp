// The trackball's rotations, checked against rotations worked out by hand in D3DX's
// row-vector, left-handed convention (d3dx-utilities.md §7).
#include <gtest/gtest.h>

#include <cmath>

#include "refx/core/math.h"
#include "refx/d3dx/trackball.h"

using namespace refx;

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kEps = 1e-5f;

void expectQuat(Quaternion q, float x, float y, float z, float w, float eps = kEps) {
  EXPECT_NEAR(q.x, x, eps);
  EXPECT_NEAR(q.y, y, eps);
  EXPECT_NEAR(q.z, z, eps);
  EXPECT_NEAR(q.w, w, eps);
}

void expectVec(Vec3 v, float x, float y, float z, float eps = kEps) {
  EXPECT_NEAR(v.x, x, eps);
  EXPECT_NEAR(v.y, y, eps);
  EXPECT_NEAR(v.z, z, eps);
}

void expectMatrix(const Matrix& a, const Matrix& b, float eps = kEps) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], eps) << "m[" << i << "][" << j << "]";
}

// Row vector times matrix, w = 0 (a direction).
Vec3 rotate(Vec3 v, const Matrix& m) { return transformNormal(v, m); }

}  // namespace

TEST(Trackball, DragRightTurnsTheFrontToTheRight) {
  // 200x200 window, ball radius = half the window. Centre (100,100) -> ball (0,0,1);
  // (200,100): x = -(200-100)/100 = -1, y = 0, z = 0. The rotation takes (0,0,1) to
  // (-1,0,0): the front point (0,0,-1) facing a camera at -z goes to (1,0,0), to the
  // right. That is D3DXMatrixRotationY(-90°): rows (0,0,1), (0,1,0), (-1,0,0).
  d3dx::Trackball ball(200, 200, 1.0f);
  ball.begin(100, 100);
  ball.drag(200, 100);
  expectMatrix(ball.rotationMatrix(), matrixRotationY(-kPi / 2), 1e-5f);
  expectVec(rotate({0, 0, -1}, ball.rotationMatrix()), 1, 0, 0);
}

TEST(Trackball, DragDownTurnsTheFrontDown) {
  // (100,200): y = +1 -> ball (0,1,0); (0,0,1) -> (0,1,0) takes the front (0,0,-1) to
  // (0,-1,0), down on the screen: D3DXMatrixRotationX(-90°).
  d3dx::Trackball ball(200, 200, 1.0f);
  ball.begin(100, 100);
  ball.drag(100, 200);
  expectMatrix(ball.rotationMatrix(), matrixRotationX(-kPi / 2), 1e-5f);
}

TEST(Trackball, PointUnderTheCursorFollowsIt) {
  // The visible sphere point under pixel (px, py) of a W x H window with radius r:
  // x = (px - W/2)/(r W/2), y = -(py - H/2)/(r H/2), z = -sqrt(1 - x² - y²).
  const int w = 320, h = 240;
  const float r = 0.9f;
  auto visible = [&](float px, float py) {
    float x = (px - w / 2.0f) / (r * w / 2.0f), y = -(py - h / 2.0f) / (r * h / 2.0f);
    return Vec3{x, y, -std::sqrt(1 - x * x - y * y)};
  };
  d3dx::Trackball ball(w, h, r);
  ball.begin(140, 100);
  ball.drag(200, 150);
  Vec3 moved = rotate(visible(140, 100), ball.rotationMatrix());
  Vec3 want = visible(200, 150);
  expectVec(moved, want.x, want.y, want.z, 1e-5f);
  // A second drag continues from the first rotation.
  Quaternion first = ball.rotation();
  ball.end();
  ball.drag(10, 10);  // no button: ignored
  expectQuat(ball.rotation(), first.x, first.y, first.z, first.w);
  ball.begin(160, 120);
  ball.drag(160, 120);  // no motion: rotation unchanged
  expectQuat(ball.rotation(), first.x, first.y, first.z, first.w, 1e-6f);
  ball.reset();
  expectQuat(ball.rotation(), 0, 0, 0, 1);
}
