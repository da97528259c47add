// Fixed-function T&L as straight-line IR. Values that are uniform for the draw
// (matrices, lights moved into camera space, material colors, fog parameters) are
// read from constants (exec/abi.h kConstVertex*) that fixedFunctionVertexConstants
// computes for every draw, so the program depends on the state's structure alone;
// per-lane decisions (range, spot cone, N·L > 0) become Slt/Sge masks multiplied
// into the terms.
#include "pipeline/ff_vertex.h"

#include <algorithm>
#include <cmath>

namespace refx::pipeline {

using namespace exec;
using namespace d3d;

namespace {

// Keeps rsq/rcp of zero lengths finite: a zero vector normalizes to zero.
constexpr float kTiny = 1e-30f;
constexpr float kHuge = 1e30f;
constexpr float kLog2e = 1.4426950408889634f;
// Vertex->viewer direction for a non-local viewer: toward -z in left-handed camera space.
constexpr Vec3 kNonLocalViewer{0, 0, -1};

constexpr uint8_t kMaskX = 0x1, kMaskXYZ = 0x7, kMaskW = 0x8, kMaskAll = 0xF;

Vec4 splat(float v) { return {v, v, v, v}; }
Vec4 rgb(Color4 c) { return {c.r, c.g, c.b, c.a}; }
bool isBlack(Color4 c) { return c.r == 0 && c.g == 0 && c.b == 0; }

// Column j of m: dp4(v, column) is component j of the row vector v * m.
Vec4 column(const Matrix& m, int j) { return {m.m[0][j], m.m[1][j], m.m[2][j], m.m[3][j]}; }

// Bits for components [from, 4).
uint8_t maskFrom(int from) { return uint8_t(0xF & ~((1u << from) - 1)); }

// Inverse transpose of the upper 3x3 of m, as a 4x4 with the rest zero. A singular
// matrix (e.g. a zero scale) falls back to the matrix itself.
Matrix normalMatrix(const Matrix& m) {
  Matrix a = Matrix::identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a.m[i][j] = m.m[i][j];
  Matrix inv;
  Matrix r;
  if (inverse(a, inv)) {
    a = transpose(inv);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[i][j];
  return r;
}

// How positions and normals reach camera space (D3DRS_VERTEXBLEND).
enum class Blend {
  None,     // World(0) * View
  Weights,  // Σ weight_i * WorldMatrix(i or index_i) * View
  Tween,    // lerp(POSITION0, POSITION1, TWEENFACTOR) (normals too), then World(0) * View
};

// Indexed vertex blending reads World(index)*View from the constant table at a
// per-lane offset: 4 position columns, then 3 normal-matrix columns, per matrix.
constexpr int kTableStride = kConstVertexBlendStride;

// Fields of a light's constants (kConstVertexLights) and of the material's.
enum LightField : int {
  kLightDirection, kLightPosition, kLightAttenuation0, kLightAttenuation1, kLightAttenuation2,
  kLightRange, kLightCosPhi, kLightSpotScale, kLightSpotOffset, kLightFalloff, kLightAmbient,
  kLightDiffuse, kLightSpecular, kLightHalfway,
};
static_assert(kLightHalfway + 1 == kConstVertexLightStride);
enum MaterialField : int { kMaterialDiffuse, kMaterialAmbient, kMaterialSpecular, kMaterialEmissive, kMaterialPower };

// An enabled light of a type D3D9 knows (others are ignored).
bool lightActive(const DeviceState& s, int i) {
  const Light& l = s.lights[size_t(i)];
  return s.lightEnabled[size_t(i)] &&
         (l.type == LIGHT_POINT || l.type == LIGHT_SPOT || l.type == LIGHT_DIRECTIONAL);
}

class Builder {
 public:
  Builder(const DeviceState& s, const FixedFunctionVertexConfig& c) : st_(s), cfg_(c) {
    const uint32_t mode = s.rs(RS_VERTEXBLEND);
    const bool indexed = s.rs(RS_INDEXEDVERTEXBLENDENABLE) && c.blendIndicesType >= 0;
    if (c.pretransformed) {
      blend_ = Blend::None;
    } else if (mode >= VBF_1WEIGHTS && mode <= VBF_3WEIGHTS) {
      blend_ = Blend::Weights;
      blendMatrices_ = int(mode) + 1;
      indexed_ = indexed;
    } else if (mode == VBF_0WEIGHTS && indexed) {
      // One matrix of weight 1; without indices that is World(0), the unblended case.
      blend_ = Blend::Weights;
      blendMatrices_ = 1;
      indexed_ = true;
    } else if (mode == VBF_TWEENING) {
      blend_ = Blend::Tween;
    }
  }

  Program build();

 private:
  // Register shorthands.
  static Src t(int r, uint8_t sw = kSwzXYZW, SrcMod m = SrcMod::None) {
    return reg(RegFile::Temp, r, sw, m);
  }
  static Dst td(int r, uint8_t mask = kMaskAll) { return dst(RegFile::Temp, r, mask); }
  static Src in(int r, uint8_t sw = kSwzXYZW) { return reg(RegFile::Input, r, sw); }
  static Dst out(int r, uint8_t mask = kMaskAll) { return dst(RegFile::Output, r, mask); }
  Src k(Vec4 v) { return p_.imm(v); }
  Src k(float v) { return p_.imm(splat(v)); }
  // A value of the draw's constant array (exec/abi.h).
  static Src c(int slot) { return reg(RegFile::Const, slot); }
  static Src column(int firstSlot, int j) { return c(firstSlot + j); }
  static Src lightValue(int light, int field) {
    return c(kConstVertexLights + kConstVertexLightStride * light + field);
  }
  Instr& emit(Op op, Dst d, Src a = {}, Src b = {}, Src c = {}) { return p_.emit(op, d, a, b, c); }

  // New temp holding normalize(s.xyz) (w undefined); zero stays zero.
  int normalize3(Src s) {
    int len = p_.newTemp(), r = p_.newTemp();
    emit(Op::Dp3, td(len, kMaskX), s, s);
    emit(Op::Max, td(len, kMaskX), t(len, kSwzXXXX), k(kTiny));
    emit(Op::Rsq, td(len, kMaskX), t(len, kSwzXXXX));
    emit(Op::Mul, td(r, kMaskXYZ), s, t(len, kSwzXXXX));
    return r;
  }

  uint32_t rs(RenderState s) const { return st_.rs(s); }
  float rsF(RenderState s) const { return st_.rsFloat(s); }

  // Lazily emitted per-vertex values (straight-line code: first use emits them).
  int cameraPosition();  // P = position * World * View (xyz)
  int cameraNormal();    // N (xyz, w = 0)
  // Vertex blending pieces.
  Src modelPosition();   // POSITION0, or the tweened position
  Src modelNormal();     // NORMAL0, or the tweened normal
  int blendWeights();    // weight of matrix i in component i (the last: 1 - the others)
  int blendOffsets();    // indexed: table offset of matrix i in component i
  // Column `col` of blended matrix `matrix` (its normal matrix with `normal`).
  Src blendColumn(int matrix, int col, bool normal);
  int blendedCameraPosition();
  int blendedCameraNormal();
  Src viewerDirection();  // V: vertex -> viewer
  int reflectionVector();  // R = E - 2(N·E)N, E = normalize(P)
  int sphereMapCoords();   // (u, v, 0, 0)

  // Material color source per D3DMCS_*, honouring COLORVERTEX and what the vertex has.
  Src materialSource(RenderState sourceState, int materialSlot);

  void emitPosition();
  void emitLighting();
  void emitLight(int index, int lightScratch);
  void emitUnlitColors();
  void emitFog();
  void emitPointSize();
  void emitTexCoords(int stage);

  const DeviceState& st_;
  const FixedFunctionVertexConfig& cfg_;
  Blend blend_ = Blend::None;
  int blendMatrices_ = 0;  // Blend::Weights: matrices blended (1-4)
  bool indexed_ = false;   // Blend::Weights: matrices chosen by BLENDINDICES
  int weights_ = -1, offsets_ = -1, tableBase_ = -1, modelPos_ = -1, modelNormal_ = -1;
  Program p_;
  int pos_ = -1, normal_ = -1, reflect_ = -1, sphere_ = -1, viewer_ = -1;
  // Lighting accumulators (rgb).
  int ambAcc_ = -1, diffAcc_ = -1, specAcc_ = -1;
  Src specularSource_{};
};

Src Builder::modelPosition() {
  if (blend_ != Blend::Tween || !cfg_.hasPosition1) return in(kVertexInPosition);
  if (modelPos_ < 0) {
    // POSITION0 * (1 - t) + POSITION1 * t = POSITION0 + t * (POSITION1 - POSITION0)
    modelPos_ = p_.newTemp();
    emit(Op::Sub, td(modelPos_), in(kVertexInPosition1), in(kVertexInPosition));
    emit(Op::Mad, td(modelPos_), t(modelPos_), c(kConstVertexTweenFactor), in(kVertexInPosition));
  }
  return t(modelPos_);
}

Src Builder::modelNormal() {
  if (blend_ != Blend::Tween || !cfg_.hasNormal1) return in(kVertexInNormal);
  if (modelNormal_ < 0) {
    modelNormal_ = p_.newTemp();
    emit(Op::Sub, td(modelNormal_, kMaskXYZ), in(kVertexInNormal1), in(kVertexInNormal));
    emit(Op::Mad, td(modelNormal_, kMaskXYZ), t(modelNormal_), c(kConstVertexTweenFactor),
         in(kVertexInNormal));
  }
  return t(modelNormal_);
}

int Builder::blendWeights() {
  if (weights_ >= 0) return weights_;
  weights_ = p_.newTemp();
  const int n = blendMatrices_ - 1;  // weights read from the vertex
  if (n == 0) {
    emit(Op::Mov, td(weights_, kMaskX), k(1.0f));
    return weights_;
  }
  emit(Op::Mov, td(weights_, uint8_t((1u << n) - 1)), in(kVertexInBlendWeight));
  Vec4 firstN(0, 0, 0, 0);
  for (int i = 0; i < n; ++i) firstN[i] = 1;
  const uint8_t last = uint8_t(1u << n);
  emit(Op::Dp4, td(weights_, last), in(kVertexInBlendWeight), k(firstN));
  emit(Op::Add, td(weights_, last), t(weights_, swz(n, n, n, n), SrcMod::Neg), k(1.0f));
  return weights_;
}

int Builder::blendOffsets() {
  if (offsets_ >= 0) return offsets_;
  // The table: World(m) * View and its normal matrix for all 256 matrices.
  tableBase_ = kConstVertexBlendTable;
  // D3DCOLOR indices arrive as byte/255 in D3DCOLOR's component order (x = bits 16-23);
  // UBYTE4 as the bytes. Indices outside 0-255 (float elements) are clamped.
  offsets_ = p_.newTemp();
  const float scale = cfg_.blendIndicesType == DECLTYPE_D3DCOLOR ? 255.0f : 1.0f;
  emit(Op::Mul, td(offsets_), in(kVertexInBlendIndices), k(scale));
  emit(Op::Round, td(offsets_), t(offsets_));
  emit(Op::Max, td(offsets_), t(offsets_), k(0.0f));
  emit(Op::Min, td(offsets_), t(offsets_), k(float(kMaxWorldMatrices - 1)));
  emit(Op::Mul, td(offsets_), t(offsets_), k(float(kTableStride)));
  return offsets_;
}

Src Builder::blendColumn(int matrix, int col, bool normal) {
  if (!indexed_) return c(kConstVertexBlendMatrices + kConstVertexBlendStride * matrix + (normal ? 4 : 0) + col);
  Src s = reg(RegFile::Const, tableBase_ + (normal ? 4 : 0) + col);
  s.rel = RelMode::Temp;
  s.relReg = uint16_t(blendOffsets());
  s.relComp = uint8_t(matrix);
  return s;
}

// P = Σ w_i * (position * World(i) * View), all four components (w stays 1 for
// affine matrices, as the weights sum to 1).
int Builder::blendedCameraPosition() {
  const int p = p_.newTemp(), x = p_.newTemp();
  if (blend_ == Blend::Tween) {
    for (int j = 0; j < 4; ++j)
      emit(Op::Dp4, td(p, uint8_t(1 << j)), modelPosition(), column(kConstVertexWorldView, j));
    return p;
  }
  const int w = blendWeights();
  if (indexed_) blendOffsets();
  for (int i = 0; i < blendMatrices_; ++i) {
    const int dst = i == 0 ? p : x;
    for (int j = 0; j < 4; ++j)
      emit(Op::Dp4, td(dst, uint8_t(1 << j)), in(kVertexInPosition), blendColumn(i, j, false));
    if (i == 0)
      emit(Op::Mul, td(p), t(p), t(w, swz(0, 0, 0, 0)));
    else
      emit(Op::Mad, td(p), t(x), t(w, swz(i, i, i, i)), t(p));
  }
  return p;
}

// N = Σ w_i * (normal * inverse transpose(World(i) * View)), w = 0.
int Builder::blendedCameraNormal() {
  const int n = p_.newTemp(), x = p_.newTemp();
  if (blend_ == Blend::Tween) {
    for (int j = 0; j < 3; ++j)
      emit(Op::Dp3, td(n, uint8_t(1 << j)), modelNormal(), column(kConstVertexNormalMatrix, j));
  } else {
    const int w = blendWeights();
    if (indexed_) blendOffsets();
    for (int i = 0; i < blendMatrices_; ++i) {
      const int dst = i == 0 ? n : x;
      for (int j = 0; j < 3; ++j)
        emit(Op::Dp3, td(dst, uint8_t(1 << j)), in(kVertexInNormal), blendColumn(i, j, true));
      if (i == 0)
        emit(Op::Mul, td(n, kMaskXYZ), t(n), t(w, swz(0, 0, 0, 0)));
      else
        emit(Op::Mad, td(n, kMaskXYZ), t(x), t(w, swz(i, i, i, i)), t(n));
    }
  }
  emit(Op::Mov, td(n, kMaskW), k(0.0f));
  return n;
}

int Builder::cameraPosition() {
  if (pos_ < 0 && blend_ != Blend::None) pos_ = blendedCameraPosition();
  if (pos_ < 0) {
    pos_ = p_.newTemp();
    for (int j = 0; j < 3; ++j)
      emit(Op::Dp4, td(pos_, uint8_t(1 << j)), in(kVertexInPosition), column(kConstVertexWorldView, j));
    emit(Op::Mov, td(pos_, kMaskW), k(1.0f));
  }
  return pos_;
}

int Builder::cameraNormal() {
  if (normal_ >= 0) return normal_;
  int n = blend_ != Blend::None && cfg_.hasNormal ? blendedCameraNormal() : p_.newTemp();
  if (cfg_.hasNormal) {
    if (blend_ == Blend::None) {
      // Row vector times the inverse transpose: component j = dp3(n, column j).
      for (int j = 0; j < 3; ++j)
        emit(Op::Dp3, td(n, uint8_t(1 << j)), in(kVertexInNormal), column(kConstVertexNormalMatrix, j));
      emit(Op::Mov, td(n, kMaskW), k(0.0f));
    }
    if (rs(RS_NORMALIZENORMALS)) {
      int u = normalize3(t(n));
      emit(Op::Mov, td(u, kMaskW), k(0.0f));
      n = u;
    }
  } else {
    emit(Op::Mov, td(n), k(0.0f));
  }
  normal_ = n;
  return normal_;
}

Src Builder::viewerDirection() {
  if (!rs(RS_LOCALVIEWER)) return k(Vec4(kNonLocalViewer, 0));
  if (viewer_ < 0) viewer_ = normalize3(t(cameraPosition(), kSwzXYZW, SrcMod::Neg));
  return t(viewer_);
}

int Builder::reflectionVector() {
  if (reflect_ >= 0) return reflect_;
  int n = cameraNormal();
  int e = normalize3(t(cameraPosition()));
  int s = p_.newTemp();
  emit(Op::Dp3, td(s, kMaskX), t(n), t(e));
  emit(Op::Add, td(s, kMaskX), t(s, kSwzXXXX), t(s, kSwzXXXX));  // 2(N·E)
  reflect_ = p_.newTemp();
  emit(Op::Mad, td(reflect_, kMaskXYZ), t(n), t(s, kSwzXXXX, SrcMod::Neg), t(e));
  emit(Op::Mov, td(reflect_, kMaskW), k(0.0f));
  return reflect_;
}

int Builder::sphereMapCoords() {
  if (sphere_ >= 0) return sphere_;
  // m = 2*sqrt(Rx² + Ry² + (Rz+1)²); (u, v) = R.xy / m + 0.5
  int r = reflectionVector();
  int q = p_.newTemp();
  emit(Op::Add, td(q, kMaskXYZ), t(r), k(Vec4(0, 0, 1, 0)));
  emit(Op::Dp3, td(q, kMaskW), t(q), t(q));
  emit(Op::Max, td(q, kMaskW), t(q, kSwzWWWW), k(kTiny));
  emit(Op::Rsq, td(q, kMaskW), t(q, kSwzWWWW));
  emit(Op::Mul, td(q, kMaskW), t(q, kSwzWWWW), k(0.5f));
  sphere_ = p_.newTemp();
  emit(Op::Mad, td(sphere_, 0x3), t(r), t(q, kSwzWWWW), k(0.5f));
  emit(Op::Mov, td(sphere_, 0xC), k(0.0f));
  return sphere_;
}

Src Builder::materialSource(RenderState sourceState, int materialSlot) {
  if (rs(RS_COLORVERTEX)) {
    uint32_t src = rs(sourceState);
    if (src == MCS_COLOR1 && cfg_.hasDiffuse) return in(kVertexInDiffuse);
    if (src == MCS_COLOR2 && cfg_.hasSpecular) return in(kVertexInSpecular);
  }
  return c(materialSlot);
}

void Builder::emitPosition() {
  if (cfg_.pretransformed) {
    emit(Op::Mov, out(kVertexOutPosition), in(kVertexInPosition));
    return;
  }
  if (blend_ != Blend::None) {
    const int p = cameraPosition();
    for (int j = 0; j < 4; ++j)
      emit(Op::Dp4, out(kVertexOutPosition, uint8_t(1 << j)), t(p), column(kConstVertexProjection, j));
    return;
  }
  for (int j = 0; j < 4; ++j)
    emit(Op::Dp4, out(kVertexOutPosition, uint8_t(1 << j)), in(kVertexInPosition),
         column(kConstVertexWorldViewProjection, j));
}

void Builder::emitUnlitColors() {
  emit(Op::Mov, out(kVertexOutDiffuse), in(kVertexInDiffuse)).saturate = true;
  emit(Op::Mov, out(kVertexOutSpecular), in(kVertexInSpecular)).saturate = true;
  specularSource_ = in(kVertexInSpecular);
}

// One enabled light, accumulated into ambAcc_/diffAcc_/specAcc_. `sc` is a scratch
// temp base (4 temps) reused by every light.
void Builder::emitLight(int index, int sc) {
  const Light& light = st_.lights[index];
  auto value = [&](int field) { return lightValue(index, field); };
  const bool specular = rs(RS_SPECULARENABLE) && !isBlack(light.specular);
  const int n = cameraNormal();
  const int ldir = sc, s = sc + 1, a = sc + 2, h = sc + 3;
  // s.x = N·L, s.y = max(N·L, 0) * factor, s.z = specular term, s.w = scratch
  // a.x = factor (atten * range * spot) for local lights
  Src ldirSrc;
  bool local = light.type != LIGHT_DIRECTIONAL;

  if (!local) {
    ldirSrc = value(kLightDirection);
  } else {
    int pos = cameraPosition();
    emit(Op::Sub, td(ldir, kMaskXYZ), value(kLightPosition), t(pos));
    emit(Op::Dp3, td(s, kMaskW), t(ldir), t(ldir));                   // d²
    emit(Op::Max, td(s, kMaskW), t(s, kSwzWWWW), k(kTiny));
    emit(Op::Rsq, td(s, kMaskX), t(s, kSwzWWWW));                     // 1/d
    emit(Op::Mul, td(ldir, kMaskXYZ), t(ldir), t(s, kSwzXXXX));      // Ldir
    emit(Op::Mul, td(s, kMaskX), t(s, kSwzWWWW), t(s, kSwzXXXX));    // d
    // atten = 1 / (a0 + a1 d + a2 d²)
    emit(Op::Mad, td(a, kMaskX), t(s, kSwzXXXX), value(kLightAttenuation1), value(kLightAttenuation0));
    emit(Op::Mad, td(a, kMaskX), t(s, kSwzWWWW), value(kLightAttenuation2), t(a, kSwzXXXX));
    emit(Op::Max, td(a, kMaskX), t(a, kSwzXXXX), k(kTiny));
    emit(Op::Rcp, td(a, kMaskX), t(a, kSwzXXXX));
    // Beyond Range the light contributes nothing: factor *= (Range >= d).
    emit(Op::Sge, td(a, 0x2), value(kLightRange), t(s, kSwzXXXX));
    emit(Op::Mul, td(a, kMaskX), t(a, kSwzXXXX), t(a, kSwzYYYY));
    if (light.type == LIGHT_SPOT) {
      // spot = rho > cos(Phi/2) ? saturate((rho - cosPhi)/(cosTheta - cosPhi))^Falloff : 0
      emit(Op::Dp3, td(a, 0x2), value(kLightDirection), t(ldir));                // rho
      emit(Op::Slt, td(a, 0x4), value(kLightCosPhi), t(a, kSwzYYYY));            // rho > cosPhi
      emit(Op::Mad, td(a, 0x2), t(a, kSwzYYYY), value(kLightSpotScale), value(kLightSpotOffset))
          .saturate = true;
      if (light.falloff != 1.0f)
        emit(Op::Pow, td(a, 0x2), t(a, kSwzYYYY), value(kLightFalloff));
      emit(Op::Mul, td(a, kMaskX), t(a, kSwzXXXX), t(a, kSwzYYYY));
      emit(Op::Mul, td(a, kMaskX), t(a, kSwzXXXX), t(a, kSwzZZZZ));
    }
    if (!isBlack(light.ambient))
      emit(Op::Mad, td(ambAcc_, kMaskXYZ), t(a, kSwzXXXX), value(kLightAmbient), t(ambAcc_));
    ldirSrc = t(ldir);
  }

  emit(Op::Dp3, td(s, kMaskX), t(n), ldirSrc);
  emit(Op::Max, td(s, 0x2), t(s, kSwzXXXX), k(0.0f));
  if (local) emit(Op::Mul, td(s, 0x2), t(s, kSwzYYYY), t(a, kSwzXXXX));
  if (!isBlack(light.diffuse))
    emit(Op::Mad, td(diffAcc_, kMaskXYZ), t(s, kSwzYYYY), value(kLightDiffuse), t(diffAcc_));

  if (specular) {
    // H = normalize(V + Ldir); term = max(N·H, 0)^Power, only where N·L > 0.
    Src hSrc;
    if (!local && !rs(RS_LOCALVIEWER)) {
      hSrc = value(kLightHalfway);
    } else {
      emit(Op::Add, td(h, kMaskXYZ), viewerDirection(), ldirSrc);
      emit(Op::Dp3, td(s, kMaskW), t(h), t(h));
      emit(Op::Max, td(s, kMaskW), t(s, kSwzWWWW), k(kTiny));
      emit(Op::Rsq, td(s, kMaskW), t(s, kSwzWWWW));
      emit(Op::Mul, td(h, kMaskXYZ), t(h), t(s, kSwzWWWW));
      hSrc = t(h);
    }
    emit(Op::Dp3, td(s, 0x4), t(n), hSrc);
    emit(Op::Max, td(s, 0x4), t(s, kSwzZZZZ), k(0.0f));
    emit(Op::Pow, td(s, 0x4), t(s, kSwzZZZZ), c(kConstVertexMaterial + kMaterialPower));
    emit(Op::Slt, td(s, kMaskW), k(0.0f), t(s, kSwzXXXX));
    emit(Op::Mul, td(s, 0x4), t(s, kSwzZZZZ), t(s, kSwzWWWW));
    if (local) emit(Op::Mul, td(s, 0x4), t(s, kSwzZZZZ), t(a, kSwzXXXX));
    emit(Op::Mad, td(specAcc_, kMaskXYZ), t(s, kSwzZZZZ), value(kLightSpecular), t(specAcc_));
  }
}

void Builder::emitLighting() {
  Src diffuseM = materialSource(RS_DIFFUSEMATERIALSOURCE, kConstVertexMaterial + kMaterialDiffuse);
  Src ambientM = materialSource(RS_AMBIENTMATERIALSOURCE, kConstVertexMaterial + kMaterialAmbient);
  Src specularM = materialSource(RS_SPECULARMATERIALSOURCE, kConstVertexMaterial + kMaterialSpecular);
  Src emissiveM = materialSource(RS_EMISSIVEMATERIALSOURCE, kConstVertexMaterial + kMaterialEmissive);
  specularSource_ = specularM;

  // Global ambient plus the ambient of directional lights (atten = spot = 1) is uniform.
  bool anyLight = false;
  for (int i = 0; i < 8; ++i) anyLight |= lightActive(st_, i);
  ambAcc_ = p_.newTemp();
  emit(Op::Mov, td(ambAcc_), c(kConstVertexAmbient));
  diffAcc_ = p_.newTemp();
  emit(Op::Mov, td(diffAcc_), k(0.0f));
  const bool specular = rs(RS_SPECULARENABLE) != 0;
  if (specular) {
    specAcc_ = p_.newTemp();
    emit(Op::Mov, td(specAcc_), k(0.0f));
  }
  if (anyLight) {
    int scratch = p_.newTemp();
    for (int i = 1; i < 4; ++i) p_.newTemp();
    for (int i = 0; i < 8; ++i)
      if (lightActive(st_, i)) emitLight(i, scratch);
  }

  // diffuse.rgb = Emissive + Ambient*(Ga + Σambient) + Diffuse*Σdiffuse; .a = Diffuse.a
  int c = p_.newTemp();
  emit(Op::Mad, td(c, kMaskXYZ), ambientM, t(ambAcc_), emissiveM);
  emit(Op::Mad, out(kVertexOutDiffuse, kMaskXYZ), diffuseM, t(diffAcc_), t(c)).saturate = true;
  emit(Op::Mov, out(kVertexOutDiffuse, kMaskW), diffuseM).saturate = true;
  // specular.rgb = Specular * Σspecular (only computed with SPECULARENABLE)
  if (specular)
    emit(Op::Mul, out(kVertexOutSpecular, kMaskXYZ), specularM, t(specAcc_)).saturate = true;
  else
    emit(Op::Mov, out(kVertexOutSpecular, kMaskXYZ), k(0.0f));
  emit(Op::Mov, out(kVertexOutSpecular, kMaskW), specularM).saturate = true;
}

// Vertex fog replaces specular alpha with f; otherwise f is the specular alpha.
void Builder::emitFog() {
  const uint32_t mode = rs(RS_FOGVERTEXMODE);
  const bool vertexFog = !cfg_.pretransformed && rs(RS_FOGENABLE) && rs(RS_FOGTABLEMODE) == FOG_NONE &&
                         (mode == FOG_LINEAR || mode == FOG_EXP || mode == FOG_EXP2);
  if (!vertexFog) {
    Src alpha = specularSource_;
    alpha.swizzle = kSwzWWWW;
    emit(Op::Mov, out(kVertexOutFog), alpha).saturate = true;
    return;
  }
  // d = camera-space |z|, or |P| with RANGEFOGENABLE.
  int pos = cameraPosition();
  int f = p_.newTemp();
  Src d;
  if (rs(RS_RANGEFOGENABLE)) {
    emit(Op::Dp3, td(f, kMaskW), t(pos), t(pos));
    emit(Op::Max, td(f, kMaskW), t(f, kSwzWWWW), k(kTiny));
    emit(Op::Rsq, td(f, kMaskX), t(f, kSwzWWWW));
    emit(Op::Mul, td(f, kMaskW), t(f, kSwzWWWW), t(f, kSwzXXXX));
    d = t(f, kSwzWWWW);
  } else {
    d = t(pos, kSwzZZZZ, SrcMod::Abs);
  }
  if (mode == FOG_LINEAR) {
    // f = (end - d) / (end - start)
    emit(Op::Mad, td(f, kMaskX), d, c(kConstVertexFog), c(kConstVertexFog + 1)).saturate = true;
  } else if (mode == FOG_EXP) {
    // f = e^-(d*density) = 2^(-d*density*log2 e)
    emit(Op::Mul, td(f, kMaskX), d, c(kConstVertexFog + 2));
    emit(Op::Exp2, td(f, kMaskX), t(f, kSwzXXXX)).saturate = true;
  } else {
    // f = e^-((d*density)²)
    emit(Op::Mul, td(f, kMaskX), d, c(kConstVertexFog + 3));
    emit(Op::Mul, td(f, kMaskX), t(f, kSwzXXXX), t(f, kSwzXXXX));
    emit(Op::Mul, td(f, kMaskX), t(f, kSwzXXXX), k(-kLog2e));
    emit(Op::Exp2, td(f, kMaskX), t(f, kSwzXXXX)).saturate = true;
  }
  emit(Op::Mov, out(kVertexOutSpecular, kMaskW), t(f, kSwzXXXX));
  emit(Op::Mov, out(kVertexOutFog), t(f, kSwzXXXX));
}

// Point size: vertex PSIZE or D3DRS_POINTSIZE; POINTSCALEENABLE scales by
// Vh * sqrt(1 / (A + B*De + C*De²)), De = eye distance; clamped to [MIN, MAX].
void Builder::emitPointSize() {
  Src size = cfg_.hasPSize ? in(kVertexInPSize, kSwzXXXX) : c(kConstVertexPointSize);
  int r = p_.newTemp();
  emit(Op::Mov, td(r, kMaskX), size);
  if (!cfg_.pretransformed && rs(RS_POINTSCALEENABLE)) {
    int pos = cameraPosition();
    int q = p_.newTemp();
    emit(Op::Dp3, td(q, kMaskW), t(pos), t(pos));                     // De²
    emit(Op::Max, td(q, kMaskW), t(q, kSwzWWWW), k(kTiny));
    emit(Op::Rsq, td(q, kMaskX), t(q, kSwzWWWW));
    emit(Op::Mul, td(q, kMaskX), t(q, kSwzWWWW), t(q, kSwzXXXX));    // De
    emit(Op::Mad, td(q, kMaskX), t(q, kSwzXXXX), c(kConstVertexPointSize + 2), c(kConstVertexPointSize + 1));
    emit(Op::Mad, td(q, kMaskX), t(q, kSwzWWWW), c(kConstVertexPointSize + 3), t(q, kSwzXXXX));
    emit(Op::Max, td(q, kMaskX), t(q, kSwzXXXX), k(kTiny));
    emit(Op::Rsq, td(q, kMaskX), t(q, kSwzXXXX));
    emit(Op::Mul, td(r, kMaskX), t(r, kSwzXXXX), t(q, kSwzXXXX));
    emit(Op::Mul, td(r, kMaskX), t(r, kSwzXXXX), c(kConstVertexPointSize + 4));
  }
  emit(Op::Max, td(r, kMaskX), t(r, kSwzXXXX), c(kConstVertexPointSize + 5));
  emit(Op::Min, out(kVertexOutPSize), t(r, kSwzXXXX), c(kConstVertexPointSize + 6));
}

void Builder::emitTexCoords(int stage) {
  const uint32_t tci = st_.tss(stage, TSS_TEXCOORDINDEX);
  const uint32_t index = tci & 0xFFFF;
  const uint32_t gen = cfg_.pretransformed ? TCI_PASSTHRU : (tci & 0xFFFF0000u);
  const Dst o = out(kVertexOutTex0 + stage);

  // Source coordinates and how many components they have.
  Src src = k(0.0f);
  int dims = 0;
  switch (gen) {
    case TCI_CAMERASPACENORMAL: src = t(cameraNormal()); dims = 3; break;
    case TCI_CAMERASPACEPOSITION: src = t(cameraPosition()); dims = 3; break;
    case TCI_CAMERASPACEREFLECTIONVECTOR: src = t(reflectionVector()); dims = 3; break;
    case TCI_SPHEREMAP: src = t(sphereMapCoords()); dims = 2; break;
    default:
      if (index < 8 && cfg_.texCoordDims[index] > 0) {
        src = in(kVertexInTex0 + int(index));
        dims = std::min(cfg_.texCoordDims[index], 4);
      }
      break;
  }

  const uint32_t flags = st_.tss(stage, TSS_TEXTURETRANSFORMFLAGS);
  const int count = std::min<int>(flags & 0xFF, 4);
  const bool projected = (flags & TTFF_PROJECTED) != 0;
  if (count == 0) {
    // No transform: the coordinates as they are, unused components 0.
    if (dims > 0) emit(Op::Mov, dst(o.file, o.index, uint8_t((1u << dims) - 1)), src);
    if (dims < 4) emit(Op::Mov, dst(o.file, o.index, maskFrom(dims)), k(0.0f));
    return;
  }

  // Expand the input: the first missing component is 1, the others 0 (absent set: all 0).
  int x = p_.newTemp();
  if (dims > 0) emit(Op::Mov, td(x, uint8_t((1u << dims) - 1)), src);
  if (dims < 4) {
    Vec4 fill(0, 0, 0, 0);
    if (dims > 0) fill[dims] = 1;
    emit(Op::Mov, td(x, maskFrom(dims)), k(fill));
  }
  // Pretransformed vertices are not transformed (the constants hold the identity);
  // COUNTn / PROJECTED still apply.
  const int m = kConstVertexTextureTransform + 4 * stage;
  for (int j = 0; j < count; ++j)
    emit(Op::Dp4, dst(o.file, o.index, uint8_t(1 << j)), t(x), column(m, j));
  uint8_t rest = maskFrom(count);
  if (projected && count < 4) {
    // The divisor (last kept component) goes to .w for a projected sample.
    emit(Op::Dp4, dst(o.file, o.index, kMaskW), t(x), column(m, count - 1));
    rest &= uint8_t(~kMaskW);
  }
  if (rest) emit(Op::Mov, dst(o.file, o.index, rest), k(0.0f));
}

Program Builder::build() {
  p_.name = cfg_.pretransformed ? "ff_vertex_pretransformed" : "ff_vertex";
  p_.inputCount = kVertexInputCount;
  p_.outputCount = kVertexOutputCount;
  emitPosition();
  if (cfg_.pretransformed || !rs(RS_LIGHTING))
    emitUnlitColors();
  else
    emitLighting();
  emitFog();
  emitPointSize();
  for (int stage = 0; stage < kMaxTextureStages; ++stage) emitTexCoords(stage);
  return std::move(p_);
}

}  // namespace

exec::Program buildFixedFunctionVertexProgram(const DeviceState& state,
                                              const FixedFunctionVertexConfig& cfg) {
  return Builder(state, cfg).build();
}

uint32_t fixedFunctionLightKey(const DeviceState& state, int i) {
  if (!lightActive(state, i)) return 0;
  const Light& l = state.lights[size_t(i)];
  return 1u | l.type << 1 | uint32_t(isBlack(l.ambient)) << 4 | uint32_t(isBlack(l.diffuse)) << 5 |
         uint32_t(isBlack(l.specular)) << 6 | uint32_t(l.falloff != 1.0f) << 7;
}

void fixedFunctionVertexConstants(const DeviceState& s, const FixedFunctionVertexConfig& cfg,
                                  std::vector<Vec4>& c) {
  const bool indexed = !cfg.pretransformed && s.rs(RS_INDEXEDVERTEXBLENDENABLE) && cfg.blendIndicesType >= 0;
  c.resize(size_t(indexed ? kConstVertexBlendTableEnd : kConstVertexBlendTable));
  auto columns = [&](int slot, const Matrix& m, int count) {
    for (int j = 0; j < count; ++j) c[size_t(slot + j)] = column(m, j);
  };
  const Matrix worldView = s.world * s.view;
  columns(kConstVertexWorldView, worldView, 4);
  columns(kConstVertexWorldViewProjection, worldView * s.projection, 4);
  columns(kConstVertexNormalMatrix, normalMatrix(worldView), 3);
  columns(kConstVertexProjection, s.projection, 4);
  if (!cfg.pretransformed && s.rs(RS_VERTEXBLEND) >= VBF_1WEIGHTS && s.rs(RS_VERTEXBLEND) <= VBF_3WEIGHTS)
    for (int i = 0; i < 4; ++i) {
      const Matrix wv = s.worldMatrix(i) * s.view;
      columns(kConstVertexBlendMatrices + kConstVertexBlendStride * i, wv, 4);
      columns(kConstVertexBlendMatrices + kConstVertexBlendStride * i + 4, normalMatrix(wv), 3);
    }
  for (int stage = 0; stage < 8; ++stage)
    columns(kConstVertexTextureTransform + 4 * stage,
            cfg.pretransformed ? Matrix::identity() : s.textureTransforms[size_t(stage)], 4);
  const Material& m = s.material;
  c[kConstVertexMaterial + kMaterialDiffuse] = rgb(m.diffuse);
  c[kConstVertexMaterial + kMaterialAmbient] = rgb(m.ambient);
  c[kConstVertexMaterial + kMaterialSpecular] = rgb(m.specular);
  c[kConstVertexMaterial + kMaterialEmissive] = rgb(m.emissive);
  c[kConstVertexMaterial + kMaterialPower] = splat(m.power);
  Color4 ga = colorFromD3D(s.rs(RS_AMBIENT));
  for (int i = 0; i < 8; ++i) {
    const Light& l = s.lights[size_t(i)];
    if (!lightActive(s, i) || l.type != LIGHT_DIRECTIONAL) continue;
    ga.r += l.ambient.r;
    ga.g += l.ambient.g;
    ga.b += l.ambient.b;
  }
  c[kConstVertexAmbient] = Vec4(ga.r, ga.g, ga.b, 0);
  const float start = s.rsFloat(RS_FOGSTART), end = s.rsFloat(RS_FOGEND), density = s.rsFloat(RS_FOGDENSITY);
  const float range = end - start;
  const float scale = range != 0 ? 1.0f / range : kHuge;
  c[kConstVertexFog] = splat(-scale);
  c[kConstVertexFog + 1] = splat(end * scale);
  c[kConstVertexFog + 2] = splat(-density * kLog2e);
  c[kConstVertexFog + 3] = splat(density);
  c[kConstVertexPointSize] = splat(s.rsFloat(RS_POINTSIZE));
  c[kConstVertexPointSize + 1] = splat(s.rsFloat(RS_POINTSCALE_A));
  c[kConstVertexPointSize + 2] = splat(s.rsFloat(RS_POINTSCALE_B));
  c[kConstVertexPointSize + 3] = splat(s.rsFloat(RS_POINTSCALE_C));
  c[kConstVertexPointSize + 4] = splat(float(s.viewport.height));
  c[kConstVertexPointSize + 5] = splat(s.rsFloat(RS_POINTSIZE_MIN));
  c[kConstVertexPointSize + 6] = splat(s.rsFloat(RS_POINTSIZE_MAX));
  c[kConstVertexTweenFactor] = splat(s.rsFloat(RS_TWEENFACTOR));
  for (int i = 0; i < 8; ++i) {
    if (!lightActive(s, i)) continue;
    const Light& l = s.lights[size_t(i)];
    Vec4* v = &c[size_t(kConstVertexLights + kConstVertexLightStride * i)];
    const Vec3 d = normalize(-transformNormal(l.direction, s.view));
    v[kLightDirection] = Vec4(d, 0);
    v[kLightPosition] = Vec4(transformCoord(l.position, s.view), 0);
    v[kLightAttenuation0] = splat(l.attenuation0);
    v[kLightAttenuation1] = splat(l.attenuation1);
    v[kLightAttenuation2] = splat(l.attenuation2);
    v[kLightRange] = splat(l.range);
    const float cosTheta = std::cos(l.theta * 0.5f), cosPhi = std::cos(l.phi * 0.5f);
    const float band = cosTheta - cosPhi;
    const float spotScale = band > 0 ? 1.0f / band : kHuge;  // no band: a hard edge at Phi
    v[kLightCosPhi] = splat(cosPhi);
    v[kLightSpotScale] = splat(spotScale);
    v[kLightSpotOffset] = splat(-cosPhi * spotScale);
    v[kLightFalloff] = splat(l.falloff);
    v[kLightAmbient] = rgb(l.ambient);
    v[kLightDiffuse] = rgb(l.diffuse);
    v[kLightSpecular] = rgb(l.specular);
    v[kLightHalfway] = Vec4(normalize(d + kNonLocalViewer), 0);
  }
  if (indexed)
    for (int i = 0; i < kMaxWorldMatrices; ++i) {
      const Matrix wv = s.worldMatrix(i) * s.view;
      columns(kConstVertexBlendTable + kConstVertexBlendStride * i, wv, 4);
      columns(kConstVertexBlendTable + kConstVertexBlendStride * i + 4, normalMatrix(wv), 3);
    }
}

}  // namespace refx::pipeline
