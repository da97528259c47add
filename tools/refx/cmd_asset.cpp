// `refx asset`: writes any built-in procedural texture or mesh to an image file.
// Cube maps become their six faces side by side (D3D face order +X -X +Y -Y +Z -Z),
// volume textures their slices in a row; .dds keeps the texture as it is. Meshes are
// previewed by a small flat-projection rasterizer of this file (front faces shaded
// from their vertex normals, back faces red), independent of the device.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "builtin_assets.h"
#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/d3dx/brdf.h"
#include "refx/d3dx/lighting_maps.h"
#include "refx/d3dx/mesh.h"
#include "refx/d3dx/sample_assets.h"
#include "refx/d3dx/teapot.h"
#include "refx/d3dx/texture_fill.h"
#include "refx/resource/image_io.h"

namespace refx::cli {

namespace {

struct Asset {
  std::string name, description;
  int defaultSize;  // texture size (see each maker) or preview image size for meshes
  std::function<TexturePtr(int size)> texture;
  std::function<d3dx::Mesh()> mesh;
};

// The BRDF factor maps share one fit per size.
const d3dx::BrdfFactorization& brdfFit(int size) {
  static std::optional<d3dx::BrdfFactorization> fit;
  if (!fit || fit->cubeSize != size) {
    d3dx::BrdfFactorizationOptions o;
    o.cubeSize = size;
    fit = d3dx::computeBrdfFactorization(d3dx::WardBrdf{}, o);
  }
  return *fit;
}

// RacorX10's illumination map (diffspec.dds), indexed by u = N.L and v = N.H: the
// diffuse value in RGB, the specular value v^16 in alpha.
TexturePtr illuminationMap(int size) {
  auto t = Texture::create2D(Format::A8R8G8B8, size, size, 1);
  d3dx::fillTexture(*t, [](Vec2 p, Vec2) { return Vec4(p.x, p.x, p.x, std::pow(p.y, 16.0f)); });
  return t;
}

// The earth normal map (as earthNormalMap makes it) with the height field's occlusion in
// alpha, with mip maps.
TexturePtr earthNormalOcclusionMap(int n) {
  const TexturePtr height = d3dx::earthHeightMap(2 * n, n, 1);
  const TexturePtr level0 = d3dx::computeNormalMap(*height, d3dx::CHANNEL_RED, 10.0f,
                                                   d3dx::NORMALMAP_MIRROR_V | d3dx::NORMALMAP_COMPUTE_OCCLUSION);
  TexturePtr out = Texture::create2D(Format::A8R8G8B8, 2 * n, n, 0);
  std::copy_n(level0->data(0, 0), level0->dataSize(0, 0), out->data(0, 0));
  out->generateMips();
  out->markDirty();
  return out;
}

// Sky and ground colors of the hemisphere samples (data/effects/hemisphere.fx).
const Vec4 kSkyColor{0.55f, 0.7f, 1.0f, 1.0f};
const Vec4 kGroundColor{0.35f, 0.25f, 0.15f, 1.0f};

// The 2-hemisphere model's exact integral (seeds/000, "The actual integral is:
// color = a*SkyColor + (1-a)*GroundColor, a = 1 - 0.5*sin(q) for q < 90, a = 0.5*sin(q)
// for q > 90"), q the angle between the direction and +y.
TexturePtr hemisphereIntegralCube(int size) {
  auto t = Texture::createCube(Format::A8R8G8B8, size, 1);
  d3dx::fillCubeTexture(*t, [](Vec3 d, Vec3) {
    const Vec3 n = normalize(d);
    const float sinQ = std::sqrt(std::max(0.0f, 1.0f - n.y * n.y));
    const float a = n.y >= 0 ? 1.0f - 0.5f * sinQ : 0.5f * sinQ;
    return Vec4(a * kSkyColor.x + (1 - a) * kGroundColor.x, a * kSkyColor.y + (1 - a) * kGroundColor.y,
                a * kSkyColor.z + (1 - a) * kGroundColor.z, 1.0f);
  });
  return t;
}

// The teapot with the occluded fraction of each vertex's hemisphere in texture
// coordinate z, where the seed's vertex hemisphere shader reads it (v7.z).
d3dx::Mesh teapotWithOcclusion() {
  const d3dx::Mesh t = d3dx::createTeapot(6);
  d3dx::Mesh m = d3dx::cloneMeshFVF(t, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1) |
                                           d3d::fvfTexCoordSize(3, 0));
  const std::vector<float> visible = d3dx::computeHemisphereVisibility(t);
  for (uint32_t i = 0; i < m.vertexCount(); ++i) m.setTexCoord(i, 0, Vec4(0, 0, 1.0f - visible[i], 0));
  return m;
}

Asset texture(std::string name, std::string description, int size, std::function<TexturePtr(int)> make) {
  return {std::move(name), std::move(description), size, std::move(make), nullptr};
}
Asset mesh(std::string name, std::string description, std::function<d3dx::Mesh()> make) {
  return {std::move(name), std::move(description), 256, nullptr, std::move(make)};
}

const std::vector<Asset>& assets() {
  using namespace d3dx;
  static const std::vector<Asset> list = {
      texture("earth-color", "earth colour map, alpha = gloss over water (A8R8G8B8, 2N x N)", 256,
              [](int n) { return earthColorMap(2 * n, n, 0); }),
      texture("earth-height", "earth height map (L8, 2N x N)", 256, [](int n) { return earthHeightMap(2 * n, n, 0); }),
      texture("earth-bump", "earth du/dv bump map for BUMPENVMAP (V8U8, 2N x N)", 256,
              [](int n) { return earthBumpMap(2 * n, n); }),
      texture("earth-bump-luminance", "earth du/dv/luminance map for BUMPENVMAPLUMINANCE (X8L8V8U8)", 256,
              [](int n) { return earthBumpMapLuminance(2 * n, n); }),
      texture("earth-normal", "earth normal map from the height map (A8R8G8B8, 2N x N)", 256,
              [](int n) { return earthNormalMap(2 * n, n, 0); }),
      texture("earth-normal-specular", "earth normal map, alpha = v^16 (RacorX9 ps.1.4's power table; A8R8G8B8, 2N x N)",
              256, [](int n) { return earthNormalMapSpecularAlpha(2 * n, n, 16.0f, 0); }),
      texture("clouds", "cloud layer, white with alpha = cover (A8R8G8B8, 2N x N; --alpha-grey)", 256, [](int n) { return cloudMap(2 * n, n, 0); }),
      texture("environment", "sky for bump environment mapping (A8R8G8B8)", 256,
              [](int n) { return environmentMap(n, 0); }),
      texture("earth-normal-occlusion",
              "earth normal map, alpha = open fraction of the sky over each texel (ComputeNormalMap with "
              "COMPUTE_OCCLUSION; A8R8G8B8, 2N x N)",
              256, [](int n) { return earthNormalOcclusionMap(n); }),
      texture("hemisphere-integral",
              "hemisphere lighting's integral: a sky + (1 - a) ground, a = 1 - sin(q)/2 (q < 90) or sin(q)/2, "
              "q from +y (cube, A8R8G8B8)",
              32, [](int n) { return hemisphereIntegralCube(n); }),
      texture("normalization-cube", "normalization cube map, 0.5 + 0.5 n (cube, A8R8G8B8)", 64,
              [](int n) { return createNormalizationCubeMap(n); }),
      texture("checker", "8 x 8 checkerboard (A8R8G8B8)", 256, [](int n) { return checker(n, 8, 0); }),
      texture("brick", "brick wall (A8R8G8B8)", 256, [](int n) { return brick(n, 0); }),
      texture("specular-pow16", "RacorX8 LightEval: RGB = pow(v, 16), A = 1 (256 x 256)", 256,
              [](int n) { return specularPowerMap(n, n, 16, SpecularAlpha::One, 1); }),
      texture("specular-table-2048", "RacorX12 LightEval: RGB = 0, A = pow(u, 16) (2048 x 1; --alpha-grey)",
              2048, [](int n) { return specularPowerTable(n, 16, 1); }),
      texture("specular-pow100", "effect paper LightEval: RGB = pow(v, 100), A = u (256 x 256)", 256,
              [](int n) { return specularPowerMap(n, n, 100, SpecularAlpha::U, 1); }),
      texture("specular-table-2048-pow100",
              "texdp3tex table of the effect paper's power: RGB = 0, A = pow(u, 100) (2048 x 1; --alpha-grey)", 2048,
              [](int n) { return specularPowerTable(n, 100, 1); }),
      texture("illumination-map",
              "RacorX10 illumination map (diffspec.dds): RGB = u (N.L), A = pow(v, 16) (N.H^16) (256 x 256)", 256,
              [](int n) { return illuminationMap(n); }),
      texture("attenuation-2d", "RacorX10 point light: RGB = x^2 + y^2, A = x^2 (256 x 256)", 256,
              [](int n) { return attenuationMap2D(n); }),
      texture("attenuation-1d", "point light z^2 alone: RGB = A = z^2 (256 x 1)", 256,
              [](int n) { return attenuationMap1D(n); }),
      texture("wood-volume", "noise volume of the wood shader (64^3, slices in a row)", 64,
              [](int n) { return woodNoiseVolume(n); }),
      texture("brdf-p", "BRDF factor p(w) of a Ward BRDF, looked up with the view vector (cube)", 32,
              [](int n) { return brdfFit(n).p; }),
      texture("brdf-p-cos", "BRDF factor p(w) cos(theta), looked up with the light vector (cube)", 32,
              [](int n) { return brdfFit(n).pCos; }),
      texture("brdf-q", "BRDF factor q(h) of a Ward BRDF, looked up with the half vector (cube)", 32,
              [](int n) { return brdfFit(n).q; }),
      mesh("sphere", "D3DXCreateSphere(1, 32, 16), axis z", [] { return createSphere(1, 32, 16); }),
      mesh("textured-sphere", "earth sphere with (u, v) and tangents, axis y",
           [] { return createTexturedSphere(1, 32, 16); }),
      mesh("box", "D3DXCreateBox(1, 1, 1)", [] { return createBox(1, 1, 1); }),
      mesh("cylinder", "D3DXCreateCylinder(0.5, 0.5, 1.5, 24, 4), axis z",
           [] { return createCylinder(0.5f, 0.5f, 1.5f, 24, 4); }),
      mesh("torus", "D3DXCreateTorus(0.25, 0.75, 16, 32), axis z", [] { return createTorus(0.25f, 0.75f, 16, 32); }),
      mesh("teapot", "the Utah teapot, 32 Bezier patches at 8 x 8 quads, y up", [] { return createTeapot(8); }),
      mesh("teapot-occlusion",
           "the teapot at 6 x 6 quads with its occluded hemisphere fraction in texture z (u, v = 0)",
           [] { return teapotWithOcclusion(); }),
  };
  return list;
}

// ---------------------------------------------------------------- textures to images

// Signed channels (du, dv, ...) show as 0.5 + 0.5 x; V8U8 and the bump-luminance
// formats sign R and G only, Q8W8V8U8 all four.
bool signedChannel(Format f, int channel) {
  const FormatInfo* info = formatInfo(f);
  if (!info || !info->isSigned) return false;
  return channel < 2 || f == Format::Q8W8V8U8;
}

enum class AlphaMode { Drop, Keep, AsGrey };

// Level 0 laid out as one 2D A8R8G8B8 image: faces or slices side by side.
TexturePtr layOut(const Texture& tex, AlphaMode alpha) {
  const int w = tex.width(), h = tex.height(), d = tex.depth(), faces = tex.faceCount();
  const int tiles = tex.type() == TextureType::Cube ? faces : d;
  TexturePtr out = Texture::create2D(Format::A8R8G8B8, w * tiles, h);
  std::vector<Color4> row(static_cast<size_t>(w * tiles));
  for (int y = 0; y < h; ++y) {
    for (int tile = 0; tile < tiles; ++tile)
      for (int x = 0; x < w; ++x) {
        bool cube = tex.type() == TextureType::Cube;
        Color4 c = tex.texel(cube ? tile : 0, 0, x, y, cube ? 0 : tile);
        float v[4] = {c.r, c.g, c.b, c.a};
        for (int k = 0; k < 4; ++k)
          if (signedChannel(tex.format(), k)) v[k] = 0.5f + 0.5f * v[k];
        if (alpha == AlphaMode::AsGrey) v[0] = v[1] = v[2] = v[3];
        if (alpha != AlphaMode::Keep) v[3] = 1;
        row[size_t(tile * w + x)] = {v[0], v[1], v[2], v[3]};
      }
    encodeRow(Format::A8R8G8B8, row.data(), w * tiles, out->data(0, 0) + size_t(y) * out->rowPitch(0));
  }
  out->markDirty();
  return out;
}

// ---------------------------------------------------------------- mesh preview

// Orthographic view of the mesh turned 35° about y and -25° about x (seen from a
// little above), fitted into size x size. Front faces (clockwise on screen, as D3D's
// default culling keeps) are lit from the upper left by their interpolated vertex
// normals (face normals when the mesh has none); back faces seen through holes or
// wrong windings are red.
TexturePtr preview(const d3dx::Mesh& mesh, int size) {
  const uint32_t nv = mesh.vertexCount();
  const bool hasNormals = mesh.layout().normal >= 0;
  const Matrix turn = matrixRotationY(0.6f) * matrixRotationX(-0.45f);
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  std::vector<Vec3> pos(nv), nrm(nv);
  for (uint32_t v = 0; v < nv; ++v) {
    pos[v] = transformCoord(mesh.position(v), turn);
    nrm[v] = hasNormals ? normalize(transformNormal(mesh.normal(v), turn)) : Vec3{};
    lo = {std::min(lo.x, pos[v].x), std::min(lo.y, pos[v].y), std::min(lo.z, pos[v].z)};
    hi = {std::max(hi.x, pos[v].x), std::max(hi.y, pos[v].y), std::max(hi.z, pos[v].z)};
  }
  const Vec3 centre = (lo + hi) * 0.5f;
  const float extent = std::max({hi.x - lo.x, hi.y - lo.y, 1e-6f});
  const float scale = 0.9f * float(size) / extent;
  // Screen: x right, y down; depth = view z (the camera looks along +z).
  std::vector<Vec3> scr(nv);
  for (uint32_t v = 0; v < nv; ++v) {
    Vec3 p = pos[v] - centre;
    scr[v] = {float(size) / 2 + p.x * scale, float(size) / 2 - p.y * scale, p.z};
  }
  std::vector<float> depth(size_t(size) * size, 1e30f);
  std::vector<Color4> color(size_t(size) * size, Color4{0.12f, 0.12f, 0.15f, 1});
  const Vec3 light = normalize({-0.5f, 0.6f, -0.8f});  // toward the light, viewer side
  for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
    const uint32_t i[3] = {mesh.indices[3 * f], mesh.indices[3 * f + 1], mesh.indices[3 * f + 2]};
    if (i[0] >= nv || i[1] >= nv || i[2] >= nv) continue;
    const Vec3 a = scr[i[0]], b = scr[i[1]], c = scr[i[2]];
    const float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (area == 0) continue;
    const bool front = area > 0;  // clockwise with y down
    const Vec3 faceN = normalize(cross(pos[i[1]] - pos[i[0]], pos[i[2]] - pos[i[0]]));
    int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
    int x1 = std::min(size - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
    int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
    int y1 = std::min(size - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        float px = float(x) + 0.5f, py = float(y) + 0.5f;
        // Barycentric weights from the edge functions, normalised by the area.
        float w0 = ((b.x - px) * (c.y - py) - (c.x - px) * (b.y - py)) / area;
        float w1 = ((c.x - px) * (a.y - py) - (a.x - px) * (c.y - py)) / area;
        float w2 = 1 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        float z = w0 * a.z + w1 * b.z + w2 * c.z;
        size_t k = size_t(y) * size + x;
        if (z >= depth[k]) continue;
        depth[k] = z;
        Vec3 n = hasNormals ? normalize(nrm[i[0]] * w0 + nrm[i[1]] * w1 + nrm[i[2]] * w2) : faceN;
        if (!front) n = -faceN;
        float lit = 0.2f + 0.8f * std::max(0.0f, dot(n, light));
        color[k] = front ? Color4{0.85f * lit, 0.88f * lit, 0.95f * lit, 1} : Color4{0.8f * lit, 0.1f, 0.1f, 1};
      }
  }
  TexturePtr out = Texture::create2D(Format::A8R8G8B8, size, size);
  for (int y = 0; y < size; ++y)
    encodeRow(Format::A8R8G8B8, color.data() + size_t(y) * size, size, out->data(0, 0) + size_t(y) * out->rowPitch(0));
  out->markDirty();
  return out;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                    [](char a, char b) { return std::tolower((unsigned char)a) == std::tolower((unsigned char)b); });
}

