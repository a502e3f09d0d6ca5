#!/bin/sh
# Times CMAA2, FSR 1 and FSR 2 as their original shaders on the GPU machine (docs/gpu.md "Original
# shaders through Vulkan"). Run there, in the repository root, with the folder gpu/vk/pack.sh
# made here carried along:
#
#   gpu/vk/run_h100.sh CARRY [OUT]       # OUT: default $OUT (the device tool's), else CARRY
#
# Installs the Vulkan loader from CARRY/debs where none is installed (dpkg -x into /, as the
# device's README says), unpacks libvulkan-dev's headers beside it (not into /), builds
# gpu/vk stand-alone with CMake, and runs aalab_vk on NVIDIA's ICD over every frame with
# --compare against the CPU outputs (FSR 2: its synthetic sequence at the first scene of each
# size, no reference). Writes OUT/vk-timings.json (for `aalab merge-gpu`) and
# OUT/vk-log.txt. WARMUP / REPEAT (default 200 / 200), VK_DRIVER_FILES and METHODS override.
set -eu
carry=${1:?usage: gpu/vk/run_h100.sh CARRY [OUT]}
out=${2:-${OUT:-$carry}}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
if ! ldconfig -p | grep -q 'libvulkan\.so\.1 '; then
  for f in "$carry"/debs/libvulkan1_*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
# NVIDIA's Vulkan ICD is libGLX_nvidia.so.0; on a fresh GPU machine without GLVND its
# vk_icdGetInstanceProcAddr returns no vkCreateInstance and the loader finds no driver. Measured
# on the H100 (2026-11-27): with libvulkan1 and libglvnd0 alone still none; with libglx0 and
# libegl1 unpacked too, vkCreateInstance is there.
if ! ldconfig -p | grep -q 'libEGL\.so\.1 '; then
  for p in libglvnd0 libglx0 libegl1; do
    for f in "$carry"/debs/${p}_*.deb; do [ -f "$f" ] && dpkg -x "$f" /; done
  done
  ldconfig
fi
lib=$(ldconfig -p | sed -n 's/^[[:space:]]*libvulkan\.so\.1 (libc6,x86-64) => //p' | head -1)
[ -n "$lib" ] || { echo "run_h100.sh: no libvulkan.so.1 after installing $carry/debs" >&2; exit 1; }
dpkg -x "$carry"/debs/libvulkan-dev_*.deb "$work/dev"
# NVIDIA's ICD where the device README puts it (unless VK_DRIVER_FILES is set already).
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$icd" ]; then export VK_DRIVER_FILES="$icd"; fi
cmake -S gpu/vk -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DVulkan_INCLUDE_DIR="$work/dev/usr/include" \
  -DVulkan_LIBRARY="$lib" > "$work/cmake.log" 2>&1 || { cat "$work/cmake.log"; exit 1; }
cmake --build "$work/build" -j 8 > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
tar xzf "$carry/frames.tgz" -C "$work"
methods=${METHODS:+--methods $METHODS}
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,clocks.mem,temperature.gpu,power.draw \
  --format=csv > "$out/vk-smi.txt" 2>&1 || true
status=0
t0=$(date +%s)
# shellcheck disable=SC2086
"$work/build/aalab_vk" --shaders "$carry/spv" --input "$work/frames" --compare "$work/refs" \
  --json "$out/vk-timings.json" --warmup "${WARMUP:-200}" --repeat "${REPEAT:-200}" $methods \
  > "$out/vk-log.txt" 2>&1 || status=$?
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,clocks.mem,temperature.gpu,power.draw \
  --format=csv,noheader >> "$out/vk-smi.txt" 2>&1 || true
echo "run_h100.sh: aalab_vk ran $(($(date +%s) - t0)) s" >> "$out/vk-log.txt"
cat "$out/vk-log.txt"
exit $status
