#include "gpu/main_json.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace aalab {
namespace {

std::string NowUtc() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string Q(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\')
      o += '\\', o += c;
    else if (static_cast<unsigned char>(c) < 0x20) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", c);
      o += b;
    } else
      o += c;
  }
  return o + "\"";
}

std::string StatsJson(const Stats& s) {
  return "{\"median_ms\": " + JsonNumber(s.median) + ", \"min_ms\": " + JsonNumber(s.min) +
         ", \"max_ms\": " + JsonNumber(s.max) + "}";
}

}  // namespace

std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

void WriteGpuTimingsJson(const std::string& path, const GpuDeviceFacts& device, const TextureProbe& probe,
                         const TextureRuleCheck& rule, int warmup, int repeat, const std::vector<Entry>& entries) {
  const std::string& json_path = path;
  std::ostringstream j;
  j << "{\n  \"schema\": \"aalab-gpu-timings\",\n  \"schema_version\": 1,\n";
  j << "  \"generated_utc\": " << Q(NowUtc()) << ",\n";
  j << "  \"device\": {\"name\": " << Q(device.name)
    << ", \"compute_capability\": " << Q(std::to_string(device.major) + "." + std::to_string(device.minor))
    << ", \"multiprocessors\": " << device.multiprocessors << ", \"l2_bytes\": " << device.l2_bytes
    << ", \"memory_bytes\": " << device.memory_bytes << "},\n";
  j << "  \"driver\": " << Q(device.nvidia_driver) << ",\n";
  j << "  \"cuda_driver_api\": "
    << Q(std::to_string(device.driver / 1000) + "." + std::to_string(device.driver % 1000 / 10))
    << ",\n  \"cuda_runtime\": "
    << Q(std::to_string(device.runtime / 1000) + "." + std::to_string(device.runtime % 1000 / 10)) << ",\n";
  j << "  \"nvidia_smi_before\": " << Q(device.smi_before) << ",\n  \"nvidia_smi_after\": " << Q(device.smi_after)
    << ",\n";
  j << "  \"nvidia_smi_fields\": \"driver_version, clocks.sm, clocks.max.sm, clocks.mem, temperature.gpu, "
       "power.draw\",\n";
  j << "  \"timing\": {\"method\": \"CUDA events recorded around each launch (all kernels of the method), on one "
       "stream, after untimed warm-up launches; median/min/max over the timed launches\", \"warmup\": "
    << warmup << ", \"repeat\": " << repeat
    << ", \"clocks\": \"not locked: the GPU boosts as it likes; nvidia_smi_before/after record the clocks\", "
       "\"floor\": \"copy\"},\n";
  j << "  \"texture_probe\": {\"samples\": " << probe.samples << ", \"distinct_values\": " << probe.distinct_values
    << ", \"max_err_float_fraction\": " << JsonNumber(probe.err_float)
    << ", \"max_err_fraction_rounded_1_256\": " << JsonNumber(probe.err_round256)
    << ", \"max_err_fraction_truncated_1_256\": " << JsonNumber(probe.err_trunc256)
    << ", \"unorm8_point_fetch_mismatches\": " << probe.unorm_mismatches
    << ", \"unorm8_point_fetch_mismatches_vs_cpu\": " << probe.unorm_mismatches_cpu
    << ", \"half_texel_pairs\": " << probe.half_pairs << ", \"half_texel_mismatches\": " << probe.half_mismatches
    << ", \"half_texel_max_err\": " << JsonNumber(probe.half_max_err) << "},\n";
  j << "  \"texture_rule\": {\"pairs\": " << rule.pairs << ", \"pair_mismatches\": " << rule.pair_mismatches
    << ", \"rgba8_quads\": " << rule.quad8 << ", \"rgba8_quad_mismatches\": " << rule.quad8_mismatches
    << ", \"coordinates\": " << rule.coords << ", \"coordinate_mismatches\": " << rule.coord_mismatches
    << ", \"rgba32f_quads\": " << rule.quadf << ", \"rgba32f_quad_mismatches\": " << rule.quadf_mismatches << "},\n";
  j << "  \"results\": [\n";
  for (size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    j << "    {\"scene\": " << Q(e.scene) << ", \"size\": " << Q(e.size) << ", \"method\": " << Q(e.spec)
      << ", \"kernels\": " << Q(e.kernels);
    if (e.timed) {
      j << ", \"median_ms\": " << JsonNumber(e.t.median) << ", \"min_ms\": " << JsonNumber(e.t.min)
        << ", \"max_ms\": " << JsonNumber(e.t.max) << ", \"ratio_to_copy\": " << JsonNumber(e.ratio)
        << ", \"ratio_to_copy_linear\": " << JsonNumber(e.ratio_linear);
      if (e.pass.median > 0) j << ", \"pass_only\": " << StatsJson(e.pass);
      if (!e.passes.empty()) {
        j << ", \"passes\": {";
        for (size_t k = 0; k < e.passes.size(); ++k) {
          j << (k ? ", " : "") << Q(e.passes[k].first) << ": " << StatsJson(e.passes[k].second);
        }
        j << "}";
      }
      if (e.frames > 0) {
        j << ", \"frames\": " << e.frames << ", \"frame_median_ms\": [";
        for (size_t k = 0; k < e.frame_ms.size(); ++k) j << (k ? ", " : "") << JsonNumber(e.frame_ms[k]);
        j << "]";
      }
    }
    if (e.has_fidelity) {
      j << ", \"fidelity\": {\"identical_share\": " << JsonNumber(e.fid.identical_share)
        << ", \"max_diff\": " << e.fid.max_diff << ", \"within_1_share\": " << JsonNumber(e.fid.within1_share)
        << ", \"differing_pixels\": " << e.fid.differing << ", \"mean_abs_diff\": " << JsonNumber(e.fid.mean_abs_diff)
        << ", \"deterministic\": " << (e.deterministic ? "true" : "false") << "}";
    }
    if (e.has_soft) {
      j << ", \"fidelity_software_filter\": {\"identical_share\": " << JsonNumber(e.soft.identical_share)
        << ", \"max_diff\": " << e.soft.max_diff << ", \"differing_pixels\": " << e.soft.differing << "}";
    }
    if (e.has_hw_mode) {
      j << ", \"fidelity_cpu_gpu_texture\": {\"identical_share\": " << JsonNumber(e.hw_mode.identical_share)
        << ", \"max_diff\": " << e.hw_mode.max_diff << ", \"differing_pixels\": " << e.hw_mode.differing << "}";
    }
    j << "}" << (i + 1 < entries.size() ? "," : "") << "\n";
  }
  j << "  ]\n}\n";
  const std::string tmp = json_path + ".tmp";
  {
    std::ofstream f(tmp);
    f << j.str();
    if (!f) throw UserError("'" + json_path + "' cannot be written");
  }
  std::filesystem::rename(tmp, json_path);
}

}  // namespace aalab
