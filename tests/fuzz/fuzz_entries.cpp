// Fuzz entry points: see fuzz_entries.h for the contract.
#include "fuzz_entries.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "io/image_io.h"
#include "scenes/scene.h"

namespace aalab::fuzz {
namespace fs = std::filesystem;

void FuzzFail(const std::string& what) {
  std::fprintf(stderr, "fuzz post-condition violated: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

namespace {

void Finite(float v, const char* what) {
  if (!std::isfinite(v)) FuzzFail(std::string("scene parsed with a non-finite ") + what);
}

void Finite(glm::vec3 v, const char* what) {
  for (int i = 0; i < 3; ++i) Finite(v[i], what);
}

void NonNegative(glm::vec3 v, const char* what) {
  Finite(v, what);
  for (int i = 0; i < 3; ++i) {
    if (v[i] < 0.0f) FuzzFail(std::string("scene parsed with a negative ") + what);
  }
}

void Positive(float v, const char* what) {
  Finite(v, what);
  if (!(v > 0.0f)) FuzzFail(std::string("scene parsed with a non-positive ") + what);
}

void CheckTexture(const Texture& t) {
  Positive(t.scale, "texture scale");
  Finite(t.angle_deg, "texture angle");
  if (!(t.duty >= 0.0f && t.duty <= 1.0f)) FuzzFail("texture duty outside [0, 1]");
  NonNegative(t.color_a, "texture colour");
  NonNegative(t.color_b, "texture colour");
}

// What a scene that ParseScene accepted must satisfy (scenes/README.md): the tracer relies on
// every number being finite, every size positive and every index in range.
void CheckScene(const Scene& s) {
  if (s.name.empty()) FuzzFail("scene parsed with an empty name");
  const Camera& c = s.camera;
  Finite(c.position, "camera position");
  Finite(c.look_at, "camera look_at");
  Finite(c.up, "camera up");
  if (c.type == CameraType::kPerspective) {
    Positive(c.fov_y_deg, "fov_y");
    if (c.fov_y_deg > 179.0f) FuzzFail("fov_y above 179");
  } else {
    Positive(c.height, "orthographic height");
  }
  Positive(s.display.exposure, "exposure");
  NonNegative(s.background, "background");
  NonNegative(s.ambient, "ambient");
  if (s.materials.empty()) FuzzFail("scene parsed without materials");
  for (const Material& m : s.materials) {
    NonNegative(m.color, "material colour");
    NonNegative(m.specular, "specular colour");
    Finite(m.shininess, "shininess");
    if (m.texture) CheckTexture(*m.texture);
    if (m.alpha) CheckTexture(*m.alpha);
    if (!(m.alpha_cutoff >= 0.0f && m.alpha_cutoff <= 1.0f)) FuzzFail("alpha_cutoff outside [0, 1]");
  }
  for (const Light& l : s.lights) {
    NonNegative(l.color, "light colour");
    Finite(l.intensity, "light intensity");
    if (l.intensity < 0.0f) FuzzFail("negative light intensity");
    if (l.type == LightType::kDirectional) {
      Finite(l.direction, "light direction");
      const float len = glm::length(l.direction);
      if (!(std::fabs(len - 1.0f) < 1e-3f)) FuzzFail("directional light direction is not unit length");
    } else {
      Finite(l.position, "light position");
    }
  }
  if (s.shapes.empty()) FuzzFail("scene parsed without objects");
  for (const Shape& sh : s.shapes) {
    if (sh.material < 0 || static_cast<size_t>(sh.material) >= s.materials.size()) {
      FuzzFail("shape material index out of range");
    }
    if (sh.kind == ShapeKind::kTriangles) {
      if (sh.positions.empty() || sh.triangles.empty()) FuzzFail("triangle shape without vertices or triangles");
      if (sh.uvs.size() != sh.positions.size()) FuzzFail("uv count differs from vertex count");
      if (!sh.normals.empty() && sh.normals.size() != sh.positions.size()) FuzzFail("normal count differs");
      for (const auto& p : sh.positions) Finite(p, "vertex position");
      for (const auto& n : sh.normals) Finite(n, "vertex normal");
      for (const auto& uv : sh.uvs) {
        Finite(uv.x, "uv");
        Finite(uv.y, "uv");
      }
      for (const auto& t : sh.triangles) {
        for (int k = 0; k < 3; ++k) {
          if (t[k] >= sh.positions.size()) FuzzFail("triangle index out of range");
        }
      }
    } else {
      Positive(sh.radius, "radius");
      Finite(sh.center, "centre");
      Finite(sh.normal, "disk normal");
      Finite(sh.tangent, "disk tangent");
      Finite(sh.p0, "segment end");
      Finite(sh.p1, "segment end");
    }
  }
}

/// A private temporary folder, removed when the process exits.
struct TempFolder {
  fs::path dir = fs::temp_directory_path() / ("aalab-fuzz-" + std::to_string(::getpid()));
  TempFolder() { fs::create_directories(dir); }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

std::string TempBase() {
  static const TempFolder folder;
  return (folder.dir / "input").string();
}

}  // namespace

Outcome CheckSceneBytes(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const Scene s = ParseScene(text, "fuzz.json", AALAB_SOURCE_DIR "/scenes/library");
    CheckScene(s);
  } catch (const UserError&) {
    return Outcome::kRefused;  // expected for bad input
  }
  return Outcome::kAccepted;
}

Outcome CheckImageBytes(const uint8_t* data, size_t size) {
  if (size == 0) return Outcome::kRefused;
  static const char* const kExt[] = {".png", ".exr", ".tif"};
  const std::string path = TempBase() + kExt[data[0] % 3];
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    if (!f) FuzzFail("cannot write the temporary file " + path);
  }
  Outcome outcome = Outcome::kAccepted;
  try {
    const LoadedImage img = ReadImage(path, kFuzzMaxPixels);
    const ImageF& p = img.pixels;
    if (p.Width() <= 0 || p.Height() <= 0) FuzzFail("image read with zero size");
    if (p.PixelCount() > kFuzzMaxPixels) FuzzFail("image read above the pixel limit");
    if (p.Channels() != 3 && p.Channels() != 4) FuzzFail("image read with a channel count other than 3 or 4");
    if (img.file_channels < 1 || img.file_channels > 4) FuzzFail("image read with a bad file channel count");
    for (float v : p.Data()) {
      if (!std::isfinite(v)) FuzzFail("image read with a non-finite pixel");
    }
  } catch (const UserError&) {
    outcome = Outcome::kRefused;  // expected for bad input
  }
  std::error_code ec;
  fs::remove(path, ec);
  return outcome;
}

int FuzzScene(const uint8_t* data, size_t size) {
  CheckSceneBytes(data, size);
  return 0;
}

int FuzzImage(const uint8_t* data, size_t size) {
  CheckImageBytes(data, size);
  return 0;
}

}  // namespace aalab::fuzz
