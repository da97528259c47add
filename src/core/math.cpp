#include "refx/core/math.h"

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
