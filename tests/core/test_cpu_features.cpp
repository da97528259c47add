#include <gtest/gtest.h>

#include <string>

#include "refx/core/cpu_features.h"

namespace refx {
namespace {

TEST(CpuFeatures, ActiveLevelIsLimitedToTheCpu) {
  const CpuIsa previous = activeIsa();
  EXPECT_LE(int(previous), int(detectedIsa()));
  EXPECT_EQ(setActiveIsa(CpuIsa::Avx2), previous);
  EXPECT_EQ(activeIsa(), CpuIsa::Avx2);
  setActiveIsa(CpuIsa::Avx512);  // only where the CPU has it
  EXPECT_EQ(activeIsa(), detectedIsa());
  setActiveIsa(previous);
  EXPECT_EQ(std::string(isaName(CpuIsa::Avx2)), "avx2");
  EXPECT_EQ(std::string(isaName(CpuIsa::Avx512)), "avx512");
}

}  // namespace
}  // namespace refx
