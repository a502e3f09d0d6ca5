// `aalab metrics --reference REF IMG [--mask MASK] [--none NONE] [--json]`: every metric for
// any two images, the same code the runner uses.
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "harness/cli/commands.h"
#include "core/color.h"
#include "core/error.h"
#include "core/exit_code.h"
#include "io/image_io.h"
#include "metrics/metrics.h"
#include "metrics/viewing.h"

namespace aalab {

namespace {

/// An image as the metrics see it: sRGB-encoded RGB in [0, 1]. 8-bit files are already
/// display-encoded; float files (EXR, float TIFF) are taken as display-linear (what
/// `aalab run` writes as reference.exr) and sRGB-encoded.
ImageF LoadEncoded(const std::string& path, int* file_channels) {
  LoadedImage img = ReadImage(path);
  *file_channels = img.file_channels;
  ImageF out(img.pixels.Width(), img.pixels.Height(), 3);
  for (int y = 0; y < out.Height(); ++y) {
    for (int x = 0; x < out.Width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        const float v = img.pixels.At(x, y, c);
        out.At(x, y, c) = img.is_float ? SrgbEncode(v) : std::min(1.0f, std::max(0.0f, v));
      }
    }
  }
  return out;
}

std::string Size(const ImageF& i) { return std::to_string(i.Width()) + "x" + std::to_string(i.Height()); }

int RunMetrics(const std::string& ref_path, const std::string& img_path, const std::string& mask_path,
               const std::string& none_path, bool json, const std::string& viewing) {
  const ViewingCondition view = ResolveViewing(viewing);  // checked before any file is read
  int ref_nc = 0, img_nc = 0;
  const ImageF ref = LoadEncoded(ref_path, &ref_nc);
  const ImageF img = LoadEncoded(img_path, &img_nc);
  RequireSameShape(ref, img, "'" + ref_path + "' (" + Size(ref) + ") and '" + img_path + "' (" + Size(img) + ")");
  if ((ref_nc >= 3) != (img_nc >= 3)) {
    throw UserError("'" + ref_path + "' has " + std::to_string(ref_nc) + " channels and '" + img_path + "' has " +
                    std::to_string(img_nc) + ": compare grey with grey and colour with colour");
  }
  ImageF mask, none;
  MetricInput in;
  in.image = &img;
  in.reference = &ref;
  in.flip_ppd = view.ppd;
  if (!mask_path.empty()) {
    int nc = 0;
    const ImageF m = LoadEncoded(mask_path, &nc);
    RequireSameShape(ref, m, "mask '" + mask_path + "' (" + Size(m) + ") and reference (" + Size(ref) + ")");
    mask = ImageF(m.Width(), m.Height(), 1);
    for (int y = 0; y < m.Height(); ++y) {
      for (int x = 0; x < m.Width(); ++x) mask.At(x, y, 0) = m.At(x, y, 0) > 0.5f ? 1.0f : 0.0f;
    }
    in.edge_mask = &mask;
  }
  if (!none_path.empty()) {
    int nc = 0;
    none = LoadEncoded(none_path, &nc);
    RequireSameShape(ref, none, "no-AA image '" + none_path + "' and reference");
    in.none_image = &none;
  }
  const auto values = ComputeAllMetrics(in);
  if (json) {
    nlohmann::ordered_json j;
    j["reference"] = ref_path;
    j["image"] = img_path;
    j["mask"] = mask_path.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(mask_path);
    nlohmann::ordered_json m = nlohmann::ordered_json::object(), reasons = nlohmann::ordered_json::object();
    bool identical = false;
    for (const auto& v : values) {
      m[v.name] = v.value ? nlohmann::ordered_json(*v.value) : nlohmann::ordered_json(nullptr);
      if (!v.value) reasons[v.name] = v.null_reason;
      if (v.name == "psnr_db" && !v.value && v.null_reason == "identical") identical = true;
    }
    j["identical"] = identical;
    j["metrics"] = m;
    j["null_reasons"] = reasons;
    std::printf("%s\n", j.dump(2).c_str());
    return ToInt(ExitCode::kOk);
  }
  for (const auto& v : values) {
    if (v.value) {
      std::printf("%-22s %.9g\n", v.name.c_str(), *v.value);
    } else {
      std::printf("%-22s null (%s)\n", v.name.c_str(), v.null_reason.c_str());
    }
  }
  return ToInt(ExitCode::kOk);
}

}  // namespace

void RegisterMetricsCommand(CLI::App& app, Commands& commands) {
  auto* cmd =
      app.add_subcommand("metrics", "every metric for any two images (same size and channel count; never resampled)");
  struct Args {
    std::string reference, image, mask, none, viewing;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--reference", a->reference, "reference image (8-bit = sRGB-encoded; float/EXR = display-linear)")
      ->required();
  cmd->add_option("image", a->image, "image to score")->required();
  cmd->add_option("--mask", a->mask, "edge mask image (white = edge), e.g. images/<scene>/edge_mask.png");
  cmd->add_option("--none", a->none, "the no-AA image, for edge_error_removed");
  cmd->add_option(
      "--viewing", a->viewing,
      "viewing condition PRESET[:key=value,...] for FLIP's pixels per degree (default 67; aalab list viewing)");
  cmd->add_flag("--json", a->json, "print JSON instead of a table");
  cmd->callback([&commands, a] {
    commands.action = [a] { return RunMetrics(a->reference, a->image, a->mask, a->none, a->json, a->viewing); };
  });
}

}  // namespace aalab
