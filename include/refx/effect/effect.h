// D3DX effects (.fx): parameters, techniques and passes of state assignments, read
// from fx_1_0 (DirectX 8) and fx_2_0 (DirectX 9) text. The API follows ID3DXEffect:
// parameters by name/semantic/index with Set/Get, technique validation against a
// caps profile (ValidateTechnique / FindNextValidTechnique), and the render loop
// Begin / BeginPass / CommitChanges / EndPass / End on a refx::Device.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/core/math.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/device.h"

namespace refx::effect {

// D3DXPARAMETER_CLASS
enum class ParameterClass : uint8_t { Scalar = 0, Vector, MatrixRows, MatrixColumns, Object, Struct };
// D3DXPARAMETER_TYPE
enum class ParameterType : uint8_t {
  Void = 0, Bool, Int, Float, String, Texture, Texture1D, Texture2D, Texture3D, TextureCube,
  Sampler, Sampler1D, Sampler2D, Sampler3D, SamplerCube, PixelShader, VertexShader,
};
std::string_view parameterTypeName(ParameterType type);  // "float", "texture2D", …

// D3DX_PARAMETER_* flags
constexpr uint32_t kParameterShared = 1;

struct Annotation;
namespace detail { struct EffectAccess; }
using Handle = int;  // index; -1 = none (a null D3DXHANDLE)

// D3DXPARAMETER_DESC plus the annotations.
struct ParameterDesc {
  std::string name, semantic;
  ParameterClass cls = ParameterClass::Scalar;
  ParameterType type = ParameterType::Float;
  int rows = 1, columns = 1, elements = 0;  // elements 0: not an array
  uint32_t flags = 0;
  bool isNumeric() const { return cls != ParameterClass::Object && cls != ParameterClass::Struct; }
  bool isTexture() const { return type >= ParameterType::Texture && type <= ParameterType::TextureCube; }
  bool isSampler() const { return type >= ParameterType::Sampler && type <= ParameterType::SamplerCube; }
  int valueCount() const { return rows * columns * (elements ? elements : 1); }
};

// An annotation: a typed constant. Numbers are kept as written (ints and floats as
// double); a string annotation has `text`.
struct Annotation {
  ParameterDesc desc;
  std::vector<double> numbers;
  std::string text;
};

struct EffectDiagnostic {
  SourceLocation where;
  std::string message;
  bool error = true;
  std::string code;         // "F1201", "A2001" (docs/diagnostics.md); empty when the finding has none
  std::string str() const;  // "file:line:col: error F1201: message" ("error: message" without a code)
};

struct PassDesc {
  std::string name;
  std::vector<Annotation> annotations;
  int stateCount = 0;
};

struct TechniqueDesc {
  std::string name;
  std::vector<Annotation> annotations;
  std::vector<PassDesc> passes;
  // Empty for a technique that loaded; otherwise why it cannot be used (a bad state,
  // a shader that does not assemble): the technique exists but never validates.
  std::string brokenReason;
};

// ValidateTechnique's answer: which pass and which state or cap failed.
struct TechniqueValidation {
  bool ok = true;
  std::string reason;  // "pass p0: pixel shader ps_1_4 needs PixelShaderVersion 1.4; dx8 has 1.1"
};

// Choosing a technique on more than caps (the white paper: "performance, distance
// from the camera, user preferences … sometimes combined"). Techniques say what they
// cost and where they apply with annotations:
//   float Cost;         relative cost (any unit the effect's author uses)
//   float MinDistance;  used from this camera distance on (default 0)
//   float MaxDistance;  used below this camera distance (default unlimited)
struct SelectionPolicy {
  std::vector<std::string> preferred;  // technique names tried first, in this order
  std::optional<float> maxCost;        // skip techniques whose Cost is above
  std::optional<float> distance;       // skip techniques whose [MinDistance, MaxDistance) excludes it
};

struct TechniqueSelection {
  Handle technique = -1;
  std::vector<std::string> rejected;  // "name: reason" for each technique tried before
};

// D3DXFX_* Begin flags.
constexpr uint32_t kDoNotSaveState = 1, kDoNotSaveShaderState = 2, kDoNotSaveSamplerState = 4;

// Shared parameters: effects created with the same pool share the storage of their
// `shared` parameters (same name and type).
class EffectPool {
 public:
  struct Storage;
  std::shared_ptr<Storage> find(const std::string& name) const;
  void add(const std::string& name, std::shared_ptr<Storage> s);

