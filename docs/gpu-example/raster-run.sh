#!/bin/bash
# The raster path's batched H100 run (docs/gpu.md "The raster path", "On the H100"): copy it
# to .devdata/run.sh and run it from the repository root on the device with the carry
# `.gl` (the GLVND/EGL runtime .debs, and their -dev .debs under .gl/dev), `.devtree` (the
# merged source tree) and `.devdata` (this script, geometry/, raster-ref.tgz), e.g.
#   run: bash .devdata/run.sh   carry: .gl .devtree .devdata
# Prepared on the CPU machine with (docs/gpu.md gives the same commands):
#   aalab export-geometry --suite synthetic --skip-unsupported --out .devdata/geometry
#   aalab export-geometry --suite default --skip-unsupported --out .devdata/geometry-default
#   aalab export-frames --scenes wedges,mesh,checker-plane,detail-texture,circle,hdr-edges,sdf-circles,shadow-stipple \
#     --sizes 1920x1080,3840x2160 --no-scaled --taa-frames 2 \
#     --render-methods msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4 --out raster-ref
#   tar czf .devdata/raster-ref.tgz raster-ref
# Expected GPU time under the default budget (--budget-ms 1000, --min-repeat 5), worked out
# from the H100's measured 1080p frame times (4K: 4×): the default suite (only `wedges` is
# drawn; its glTF scenes are skipped and listed) ≈ 16 s shader + 8 s blit; the synthetic
# suite's 8 scenes ≈ 162 s shader + 66 s blit (its longest row: shadow-stipple 4K ssaa-4x4,
# ≈ 2.2 s a frame, 8 frames ≈ 18 s); plus the build, context creation and --compare's reads.
# The same runs at --budget-ms 0 (200 + 200 frames a row) would take ≈ 36 min of GPU time.
# Exit status 2 from aalab_raster: some rows' timings were refused (stderr names each and
# why; the JSON lists them under "refused" and holds only the checked rows).
set -o pipefail
for f in .gl/*.deb .gl/dev/*.deb; do dpkg -x "$f" /; done
ldconfig
E=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f $E ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$E
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
tar xzf .devdata/raster-ref.tgz -C /tmp
cd .devtree || exit 1
echo "== raster build"
date
cmake -S gpu/raster -B build-raster -DCMAKE_BUILD_TYPE=Release >"$OUT/raster-build.log" 2>&1 &&
  cmake --build build-raster -j16 >>"$OUT/raster-build.log" 2>&1
echo "raster build rc=$?"
R=build-raster/aalab_raster
ALL=none,msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4,taa
for suite in default synthetic; do
  G=../.devdata/geometry
  [ $suite = default ] && G=../.devdata/geometry-default
  echo "== $suite: shader resolve"
  date
  $R --geometry $G --egl device --sizes 1920x1080,3840x2160 --methods $ALL --warmup 200 --repeat 200 \
    --json "$OUT/raster-h100-$suite.json" --compare /tmp/raster-ref >"$OUT/raster-$suite.log" 2>&1
  echo "rc=$?"
  tail -30 "$OUT/raster-$suite.log"
  echo "== $suite: blit resolve"
  date
  $R --geometry $G --egl device --sizes 1920x1080,3840x2160 --methods msaa-2x,msaa-4x,msaa-8x --resolve blit \
    --warmup 200 --repeat 200 --json "$OUT/raster-h100-$suite-blit.json" --compare /tmp/raster-ref \
    >"$OUT/raster-$suite-blit.log" 2>&1
  echo "rc=$?"
  tail -12 "$OUT/raster-$suite-blit.log"
done
date
