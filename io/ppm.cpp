#include "io/ppm.h"

#include <cctype>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "io/file_write.h"

namespace aalab {
namespace {

// Next header token: skips whitespace and '#' comments.
std::string Token(std::istream& in) {
  std::string tok;
  int c = in.get();
  while (c != EOF) {
    if (c == '#') {
      while (c != EOF && c != '\n') c = in.get();
    } else if (!std::isspace(c)) {
      break;
    }
    c = in.get();
  }
  while (c != EOF && !std::isspace(c)) {
    tok.push_back(static_cast<char>(c));
    c = in.get();
  }
  return tok;  // the single whitespace after the last token is consumed
}

int Number(std::istream& in, const std::string& path, const char* what) {
  const std::string t = Token(in);
  if (t.empty() || t.size() > 6 || t.find_first_not_of("0123456789") != std::string::npos) {
    throw UserError("'" + path + "': bad PPM header (" + what + " '" + t + "'; expected a number)");
  }
  return std::stoi(t);
}

// The bit pattern of the centre of pixel k along one axis (k + 0.5, exact in float).
uint32_t CentreBits(int k) {
  const float c = static_cast<float>(k) + 0.5f;
  uint32_t b;
  std::memcpy(&b, &c, sizeof b);
  return b;
}

}  // namespace

Image8 ReadPpm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("'" + path + "' cannot be read");
  if (Token(in) != "P6") throw UserError("'" + path + "' is not a binary PPM (P6)");
  const int w = Number(in, path, "width");
  const int h = Number(in, path, "height");
  const int maxval = Number(in, path, "maxval");
  if (w < 1 || h < 1 || w > 65536 || h > 65536) {
    throw UserError("'" + path + "': size " + std::to_string(w) + "x" + std::to_string(h) +
                    " is out of range (1..65536 per side)");
  }
  if (maxval != 255) throw UserError("'" + path + "': maxval " + std::to_string(maxval) + " (only 255 is allowed)");
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * h * 3);
  in.read(reinterpret_cast<char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
  if (in.gcount() != static_cast<std::streamsize>(rgb.size())) {
    throw UserError("'" + path + "': pixel data is truncated");
  }
  Image8 img(w, h, 4, 255);
  for (size_t i = 0, n = static_cast<size_t>(w) * h; i < n; ++i) {
    uint8_t* p = img.Data().data() + 4 * i;
    p[0] = rgb[3 * i];
    p[1] = rgb[3 * i + 1];
    p[2] = rgb[3 * i + 2];
  }
  return img;
}

void WritePpm(const std::string& path, const Image8& img) {
  AALAB_CHECK(img.Channels() == 4, "WritePpm needs an RGBA8 frame");
  std::string bytes = "P6\n" + std::to_string(img.Width()) + " " + std::to_string(img.Height()) + "\n255\n";
  const size_t header = bytes.size();
  bytes.resize(header + static_cast<size_t>(img.Width()) * img.Height() * 3);
  for (size_t i = 0, n = static_cast<size_t>(img.Width()) * img.Height(); i < n; ++i) {
    const uint8_t* p = img.Data().data() + 4 * i;
    for (int c = 0; c < 3; ++c) bytes[header + 3 * i + c] = static_cast<char>(p[c]);
  }
  WriteTextFile(path, bytes);  // checked, atomic (io/image_io.h)
}

void WritePreviousPositions(const std::string& path, int width, int height, const std::vector<float>& previous) {
  AALAB_CHECK(width > 0 && height > 0 && previous.size() == 2 * static_cast<size_t>(width) * height,
              "WritePreviousPositions: size");
  std::vector<uint8_t> bytes(previous.size() * 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = 2 * (static_cast<size_t>(y) * width + x);
      for (int c = 0; c < 2; ++c) {
        uint32_t b;
        std::memcpy(&b, &previous[i + c], sizeof b);
        const uint32_t d = b - CentreBits(c == 0 ? x : y);
        for (int k = 0; k < 4; ++k) bytes[4 * (i + c) + k] = static_cast<uint8_t>(d >> (8 * k));
      }
    }
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw UserError("'" + path + "' cannot be written");
    out << "AALABPREV 1 " << width << " " << height << "\n";
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw UserError("'" + path + "': write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw UserError("'" + path + "' cannot be written: " + ec.message());
}

std::vector<float> ReadPreviousPositions(const std::string& path, int width, int height) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("'" + path + "' cannot be read");
  if (Token(in) != "AALABPREV" || Token(in) != "1") {
    throw UserError("'" + path + "' is not a previous-positions file (AALABPREV 1)");
  }
  const int w = Number(in, path, "width");
  const int h = Number(in, path, "height");
  if (w != width || h != height) {
    throw UserError("'" + path + "' is " + std::to_string(w) + "x" + std::to_string(h) + ", expected " +
                    std::to_string(width) + "x" + std::to_string(height));
  }
  std::vector<uint8_t> bytes(static_cast<size_t>(w) * h * 8);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (in.gcount() != static_cast<std::streamsize>(bytes.size())) throw UserError("'" + path + "': data is truncated");
  std::vector<float> out(static_cast<size_t>(w) * h * 2);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = 2 * (static_cast<size_t>(y) * w + x);
      for (int c = 0; c < 2; ++c) {
        uint32_t d = 0;
        for (int k = 0; k < 4; ++k) d |= static_cast<uint32_t>(bytes[4 * (i + c) + k]) << (8 * k);
        const uint32_t b = d + CentreBits(c == 0 ? x : y);
        std::memcpy(&out[i + c], &b, sizeof b);
      }
    }
  }
  return out;
}

}  // namespace aalab
