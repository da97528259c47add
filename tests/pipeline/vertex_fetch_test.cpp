// Vertex fetch (pipeline/vertex_fetch.h): a batch's elements from the stream bytes into
// its input lanes. FLOATn elements are the stream's floats bit for bit (a NaN's payload
// and -0 included), whether the batch lies inside the stream or ends at its last byte;
// an element reaching past the end is an error; other types are decoded as D3D defines.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "pipeline/vertex_fetch.h"
#include "refx/core/diagnostics.h"

namespace refx::pipeline {
namespace {

// Vertices of `stride` bytes: a D3DCOLOR at offset 0, float3 at offset 8 (the last
// element of a vertex).
constexpr uint32_t kStride = 24;

std::vector<uint8_t> makeStream(int vertices) {
  std::vector<uint8_t> bytes(size_t(vertices) * kStride, 0xcd);
  for (int v = 0; v < vertices; ++v) {
    const float xyz[3] = {float(v) + 0.25f, -0.0f, std::nanf("0x2a")};
    std::memcpy(&bytes[size_t(v) * kStride + 8], xyz, sizeof xyz);
    const uint8_t bgra[4] = {uint8_t(v), 51, 102, 255};  // memory order B, G, R, A
    std::memcpy(&bytes[size_t(v) * kStride], bgra, sizeof bgra);
  }
  return bytes;
}

std::vector<FetchElement> elements() {
  VertexElement position;
  position.offset = 8;
  position.type = d3d::DECLTYPE_FLOAT3;
  VertexElement color;
  color.offset = 0;
  color.type = d3d::DECLTYPE_D3DCOLOR;
  color.usage = d3d::DECLUSAGE_COLOR;
  return {{position, 0}, {color, 1}};
}

exec::BatchRegisters batchRegisters() {
  exec::BatchRegisters regs;
  regs.inputs.resize(2);
  resetInputs(regs, false);
  return regs;
}

uint32_t bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

void expectVertices(const exec::BatchRegisters& regs, uint32_t first, int count) {
  for (int l = 0; l < count; ++l) {
    const float v = float(first + uint32_t(l));
    EXPECT_EQ(regs.inputs[0].c[0][l], v + 0.25f) << l;
    EXPECT_EQ(bits(regs.inputs[0].c[1][l]), 0x80000000u) << l;  // -0 stays -0
    EXPECT_EQ(bits(regs.inputs[0].c[2][l]), bits(std::nanf("0x2a"))) << l;  // the NaN's payload
    EXPECT_EQ(regs.inputs[0].c[3][l], 1.0f) << l;  // absent w: resetInputs' 1
    // D3DCOLOR: (R, G, B, A) = (102, 51, v, 255) / 255.
    EXPECT_EQ(regs.inputs[1].c[0][l], 102.0f / 255.0f) << l;
    EXPECT_EQ(regs.inputs[1].c[1][l], 51.0f / 255.0f) << l;
    EXPECT_EQ(regs.inputs[1].c[2][l], float(first + uint32_t(l)) / 255.0f) << l;
    EXPECT_EQ(regs.inputs[1].c[3][l], 1.0f) << l;
  }
  for (int l = count; l < kBatchLanes; ++l) {  // lanes past the batch keep the defaults
    EXPECT_EQ(regs.inputs[0].c[0][l], 0.0f) << l;
    EXPECT_EQ(regs.inputs[0].c[3][l], 1.0f) << l;
  }
}

TEST(VertexFetch, FloatsAreCopiedBitForBitInsideTheStream) {
  const std::vector<uint8_t> bytes = makeStream(40);
  const StreamView streams[1] = {{bytes.data(), bytes.size(), kStride}};
  exec::BatchRegisters regs = batchRegisters();
  fetchVertices(elements(), streams, 3, 16, regs);
  expectVertices(regs, 3, 16);
}

// The batch's last vertex ends at the stream's last byte: every vertex read.
TEST(VertexFetch, BatchEndingAtTheStreamsEndIsRead) {
  const std::vector<uint8_t> bytes = makeStream(20);
  const size_t end = size_t(19) * kStride + 20;  // the last vertex's float3 ends here
  const StreamView streams[1] = {{bytes.data(), end, kStride}};
  exec::BatchRegisters regs = batchRegisters();
  fetchVertices(elements(), streams, 9, 11, regs);
  expectVertices(regs, 9, 11);
}

// One byte short: the last vertex's float3 does not fit (its color does).
TEST(VertexFetch, ElementPastTheStreamsEndIsAnError) {
  const std::vector<uint8_t> bytes = makeStream(20);
  const size_t end = size_t(19) * kStride + 20 - 1;
  const StreamView streams[1] = {{bytes.data(), end, kStride}};
  exec::BatchRegisters regs = batchRegisters();
  try {
    fetchVertices(elements(), streams, 9, 11, regs);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 19 reads past the end of stream 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace refx::pipeline
