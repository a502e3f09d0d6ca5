// The HTML report's stylesheet and metric descriptions (see html_assets.h).
#include "reports/html_assets.h"

#include <map>

namespace aalab::html {

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool IsPsnrMetric(const std::string& name) { return name == "psnr_db" || EndsWith(name, "_psnr_db"); }

MetricInfo DescribeMetric(const std::string& name) {
  // From metrics/METRICS.md.
  static const std::map<std::string, MetricInfo> kKnown = {
      {"psnr_db", {"PSNR", "dB", +1, "PSNR against the reference over all pixels (sRGB-encoded RGB, peak 1)."}},
      {"mse", {"MSE", "", -1, "Mean squared error over all pixels (sRGB-encoded RGB, 0..1)."}},
      {"edge_psnr_db",
       {"Edge PSNR", "dB", +1, "PSNR over the geometric edge mask: the aliasing that AA should remove."}},
      {"edge_rmse", {"Edge RMSE", "", -1, "Root mean squared error over the edge mask (0..1)."}},
      {"interior_psnr_db",
       {"Interior PSNR", "dB", +1, "PSNR off the edge mask: detail that AA should not blur."}},
      {"edge_error_removed",
       {"Edge err. removed", "", +1,
        "1 − edge MSE / none's edge MSE: 1 removes all of no-AA's edge error, 0 is no better than no AA, "
        "negative is worse."}},
      {"ssim", {"SSIM", "", +1, "Structural similarity (Wang et al. 2004), mean of R, G, B."}},
      {"flip_mean", {"FLIP mean", "", -1, "LDR-FLIP per-pixel error (0..1) averaged over the image, 67 px/degree."}},
      {"flip_median_weighted",
       {"FLIP wtd. median", "", -1, "Value-weighted median of the LDR-FLIP error (as NVIDIA's FLIP tool prints)."}},
      {"flip_max", {"FLIP max", "", -1, "Largest per-pixel LDR-FLIP error."}},
      {"abs_err_p50", {"|err| p50", "", -1, "Median of the per-pixel absolute error (RGB mean, 0..1)."}},
      {"abs_err_p95", {"|err| p95", "", -1, "95th percentile of the per-pixel absolute error."}},
      {"abs_err_p99", {"|err| p99", "", -1, "99th percentile of the per-pixel absolute error."}},
      {"abs_err_max", {"|err| max", "", -1, "Largest per-pixel absolute error."}},
  };
  const auto it = kKnown.find(name);
  if (it != kKnown.end()) return it->second;
  MetricInfo info{name, "", 0, "Not described by this version of the page (see metrics/METRICS.md)."};
  if (EndsWith(name, "_db")) {
    info.unit = "dB";
    if (IsPsnrMetric(name)) info.better = +1;
  } else if (EndsWith(name, "mse") || EndsWith(name, "rmse") || EndsWith(name, "_err")) {
    info.better = -1;
  }
  return info;
}

const char* const kStyle = R"CSS(
:root { --fg:#1b1f24; --muted:#5b6570; --bg:#fff; --panel:#f5f7f9; --line:#d5dbe1; --accent:#0b62c4;
  --warn:#b35900; --front:#d12f2f; --sel:#ffd54a; color-scheme: light dark; }
@media (prefers-color-scheme: dark) {
  :root { --fg:#e4e8ec; --muted:#9aa5b1; --bg:#15181c; --panel:#1e2328; --line:#36404a; --accent:#6cb0ff;
    --warn:#ffa94d; --front:#ff6b6b; --sel:#b8860b; } }
* { box-sizing: border-box; }
body { margin:0; font:14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif;
  color:var(--fg); background:var(--bg); }
a { color:var(--accent); }
code { font-family: ui-monospace, "DejaVu Sans Mono", monospace; font-size:0.92em; }
.skip { position:absolute; left:-999px; } .skip:focus { left:8px; top:8px; background:var(--bg); z-index:10; }
header.top { padding:12px 20px 0; border-bottom:1px solid var(--line); background:var(--panel);
  position:sticky; top:0; z-index:5; }
h1 { font-size:20px; margin:0 0 4px; } h1 .sub { font-weight:normal; color:var(--muted); font-size:15px; }
h2 { font-size:18px; margin:18px 0 6px; } h3 { font-size:15px; margin:18px 0 6px; }
h4 { font-size:13px; margin:14px 0 6px; color:var(--muted); text-transform:uppercase; letter-spacing:.04em; }
.facts, .links { margin:2px 0; color:var(--muted); font-size:13px; }
nav.views { display:flex; flex-wrap:wrap; gap:2px; margin-top:8px; }
nav.views a { padding:5px 11px; border:1px solid var(--line); border-bottom:none; border-radius:6px 6px 0 0;
  text-decoration:none; background:var(--bg); color:var(--fg); }
nav.views a[aria-current="page"] { background:var(--accent); color:#fff; border-color:var(--accent); }
main { padding:0 20px 20px; }
.js .view { display:none; } .js .view.active { display:block; }
.desc { color:var(--muted); max-width:1100px; margin:4px 0 8px; }
.note { color:var(--muted); font-style:italic; }
.scene-facts { display:flex; flex-wrap:wrap; gap:4px 18px; margin:6px 0; font-size:13px; }
.scene-facts div { display:flex; gap:6px; } .scene-facts dt { color:var(--muted); } .scene-facts dd { margin:0; }
.qc { display:flex; flex-wrap:wrap; gap:16px; align-items:flex-start; }
.qc .chart-box { flex:0 1 660px; min-width:320px; }
.qc .cost-box { flex:1 1 480px; min-width:320px; }
.qc .ctl { font-size:13px; margin-bottom:4px; display:flex; gap:12px; flex-wrap:wrap; align-items:center; }
.qc svg { width:100%; height:auto; background:var(--panel); border:1px solid var(--line); border-radius:6px; }
.qc svg text { fill:var(--fg); font-size:11px; font-family:inherit; }
.qc svg .axis line, .qc svg .grid line { stroke:var(--line); }
.qc svg .axis-label { font-size:12px; font-weight:600; }
.qc svg .front { fill:none; stroke:var(--front); stroke-width:1.5; }
.qc svg .floor { stroke:var(--warn); stroke-dasharray:5 4; }
.qc svg .floor-label { fill:var(--warn); }
.qc svg .pt { cursor:pointer; outline:none; }
.qc svg .pt circle { stroke-width:1.6; }
.qc svg .pt.dominated circle { fill:var(--panel) !important; }
.qc svg .pt:focus circle, .qc svg .pt:hover circle { stroke:var(--fg); stroke-width:3; }
.qc svg .pt.selected circle { stroke:var(--fg); stroke-width:2.5; }
.qc svg .pt text { font-size:10.5px; }
.qc .legend { font-size:12px; color:var(--muted); display:flex; flex-wrap:wrap; gap:4px 12px; margin-top:4px; }
.qc .legend i { display:inline-block; width:10px; height:10px; border-radius:50%; margin-right:4px; vertical-align:-1px; }
.qc .unplotted { font-size:12px; color:var(--muted); }
#tooltip { position:fixed; z-index:20; pointer-events:none; background:var(--fg); color:var(--bg);
  padding:6px 8px; border-radius:5px; font-size:12px; line-height:1.35; max-width:340px; white-space:pre-line; }
.table-wrap { overflow-x:auto; max-width:100%; }
table { border-collapse:collapse; font-size:12.5px; }
caption { text-align:left; color:var(--muted); padding:4px 0; caption-side:top; }
th, td { padding:3px 7px; border-bottom:1px solid var(--line); text-align:left; vertical-align:top; }
thead th { position:sticky; top:0; background:var(--panel); vertical-align:bottom; white-space:nowrap; }
thead th button { all:unset; cursor:pointer; font-weight:600; }
thead th button:focus-visible { outline:2px solid var(--accent); outline-offset:2px; }
thead th[aria-sort="ascending"] button::after { content:" ▲"; }
thead th[aria-sort="descending"] button::after { content:" ▼"; }
.unit { font-weight:normal; color:var(--muted); }
td.num { text-align:right; font-variant-numeric:tabular-nums; white-space:nowrap; }
td.null { color:var(--muted); text-align:center; }
.range { color:var(--muted); }
tbody th { font-weight:normal; white-space:nowrap; }
.method { font-family: ui-monospace, "DejaVu Sans Mono", monospace; }
small { color:var(--muted); } small.same { color:var(--warn); }
tr.selected > * { background:color-mix(in srgb, var(--sel) 30%, transparent); }
.warn { color:var(--warn); font-weight:bold; margin-left:3px; cursor:help; }
td.near-floor { color:var(--warn); }
.cost td.dash { text-align:center; color:var(--muted); cursor:help; }
.cost .front-mark { color:var(--front); }
.gallery { border:1px solid var(--line); border-radius:6px; padding:10px; background:var(--panel); outline:none; }
.gallery:focus-visible { outline:2px solid var(--accent); }
.gallery .bar { display:flex; flex-wrap:wrap; gap:8px 16px; align-items:center; font-size:13px; margin-bottom:8px; }
.gallery .methods { display:flex; flex-wrap:wrap; gap:3px; margin:4px 0 8px; }
.gallery .methods button { font:12px ui-monospace, "DejaVu Sans Mono", monospace; padding:2px 7px; cursor:pointer;
  border:1px solid var(--line); border-radius:4px; background:var(--bg); color:var(--fg); }
.gallery .methods button[aria-pressed="true"] { background:var(--accent); color:#fff; border-color:var(--accent); }
.gallery .hint { color:var(--muted); font-size:12px; }
.gallery .summary { font-size:13px; margin:4px 0; }
.ab-scroll { overflow:auto; max-height:80vh; background:#000; }
.ab-wrap { max-width:100%; }
.ab { position:relative; user-select:none; touch-action:none; cursor:ew-resize; }
.ab img { position:absolute; inset:0; width:100%; height:100%; display:block; }
.ab .b { position:absolute; inset:0; }
.ab .line { position:absolute; top:0; bottom:0; width:2px; margin-left:-1px; background:#fff;
  box-shadow:0 0 0 1px #000; pointer-events:none; }
.ab .tag { position:absolute; top:4px; background:rgba(0,0,0,.65); color:#fff; font-size:12px; padding:1px 6px;
  border-radius:3px; pointer-events:none; }
.ab .crop-box { position:absolute; border:1px solid #ffd54a; pointer-events:none; }
.ab .crop-box span { position:absolute; left:1px; top:0; color:#ffd54a; font-size:10px; text-shadow:0 0 2px #000; }
.pixelated, .ab.zoomed img, .crop img, .debug img { image-rendering: pixelated; }
.ab-range { width:100%; max-width:100%; }
.crops { display:flex; flex-direction:column; gap:10px; }
.crop-strip { display:flex; flex-wrap:wrap; gap:6px; }
.crop-cell { display:flex; flex-direction:column; align-items:center; }
.crop-cell.selected .crop { outline:3px solid var(--sel); }
.crop { position:relative; overflow:hidden; display:block; background:#000; }
.crop img { position:absolute; left:0; top:0; max-width:none; }
.crop-cell button { all:unset; cursor:pointer; font:11px ui-monospace, "DejaVu Sans Mono", monospace;
  max-width:100%; overflow:hidden; text-overflow:ellipsis; white-space:nowrap; }
.crop-cell button:focus-visible { outline:2px solid var(--accent); }
.figs { display:flex; flex-wrap:wrap; gap:10px; }
.figs figure { margin:0; } .figs img { max-width:100%; display:block; border:1px solid var(--line); }
.figs figcaption { font-size:12px; color:var(--muted); }
.prose { max-width:1000px; } .prose li { margin:4px 0; } .caveat { color:var(--warn); }
footer { padding:4px 20px 30px; border-top:1px solid var(--line); background:var(--panel); }
.ctx { display:flex; flex-wrap:wrap; gap:24px; }
table.stability td, table.stability th { padding:3px 8px; vertical-align:top; border-bottom:1px solid #ddd; }
table.stability tr.hard th { color:#8a3b00; } .tag { font-size:11px; border:1px solid currentColor; border-radius:3px; padding:0 3px; }
ul.nulls { margin:0; padding-left:16px; font-size:12px; }
table.kv th { color:var(--muted); } table.kv td { font-family: ui-monospace, "DejaVu Sans Mono", monospace; }
#selftest { white-space:pre-wrap; font-size:12px; border:2px solid var(--accent); padding:6px; margin:10px 20px; }
@media print { .js .view { display:block; } header.top { position:static; } .gallery { display:none; } }
)CSS";

}  // namespace aalab::html
