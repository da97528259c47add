// The D3DCAPS9 flag names and bits, one table per field: read by the caps file parser
// (caps.cpp) and by ValidateDevice (validate.cpp), which names the flag it needs.
#pragma once
#include <cstdint>
#include <span>
#include <string_view>

namespace refx::caps_flags {

struct FlagBit {
  std::string_view name;  // without the D3D prefix
  uint32_t bit;
};

inline constexpr FlagBit kTextureCaps[] = {
    {"PERSPECTIVE", 0x1}, {"POW2", 0x2}, {"ALPHA", 0x4}, {"SQUAREONLY", 0x20},
    {"TEXREPEATNOTSCALEDBYSIZE", 0x40}, {"ALPHAPALETTE", 0x80},
    {"NONPOW2CONDITIONAL", 0x100}, {"PROJECTED", 0x400}, {"CUBEMAP", 0x800},
    {"VOLUMEMAP", 0x2000}, {"MIPMAP", 0x4000}, {"MIPVOLUMEMAP", 0x8000},
    {"MIPCUBEMAP", 0x10000}, {"CUBEMAP_POW2", 0x20000}, {"VOLUMEMAP_POW2", 0x40000},
    {"NOPROJECTEDBUMPENV", 0x200000}};

inline constexpr FlagBit kFilterCaps[] = {
    {"MINFPOINT", 0x100}, {"MINFLINEAR", 0x200}, {"MINFANISOTROPIC", 0x400},
    {"MINFPYRAMIDALQUAD", 0x800}, {"MINFGAUSSIANQUAD", 0x1000}, {"MIPFPOINT", 0x10000},
    {"MIPFLINEAR", 0x20000}, {"CONVOLUTIONMONO", 0x40000}, {"MAGFPOINT", 0x1000000},
    {"MAGFLINEAR", 0x2000000}, {"MAGFANISOTROPIC", 0x4000000},
    {"MAGFPYRAMIDALQUAD", 0x8000000}, {"MAGFGAUSSIANQUAD", 0x10000000}};

inline constexpr FlagBit kAddressCaps[] = {
    {"WRAP", 0x1}, {"MIRROR", 0x2}, {"CLAMP", 0x4}, {"BORDER", 0x8},
    {"INDEPENDENTUV", 0x10}, {"MIRRORONCE", 0x20}};

inline constexpr FlagBit kMiscCaps[] = {
    {"MASKZ", 0x2}, {"LINEPATTERNREP", 0x4}, {"CULLNONE", 0x10}, {"CULLCW", 0x20},
    {"CULLCCW", 0x40}, {"COLORWRITEENABLE", 0x80}, {"CLIPPLANESCALEDPOINTS", 0x100},
    {"CLIPTLVERTS", 0x200}, {"TSSARGTEMP", 0x400}, {"BLENDOP", 0x800},
    {"NULLREFERENCE", 0x1000}, {"INDEPENDENTWRITEMASKS", 0x4000},
    {"PERSTAGECONSTANT", 0x8000}, {"FOGANDSPECULARALPHA", 0x10000},
    {"SEPARATEALPHABLEND", 0x20000}, {"MRTINDEPENDENTBITDEPTHS", 0x40000},
    {"MRTPOSTPIXELSHADERBLENDING", 0x80000}, {"FOGVERTEXCLAMPED", 0x100000},
    {"POSTBLENDSRGBCONVERT", 0x200000}};

inline constexpr FlagBit kRasterCaps[] = {
    {"DITHER", 0x1}, {"ZTEST", 0x10}, {"FOGVERTEX", 0x80}, {"FOGTABLE", 0x100},
    {"MIPMAPLODBIAS", 0x2000}, {"ZBUFFERLESSHSR", 0x8000}, {"FOGRANGE", 0x10000},
    {"ANISOTROPY", 0x20000}, {"WBUFFER", 0x40000}, {"WFOG", 0x100000}, {"ZFOG", 0x200000},
    {"COLORPERSPECTIVE", 0x400000}, {"SCISSORTEST", 0x1000000},
    {"SLOPESCALEDEPTHBIAS", 0x2000000}, {"DEPTHBIAS", 0x4000000},
    {"MULTISAMPLE_TOGGLE", 0x8000000}};

// D3DTEXOPCAPS_*: named as the D3DTOP each bit allows (d3d9caps.h).
inline constexpr FlagBit kTextureOpCaps[] = {
    {"DISABLE", 0x1}, {"SELECTARG1", 0x2}, {"SELECTARG2", 0x4}, {"MODULATE", 0x8},
    {"MODULATE2X", 0x10}, {"MODULATE4X", 0x20}, {"ADD", 0x40}, {"ADDSIGNED", 0x80},
    {"ADDSIGNED2X", 0x100}, {"SUBTRACT", 0x200}, {"ADDSMOOTH", 0x400},
    {"BLENDDIFFUSEALPHA", 0x800}, {"BLENDTEXTUREALPHA", 0x1000}, {"BLENDFACTORALPHA", 0x2000},
    {"BLENDTEXTUREALPHAPM", 0x4000}, {"BLENDCURRENTALPHA", 0x8000}, {"PREMODULATE", 0x10000},
    {"MODULATEALPHA_ADDCOLOR", 0x20000}, {"MODULATECOLOR_ADDALPHA", 0x40000},
    {"MODULATEINVALPHA_ADDCOLOR", 0x80000}, {"MODULATEINVCOLOR_ADDALPHA", 0x100000},
    {"BUMPENVMAP", 0x200000}, {"BUMPENVMAPLUMINANCE", 0x400000}, {"DOTPRODUCT3", 0x800000},
    {"MULTIPLYADD", 0x1000000}, {"LERP", 0x2000000}};

// D3DPBLENDCAPS_*: named as the D3DBLEND each bit allows; BLENDFACTOR covers
// INVBLENDFACTOR too, SRCCOLOR2/INVSRCCOLOR2 are the D3D9Ex dual-source factors.
inline constexpr FlagBit kBlendCaps[] = {
    {"ZERO", 0x1}, {"ONE", 0x2}, {"SRCCOLOR", 0x4}, {"INVSRCCOLOR", 0x8},
    {"SRCALPHA", 0x10}, {"INVSRCALPHA", 0x20}, {"DESTALPHA", 0x40}, {"INVDESTALPHA", 0x80},
    {"DESTCOLOR", 0x100}, {"INVDESTCOLOR", 0x200}, {"SRCALPHASAT", 0x400},
    {"BOTHSRCALPHA", 0x800}, {"BOTHINVSRCALPHA", 0x1000}, {"BLENDFACTOR", 0x2000},
    {"SRCCOLOR2", 0x4000}, {"INVSRCCOLOR2", 0x8000}};

// The flag `name` of a table; a name not in it does not compile where constant-evaluated.
consteval FlagBit flag(std::span<const FlagBit> table, std::string_view name) {
  for (const FlagBit& f : table)
    if (f.name == name) return f;
  throw "unknown caps flag";
}

// The bit of flag `name` at run time; 0 when the table has no such flag.
constexpr uint32_t bitOf(std::span<const FlagBit> table, std::string_view name) {
  for (const FlagBit& f : table)
    if (f.name == name) return f.bit;
  return 0;
}

}  // namespace refx::caps_flags
