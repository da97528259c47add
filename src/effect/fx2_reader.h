// Reading an fx_2_0 binary (reference fx2-binary.md) into the parsed form of an effect,
// which the Effect then builds as it builds a text effect.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "ast.h"

namespace refx::effect::detail {

// True when `bytes` starts with the fx_2_0 tag 0xFEFF0901.
bool isFx2Binary(std::span<const uint8_t> bytes);
// Throws refx::Error ("name: error: fx_2_0 offset 0x…: …") for a damaged binary.
EffectAst readFx2(std::span<const uint8_t> bytes, const std::string& name);

}  // namespace refx::effect::detail
