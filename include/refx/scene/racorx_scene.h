// What the RacorX samples of the seeds share: the shader files of data/shaders, the
// articles' ConfirmDevice test, their constant layout, the earth globe and the
// RacorX7 / RacorX8 specular scenes (also drawn by the precision test).
//
// Constant layout of RacorX6-9 (seeds/003, FrameMove / RestoreDeviceObjects):
//   c0-c3   world matrix, transposed (D3DXMatrixTranspose before SetVertexShaderConstant,
//           so that m4x4 r, v0, c0 computes v0 * World)
//   c8-c11  world * view * projection, transposed
//   c12     light direction (the direction the light travels; the shaders use -c12)
//   c24     eye position
//   c33     (0.5, 0.5, 0.5, 0.5)
#pragma once
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "refx/core/diagnostics.h"
#include "refx/core/math.h"
#include "refx/d3dx/lighting_maps.h"
#include "refx/d3dx/mesh.h"
#include "refx/d3dx/texture_fill.h"
#include "refx/pipeline/device.h"
#include "refx/shader/assembler.h"

namespace refx::scene::racorx {

inline std::string shaderPath(const std::string& file) { return std::string(REFX_DATA_DIR) + "/shaders/" + file; }

inline std::string loadShaderText(const std::string& file) {
  const std::string path = shaderPath(file);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the shader file", path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Assemble a data/shaders file and create the shader on the device (validated for
// its version, lowered); refx::Error on any failure, naming the file.
inline VertexShaderPtr loadVertexShader(const Device& dev, const std::string& file) {
  const auto tokens = shader::assembleTokens(loadShaderText(file), shaderPath(file));
  return dev.createVertexShader(tokens);
}
inline PixelShaderPtr loadPixelShader(const Device& dev, const std::string& file) {
  const auto tokens = shader::assembleTokens(loadShaderText(file), shaderPath(file));
  return dev.createPixelShader(tokens);
}

// D3DPS_VERSION(major, minor) <= PixelShaderVersion, as ConfirmDevice compares them.
inline bool supportsPixelShader(const CapsProfile& caps, int major, int minor) {
  return caps.pixelShaderVersion != 0 && caps.psMajor() * 256 + caps.psMinor() >= major * 256 + minor;
}
inline bool supportsVertexShader11(const CapsProfile& caps) {
  return caps.vertexShaderVersion != 0 && caps.vsMajor() >= 1;
}

// Camera and light of a frame.
struct View {
  Matrix world = Matrix::identity(), view = Matrix::identity(), projection = Matrix::identity();
  Vec3 eye;
  Vec3 lightDirection;  // where the light travels (from the light)
};

inline void setMatrix(Device& dev, uint32_t reg, const Matrix& m) {
  const Matrix t = transpose(m);
  dev.setVertexShaderConstantF(reg, &t.m[0][0], 4);
}
inline void setVector(Device& dev, uint32_t reg, Vec4 v) { dev.setVertexShaderConstantF(reg, &v.x, 1); }

// The constants of RacorX6-9 (layout above).
inline void setConstants(Device& dev, const View& v) {
  setMatrix(dev, 0, v.world);
  setMatrix(dev, 8, v.world * v.view * v.projection);
  setVector(dev, 12, Vec4(normalize(v.lightDirection), 0));  // D3DXVec4Normalize(&m_LightDir)
  setVector(dev, 24, Vec4(v.eye, 1));
  setVector(dev, 33, Vec4(0.5f, 0.5f, 0.5f, 0.5f));
}

// The globe the articles light: createTexturedSphere has the layout of their vertex
// shaders' declaration through its FVF (v0 position, v3 normal, v7 texture
// coordinates, v8 tangent = D3DXComputeTangent's U).
inline d3dx::Mesh globe(uint32_t slices = 48, uint32_t stacks = 24) {
  return d3dx::createTexturedSphere(1.0f, slices, stacks);
}

inline void drawGlobe(Device& dev, const d3dx::Mesh& m) {
  dev.drawIndexedPrimitive(d3d::PT_TRIANGLELIST, 0, 0, m.vertexCount(), 0, m.faceCount());
}

// Bilinear, optionally with mip maps (the articles set LINEAR on the color map and
// suggest it "in production code" for the others; the lookup tables are "nicely
// filtered" by the texture unit, which is what reduces their banding).
inline void linearSampling(Device& dev, int sampler, bool mips) {
  dev.setSamplerState(sampler, d3d::SAMP_MINFILTER, 2);
  dev.setSamplerState(sampler, d3d::SAMP_MAGFILTER, 2);
  dev.setSamplerState(sampler, d3d::SAMP_MIPFILTER, mips ? 2 : 0);
}
inline void clampAddressing(Device& dev, int sampler) {
  dev.setSamplerState(sampler, d3d::SAMP_ADDRESSU, 3);  // D3DTADDRESS_CLAMP
  dev.setSamplerState(sampler, d3d::SAMP_ADDRESSV, 3);
  dev.setSamplerState(sampler, d3d::SAMP_ADDRESSW, 3);
}

// A camera at `distance` on -z looking at the globe's centre; `zoom` narrows the
// field of view.
inline View globeView(const Device& dev, Matrix world, float distance = 3.0f, float fov = 0.7853982f) {
  View v;
  const Texture& rt = *dev.renderTarget();
  v.world = world;
  v.eye = {0, 0, -distance};
  v.view = matrixLookAtLH(v.eye, {0, 0, 0}, {0, 1, 0});
  v.projection = matrixPerspectiveFovLH(fov, float(rt.width()) / float(rt.height()), 0.1f, 100.0f);
  return v;
}

// ---------------------------------------------------------------- RacorX7 / RacorX8
// The two specular scenes compared by the precision test, with the textures given:
// RacorX7 (specular power 16 by four squarings of N.H, racorx7_ps11/ps14.psh) and
// RacorX8 (the power read from RacorX8's 256x256 LightEval table through
// texm3x2pad/texm3x2tex, or texcrd/dp3/texld in ps.1.4).
struct SpecularTextures {
  TexturePtr color;   // color map (RacorX7: stage 0, RacorX8: stage 3)
  TexturePtr normal;  // normal map (stage 1 / stage 0)
  TexturePtr table;   // RacorX8's specular power table (stage 2)
};

inline TexturePtr racorx8Table() { return d3dx::specularPowerMap(256, 256, 16.0f); }

enum class PSVersion { PS11, PS12, PS14 };

inline void setupRacorX7(Device& dev, const View& v, const SpecularTextures& t, PSVersion ps) {
  dev.setRenderState(d3d::RS_ZENABLE, d3d::ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "racorx7.vsh"));
  dev.setPixelShader(loadPixelShader(dev, ps == PSVersion::PS14 ? "racorx7_ps14.psh" : "racorx7_ps11.psh"));
  setConstants(dev, v);
  dev.setTexture(0, t.color);
  dev.setTexture(1, t.normal);
  linearSampling(dev, 0, true);
  linearSampling(dev, 1, true);
}

inline void setupRacorX8(Device& dev, const View& v, const SpecularTextures& t, PSVersion ps) {
  dev.setRenderState(d3d::RS_ZENABLE, d3d::ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "racorx8.vsh"));
  dev.setPixelShader(loadPixelShader(dev, ps == PSVersion::PS14 ? "racorx8_ps14.psh" : "racorx8_ps11.psh"));
  setConstants(dev, v);
  // ps.1.1: t0 normal map, t1 texm3x2pad (no texture), t2 the table, t3 color map.
  // ps.1.4 samples the same stages: r0 normal map, r2 the table, r3 color map.
  dev.setTexture(0, t.normal);
  dev.setTexture(2, t.table);
  dev.setTexture(3, t.color);
  linearSampling(dev, 0, true);
  linearSampling(dev, 2, false);
  linearSampling(dev, 3, true);
  // "Without the clamping a white ring around the earth would be visible."
  clampAddressing(dev, 2);
}

}  // namespace refx::scene::racorx
