// A fixed-function T&L program with the constants it reads, for tests that run it
// directly on the interpreter.
#pragma once
#include <vector>

#include "pipeline/ff_vertex.h"

namespace refx::test {

// The program and the constants it reads (exec/abi.h kConstVertex*) for state s.
struct BuiltProgram {
  exec::Program program;
  std::vector<Vec4> constants;
};
inline BuiltProgram build(const DeviceState& s, const pipeline::FixedFunctionVertexConfig& c) {
  BuiltProgram b{pipeline::buildFixedFunctionVertexProgram(s, c), {}};
  pipeline::fixedFunctionVertexConstants(s, c, b.constants);
  return b;
}

}  // namespace refx::test
