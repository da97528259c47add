// Scene scripts: a Direct3D 9 frame as plain text, one command per line, run in order
// against one Device (reference/scene-script.md). Parsing resolves every name and
// value, so a parsed script only fails at run time for I/O, device limits and shaders.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "refx/core/color.h"
#include "refx/core/math.h"
#include "refx/pipeline/state.h"
#include "refx/resource/texture.h"

namespace refx {
class Device;
struct DepthStencilSurface;
}  // namespace refx

namespace refx::scene {

// `clear COLOR [Z [STENCIL]]`: target, Z and stencil together.
struct Clear {
  D3DColor color = 0;
  float z = 1;
  uint32_t stencil = 0;
};
struct SetRenderState {
  d3d::RenderState state;
  uint32_t value;
};
struct SetStageState {
  int stage;
  d3d::TextureStageState state;
  uint32_t value;
};
struct SetSamplerState {
  int sampler;  // 0-15, d3d::kVertexSampler0 + n for vsN
  d3d::SamplerStateType state;
  uint32_t value;
};

enum class Generator {
  Solid, Checker, Gradient, Coords, Pixels, Noise, Dome, Normalize, Faces, MipColors, File,
};
// `texture NAME 2d|cube|volume FMT ... GEN ...`
struct TextureDef {
  std::string name;
  TextureType type = TextureType::Texture2D;
  Format format = Format::A8R8G8B8;
  int width = 1, height = 1, depth = 1;
  int levels = 1;  // 0 = full chain
  Generator generator = Generator::Solid;
  // solid: 1, checker: 2, gradient: TL TR BL BR, pixels: every texel (cube: face by
  // face in D3DCUBEMAP_FACES order), faces: +X -X +Y -Y +Z -Z, mipcolors: one per level.
  std::vector<Color4> colors;
  int cell = 1;        // checker square size in texels
  uint64_t seed = 0;   // noise
  std::string path;    // file, as written in the script
};
struct SetTexture {
  int sampler;
  std::string name;  // empty: none
};
// `vs`/`ps`: heredoc text, a file, or none (fixed function).
struct Shader {
  bool pixel = false;
  enum class Source { None, Inline, File } source = Source::None;
  std::string text;  // Inline: the block between the markers
  int textLine = 0;  // Inline: script line of the block's first line
  std::string path;  // File: as written in the script
};
// vsconst/vsconsti/vsconstb/psconst/psconsti/psconstb
struct SetConstants {
  bool pixel = false;
  enum class Type { Float, Int, Bool } type = Type::Float;
  int reg = 0;
  std::vector<float> floats;  // groups of 4
  std::vector<int32_t> ints;  // Int: groups of 4; Bool: one per register (0/1)
};
// The pending `v` (and `i`) lines packed in the FVF layout, drawn by `draw`.
struct Draw {
  d3d::PrimitiveType type = d3d::PT_TRIANGLELIST;
  uint32_t fvf = 0;
  // Set by `decl`: the vertices use this declaration (stream 0) instead of the FVF.
  std::optional<VertexDeclaration> declaration;
  uint32_t stride = 0;
  uint32_t vertexCount = 0;
  uint32_t primitiveCount = 0;
  std::vector<uint8_t> vertices;
  std::vector<uint16_t> indices;  // empty: DrawPrimitiveUP
};
struct SetTransform {
  uint32_t type;  // d3d::TransformType, TS_TEXTURE0 + n
  Matrix matrix;
};
struct SetMaterial {
  Material material;
};
struct SetLight {
  int index = 0;
  bool enable = true;  // false: `light N off` (the light itself is left as it was)
  Light light;
};
struct SetViewport {
  Viewport viewport;
};
struct SetScissor {
  Rect rect;
};
// `rendertarget N W H FORMAT` creates a texture (all texels 0) and binds it as render
// target N (1-3); `rendertarget N none` unbinds target N.
struct SetRenderTarget {
  int index = 1;
  bool none = false;
  int width = 0, height = 0;
  Format format = Format::A8R8G8B8;
};
struct SetClipPlane {
  int index = 0;
  Vec4 plane;  // A, B, C, D
};

using Action = std::variant<Clear, SetRenderState, SetStageState, SetSamplerState, TextureDef,
                            SetTexture, Shader, SetConstants, Draw, SetTransform, SetMaterial,
                            SetLight, SetViewport, SetScissor, SetRenderTarget,
                            SetClipPlane>;

struct Command {
  int line = 0;
  std::string name;  // the command word as written ("rs", "draw", ...)
  Action action;
};

// `# expect X Y r g b a [tolerance]`: one pixel of the final image (0-255 values);
// `# expect@N ...` the same for the last texture `rendertarget N` created.
struct Expectation {
  int line = 0;
  int target = 0;
  int x = 0, y = 0;
  int rgba[4] = {0, 0, 0, 0};
  int tolerance = 2;
};

struct SceneScript {
  std::string file;  // names the script in messages; relative paths resolve from its folder
  int width = 64, height = 64;
  Format targetFormat = Format::A8R8G8B8;
  std::vector<scene::Command> commands;
  std::vector<scene::Expectation> expectations;
};

// Parses a script; throws refx::Error "file:line[:col]: error: command: what was expected".
SceneScript parseSceneScript(std::string_view text, const std::string& file);
// Reads and parses a script file.
SceneScript loadSceneScript(const std::string& path);

// Builds the texture a `texture` command describes. `image` is the decoded file for the
// `file` generator (required then, ignored otherwise). Throws refx::Error without location.
TexturePtr createSceneTexture(const scene::TextureDef& def, const Texture* image = nullptr);

struct SceneOutput {
  TexturePtr target;
  std::shared_ptr<DepthStencilSurface> depthStencil;
  // Render target N as the expectations see it: [0] = target, [N] the last texture a
  // `rendertarget N W H FORMAT` command created (bound or not at the end), or null.
  std::array<TexturePtr, 4> targets;
};
// Decides before each command whether it runs (true) or is skipped (false).
using SceneCommandFilter = std::function<bool(const scene::Command&)>;
// Creates the render target (all texels 0) and D24S8 surface, attaches them to `device`
// and runs every command in order, or those `filter` lets through (limits on the work a
// script may do, e.g. when fuzzing).
SceneOutput runSceneScript(const SceneScript& script, Device& device,
                           const SceneCommandFilter& filter = {});

// Reads pixel (x, y) of a render target as 0-255 r, g, b, a.
void readTargetPixel(const Texture& target, int x, int y, int rgba[4]);
// Compares every `# expect` pixel; returns one line per mismatch:
// "file:LINE: expected X,Y = r g b a, got r g b a" ("expected target N X,Y ..." for
// `expect@N`).
std::vector<std::string> checkSceneExpectations(const SceneScript& script, const SceneOutput& output);

}  // namespace refx::scene
