// Image files: read PNG, TGA, BMP, DDS, PPM (P6), PGM (P5), PAM (P7); write PNG,
// DDS, PPM, PAM. Errors name the file and the problem.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "refx/resource/texture.h"

namespace refx {

// Reads any supported image file. 2D formats (PNG/TGA/BMP/PNM) give a one-level
// A8R8G8B8 texture (L8 for grey images without alpha); DDS keeps its format, type
// (2D/cube/volume) and mip levels.
TexturePtr loadTexture(const std::string& path);
// Same from memory; `name` is used in error messages.
TexturePtr loadTextureFromMemory(std::span<const uint8_t> bytes, const std::string& name);

// Writes face/level as PNG (RGB, or RGBA with alpha=true). Non-8-bit formats are converted.
void savePNG(const Texture& tex, const std::string& path, bool alpha = false, int face = 0,
             int level = 0);
// Writes the whole texture (all faces/levels) as DDS in its own format.
void saveDDS(const Texture& tex, const std::string& path);
// P6 (RGB) or P7 RGB_ALPHA when alpha=true.
void savePNM(const Texture& tex, const std::string& path, bool alpha = false, int face = 0,
             int level = 0);
// Picks the writer from the extension (.png, .dds, .ppm, .pam).
void saveImage(const Texture& tex, const std::string& path, bool alpha = false);

}  // namespace refx
