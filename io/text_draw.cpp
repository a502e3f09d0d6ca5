// Text labels on 8-bit images (io/text_draw.h).
#include "io/text_draw.h"

#include <filesystem>

#include "core/error.h"
#include "io/oiio_loader.h"

namespace aalab {

namespace {

/// The font file: fonts-dejavu-core's DejaVuSans.ttf (Debian path first).
std::string FontPath() {
  for (const char* p : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf",
                        "/usr/local/share/fonts/DejaVuSans.ttf"}) {
    if (std::filesystem::is_regular_file(p)) return p;
  }
  throw UserError(
      "no DejaVu Sans font for the figure labels (looked for /usr/share/fonts/truetype/dejavu/"
      "DejaVuSans.ttf); install the Debian package fonts-dejavu-core");
}

}  // namespace

void DrawText(Image8& img, int x, int y, const std::string& text, int size_px) {
  AALAB_CHECK(img.Channels() == 4, "DrawText needs an RGBA8 image");
  const std::string font = FontPath();
  std::string why;
  const auto& oiio = io_detail::OiioModule("drawing the label '" + text + "'");
  if (!oiio.draw_text(img.Data().data(), img.Width(), img.Height(), x, y, text, size_px, font, &why)) {
    throw UserError("cannot draw the label '" + text + "': " + why);
  }
}

}  // namespace aalab
