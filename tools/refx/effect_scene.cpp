#include "effect_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "builtin_assets.h"
#include "refx/scene/mesh_binding.h"
#include "refx/core/text.h"
#include "refx/d3dx/obj.h"
#include "refx/d3dx/teapot.h"
#include "refx/d3dx/xfile.h"
#include "refx/resource/image_io.h"
#include "refx/shader/constant_table.h"

namespace refx::cli {

using effect::Effect;
using effect::Handle;
using effect::ParameterClass;
using effect::ParameterType;

namespace {

constexpr float kPi = 3.14159265358979f;
// Direction toward the light (world space), as the built-in samples light their globes.
const Vec3 kTowardLight = normalize(Vec3{-0.6f, 0.5f, -0.7f});
const Vec3 kEye{0, 0, -3.0f};
constexpr uint32_t kDefaultBackground = 0xff303040;

// DirectX 8 effect files have no semantics; EffectEdit-era applications bound these
// names. Matched case-insensitively.
struct NameConvention {
  std::string_view name, semantic;
};
constexpr NameConvention kNameConventions[] = {
    {"mWld", "WORLD"}, {"mWorld", "WORLD"}, {"matWorld", "WORLD"},
    {"mView", "VIEW"}, {"matView", "VIEW"},
    {"mProj", "PROJECTION"}, {"mProjection", "PROJECTION"}, {"matProj", "PROJECTION"},
    {"mTot", "WORLDVIEWPROJECTION"}, {"mWVP", "WORLDVIEWPROJECTION"},
    {"mWorldViewProj", "WORLDVIEWPROJECTION"}, {"matWVP", "WORLDVIEWPROJECTION"},
    {"lhtR", "LIGHTDIRECTION"}, {"vLightDir", "LIGHTDIRECTION"}, {"LightDir", "LIGHTDIRECTION"},
    {"vEye", "CAMERAPOSITION"}, {"vEyePos", "CAMERAPOSITION"}, {"EyePos", "CAMERAPOSITION"},
    // "Implementing Lighting Models With HLSL": the application sets these by name.
    {"matWorldViewProj", "WORLDVIEWPROJECTION"}, {"vecEye", "CAMERAPOSITION"}, {"vecLightDir", "LIGHTVECTOR"},
};

std::string semanticOf(const effect::ParameterDesc& d) {
  if (!d.semantic.empty()) return toUpper(d.semantic);
  for (const NameConvention& c : kNameConventions)
    if (equalsNoCase(c.name, d.name)) return std::string(c.semantic);
  return {};
}

d3dx::Mesh namedMesh(const std::string& name) {
  if (name == "sphere") return d3dx::createTexturedSphere(1.0f, 48, 24);
  if (name == "teapot") return d3dx::createTeapot(8);
  if (name == "torus") return d3dx::createTorus(0.35f, 0.8f, 24, 48);
  if (name == "box") return d3dx::createBox(1.3f, 1.3f, 1.3f);
  if (auto m = builtinMesh(name)) return *m;
  const std::string ext = toLower(std::filesystem::path(name).extension().string());
  if (ext == ".x") return d3dx::loadXFile(name);
  if (ext == ".obj") return d3dx::loadOBJ(name);
  fail("--mesh: '{}' is not sphere, teapot, torus, box, a built-in mesh (refx asset --list) or a .x/.obj file",
       name);
}

// Radius of the mesh's bounding sphere around the origin.
float meshRadius(const d3dx::Mesh& m) {
  float r = 0;
  for (uint32_t i = 0; i < m.vertexCount(); ++i) r = std::max(r, length(m.position(i)));
  return r > 0 ? r : 1;
}

void writeFloat(uint8_t* p, float f) { std::memcpy(p, &f, 4); }

}  // namespace

TechniqueChoice chooseTechnique(const Effect& fx, const CapsProfile& caps, const std::string& name,
                                const effect::SelectionPolicy& policy) {
  TechniqueChoice c;
  if (!name.empty()) {
    c.technique = fx.techniqueByName(name);
    if (c.technique < 0) {
      std::string names;
      for (Handle t = 0; t < fx.techniqueCount(); ++t)
        names += (t ? ", " : "") + fx.techniqueDesc(t).name;
      fail("{}: error: no technique named '{}' (the effect has: {})", fx.fileName(), name, names);
    }
    const auto v = fx.validateTechnique(c.technique, caps);
    if (!v.ok) c.rejected.push_back(fmt::format("{}: {}", name, v.reason));
    return c;
  }
  const effect::TechniqueSelection sel = fx.selectTechnique(caps, policy);
  c.technique = sel.technique;
  c.rejected = sel.rejected;
  return c;
}

EffectScene::EffectScene(EffectSceneOptions options) : options_(std::move(options)) {}

const d3dx::Mesh& EffectScene::mesh() {
  if (!mesh_ || meshName_ != options_.mesh) {
    mesh_ = namedMesh(options_.mesh);
    meshName_ = options_.mesh;
    repacked_.clear();
  }
  return *mesh_;
}

std::vector<std::string> EffectScene::prepare(Effect& fx) {
  std::vector<std::string> warnings;
  samplerTextures_.clear();
  const std::filesystem::path dir = std::filesystem::path(fx.fileName()).parent_path();
  auto resolveTexture = [&](const std::string& spec) -> TexturePtr {
    if (TexturePtr t = builtinTexture(spec)) return t;
    std::filesystem::path p(spec);
    if (p.is_relative() && !std::filesystem::exists(p)) p = dir / p;
    return loadTexture(p.string());
  };
  for (Handle p = 0; p < fx.parameterCount(); ++p) {
    const effect::ParameterDesc& d = fx.parameterDesc(p);
    if (d.isSampler()) {
      // A sampler without sampler_state gets its texture from the application, on the
      // sampler register the shader's constant table gives (bound after each BeginPass).
      if (auto it = options_.textures.find(d.name); it != options_.textures.end()) {
        try {
          samplerTextures_.emplace_back(d.name, resolveTexture(it->second));
        } catch (const Error& e) {
          warnings.push_back(fmt::format("sampler parameter '{}': {}", d.name, e.what()));
        }
      }
      continue;
    }
    if (d.isTexture()) {
      std::string spec;
      if (auto it = options_.textures.find(d.name); it != options_.textures.end()) spec = it->second;
      for (const char* key : {"ResourceName", "Name", "File", "TextureFile", "Texture"}) {
        if (!spec.empty()) break;
        const effect::Annotation* a = fx.annotationByName(fx.parameterAnnotations(p), key);
        if (a && a->desc.type == ParameterType::String) spec = a->text;
      }
      if (spec.empty()) {
        if (!fx.getTexture(p))
          warnings.push_back(fmt::format("texture parameter '{}' has no texture (bind one with --texture {}=ASSET|FILE)",
                                         d.name, d.name));
        continue;
      }
      try {
        fx.setTexture(p, resolveTexture(spec));
      } catch (const Error& e) {
        warnings.push_back(fmt::format("texture parameter '{}': {}", d.name, e.what()));
      }
    }
    // An all-zero material colour would draw black: EffectEdit's default material is white.
    if (equalsNoCase(d.name, "MaterialColor") && d.isNumeric()) {
      bool zero = true;
      for (float f : fx.getFloatArray(p)) zero &= f == 0;
      if (zero) fx.setVector(p, Vec4(1, 1, 1, 1));
    }
  }
  for (const auto& [name, value] : options_.sets) {
    const Handle p = fx.parameterByName(name);
    if (p < 0) fail("--set: the effect has no parameter '{}'", name);
    const effect::ParameterDesc& d = fx.parameterDesc(p);
    if (d.type == ParameterType::String) {
      fx.setString(p, value);
    } else if (d.isTexture()) {
      fx.setTexture(p, resolveTexture(value));
    } else if (d.isNumeric()) {
      std::vector<float> numbers;
      std::string_view rest = value;
      while (!rest.empty()) {
        const size_t comma = rest.find(',');
        const std::string part(trim(rest.substr(0, comma)));
        char* end = nullptr;
        const float f = std::strtof(part.c_str(), &end);
        if (part.empty() || *end) fail("--set {}={}: '{}' is not a number", name, value, part);
        numbers.push_back(f);
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
      if (int(numbers.size()) > d.valueCount())
        fail("--set {}: the parameter has {} values, {} given", name, d.valueCount(), numbers.size());
      fx.setFloatArray(p, numbers.data(), int(numbers.size()));
    } else {
      fail("--set {}: a {} parameter cannot be set from the command line", name, effect::parameterTypeName(d.type));
    }
  }
  return warnings;
}

// What an application does with ID3DXConstantTable::GetSamplerIndex: the texture of a
// sampler parameter goes on the register the current shaders read that sampler from.
void EffectScene::bindSamplerTextures(Device& device) {
  if (samplerTextures_.empty()) return;
  const DeviceState& st = device.state();
  const std::pair<const ShaderObject*, int> shaders[] = {{st.pixelShader.get(), 0},
                                                         {st.vertexShader.get(), d3d::kVertexSampler0}};
  for (const auto& [shaderObject, base] : shaders) {
    if (!shaderObject) continue;
    const auto table = shader::readConstantTable(shaderObject->decoded());
    if (!table) continue;
    for (const auto& [name, texture] : samplerTextures_) {
      const shader::ShaderConstant* c = table->find(name);
      if (c && c->registerSet == shader::RegisterSet::Sampler && base + c->registerIndex < d3d::kMaxSamplers)
        device.setTexture(base + c->registerIndex, texture);
    }
  }
}

// An application drawing a mesh with a vertex shader whose inputs its FVF does not
// name (TANGENT, BINORMAL) declares them: one float4 element per dcl input, filled
// from the mesh by bindDeclarationStream.
void EffectScene::declareShaderInputs(Device& device) {
  const DeviceState& st = device.state();
  if (!st.vertexShader || st.declaration.fvf == 0) return;
  std::vector<std::pair<uint8_t, uint8_t>> inputs;  // (usage, index)
  bool missing = false;
  for (const shader::Instruction& ins : st.vertexShader->decoded().instructions) {
    if (ins.opcode != shader::Opcode::Dcl || ins.dst.type != shader::RegType::Input) continue;
    const auto usage = uint8_t(ins.usage);
    inputs.emplace_back(usage, ins.usageIndex);
    missing |= st.declaration.find(usage, ins.usageIndex) == nullptr;
  }
  if (!missing) return;
  VertexDeclaration decl;
  for (size_t i = 0; i < inputs.size(); ++i) {
    VertexElement e;
    e.offset = uint16_t(16 * i);
    e.type = d3d::DECLTYPE_FLOAT4;
    e.usage = inputs[i].first;
    e.usageIndex = inputs[i].second;
    decl.elements.push_back(e);
  }
  device.setVertexDeclaration(decl);
}

// A vertex buffer laid out for a declaration a pass set (a DirectX 8 `decl` block):
// each element is filled from the mesh element of its usage.
void EffectScene::bindDeclarationStream(Device& device) {
  const VertexDeclaration& decl = device.state().declaration;
  if (decl.fvf != 0 || decl.elements.empty()) return;
  for (const auto& [d, vb] : repacked_) {
    if (d == decl) {
      device.setStreamSource(0, vb, 0, decl.streamStride(0));
      return;
    }
  }
  const d3dx::Mesh& m = mesh();
  const FVFLayout layout = m.layout();
  const uint32_t stride = decl.streamStride(0);
  auto vb = std::make_shared<VertexBuffer>();
  vb->data.assign(size_t(stride) * m.vertexCount(), 0);
  for (uint32_t v = 0; v < m.vertexCount(); ++v) {
    uint8_t* out = vb->data.data() + size_t(v) * stride;
    for (const VertexElement& e : decl.elements) {
      if (e.stream != 0) continue;
      float src[4] = {0, 0, 0, 1};
      if (e.usage == d3d::DECLUSAGE_POSITION && layout.position >= 0) {
        const Vec3 p = m.position(v);
        src[0] = p.x, src[1] = p.y, src[2] = p.z;
      } else if (e.usage == d3d::DECLUSAGE_NORMAL && layout.normal >= 0) {
        const Vec3 n = m.normal(v);
        src[0] = n.x, src[1] = n.y, src[2] = n.z, src[3] = 0;
      } else if (e.usage == d3d::DECLUSAGE_TEXCOORD && e.usageIndex < 8 && layout.texCoord[e.usageIndex] >= 0) {
        const Vec4 t = m.texCoord(v, e.usageIndex);
        src[0] = t.x, src[1] = t.y, src[2] = t.z, src[3] = t.w;
      } else if ((e.usage == d3d::DECLUSAGE_TANGENT || e.usage == d3d::DECLUSAGE_BINORMAL) && layout.normal >= 0 &&
                 layout.texCoord[1] >= 0 && layout.texDims[1] == 3) {
        // The textured sphere keeps its tangent in texture set 1; the binormal is N x T.
        const Vec4 t4 = m.texCoord(v, 1);
        Vec3 t{t4.x, t4.y, t4.z};
        if (e.usage == d3d::DECLUSAGE_BINORMAL) t = cross(m.normal(v), t);
        src[0] = t.x, src[1] = t.y, src[2] = t.z, src[3] = 0;
      } else if (e.usage == d3d::DECLUSAGE_COLOR && layout.diffuse >= 0) {
        const D3DColor c = m.diffuse(v);
        std::memcpy(out + e.offset, &c, 4);
        continue;
      } else {
        src[3] = 0;
      }
      uint8_t* dst = out + e.offset;
      switch (e.type) {
        case d3d::DECLTYPE_FLOAT1: writeFloat(dst, src[0]); break;
        case d3d::DECLTYPE_FLOAT2: for (int k = 0; k < 2; ++k) writeFloat(dst + 4 * k, src[k]); break;
        case d3d::DECLTYPE_FLOAT3: for (int k = 0; k < 3; ++k) writeFloat(dst + 4 * k, src[k]); break;
        case d3d::DECLTYPE_FLOAT4: for (int k = 0; k < 4; ++k) writeFloat(dst + 4 * k, src[k]); break;
        case d3d::DECLTYPE_D3DCOLOR: {
          const uint32_t c = 0xff000000u | uint32_t(std::clamp(src[0], 0.f, 1.f) * 255 + 0.5f) << 16 |
                             uint32_t(std::clamp(src[1], 0.f, 1.f) * 255 + 0.5f) << 8 |
                             uint32_t(std::clamp(src[2], 0.f, 1.f) * 255 + 0.5f);
          std::memcpy(dst, &c, 4);
          break;
        }
        default: break;  // integer types: left zero
      }
    }
  }
  repacked_.emplace_back(decl, vb);
  device.setStreamSource(0, vb, 0, stride);
}

void EffectScene::draw(Effect& fx, Device& device) {
  const d3dx::Mesh& m = mesh();
  const Texture& rt = *device.renderTarget();
  const float scale = 1.0f / meshRadius(m);
  const Matrix world = matrixScaling(scale, scale, scale) * matrixRotationY(0.6f + 0.5f * options_.time) *
                       matrixRotationX(0.3f);
  const Matrix view = matrixLookAtLH(kEye, {0, 0, 0}, {0, 1, 0});
  const Matrix proj = matrixPerspectiveFovLH(kPi / 4, float(rt.width()) / float(rt.height()), 0.1f, 100.0f);

  uint32_t background = kDefaultBackground;
  for (Handle p = 0; p < fx.parameterCount(); ++p) {
    const effect::ParameterDesc& d = fx.parameterDesc(p);
    if (equalsNoCase(d.name, "BCLR") && d.isNumeric()) background = uint32_t(fx.getInt(p));
    std::string sem = semanticOf(d);
    // DirectX SDK annotations: `float4 p : POSITION < string Object = "PointLight0"; >`
    // names a light's position, DIRECTION with a light object its direction.
    if (const effect::Annotation* obj = fx.annotationByName(fx.parameterAnnotations(p), "Object");
        obj && toLower(obj->text).find("light") != std::string::npos) {
      if (sem == "POSITION") sem = "LIGHTPOSITION";
      if (sem == "DIRECTION") sem = "LIGHTDIRECTION";
    }
    if (sem.empty()) continue;
    if (std::any_of(options_.sets.begin(), options_.sets.end(), [&](const auto& set) { return set.first == d.name; }))
      continue;  // the user's --set value stands
    if (sem == "TIME") {
      if (d.isNumeric()) fx.setFloat(p, options_.time);
      continue;
    }
    if (sem == "CAMERAPOSITION" || sem == "VIEWPOSITION") {
      fx.setVector(p, Vec4(kEye, 1));
      continue;
    }
    if (sem == "LIGHTDIRECTION" || sem == "DIRECTION") {
      fx.setVector(p, Vec4(-kTowardLight, 0));
      continue;
    }
    if (sem == "LIGHTVECTOR") {  // from the surface toward the light: the L of N.L
      fx.setVector(p, Vec4(kTowardLight, 0));
      continue;
    }
    if (sem == "LIGHTPOSITION") {  // a point light as far out as the camera, toward the light
      fx.setVector(p, Vec4(kTowardLight * length(kEye), 1));
      continue;
    }
    // WORLD, VIEW, PROJECTION and products, with INVERSE / TRANSPOSE suffixes.
    bool inv = false, transp = false;
    if (sem.size() > 9 && sem.ends_with("TRANSPOSE")) transp = true, sem.resize(sem.size() - 9);
    if (sem.size() > 7 && sem.ends_with("INVERSE")) inv = true, sem.resize(sem.size() - 7);
    Matrix mat;
    if (sem == "WORLD") mat = world;
    else if (sem == "VIEW") mat = view;
    else if (sem == "PROJECTION") mat = proj;
    else if (sem == "WORLDVIEW") mat = world * view;
    else if (sem == "VIEWPROJECTION") mat = view * proj;
    else if (sem == "WORLDVIEWPROJECTION") mat = world * view * proj;
    else continue;
    if (d.cls != ParameterClass::MatrixRows && d.cls != ParameterClass::MatrixColumns) continue;
    if (inv) {
      Matrix i;
      if (inverse(mat, i)) mat = i;
    }
    if (transp) mat = transpose(mat);
    fx.setMatrix(p, mat);
  }
  device.setTransform(d3d::TS_WORLD, world);
  device.setTransform(d3d::TS_VIEW, view);
  device.setTransform(d3d::TS_PROJECTION, proj);
  device.setRenderState(d3d::RS_ZENABLE, d3d::ZB_TRUE);
  device.clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER, background, 1.0f, 0);

  scene::bindMesh(device, m);
  const int passes = fx.begin(device, 0);
  for (int i = 0; i < passes; ++i) {
    fx.beginPass(i);
    bindSamplerTextures(device);
    declareShaderInputs(device);
    for (const auto& [reg, v] : options_.vsConstants) device.setVertexShaderConstantF(uint32_t(reg), &v.x, 1);
    for (const auto& [reg, v] : options_.psConstants) device.setPixelShaderConstantF(uint32_t(reg), &v.x, 1);
    bindDeclarationStream(device);
    device.drawIndexedPrimitive(d3d::PT_TRIANGLELIST, 0, 0, m.vertexCount(), 0, m.faceCount());
    fx.endPass();
  }
  fx.end();
}

}  // namespace refx::cli
