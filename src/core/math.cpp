#include "refx/core/math.h"

#include <algorithm>

namespace refx {

Matrix operator*(const Matrix& a, const Matrix& b) {
  Matrix r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j] +
                  a.m[i][3] * b.m[3][j];
  return r;
}

Vec4 operator*(Vec4 v, const Matrix& m) {
  Vec4 r;
  for (int j = 0; j < 4; ++j)
    r[j] = v.x * m.m[0][j] + v.y * m.m[1][j] + v.z * m.m[2][j] + v.w * m.m[3][j];
  return r;
}

Matrix transpose(const Matrix& m) {
  Matrix r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = m.m[j][i];
  return r;
}

bool inverse(const Matrix& in, Matrix& out) {
  // Gauss-Jordan with partial pivoting, in double for stability.
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      a[i][j] = in.m[i][j];
      a[i][j + 4] = i == j ? 1.0 : 0.0;
    }
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (std::fabs(a[p][c]) < 1e-30) return false;
    if (p != c)
      for (int j = 0; j < 8; ++j) std::swap(a[p][j], a[c][j]);
    double inv = 1.0 / a[c][c];
    for (int j = 0; j < 8; ++j) a[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      double f = a[r][c];
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out.m[i][j] = static_cast<float>(a[i][j + 4]);
  return true;
}

Matrix matrixTranslation(float x, float y, float z) {
  Matrix r = Matrix::identity();
  r.m[3][0] = x;
  r.m[3][1] = y;
  r.m[3][2] = z;
  return r;
}

Matrix matrixScaling(float x, float y, float z) {
  Matrix r;
  r.m[0][0] = x;
  r.m[1][1] = y;
  r.m[2][2] = z;
  r.m[3][3] = 1;
  return r;
}

Matrix matrixRotationX(float a) {
  Matrix r = Matrix::identity();
  float c = std::cos(a), s = std::sin(a);
  r.m[1][1] = c;
  r.m[1][2] = s;
  r.m[2][1] = -s;
  r.m[2][2] = c;
  return r;
}

Matrix matrixRotationY(float a) {
  Matrix r = Matrix::identity();
  float c = std::cos(a), s = std::sin(a);
  r.m[0][0] = c;
  r.m[0][2] = -s;
  r.m[2][0] = s;
  r.m[2][2] = c;
  return r;
}

Matrix matrixRotationZ(float a) {
  Matrix r = Matrix::identity();
  float c = std::cos(a), s = std::sin(a);
  r.m[0][0] = c;
  r.m[0][1] = s;
  r.m[1][0] = -s;
  r.m[1][1] = c;
  return r;
}

Matrix matrixRotationAxis(Vec3 axis, float a) {
  Vec3 n = normalize(axis);
  float c = std::cos(a), s = std::sin(a), t = 1 - c;
  Matrix r = Matrix::identity();
  r.m[0][0] = t * n.x * n.x + c;
  r.m[0][1] = t * n.x * n.y + s * n.z;
  r.m[0][2] = t * n.x * n.z - s * n.y;
  r.m[1][0] = t * n.x * n.y - s * n.z;
  r.m[1][1] = t * n.y * n.y + c;
  r.m[1][2] = t * n.y * n.z + s * n.x;
  r.m[2][0] = t * n.x * n.z + s * n.y;
  r.m[2][1] = t * n.y * n.z - s * n.x;
  r.m[2][2] = t * n.z * n.z + c;
  return r;
}

Matrix matrixRotationYawPitchRoll(float yaw, float pitch, float roll) {
  // D3DX order: roll (Z), then pitch (X), then yaw (Y).
  return matrixRotationZ(roll) * matrixRotationX(pitch) * matrixRotationY(yaw);
}

Matrix matrixLookAtLH(Vec3 eye, Vec3 at, Vec3 up) {
  Vec3 z = normalize(at - eye);
  Vec3 x = normalize(cross(up, z));
  Vec3 y = cross(z, x);
  Matrix r = Matrix::identity();
  r.m[0][0] = x.x; r.m[0][1] = y.x; r.m[0][2] = z.x;
  r.m[1][0] = x.y; r.m[1][1] = y.y; r.m[1][2] = z.y;
  r.m[2][0] = x.z; r.m[2][1] = y.z; r.m[2][2] = z.z;
  r.m[3][0] = -dot(x, eye);
  r.m[3][1] = -dot(y, eye);
  r.m[3][2] = -dot(z, eye);
  return r;
}

Matrix matrixPerspectiveFovLH(float fovy, float aspect, float zn, float zf) {
  float ys = 1.0f / std::tan(fovy / 2), xs = ys / aspect;
  Matrix r;
  r.m[0][0] = xs;
  r.m[1][1] = ys;
  r.m[2][2] = zf / (zf - zn);
  r.m[2][3] = 1;
  r.m[3][2] = -zn * zf / (zf - zn);
  return r;
}

