// Text labels on 8-bit images (io/text_draw.h).
#include "io/text_draw.h"

#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "core/error.h"

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
  OIIO::ImageSpec spec(img.Width(), img.Height(), 4, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf buf(spec, img.Data().data());
  const float black[] = {0, 0, 0, 1};
  if (!OIIO::ImageBufAlgo::render_text(buf, x, y, text, size_px, FontPath(), black)) {
    throw UserError("cannot draw the label '" + text + "': " + buf.geterror());
  }
}

}  // namespace aalab