 private:
  std::vector<std::pair<std::string, std::shared_ptr<Storage>>> shared_;
};

struct EffectOptions {
  std::vector<std::string> includeDirs;  // for #include <file> and "file" not found beside the effect
  std::vector<std::pair<std::string, std::string>> defines;  // D3DXMACRO
  std::shared_ptr<EffectPool> pool;
};


class Effect {
 public:
  // Parses `text`; `fileName` names it in diagnostics and anchors relative #includes.
  // Throws refx::Error when the file cannot be used at all (syntax errors, an unknown
  // type, a parameter that cannot be declared); its message lists every such error,
  // one per line, as "file:line:col: error F1100: …" (codes in docs/diagnostics.md).
  // Errors binding the states of a technique mark only that technique broken
  // (diagnostics() lists them, with their codes), as D3DX does.
  static std::unique_ptr<Effect> fromText(std::string_view text, const std::string& fileName,
                                          const EffectOptions& options = {});
  // A compiled effect: the fx_2_0 binary `fxc /T fx_2_0` (or `refx fxc`) writes, tag
  // 0xFEFF0901. Throws refx::Error ("name: error: fx_2_0 offset 0x…: …") for a damaged
  // binary; like text effects, a technique whose states or shaders cannot be used is
  // marked broken.
  static std::unique_ptr<Effect> fromFx2(std::span<const uint8_t> bytes, const std::string& name,
                                         const EffectOptions& options = {});
  // Text, or an fx_2_0 binary when the file starts with its tag.
  static std::unique_ptr<Effect> fromFile(const std::string& path, const EffectOptions& options = {});
  ~Effect();

  const std::string& fileName() const;
  // Every file read (the effect and its includes), for reload on change.
  const std::vector<std::string>& sourceFiles() const;
  const std::vector<EffectDiagnostic>& diagnostics() const;

  // ---- parameters (top level; array elements by "name[i]")
  int parameterCount() const;
  const ParameterDesc& parameterDesc(Handle p) const;
  const std::vector<Annotation>& parameterAnnotations(Handle p) const;
  Handle parameterByName(std::string_view name) const;
  Handle parameterBySemantic(std::string_view semantic) const;  // case-insensitive
  const Annotation* annotationByName(const std::vector<Annotation>& list, std::string_view name) const;

  // Set/Get convert between bool, int and float as D3DX does; a value larger than the
  // parameter is truncated, a smaller one fills the front. Throws refx::Error for a
  // bad handle or a type that cannot convert (a float into a texture).
  void setBool(Handle p, bool v);
  void setInt(Handle p, int v);
  void setFloat(Handle p, float v);
  void setFloatArray(Handle p, const float* v, int count);
  void setIntArray(Handle p, const int* v, int count);
  void setVector(Handle p, const Vec4& v);
  // D3DX row-vector matrices: for a column_major parameter (the default) the value is
  // stored so that shader `m4x4 r, v, c#` / HLSL mul(v, M) computes v * M.
  void setMatrix(Handle p, const Matrix& m);
  void setMatrixTranspose(Handle p, const Matrix& m);
  void setString(Handle p, std::string_view s);
  void setTexture(Handle p, TexturePtr t);
  bool getBool(Handle p) const;
  int getInt(Handle p) const;
  float getFloat(Handle p) const;
  std::vector<float> getFloatArray(Handle p) const;
  Vec4 getVector(Handle p) const;
  Matrix getMatrix(Handle p) const;
  std::string getString(Handle p) const;
  TexturePtr getTexture(Handle p) const;

  // ---- techniques and passes
  int techniqueCount() const;
  const TechniqueDesc& techniqueDesc(Handle t) const;
  Handle techniqueByName(std::string_view name) const;

  // Applies every pass, in order, to a device of `caps` in its default state and asks
  // ValidateDevice after each.
  TechniqueValidation validateTechnique(Handle t, const CapsProfile& caps) const;
  // The first valid technique after `after` (-1: from the first); -1 when none.
  Handle findNextValidTechnique(Handle after, const CapsProfile& caps) const;

  // The first technique that validates on `caps` and passes the policy: preferred
  // names first, then the rest in file order (best first).
  TechniqueSelection selectTechnique(const CapsProfile& caps, const SelectionPolicy& policy = {}) const;

  void setTechnique(Handle t);
  Handle currentTechnique() const;

  // ---- rendering
  // Saves the device state (per kDoNotSave* flags) and returns the pass count.
  int begin(Device& device, uint32_t flags = 0);
  void beginPass(int pass);
  // Re-applies the active pass with the parameters' current values.
  void commitChanges();
  void endPass();
  void end();  // restores what begin saved

 private:
  friend struct detail::EffectAccess;  // the layer's binary writer reads the internals
  Effect();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace refx::effect
