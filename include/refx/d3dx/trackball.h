// A virtual trackball as the DirectX 8 SDK samples' CD3DArcBall: a mouse drag in
// window coordinates turns the object so that the point of a sphere under the
// cursor follows the cursor.
#pragma once
#include "refx/core/math.h"

namespace refx::d3dx {

class Trackball {
 public:
  // radius: of the ball as a fraction of half the window size (CD3DArcBall's 0.9).
  explicit Trackball(int width = 1, int height = 1, float radius = 0.9f);
  void setWindow(int width, int height, float radius = 0.9f);

  // Button down at window position (x, y) (pixels, y down): the drag starts from the
  // current rotation.
  void begin(float x, float y);
  // Mouse move while the button is down: rotation = the rotation at begin() followed
  // by the rotation taking the ball point at begin() to the ball point at (x, y).
  // Ignored when no drag is in progress.
  void drag(float x, float y);
  void end() { dragging_ = false; }
  bool dragging() const { return dragging_; }
  void reset();

  Quaternion rotation() const { return now_; }
  // The world matrix of the rotation (D3DXMatrixRotationQuaternion).
  Matrix rotationMatrix() const { return matrixRotationQuaternion(now_); }

  // CD3DArcBall::ScreenToVector: x = -(px - W/2) / (radius * W/2),
  // y = (py - H/2) / (radius * H/2), z = sqrt(1 - x² - y²) inside the ball; outside it
  // (x, y) is scaled to unit length and z = 0. This is the antipode of the point of a
  // unit sphere seen under the cursor by a camera looking down +z with y up, so a
  // rotation that moves one onto the other moves the visible point with the cursor.
  Vec3 screenToVector(float x, float y) const;

 private:
  int width_ = 1, height_ = 1;
  float radius_ = 0.9f;
  bool dragging_ = false;
  Vec3 down_{0, 0, 1};
  Quaternion qDown_, now_;
};

}  // namespace refx::d3dx
