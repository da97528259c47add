// Facts about IR programs that let a caller run them by a shorter route with the same
// results.
#pragma once
#include <optional>
#include <vector>

#include "refx/exec/ir.h"

namespace refx::exec {

// A program whose only effect is output 0 = the texture sample of `sampler` at input
// register `input` (Op::Tex, λ from quad derivatives, coordinates .xyzw unchanged),
// with at most a clamp or saturate that keeps [0, 1] as it is, and nothing else: no
// other output, no kill, no quantization, no flow control. Such a program writes
// exactly the sampled value whenever the sample lies in [0, 1] (8-bit unorm texels).
struct SamplePassthrough {
  int sampler = 0;
  int input = 0;
};
std::optional<SamplePassthrough> findSamplePassthrough(const Program& program);

// The texture lookups a program can make before anything else: each reads an input
// register as it is (Op::Tex, λ from quad derivatives, coordinates .xyzw unchanged),
// writes all four components of a temporary or output register unchanged, and no
// instruction before it writes its coordinates or reads or writes its result (and no
// kill comes before it). Such lookups read nothing the program computes, so a caller
// may make them for many batches at once (PreparedSampler::sampleImplicitGroup), in
// their order, and then run `rest` (the program without them, same registers) on each
// batch: the same results as the whole program. None when the program has flow
// control or has no such lookup.
struct TexturePrologue {
  struct Lookup {
    int sampler = 0;
    int input = 0;  // the coordinates' input register
    RegFile file = RegFile::Temp;  // the result's register
    int index = 0;
    // The result's components `rest` reads (bit c: component c; channelsRead); the
    // others need not be written.
    uint8_t channels = 0xF;
  };
  std::vector<Lookup> lookups;
  Program rest;
};
std::optional<TexturePrologue> findTexturePrologue(const Program& program);

// The components of temporary register `index` that `program` reads before it writes
// the whole register (bit c: component c), from each op's reads, the write masks and
// the swizzles. 0xF wherever that is not plain: flow control, relative addressing.
uint8_t channelsRead(const Program& program, int index);

}  // namespace refx::exec