Matrix matrixOrthoLH(float w, float h, float zn, float zf) {
  Matrix r;
  r.m[0][0] = 2 / w;
  r.m[1][1] = 2 / h;
  r.m[2][2] = 1 / (zf - zn);
  r.m[3][2] = zn / (zn - zf);
  r.m[3][3] = 1;
  return r;
}

Quaternion normalize(Quaternion q) {
  float len = length(q);
  if (!(len > 0)) return {0, 0, 0, 0};
  float inv = 1.0f / len;
  return {q.x * inv, q.y * inv, q.z * inv, q.w * inv};
}

Quaternion quaternionRotationAxis(Vec3 axis, float angle) {
  Vec3 n = normalize(axis);
  float s = std::sin(angle / 2);
  return {n.x * s, n.y * s, n.z * s, std::cos(angle / 2)};
}

Quaternion multiply(Quaternion q1, Quaternion q2) {
  // Hamilton product q2 * q1.
  return {q2.w * q1.x + q2.x * q1.w + q2.y * q1.z - q2.z * q1.y,
          q2.w * q1.y - q2.x * q1.z + q2.y * q1.w + q2.z * q1.x,
          q2.w * q1.z + q2.x * q1.y - q2.y * q1.x + q2.z * q1.w,
          q2.w * q1.w - q2.x * q1.x - q2.y * q1.y - q2.z * q1.z};
}

Quaternion slerp(Quaternion q1, Quaternion q2, float t) {
  float d = dot(q1, q2), sign = 1;
  if (d < 0) d = -d, sign = -1;
  float a = 1 - t, b = t;
  if (1 - d > 0.001f) {  // otherwise sin(theta) is too small to divide by
    float theta = std::acos(d), st = std::sin(theta);
    a = std::sin(theta * (1 - t)) / st;
    b = std::sin(theta * t) / st;
  }
  b *= sign;
  return {a * q1.x + b * q2.x, a * q1.y + b * q2.y, a * q1.z + b * q2.z, a * q1.w + b * q2.w};
}

Matrix matrixRotationQuaternion(Quaternion q) {
  Matrix r = Matrix::identity();
  r.m[0][0] = 1 - 2 * (q.y * q.y + q.z * q.z);
  r.m[0][1] = 2 * (q.x * q.y + q.z * q.w);
  r.m[0][2] = 2 * (q.x * q.z - q.y * q.w);
  r.m[1][0] = 2 * (q.x * q.y - q.z * q.w);
  r.m[1][1] = 1 - 2 * (q.x * q.x + q.z * q.z);
  r.m[1][2] = 2 * (q.y * q.z + q.x * q.w);
  r.m[2][0] = 2 * (q.x * q.z + q.y * q.w);
  r.m[2][1] = 2 * (q.y * q.z - q.x * q.w);
  r.m[2][2] = 1 - 2 * (q.x * q.x + q.y * q.y);
  return r;
}

Quaternion quaternionRotationMatrix(const Matrix& mat) {
  const auto& m = mat.m;
  float trace = m[0][0] + m[1][1] + m[2][2] + 1;
  Quaternion q;
  if (trace > 1) {  // |w| > 1/2: divide by 4w
    float s = 2 * std::sqrt(trace);
    q = {(m[1][2] - m[2][1]) / s, (m[2][0] - m[0][2]) / s, (m[0][1] - m[1][0]) / s, 0.25f * s};
  } else {  // divide by the largest of |x|, |y|, |z|
    int i = 0;
    if (m[1][1] > m[0][0]) i = 1;
    if (m[2][2] > m[i][i]) i = 2;
    if (i == 0) {
      float s = 2 * std::sqrt(std::max(0.0f, 1 + m[0][0] - m[1][1] - m[2][2]));
      q = {0.25f * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] - m[2][1]) / s};
    } else if (i == 1) {
      float s = 2 * std::sqrt(std::max(0.0f, 1 + m[1][1] - m[0][0] - m[2][2]));
      q = {(m[0][1] + m[1][0]) / s, 0.25f * s, (m[1][2] + m[2][1]) / s, (m[2][0] - m[0][2]) / s};
    } else {
      float s = 2 * std::sqrt(std::max(0.0f, 1 + m[2][2] - m[0][0] - m[1][1]));
      q = {(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25f * s, (m[0][1] - m[1][0]) / s};
    }
  }
  return q;
}

Vec3 transformCoord(Vec3 v, const Matrix& m) {
  Vec4 r = Vec4(v, 1) * m;
  float iw = r.w != 0 ? 1.0f / r.w : 0.0f;
  return {r.x * iw, r.y * iw, r.z * iw};
}

Vec3 transformNormal(Vec3 v, const Matrix& m) {
  Vec4 r = Vec4(v, 0) * m;
  return {r.x, r.y, r.z};
}

}  // namespace refx
