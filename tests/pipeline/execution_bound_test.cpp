// A shader stopped by the executed-instruction bound (kMaxExecutedInstructions) is
// reported once per draw through Device::diagnostics(), code D1001.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "device_helpers.h"
#include "refx/exec/interpreter.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::test;

namespace {

std::vector<uint32_t> tokens(std::string_view text) { return shader::assembleTokens(text, "t.sh"); }

std::unique_ptr<Device> quietDevice() {
  DeviceOptions opt;
  opt.threads = 1;
  opt.warningsToStderr = false;
  auto dev = std::make_unique<Device>(loadCapsProfile("ref"), opt);
  dev->setRenderTarget(Texture::create2D(Format::A8R8G8B8, 8, 8));
  dev->clear(d3d::CLEAR_TARGET, 0xff000000, 1.0f, 0);
  return dev;
}

// A clip-space quad over the whole 8x8 target.
void drawClipQuad(Device& dev) {
  const std::vector<ColorVertex> v = {
      {-1, 1, 0.5f, 0xffffffff}, {1, 1, 0.5f, 0xffffffff}, {-1, -1, 0.5f, 0xffffffff}, {1, -1, 0.5f, 0xffffffff}};
  dev.setFVF(kColorVertexFVF);
  dev.setRenderState(d3d::RS_CULLMODE, d3d::CULL_NONE);
  dev.setRenderState(d3d::RS_LIGHTING, 0);
  dev.drawPrimitiveUP(d3d::PT_TRIANGLESTRIP, 2, v.data(), sizeof(ColorVertex));
}

const char* kPassThroughVs30 = "vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n";

// Two nested `rep i0` loops adding c0 to r0: with i0 = n the add runs n*n times.
// Each inner pass executes 2 instructions (add, endrep), each outer pass 2 more
// (rep, endrep), so n = 255 executes about 255 * (2*255 + 2) = 130,560 instructions
// per batch: more than 65,535, and the final `mov oC0` is never reached.
std::string nestedLoopPs(int n) {
  return fmt::format("ps_3_0\n"
         "defi i0, {}, 0, 0, 0\n", n) +
         "def c0, 0.25, 0.25, 0.25, 0.25\n"
         "def c1, 0, 0, 0, 0\n"
         "mov r0, c1\n"
         "rep i0\n"
         "rep i0\n"
         "add r0, r0, c0\n"
         "endrep\n"
         "endrep\n"
         "mov oC0, r0\n";
}

}  // namespace

TEST(ExecutionBound, PixelShaderStoppedByTheBoundIsReportedOncePerDraw) {
  auto dev = quietDevice();
  dev->setVertexShader(dev->createVertexShader(tokens(kPassThroughVs30)));
  dev->setPixelShader(dev->createPixelShader(tokens(nestedLoopPs(255))));
  drawClipQuad(*dev);
  ASSERT_EQ(dev->diagnostics().all().size(), 1u);
  const Diagnostic& d = dev->diagnostics().all()[0];
  EXPECT_EQ(d.code, "D1001");
  EXPECT_EQ(d.severity, Severity::Warning);
  EXPECT_NE(d.message.find("pixel shader stopped after 65535 executed instructions"), std::string::npos)
      << d.message;
  EXPECT_NE(d.message.find("draw 1:"), std::string::npos) << d.message;
  drawClipQuad(*dev);  // a second draw: a second report, not one per batch
  ASSERT_EQ(dev->diagnostics().all().size(), 2u);
  EXPECT_NE(dev->diagnostics().all()[1].message.find("draw 2:"), std::string::npos);
}

// Also: a Clear with no depth-stencil surface attached, then a draw (the deferred
// clear once read the missing depth surface).
TEST(ExecutionBound, ShaderWithinTheBoundIsNotReported) {
  auto dev = quietDevice();
  dev->setVertexShader(dev->createVertexShader(tokens(kPassThroughVs30)));
  // n = 2: r0 = 2 * 2 * 0.25 = 1.0 in every channel -> 0xffffffff.
  dev->setPixelShader(dev->createPixelShader(tokens(nestedLoopPs(2))));
  drawClipQuad(*dev);
  EXPECT_TRUE(dev->diagnostics().all().empty());
  EXPECT_EQ(pixel(*dev, 4, 4), 0xffffffffu);
}

TEST(ExecutionBound, VertexShaderStoppedByTheBoundIsReported) {
  auto dev = quietDevice();
  // The same nested loop in a vertex shader (about 130,560 instructions per batch of
  // vertices; vs_3_0, since vs_2_0 does not nest rep); the pixel stage is fixed function.
  dev->setVertexShader(dev->createVertexShader(tokens(
      "vs_3_0\n"
      "defi i0, 255, 0, 0, 0\n"
      "def c0, 0.25, 0.25, 0.25, 0.25\n"
      "dcl_position v0\n"
      "dcl_position o0\n"
      "mov r0, v0\n"
      "rep i0\n"
      "rep i0\n"
      "add r1, r0, c0\n"
      "endrep\n"
      "endrep\n"
      "mov o0, v0\n")));
  drawClipQuad(*dev);
  ASSERT_EQ(dev->diagnostics().all().size(), 1u);
  EXPECT_NE(dev->diagnostics().all()[0].message.find("vertex shader stopped"), std::string::npos)
      << dev->diagnostics().all()[0].message;
  dev->clearDiagnostics();
  EXPECT_TRUE(dev->diagnostics().all().empty());
}
