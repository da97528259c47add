// CD3DArcBall of the DirectX 8 SDK framework (d3dutil.cpp).
#include "refx/d3dx/trackball.h"

#include <algorithm>
#include <cmath>

namespace refx::d3dx {

namespace {

// D3DXQuaternionAxisToAxis of the SDK framework: the rotation by the angle between
// `from` and `to` about their cross product, built from the half-way vector
// (q = (a x h, a . h) has half the angle of a -> b).
Quaternion axisToAxis(Vec3 from, Vec3 to) {
  Vec3 a = normalize(from), b = normalize(to);
  Vec3 h = normalize(a + b);
  Vec3 axis = cross(a, h);
  return {axis.x, axis.y, axis.z, dot(a, h)};
}

}  // namespace

Trackball::Trackball(int width, int height, float radius) { setWindow(width, height, radius); }

void Trackball::setWindow(int width, int height, float radius) {
  width_ = std::max(width, 1);
  height_ = std::max(height, 1);
  radius_ = radius > 0 && std::isfinite(radius) ? radius : 0.9f;
}

void Trackball::reset() {
  dragging_ = false;
  qDown_ = now_ = Quaternion::identity();
}

Vec3 Trackball::screenToVector(float px, float py) const {
  float x = -(px - float(width_) / 2) / (radius_ * float(width_) / 2);
  float y = (py - float(height_) / 2) / (radius_ * float(height_) / 2);
  float mag = x * x + y * y;
  if (mag > 1) {
    float scale = 1 / std::sqrt(mag);
    return {x * scale, y * scale, 0};
  }
  return {x, y, std::sqrt(1 - mag)};
}

void Trackball::begin(float x, float y) {
  dragging_ = true;
  down_ = screenToVector(x, y);
  qDown_ = now_;
}

void Trackball::drag(float x, float y) {
  if (!dragging_) return;
  Vec3 cur = screenToVector(x, y);
  // Opposite ball points have no unique half-way vector; keep the last rotation.
  if (length(down_ + cur) < 1e-6f) return;
  now_ = normalize(multiply(qDown_, axisToAxis(down_, cur)));
}

}  // namespace refx::d3dx
