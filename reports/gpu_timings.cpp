#include "reports/gpu_timings.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"

namespace aalab {

std::vector<std::string> GpuTimingsFile::Scenes() const {
  std::vector<std::string> out;
  for (const auto& r : results) {
    bool seen = false;
    for (const auto& s : out) seen = seen || s == r.scene;
    if (!seen) out.push_back(r.scene);
  }
  return out;
}

GpuTimingsFile ReadGpuTimingsFile(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw UserError("GPU timings '" + path + "' cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError("GPU timings '" + path + "' is not valid JSON: " + e.what());
  }
  GpuTimingsFile g;
  try {
    if (doc.at("schema").get<std::string>() != "aalab-gpu-timings") {
      throw UserError("'" + path + "' is not an aalab_gpu file (schema '" + doc.at("schema").get<std::string>() +
                      "', expected 'aalab-gpu-timings')");
    }
    const int version = doc.at("schema_version").get<int>();
    if (version != 1) {
      throw UserError("'" + path + "': schema_version " + std::to_string(version) +
                      " is not supported (this aalab reads 1)");
    }
    g.device = doc.at("device").at("name").get<std::string>();
    g.driver = doc.at("driver").get<std::string>();
    g.cuda_runtime = doc.at("cuda_runtime").get<std::string>();
    g.generated_utc = doc.at("generated_utc").get<std::string>();
    for (const auto& j : doc.at("results")) {
      GpuResult r;
      r.scene = j.at("scene").get<std::string>();
      r.size = j.at("size").get<std::string>();
      r.method = j.at("method").get<std::string>();
      r.kernels = j.at("kernels").get<std::string>();
      r.timed = j.contains("median_ms");
      if (r.timed) {
        r.median_ms = j.at("median_ms").get<double>();
        r.min_ms = j.at("min_ms").get<double>();
        r.max_ms = j.at("max_ms").get<double>();
        r.ratio_to_copy = j.at("ratio_to_copy").get<double>();
        if (!(r.median_ms > 0) || !(r.min_ms > 0) || r.min_ms > r.median_ms || r.median_ms > r.max_ms) {
          throw UserError("'" + path + "': " + r.scene + " " + r.size + " " + r.method +
                          " has timings that are not 0 < min <= median <= max");
        }
      }
      r.has_fidelity = j.contains("fidelity");
      if (r.has_fidelity) {
        r.identical_share = j.at("fidelity").at("identical_share").get<double>();
        r.max_diff = j.at("fidelity").at("max_diff").get<int>();
      }
      g.results.push_back(r);
    }
  } catch (const nlohmann::json::exception& e) {
    throw UserError("'" + path + "' is not an aalab_gpu file (" + std::string(e.what()) + ")");
  }
  return g;
}

namespace {

/// True when two blocks were measured on the same setup: the same device, driver, CUDA runtime
/// and kernels, so their sizes can stand side by side in one block.
bool SameSetup(const GpuTiming& a, const GpuTiming& b) {
  return a.device == b.device && a.driver == b.driver && a.cuda_runtime == b.cuda_runtime && a.kernels == b.kernels;
}

/// `list` with `item` appended after "; " unless it is already one of its entries.
std::string AppendOnce(const std::string& list, const std::string& item) {
  if (list.empty()) return item;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find("; ", start), list.size());
    if (list.compare(start, end - start, item) == 0) return list;
    start = end + 2;
  }
  return list + "; " + item;
}

/// Folds `add` into `into` (same setup): a size both have takes `add`'s timing, a new size is
/// appended; the block's `measured_utc` lists the times of the files its sizes now come from.
void FoldSizes(GpuTiming& into, const GpuTiming& add) {
  for (const GpuTimingAt& at : add.sizes) {
    auto same =
        std::find_if(into.sizes.begin(), into.sizes.end(), [&at](const GpuTimingAt& x) { return x.size == at.size; });
    if (same != into.sizes.end()) {
      *same = at;
    } else {
      into.sizes.push_back(at);
    }
  }
  into.measured_utc.clear();
  for (const GpuTimingAt& at : into.sizes) into.measured_utc = AppendOnce(into.measured_utc, at.measured_utc);
}

}  // namespace

int MergeGpuTimings(Report& report, const GpuTimingsFile& gpu) {
  auto copy_ms = [&gpu](const std::string& scene, const std::string& size) {
    for (const auto& r : gpu.results) {
      if (r.scene == scene && r.size == size && r.method == "copy" && r.timed) return r.median_ms;
    }
    return 0.0;
  };
  int matched = 0;
  for (ResultRow& row : report.rows) {
    GpuTiming t;
    t.device = gpu.device;
    t.driver = gpu.driver;
    t.cuda_runtime = gpu.cuda_runtime;
    t.measured_utc = gpu.generated_utc;
    for (const auto& r : gpu.results) {
      if (r.scene != row.scene || r.method != row.spec || !r.timed) continue;
      t.kernels = r.kernels;
      GpuTimingAt at;
      at.size = r.size;
      at.median_ms = r.median_ms;
      at.min_ms = r.min_ms;
      at.max_ms = r.max_ms;
      at.copy_ms = copy_ms(r.scene, r.size);
      at.ratio_to_copy = r.ratio_to_copy;
      at.measured_utc = gpu.generated_utc;
      if (r.has_fidelity) {
        at.identical_share = r.identical_share;
        at.max_diff = r.max_diff;
      }
      t.sizes.push_back(at);
    }
    if (t.sizes.empty()) continue;
    if (row.gpu && SameSetup(*row.gpu, t)) {
      FoldSizes(*row.gpu, t);
    } else {
      row.gpu = t;
    }
    ++matched;
  }
  if (matched > 0) {
    const std::string source =
        gpu.device + ", driver " + gpu.driver + ", CUDA " + gpu.cuda_runtime + ", measured " + gpu.generated_utc;
    const auto old = report.context.find("gpu_timings");
    report.context["gpu_timings"] = old == report.context.end() ? source : AppendOnce(old->second, source);
  }
  return matched;
}

}  // namespace aalab
