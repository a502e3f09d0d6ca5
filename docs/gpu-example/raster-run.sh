#!/bin/bash
# The raster path's batched H100 run (docs/gpu.md "The raster path", "On the H100"): copy it
# to .devdata/run.sh and run it from the repository root on the device with the carry
# `.gl` (the GLVND/EGL runtime .debs, and their -dev .debs under .gl/dev), `.devtree` (the
# merged source tree) and `.devdata` (this script, geometry/, raster-ref.tgz), e.g.
#   run: bash .devdata/run.sh default   carry: .gl .devtree .devdata
#   run: bash .devdata/run.sh synthetic carry: .gl .devtree .devdata
# METHODS (default: none,msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4,taa) chooses the shader-
# resolve run's methods, TAG is added to its JSON's name, BLIT=0 skips the blit-resolve run;
# the default suite's 9 raster rows in one file (docs/gpu.md, 2026-11-27 s7):
#   run: METHODS=none,aaa,msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4,scale43,taa TAG=-all BLIT=0 \
#        bash .devdata/run.sh default
# Prepared on the CPU machine with (docs/gpu.md gives the same commands):
#   aalab export-geometry --suite synthetic --skip-unsupported --out .devdata/geometry
#   aalab export-geometry --suite default --out .devdata/geometry-default   # all four scenes (AALABRG3)
#   aalab export-frames --scenes wedges,mesh,checker-plane,detail-texture,circle,hdr-edges,sdf-circles,shadow-stipple \
#     --sizes 1920x1080,3840x2160 --no-scaled --taa-frames 2 \
#     --render-methods msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4 --out raster-ref
#   aalab export-frames --scenes real-glossy,real-fence,real-foliage --sizes 1920x1080 --no-scaled \
#     --out raster-ref-gltf && cp raster-ref-gltf/*.ppm raster-ref/
# (scale43's references are export-frames' -scaled.ppm frames: leave out --no-scaled for them;
# the s7 run carried only the 1x and -scaled frames: wedges at both sizes, the glTF scenes at 1080p)
#   tar czf .devdata/raster-ref.tgz raster-ref
#   du -sh .devdata .gl .devtree   # the carry holds 64 MiB in all
# The glTF scenes' reference is their 1x frame at 1080p only: their textured frames compress
# poorly, and 4K or MSAA/SSAA references of three textured scenes would not fit the carry;
# --compare says "no such frame" for the others and goes on.
# Expected GPU time under the default budget (--budget-ms 1000, --min-repeat 5), worked out
# from the H100's measured 1080p frame times (4K: 4x): the synthetic suite's 8 scenes
# ≈ 162 s shader + 66 s blit (its longest row: shadow-stipple 4K ssaa-4x4, ≈ 2.2 s a frame,
# 8 frames ≈ 18 s). The default suite now draws all four scenes: 4 scenes x 2 sizes x 7
# methods = 56 rows of at least 1.5 s each ≈ 84 s, plus the rows whose 8 frames exceed it:
# real-foliage's shadow loop (142 triangles a lit fragment against shadow-stipple's 217,
# which took 34 ms a 1080p frame) ≈ 22 ms at 1080p, so its 4K ssaa-4x4 ≈ 1.4 s a frame,
# 8 frames ≈ 11 s; in all ≈ 2–3 min shader + 1–2 min blit (an estimate, not measured: the
# glTF shading has not run on the H100 yet); plus the build, contexts and --compare's reads.
# The same runs at --budget-ms 0 (200 + 200 frames a row) would take far longer (the
# synthetic suite alone ≈ 36 min of GPU time).
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
ALL="${METHODS:-none,msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4,taa}"
# Suites from the arguments (default: both). One command may run 10 minutes: run
# `bash .devdata/run.sh default` and `bash .devdata/run.sh synthetic` as two calls.
SUITES="${*:-default synthetic}"
for suite in $SUITES; do
  G=../.devdata/geometry
  [ $suite = default ] && G=../.devdata/geometry-default
  echo "== $suite: shader resolve"
  date
  $R --geometry $G --egl device --sizes 1920x1080,3840x2160 --methods $ALL --warmup 200 --repeat 200 \
    --json "$OUT/raster-h100-$suite${TAG:-}.json" --compare /tmp/raster-ref >"$OUT/raster-$suite${TAG:-}.log" 2>&1
  echo "rc=$?"
  tail -30 "$OUT/raster-$suite${TAG:-}.log"
  [ "${BLIT:-1}" = 0 ] && continue
  echo "== $suite: blit resolve"
  date
  $R --geometry $G --egl device --sizes 1920x1080,3840x2160 --methods msaa-2x,msaa-4x,msaa-8x --resolve blit \
    --warmup 200 --repeat 200 --json "$OUT/raster-h100-$suite-blit.json" --compare /tmp/raster-ref \
    >"$OUT/raster-$suite-blit.log" 2>&1
  echo "rc=$?"
  tail -12 "$OUT/raster-$suite-blit.log"
done
date
