// `.shader_test` files, the text format of vkd3d's shader test suite: shaders,
// resources and [test] lines that draw and probe pixels. refx runs the part a
// Direct3D 9 device can run (docs/shader_test_format.md): one run per file, at shader
// model 2.0 or 3.0.
//
// parseShaderTest() turns a file into a small model (sections in order, each line
// parsed); runShaderTest() drives a refx::Device through it. Errors in a section
// header, [require], resource or sampler line are refx::Error "file:line: error: …";
// a malformed [test] line becomes a Malformed command that fails when it is reached,
// because vkd3d only reads [test] lines for the shader models it runs.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "refx/hlsl/compiler.h"

namespace refx::scene {

// Shader model as major * 10 + minor: 20 = 2.0, 41 = 4.1, 66 = 6.6.
using ShaderModel = int;
constexpr ShaderModel kLowestShaderModel = 20;
constexpr ShaderModel kHighestShaderModel = 69;

// A qualifier such as `(sm>=3 & !glsl | d3d9)`: an OR of ANDs of atoms. Tags name
// the runner's backend; refx is a D3D9 runner, so `d3d9` holds and every other tag
// (glsl, msl, vulkan, mesa<24 …) does not.
struct Condition {
  struct Atom {
    enum class Kind { ModelAtLeast, ModelBelow, Tag } kind = Kind::Tag;
    ShaderModel model = 0;  // ModelAtLeast / ModelBelow
    std::string tag;        // Tag, without any version comparison
    bool negate = false;
  };
  std::vector<std::vector<Atom>> anyOf;  // empty: always holds
  bool holds(ShaderModel model) const;
};

// Parses the text between the parentheses of a qualifier ("sm>=3 & !glsl | d3d9").
// Throws refx::Error (no location) for text it does not understand.
Condition parseCondition(std::string_view text);

enum class ShaderStage { Vertex, Pixel, Effect, Unsupported };  // Unsupported: compute, hull …
enum class ShaderSource { Hlsl, D3dbcHex, OtherHex };          // OtherHex: dxbc-tpf/dxil

struct ShaderSection {
  ShaderStage stage = ShaderStage::Pixel;
  ShaderSource source = ShaderSource::Hlsl;
  std::string stageName;  // "pixel shader", "compute shader" … as written
  // `fail(q)`, `notimpl(q)`, `todo(q)`; a qualifier without parentheses always holds.
  std::optional<Condition> fail, notimpl, todo;
  std::string text;        // the body, lines as written (% lines removed)
  int bodyLine = 0;        // file line of the body's first line
};

struct RequireSection {
  ShaderModel minModel = kLowestShaderModel;
  ShaderModel belowModel = kHighestShaderModel + 1;  // exclusive upper bound
  bool rowMajor = false, backCompat = false;
  std::vector<std::string> missingCaps;  // caps (or tag lines) refx lacks, as written
};

enum class AddressMode { Wrap = 1, Mirror = 2, Clamp = 3, Border = 4, MirrorOnce = 5 };  // D3DTADDRESS
enum class FilterMode { Point = 1, Linear = 2 };  // D3DTEXF

struct SamplerSection {
  int slot = 0;
  FilterMode minFilter = FilterMode::Point, magFilter = FilterMode::Point, mipFilter = FilterMode::Point;
  AddressMode address[3] = {AddressMode::Clamp, AddressMode::Clamp, AddressMode::Clamp};
  std::string unsupported;  // e.g. "comparison sampler"; empty when D3D9 can do it
};

// Element formats of the format's resources and input layouts.
enum class ElementFormat { Float1, Float2, Float3, Float4, Unsupported };

struct ResourceSection {
  enum class Kind { Texture, RenderTarget, VertexBuffer, Unsupported } kind = Kind::Texture;
  int slot = 0;
  enum class Dimension { Tex2D, Tex3D, Cube, Buffer } dimension = Dimension::Tex2D;
  int width = 1, height = 1, depth = 1;
  int levels = 1;
  ElementFormat format = ElementFormat::Float4;
  std::string formatName = "r32g32b32a32-float";
  std::vector<uint32_t> data;  // 32-bit words, as written (floats as their bits)
  std::string unsupported;     // why D3D9 cannot create it; empty when it can
};

struct InputElement {
  int slot = 0;
  ElementFormat format = ElementFormat::Float4;
  std::string formatName;
  std::string semantic;  // "position", "texcoord", "color" …
  int semanticIndex = 0;
};

struct InputLayoutSection {
  std::vector<InputElement> elements;
};

// ---- [test] lines ----

// `uniform OFFSET TYPE values`: OFFSET counts 32-bit words from c0.
struct UniformCommand {
  int offset = 0;
  enum class Type { Float, Float4, Int, Int4, Uint, Uint4 } type = Type::Float4;
  std::vector<float> floats;    // Float / Float4
  std::vector<int64_t> ints;    // Int / Int4 / Uint / Uint4
};

enum class Topology { TriangleList = 4, TriangleStrip = 5, PointList = 1 };  // D3DPT
struct DrawCommand {
  bool quad = false;
  Topology topology = Topology::TriangleList;
  int vertexCount = 3;
};

struct ClearCommand {
  int slot = 0;
  float color[4] = {0, 0, 0, 0};
};

struct ProbeCommand {
  int rtvSlot = 0;
  bool all = false;                         // the whole target
  int left = 0, top = 0, right = 1, bottom = 1;  // exclusive right/bottom
  enum class Kind { Float, Uint, Int } kind = Kind::Float;
  int count = 4;                            // components compared: 1, 2 or 4
  float floats[4] = {0, 0, 0, 0};
  int64_t ints[4] = {0, 0, 0, 0};
  uint32_t ulps = 0;
};

struct AlphaTestCommand {
  uint32_t func = 8;  // D3DCMP_ALWAYS
  float reference = 0;  // 0..1
};
struct ShadeModeCommand {
  bool flat = false;
};
struct FogCommand {
  enum class Mode { Disable, None, Linear, Exp, Exp2 } mode = Mode::Disable;
  bool ortho = false;
  float start = 0, end = 1, density = 1;
};
struct FogColorCommand {
  float color[4] = {0, 0, 0, 0};
};
// A line refx does not know, or knows but cannot run on a D3D9 device.
struct UnknownCommand {
  std::string text;
};
struct MalformedCommand {
  std::string message;
};

using TestCommandBody = std::variant<UniformCommand, DrawCommand, ClearCommand, ProbeCommand, AlphaTestCommand,
                                     ShadeModeCommand, FogCommand, FogColorCommand, UnknownCommand,
                                     MalformedCommand>;

struct TestCommand {
  int line = 0;
  std::string text;                     // the line as written
  std::vector<Condition> onlyIf;        // `if(q)` prefixes: run only when all hold
  bool todo = false, bug = false;       // informative: todo/bug lines count like others
  TestCommandBody body;
};

// Parses one [test] line (prefixes included). Never throws: a malformed line gives
// a MalformedCommand, an unknown one an UnknownCommand.
TestCommand parseTestCommand(std::string_view text, int line = 0);

struct TestSection {
  std::vector<TestCommand> commands;
};
// [preproc], [descriptors], [dsv], [uav N] …: sections a D3D9 device has no use for.
struct UnsupportedSection {
  std::string name;
};

using Section = std::variant<RequireSection, ShaderSection, SamplerSection, ResourceSection,
                             InputLayoutSection, TestSection, UnsupportedSection>;

struct ShaderTestFile {
  std::string path;
  struct Entry {
    int line = 0;  // line of the `[` header
    Section section;
  };
  std::vector<Entry> sections;
};

ShaderTestFile parseShaderTest(std::string_view text, const std::string& path);
ShaderTestFile loadShaderTest(const std::string& path);  // throws refx::Error when unreadable

// The model a file runs at: the lowest of 2.0 and 3.0 that some [require] section
// allows (2.0 when there is none); nullopt when no section allows either.
std::optional<ShaderModel> chooseShaderModel(const ShaderTestFile& file);

struct ShaderTestFailure {
  int line = 0;
  std::string message;  // "probe (1,2) expected rgba(...), got rgba(...)"
};

struct ShaderTestResult {
  enum class Status { Passed, Failed, Skipped } status = Status::Passed;
  std::string skipReason;
  std::vector<ShaderTestFailure> failures;  // in file order
  ShaderModel model = 0;
  int commandsRun = 0;
};

struct ShaderTestOptions {
  int threads = 0;  // rendering threads, 0: all cores
};

// Runs a parsed file on a fresh device (ref caps profile, 640x480 target). Never
// throws for bad input: device errors become failures at their line.
ShaderTestResult runShaderTest(const ShaderTestFile& file, const ShaderTestOptions& options = {});

// One HLSL compilation runShaderTest() makes: a [vertex shader] or [pixel shader]
// section written in HLSL that is active at the file's model and comes before
// anything that ends the run. hlsl::compile(source, file.path, options) compiles it
// exactly as the runner does.
struct ShaderCompilation {
  const ShaderSection* section = nullptr;  // points into the file
  int line = 0;                            // line of the section header
  hlsl::CompileOptions options;            // profile ("ps_2_0", "vs_3_0" …), matrix packing
  std::string source;                      // the body behind blank lines: line numbers are the file's
  bool mustFail = false;                   // fail(q) holds at the model
  bool notImplemented = false;             // notimpl(q) holds at the model
};

// The compilations of a file in order; empty when no model of 2.0 and 3.0 runs it.
std::vector<ShaderCompilation> listShaderCompilations(const ShaderTestFile& file);

}  // namespace refx::scene
