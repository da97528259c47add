// Pixels of the gallery images (`refx gallery --caps ref --size 64x64`), each expected
// value derived by hand in the probe file next to it. Every image the gallery wrote
// must have at least one probe, so a sample added later is not left unchecked.
// Probe lines: `IMAGE X Y R G B TOLERANCE`; `#` starts a comment (the derivation).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/scene/scene_script.h"
#include "refx/resource/image_io.h"

namespace fs = std::filesystem;

namespace {

struct Probe {
  int line = 0;
  std::string image;
  int x = 0, y = 0, rgb[3] = {0, 0, 0}, tolerance = 0;
};

std::vector<Probe> readProbes(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path << ": cannot open";
  std::vector<Probe> probes;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream s(text);
    Probe p;
    p.line = line;
    if (!(s >> p.image)) continue;  // blank or comment line
    std::string rest;
    if (!(s >> p.x >> p.y >> p.rgb[0] >> p.rgb[1] >> p.rgb[2] >> p.tolerance) || (s >> rest)) {
      ADD_FAILURE() << path << ":" << line << ": expected `IMAGE X Y R G B TOLERANCE`";
      continue;
    }
    probes.push_back(p);
  }
  return probes;
}

TEST(GalleryProbes, EveryImageMatchesItsHandDerivedPixels) {
  const std::vector<Probe> probes = readProbes(REFX_GALLERY_PROBES);
  std::set<std::string> probed;
  for (const Probe& p : probes) probed.insert(p.image);

  std::set<std::string> images;
  for (const auto& e : fs::directory_iterator(REFX_GALLERY_DIR))
    if (e.path().extension() == ".png") images.insert(e.path().filename().string());
  ASSERT_FALSE(images.empty()) << REFX_GALLERY_DIR << " holds no images: did `refx gallery` run?";
  for (const std::string& image : images) EXPECT_TRUE(probed.count(image)) << image << " has no probe";

  std::map<std::string, refx::TexturePtr> loaded;
  for (const Probe& p : probes) {
    SCOPED_TRACE(std::string(REFX_GALLERY_PROBES) + ":" + std::to_string(p.line) + ": " + p.image);
    if (!images.count(p.image)) {
      ADD_FAILURE() << "the gallery wrote no " << p.image;
      continue;
    }
    refx::TexturePtr& tex = loaded[p.image];
    if (!tex) tex = refx::loadTexture((fs::path(REFX_GALLERY_DIR) / p.image).string());
    ASSERT_TRUE(p.x >= 0 && p.y >= 0 && p.x < tex->width() && p.y < tex->height())
        << "pixel " << p.x << "," << p.y << " is outside the image";
    int got[4];
    refx::scene::readTargetPixel(*tex, p.x, p.y, got);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(got[c], p.rgb[c], p.tolerance)
          << "pixel " << p.x << "," << p.y << " channel " << "rgb"[c] << ": got " << got[0] << " " << got[1]
          << " " << got[2];
  }
}

}  // namespace
