#!/bin/sh
# Packs what gpu/vk/run_h100.sh needs on the GPU machine into CARRY (docs/gpu.md "Original
# shaders through Vulkan"). Run here, in the repository root, after building aalab:
#
#   gpu/vk/pack.sh CARRY [SCENES]        # SCENES: comma-separated; default: the default suite
#
# CARRY/spv         the SPIR-V modules (scripts/vk_shaders.sh: needs glslang-tools, spirv-tools):
#                   CMAA2, FSR 1, FSR 2's six passes, the copy
# CARRY/frames.tgz  frames/: `aalab export-frames` at $SIZES (default 1920x1080,3840x2160) with
#                   the render-size frame of scale43-easu; refs/: aalab's CPU outputs of
#                   cmaa2-high and rcas on each 1x frame at the first size (`aalab apply
#                   --sampler $SAMPLER`, default gpu-texture: the H100 texture unit's UNORM8
#                   values), for aalab_vk --compare
# CARRY/debs        libvulkan1 and libvulkan-dev (Debian 12, amd64): the loader, and the
#                   headers CMake needs there (the GPU machine has neither); libglvnd0,
#                   libglx0, libegl1: GLVND, without which NVIDIA's Vulkan ICD (libGLX_nvidia)
#                   gives the loader no vkCreateInstance on a fresh GPU machine
# CARRY must be a folder .git/info/exclude ignores (the device tool's `carry`); it must stay
# under the device's 64 MiB with the working tree: give fewer SCENES if it does not.
set -eu
carry=${1:?usage: gpu/vk/pack.sh CARRY [SCENES]}
scenes=${2:-}
sizes=${SIZES:-1920x1080,3840x2160}
sampler=${SAMPLER:-gpu-texture}
aalab=${AALAB:-build/aalab}
[ -x "$aalab" ] || { echo "pack.sh: $aalab not found: build aalab first (or set AALAB)" >&2; exit 1; }
command -v oiiotool > /dev/null || { echo "pack.sh: oiiotool not found: install openimageio-tools" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rm -rf "$carry"
mkdir -p "$carry/debs" "$tmp/refs"
scripts/vk_shaders.sh "$carry/spv"
if [ -n "$scenes" ]; then sel="--scenes $scenes"; else sel="--suite default"; fi
# shellcheck disable=SC2086
"$aalab" export-frames $sel --sizes "$sizes" --no-scaled --render-methods scale43-easu --out "$tmp/frames"
first=${sizes%%,*}
for f in "$tmp/frames"/*-"$first".ppm; do
  stem=$(basename "$f" .ppm)
  oiiotool "$f" -o "$tmp/in.png"
  for m in cmaa2-high rcas; do
    "$aalab" apply --sampler "$sampler" --method "$m" "$tmp/in.png" "$tmp/out.png" > /dev/null
    oiiotool "$tmp/out.png" -o "$tmp/refs/$stem-$m.ppm"
  done
done
tar czf "$carry/frames.tgz" -C "$tmp" frames refs
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64'
# shellcheck disable=SC2086
(cd "$carry/debs" && apt-get $o download libvulkan1 libvulkan-dev libglvnd0 libglx0 libegl1 > /dev/null)
echo "pack.sh: $(du -sh "$carry" | cut -f1) in $carry (frames.tgz $(du -h "$carry/frames.tgz" | cut -f1))"
if [ "$(du -sm "$carry" | cut -f1)" -gt 48 ]; then
  echo "pack.sh: warning: over 48 MiB: with the working tree it may not fit the device's 64 MiB; pack fewer" \
    "scenes per batch (gpu/vk/pack.sh CARRY scene1,scene2,...), run each, merge each JSON" >&2
fi