struct AssetOptions {
  bool list = false;
  std::string name, output;
  int size = 0;
  bool alpha = false, alphaGrey = false;
};

int runAsset(const AssetOptions& o) {
  if (o.list) {
    size_t width = 0;
    for (const Asset& a : assets()) width = std::max(width, a.name.size());
    for (const Asset& a : assets()) std::printf("%-*s  %s\n", int(width), a.name.c_str(), a.description.c_str());
    return 0;
  }
  if (o.name.empty()) fail("asset: give an asset name (see refx asset --list)");
  auto it = std::find_if(assets().begin(), assets().end(), [&](const Asset& a) { return a.name == o.name; });
  if (it == assets().end()) fail("unknown asset '{}' (see refx asset --list)", o.name);
  if (o.size < 0 || o.size > 4096) fail("asset: --size must be between 1 and 4096, not {}", o.size);
  const int size = o.size > 0 ? o.size : it->defaultSize;
  const std::string out = o.output.empty() ? it->name + ".png" : o.output;
  if (it->mesh) {
    d3dx::Mesh m = it->mesh();
    saveImage(*preview(m, size), out, false);
    std::printf("%s: %u vertices, %u triangles -> %s\n", it->name.c_str(), m.vertexCount(), m.faceCount(),
                out.c_str());
    return 0;
  }
  TexturePtr tex = it->texture(size);
  if (endsWith(out, ".dds")) {
    saveDDS(*tex, out);
  } else {
    AlphaMode mode = o.alphaGrey ? AlphaMode::AsGrey : o.alpha ? AlphaMode::Keep : AlphaMode::Drop;
    saveImage(*layOut(*tex, mode), out, mode == AlphaMode::Keep);
  }
  const char* kind = tex->type() == TextureType::Cube ? "cube " : tex->type() == TextureType::Volume ? "volume " : "";
  if (tex->type() == TextureType::Volume)
    std::printf("%s: %s%s %dx%dx%d -> %s\n", it->name.c_str(), kind, std::string(formatName(tex->format())).c_str(),
                tex->width(), tex->height(), tex->depth(), out.c_str());
  else
    std::printf("%s: %s%s %dx%d -> %s\n", it->name.c_str(), kind, std::string(formatName(tex->format())).c_str(),
                tex->width(), tex->height(), out.c_str());
  return 0;
}

}  // namespace

