// The trackball's rotations, checked against rotations worked out by hand in D3DX's
// row-vector, left-handed convention (d3dx-utilities.md §7).
#include <gtest/gtest.h>

#include <cmath>

#include "core/math_expect.h"
#include "refx/core/math.h"
#include "refx/d3dx/trackball.h"

using namespace refx;

using namespace refx::test;

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
