// The HTML report's embedded assets (reports/html/) and metric descriptions (from the registry; see html_assets.h).
#include "reports/html_assets.h"

#include <stdexcept>

#include "metrics/metric.h"

namespace aalab::html {

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool IsPsnrMetric(const std::string& name) { return name == "psnr_db" || EndsWith(name, "_psnr_db"); }

MetricInfo DescribeMetric(const std::string& name) {
  // The registry's description (metrics/metric.h MetricOutput); sequence outputs too.
  if (const MetricOutput* o = FindMetricOutput(name)) {
    const int better = o->better == Improves::kHigher ? +1 : o->better == Improves::kLower ? -1 : 0;
    return {o->label, o->unit, better, o->help, o->rewards};
  }
  // A name this version does not produce (a report from another version): a label equal to
  // the name and a direction only from unambiguous suffixes.
  MetricInfo info{name, "", 0, "Not described by this version of the page (see metrics/METRICS.md).", ""};
  if (EndsWith(name, "_db")) {
    info.unit = "dB";
    if (IsPsnrMetric(name)) info.better = +1;
  } else if (EndsWith(name, "mse") || EndsWith(name, "rmse") || EndsWith(name, "_err")) {
    info.better = -1;
  }
  return info;
}

std::string_view Asset(std::string_view name) {
  for (std::size_t i = 0; i < kEmbeddedAssetCount; ++i) {
    if (name == kEmbeddedAssets[i].name) return {kEmbeddedAssets[i].data, kEmbeddedAssets[i].size};
  }
  throw std::logic_error("HTML asset '" + std::string(name) + "' was not embedded (reports/CMakeLists.txt)");
}

std::string PageStyle() { return std::string(Asset("style.css")) + "\n" + std::string(Asset("abview.css")); }

std::string AbViewAssets() {
  return "<style>\n" + std::string(Asset("abview.css")) + "</style>\n<script>\n" + std::string(Asset("abview.js")) +
         "\nAAB.autoMount();\n</script>\n";
}

std::string PageScript() {
  std::string script;
  for (std::size_t i = 0; i < kEmbeddedAssetCount; ++i) {
    const std::string_view name = kEmbeddedAssets[i].name;
    if (name.size() < 3 || name.substr(name.size() - 3) != ".js") continue;
    script += '\n';
    script.append(kEmbeddedAssets[i].data, kEmbeddedAssets[i].size);
  }
  return script;
}

}  // namespace aalab::html
