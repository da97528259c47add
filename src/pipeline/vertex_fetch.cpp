#include "vertex_fetch.h"

#include <cstring>

#include "ff_vertex.h"
#include "refx/core/diagnostics.h"

namespace refx::pipeline {

using namespace d3d;

int inputRegisterForElement(const VertexElement& e) {
  switch (e.usage) {
    case DECLUSAGE_POSITION: case DECLUSAGE_POSITIONT:
      return e.usageIndex == 0 ? kVertexInPosition : kVertexInPosition1;
    case DECLUSAGE_BLENDWEIGHT: return kVertexInBlendWeight;
    case DECLUSAGE_BLENDINDICES: return kVertexInBlendIndices;
    case DECLUSAGE_NORMAL: return e.usageIndex == 0 ? kVertexInNormal : kVertexInNormal1;
    case DECLUSAGE_PSIZE: return kVertexInPSize;
    case DECLUSAGE_COLOR: return e.usageIndex == 0 ? kVertexInDiffuse : e.usageIndex == 1 ? kVertexInSpecular : -1;
    case DECLUSAGE_TEXCOORD: return e.usageIndex < 8 ? kVertexInTex0 + e.usageIndex : -1;
    default: return -1;
  }
}

static float halfToFloat(uint16_t h) {
  const uint32_t sign = (h >> 15) & 1, exp = (h >> 10) & 0x1f, man = h & 0x3ff;
  float v;
  if (exp == 0) v = std::ldexp(float(man), -24);
  else if (exp == 31) v = man ? NAN : INFINITY;
  else v = std::ldexp(float(man | 0x400), int(exp) - 25);
  return sign ? -v : v;
}

// Decodes one element into up to 4 floats; returns the number of components it supplies.
static int decodeElement(uint8_t type, const uint8_t* p, float out[4]) {
  auto rd = [&](int i, auto t) {
    decltype(t) v;
    std::memcpy(&v, p + i * sizeof(v), sizeof(v));
    return v;
  };
  switch (type) {
    case DECLTYPE_FLOAT1: case DECLTYPE_FLOAT2: case DECLTYPE_FLOAT3: case DECLTYPE_FLOAT4: {
      int n = type - DECLTYPE_FLOAT1 + 1;
      for (int i = 0; i < n; ++i) out[i] = rd(i, 0.0f);
      return n;
    }
    case DECLTYPE_D3DCOLOR:  // memory B G R A, shader sees (R, G, B, A)
      out[0] = p[2] / 255.0f;
      out[1] = p[1] / 255.0f;
      out[2] = p[0] / 255.0f;
      out[3] = p[3] / 255.0f;
      return 4;
    case DECLTYPE_UBYTE4:
      for (int i = 0; i < 4; ++i) out[i] = p[i];
      return 4;
    case DECLTYPE_UBYTE4N:
      for (int i = 0; i < 4; ++i) out[i] = p[i] / 255.0f;
      return 4;
    case DECLTYPE_SHORT2: case DECLTYPE_SHORT4: {
      int n = type == DECLTYPE_SHORT2 ? 2 : 4;
      for (int i = 0; i < n; ++i) out[i] = rd(i, int16_t());
      return n;
    }
    case DECLTYPE_SHORT2N: case DECLTYPE_SHORT4N: {
      int n = type == DECLTYPE_SHORT2N ? 2 : 4;
      for (int i = 0; i < n; ++i) out[i] = std::max(-1.0f, rd(i, int16_t()) / 32767.0f);
      return n;
    }
    case DECLTYPE_USHORT2N: case DECLTYPE_USHORT4N: {
      int n = type == DECLTYPE_USHORT2N ? 2 : 4;
      for (int i = 0; i < n; ++i) out[i] = rd(i, uint16_t()) / 65535.0f;
      return n;
    }
    case DECLTYPE_UDEC3: {
      uint32_t v = rd(0, uint32_t());
      for (int i = 0; i < 3; ++i) out[i] = float((v >> (10 * i)) & 0x3ff);
      return 3;
    }
    case DECLTYPE_DEC3N: {
      uint32_t v = rd(0, uint32_t());
      for (int i = 0; i < 3; ++i) {
        int s = int((v >> (10 * i)) & 0x3ff);
        if (s & 0x200) s -= 0x400;
        out[i] = std::max(-1.0f, s / 511.0f);
      }
      return 3;
    }
    case DECLTYPE_FLOAT16_2: case DECLTYPE_FLOAT16_4: {
      int n = type == DECLTYPE_FLOAT16_2 ? 2 : 4;
      for (int i = 0; i < n; ++i) out[i] = halfToFloat(rd(i, uint16_t()));
      return n;
    }
    default: return 0;
  }
}

static uint32_t elementSize(uint8_t type) {
  static const uint8_t sizes[] = {4, 8, 12, 16, 4, 4, 4, 8, 4, 4, 8, 4, 8, 4, 4, 4, 8};
  return type < sizeof(sizes) ? sizes[type] : 0;
}

void resetInputs(exec::BatchRegisters& regs, bool fixedFunction) {
  for (size_t r = 0; r < regs.inputs.size(); ++r)
    for (int c = 0; c < 4; ++c) {
      float v = c == 3 ? 1.0f : 0.0f;
      if (fixedFunction && r == kVertexInDiffuse) v = 1.0f;
      if (fixedFunction && r == kVertexInSpecular) v = 0.0f;
      for (int l = 0; l < kBatchLanes; ++l) regs.inputs[r].c[c][l] = v;
    }
}

std::vector<FetchElement> fixedFunctionFetch(const VertexDeclaration& decl) {
  std::vector<FetchElement> out;
  for (const VertexElement& e : decl.elements)
    if (int r = inputRegisterForElement(e); r >= 0) out.push_back({e, r});
  return out;
}

std::vector<FetchElement> shaderFetch(const VertexDeclaration& decl,
                                      const exec::LoweredShader& shader) {
  constexpr int kShaderInputs = 16;
  std::vector<FetchElement> out;
  if (shader.vertexInputs.empty() && !shader.version.sm2plus()) {
    for (const VertexElement& e : decl.elements) {
      const int r = e.shaderRegister >= 0 ? e.shaderRegister : inputRegisterForElement(e);
      if (r >= 0 && r < kShaderInputs) out.push_back({e, r});
    }
    return out;
  }
  for (const exec::LoweredShader::InputBinding& b : shader.vertexInputs) {
    const uint8_t usage = uint8_t(b.usage);
    const VertexElement* e = decl.find(usage, b.usageIndex);
    if (!e && usage == DECLUSAGE_POSITION) e = decl.find(DECLUSAGE_POSITIONT, b.usageIndex);
    if (!e && usage == DECLUSAGE_POSITIONT) e = decl.find(DECLUSAGE_POSITION, b.usageIndex);
    if (e && b.reg < kShaderInputs) out.push_back({*e, b.reg});
  }
  return out;
}

void fetchVertices(const std::vector<FetchElement>& elements, const StreamView* streams,
                   uint32_t first, int count, exec::BatchRegisters& regs) {
  for (const FetchElement& fe : elements) {
    const VertexElement& e = fe.element;
    const int r = fe.reg;
    if (r < 0 || r >= int(regs.inputs.size()) || e.stream >= 16) continue;
    const StreamView& s = streams[e.stream];
    const uint32_t esize = elementSize(e.type);
    if (e.type >= DECLTYPE_FLOAT1 && e.type <= DECLTYPE_FLOAT4 && count > 0 && s.data &&
        (size_t(first) + size_t(count) - 1) * s.stride + e.offset + esize <= s.size) {
      // Floats with the whole batch inside the stream: copied as they are (decodeElement's
      // FLOATn), one bounds check for the batch.
      const int n = e.type - DECLTYPE_FLOAT1 + 1;
      const uint8_t* p = s.data + size_t(first) * s.stride + e.offset;
      for (int l = 0; l < count; ++l, p += s.stride)
        for (int c = 0; c < n; ++c) std::memcpy(&regs.inputs[r].c[c][l], p + 4 * c, 4);
      continue;
    }
    for (int l = 0; l < count; ++l) {
      size_t off = size_t(first + l) * s.stride + e.offset;
      float v[4];
      if (!s.data || off + esize > s.size) fail("vertex {} reads past the end of stream {}", first + l, e.stream);
      int n = decodeElement(e.type, s.data + off, v);
      for (int c = 0; c < n; ++c) regs.inputs[r].c[c][l] = v[c];
    }
  }
}

}  // namespace refx::pipeline
