// What a D3DTEXTUREOP reads, from the same recipes the fixed-function pixel program is
// built from (ff_pixel.cpp), so ValidateDevice and the program cannot disagree.
#pragma once
#include <cstdint>

namespace refx::pipeline {

struct TextureOpUse {
  bool valid = false;       // a D3DTEXTUREOP value (DISABLE … LERP)
  bool arg0 = false, arg1 = false, arg2 = false;  // COLORARG0/1/2 (ALPHAARG0/1/2) read
  bool ownTexture = false;  // reads this stage's texture whatever its arguments name
                            // (BLENDTEXTUREALPHA's alpha, the bump stage's du/dv)
  bool colorOnly = false;   // valid as COLOROP only
};

TextureOpUse textureOpUse(uint32_t top);

}  // namespace refx::pipeline