TexturePtr builtinTexture(const std::string& name) {
  // Each built-in texture is made once per process at its default size.
  static std::vector<std::pair<std::string, TexturePtr>> made;
  for (const auto& [n, t] : made)
    if (n == name) return t;
  for (const Asset& a : assets())
    if (a.name == name && a.texture) return made.emplace_back(name, a.texture(a.defaultSize)).second;
  return nullptr;
}

std::optional<d3dx::Mesh> builtinMesh(const std::string& name) {
  for (const Asset& a : assets())
    if (a.name == name && a.mesh) return a.mesh();
  return std::nullopt;
}

Action addAssetCommand(CLI::App& app) {
  auto o = std::make_shared<AssetOptions>();
  CLI::App* cmd = app.add_subcommand("asset", "Write a built-in procedural texture or mesh preview to an image");
  cmd->add_flag("--list", o->list, "List the assets, one per line: name, then what it is");
  cmd->add_option("name", o->name, "Asset name (see --list)");
  cmd->add_option("-o,--output", o->output,
                  "Output file: .png, .ppm, .pam (cube faces / volume slices side by side) or .dds "
                  "(the texture as it is); default NAME.png");
  cmd->add_option("--size", o->size, "Texture size (the asset's N) or mesh preview size; default per asset");
  cmd->add_flag("--alpha", o->alpha, "Keep the alpha channel (RGBA PNG)");
  cmd->add_flag("--alpha-grey", o->alphaGrey, "Write the alpha channel as a grey image");
  return [o] { return runAsset(*o); };
}

}  // namespace refx::cli
