// Vectors and matrices with Direct3D/D3DX conventions: row vectors, v * M,
// left-handed coordinate helpers.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>

namespace refx {

struct Vec2 {
  float x = 0, y = 0;
};

struct Vec3 {
  float x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr Vec3 operator+(Vec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(Vec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr bool operator==(const Vec3&) const = default;
};

struct Vec4 {
  float x = 0, y = 0, z = 0, w = 0;
  constexpr Vec4() = default;
  constexpr Vec4(float x_, float y_, float z_, float w_) : x(x_), y(y_), z(z_), w(w_) {}
  constexpr Vec4(Vec3 v, float w_) : x(v.x), y(v.y), z(v.z), w(w_) {}
  constexpr float operator[](int i) const { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }
  float& operator[](int i) { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }
  constexpr Vec3 xyz() const { return {x, y, z}; }
  constexpr bool operator==(const Vec4&) const = default;
};

constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr float dot(Vec4 a, Vec4 b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 v) { return std::sqrt(dot(v, v)); }
inline Vec3 normalize(Vec3 v) {
  float len = length(v);
  return len > 0 ? v * (1.0f / len) : v;
}

// 4x4 matrix, m[row][col], as D3DMATRIX (_11 = m[0][0], _43 = m[3][2]).
struct Matrix {
  float m[4][4] = {};
  static constexpr Matrix identity() {
    Matrix r;
    for (int i = 0; i < 4; ++i) r.m[i][i] = 1;
    return r;
  }
  constexpr bool operator==(const Matrix&) const = default;
};

Matrix operator*(const Matrix& a, const Matrix& b);
Vec4 operator*(Vec4 v, const Matrix& m);  // row vector times matrix
Matrix transpose(const Matrix& m);
// General inverse; returns false (and leaves out unchanged) when singular.
bool inverse(const Matrix& m, Matrix& out);

Matrix matrixTranslation(float x, float y, float z);
Matrix matrixScaling(float x, float y, float z);
Matrix matrixRotationX(float angle);
Matrix matrixRotationY(float angle);
Matrix matrixRotationZ(float angle);
Matrix matrixRotationAxis(Vec3 axis, float angle);
Matrix matrixRotationYawPitchRoll(float yaw, float pitch, float roll);
Matrix matrixLookAtLH(Vec3 eye, Vec3 at, Vec3 up);
Matrix matrixPerspectiveFovLH(float fovy, float aspect, float zn, float zf);
Matrix matrixOrthoLH(float w, float h, float zn, float zf);

// D3DXQUATERNION: (x, y, z) = axis * sin(angle/2), w = cos(angle/2) for a unit quaternion.
struct Quaternion {
  float x = 0, y = 0, z = 0, w = 1;
  constexpr Quaternion() = default;
  constexpr Quaternion(float x_, float y_, float z_, float w_) : x(x_), y(y_), z(z_), w(w_) {}
  static constexpr Quaternion identity() { return {0, 0, 0, 1}; }
  constexpr bool operator==(const Quaternion&) const = default;
};

constexpr float dot(Quaternion a, Quaternion b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
inline float length(Quaternion q) { return std::sqrt(dot(q, q)); }
// D3DXQuaternionNormalize; a zero quaternion stays zero.
Quaternion normalize(Quaternion q);
// D3DXQuaternionConjugate: (-x, -y, -z, w), the inverse rotation of a unit quaternion.
constexpr Quaternion conjugate(Quaternion q) { return {-q.x, -q.y, -q.z, q.w}; }
// D3DXQuaternionRotationAxis: rotation by `angle` about `axis` (normalized here), with
// the handedness of matrixRotationAxis.
Quaternion quaternionRotationAxis(Vec3 axis, float angle);
// D3DXQuaternionMultiply(q1, q2): the rotation q1 followed by q2, i.e. the Hamilton
// product q2 * q1, so matrixRotationQuaternion(multiply(q1, q2)) ==
// matrixRotationQuaternion(q1) * matrixRotationQuaternion(q2) for row vectors.
Quaternion multiply(Quaternion q1, Quaternion q2);
// D3DXQuaternionSlerp: spherical interpolation from q1 (t = 0) to q2 (t = 1) along the
// shorter arc (q2 is negated when dot(q1, q2) < 0); nearly equal inputs blend linearly.
Quaternion slerp(Quaternion q1, Quaternion q2, float t);
// D3DXMatrixRotationQuaternion (q is assumed unit length).
Matrix matrixRotationQuaternion(Quaternion q);
// D3DXQuaternionRotationMatrix: the unit quaternion of the rotation in the upper 3x3.
Quaternion quaternionRotationMatrix(const Matrix& m);

Vec3 transformCoord(Vec3 v, const Matrix& m);   // w-divided
Vec3 transformNormal(Vec3 v, const Matrix& m);  // upper 3x3 only

}  // namespace refx
