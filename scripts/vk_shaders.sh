#!/bin/sh
# Compiles the SPIR-V modules gpu/vk/aalab_vk runs (docs/gpu.md "Original shaders through
# Vulkan") into OUT, from the ORIGINAL sources in ../shared/third_party (or
# $AALAB_THIRD_PARTY_DIR) and aalab's own wrappers in gpu/vk/shaders. Needs glslangValidator
# (glslang-tools) and spirv-dis / spirv-as (spirv-tools). The modules are build outputs:
# never commit them.
#
#   scripts/vk_shaders.sh OUT
#
# CMAA2.hlsl: each of its presets (LOW..ULTRA = 0..3) x its four entry points, with the
# sample's defaults for an 8-bit frame (CMAA2_UAV_STORE_TYPED 1, _TYPED_UNORM_FLOAT 1,
# _CONVERT_TO_SRGB 1: the shader converts to sRGB and stores to an R8G8B8A8_UNORM UAV),
# luma edges, no extra sharpness; compiled as tests/oracle/cmaa2_shader.cpp compiles it (the
# `#error` lines dropped from a working copy: glslang's preprocessor trips on an apostrophe in
# one; registers t<n> -> binding n, u<n> -> binding 10 + n). glslang declares the colour UAV
# `Rgba32f` whatever its HLSL type; the module is re-typed to `Rgba8` (the format of the view
# the sample binds, what D3D's typed `unorm float4` UAV means) by editing that one
# OpTypeImage in the disassembly. FSR 1: gpu/vk/shaders/fsr1.comp with AALAB_EASU 1 and 0.
# FSR 2: the six passes of the default pipeline, ffx_fsr2_<pass>_pass.glsl as they are, with
# FFX_GPU FFX_GLSL FFX_HALF=0 (the 32-bit path aalab ports) and the options aalab's port
# defaults to (tests/oracle/fsr2_shader.cpp's defines): LDR colour, low-resolution motion
# vectors, not jittered, depth not inverted, the reference Lanczos for the reprojection
# (REPROJECT_USE_LANCZOS_TYPE 0), the upsample's Lanczos2ApproxSq (2); accumulate with
# APPLY_SHARPENING=1 (the API's pipelineAccumulateSharpen, RCAS after it). The luminance
# pyramid's subgroup quad ops need SPIR-V 1.3 (--target-env vulkan1.1). No FFX_HALF=1 build:
# the pyramid has none in GLSL, and the other passes' would hold no 16-bit float (docs/gpu.md).
set -eu
out=${1:?usage: scripts/vk_shaders.sh OUT}
here=$(cd "$(dirname "$0")/.." && pwd)
tp=${AALAB_THIRD_PARTY_DIR:-$here/../shared/third_party}
fsr2="$tp/fidelityfx-fsr2/shaders"
for f in "$tp/cmaa2/CMAA2.hlsl" "$tp/fidelityfx-fsr1/ffx_fsr1.h" "$tp/fidelityfx-fsr1/ffx_a.h" \
  "$fsr2/ffx_fsr2_accumulate_pass.glsl"; do
  [ -f "$f" ] || { echo "vk_shaders.sh: $f is missing (set AALAB_THIRD_PARTY_DIR to the third_party folder)" >&2; exit 1; }
done
for t in glslangValidator spirv-dis spirv-as; do
  command -v $t > /dev/null || { echo "vk_shaders.sh: $t not found: install glslang-tools spirv-tools" >&2; exit 1; }
done
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -v '^[[:space:]]*#error' "$tp/cmaa2/CMAA2.hlsl" > "$tmp/CMAA2.hlsl"
preset=0
for name in low medium high ultra; do
  for entry in EdgesColor2x2CS ComputeDispatchArgsCS ProcessCandidatesCS DeferredColorApply2x2CS; do
    glslangValidator -D -V -S comp --hlsl-iomap --shift-UAV-binding comp 10 -e main --source-entrypoint "$entry" \
      -DCMAA2_STATIC_QUALITY_PRESET=$preset -DCMAA2_EXTRA_SHARPNESS=0 -DCMAA2_EDGE_DETECTION_LUMA_PATH=1 \
      -DCMAA2_UAV_STORE_TYPED=1 -DCMAA2_UAV_STORE_TYPED_UNORM_FLOAT=1 -DCMAA2_UAV_STORE_CONVERT_TO_SRGB=1 \
      -o "$tmp/m.spv" "$tmp/CMAA2.hlsl" > "$tmp/log" || { cat "$tmp/log" >&2; exit 1; }
    spirv-dis --raw-id "$tmp/m.spv" > "$tmp/m.spvasm"
    # The colour UAV is the only float storage image (Sampled = 2) of the module.
    sed -E 's/(OpTypeImage %[0-9]+ 2D 0 0 0 2) Rgba32f/\1 Rgba8/' "$tmp/m.spvasm" > "$tmp/m8.spvasm"
    spirv-as --preserve-numeric-ids --target-env vulkan1.0 -o "$out/cmaa2-$name-$entry.spv" "$tmp/m8.spvasm"
  done
  preset=$((preset + 1))
done
for e in 1 0; do
  name=$([ $e = 1 ] && echo easu || echo rcas)
  glslangValidator -V -S comp -DAALAB_EASU=$e -I"$tp/fidelityfx-fsr1" -o "$out/fsr1-$name.spv" \
    "$here/gpu/vk/shaders/fsr1.comp" > "$tmp/log" || { cat "$tmp/log" >&2; exit 1; }
done
for pass in compute_luminance_pyramid reconstruct_previous_depth depth_clip lock accumulate rcas; do
  sharpen=$([ $pass = accumulate ] && echo 1 || echo 0)
  glslangValidator -V -S comp --target-env vulkan1.1 -DFFX_GPU=1 -DFFX_GLSL=1 -DFFX_HALF=0 \
    -DFFX_FSR2_OPTION_HDR_COLOR_INPUT=0 -DFFX_FSR2_OPTION_LOW_RESOLUTION_MOTION_VECTORS=1 \
    -DFFX_FSR2_OPTION_JITTERED_MOTION_VECTORS=0 -DFFX_FSR2_OPTION_INVERTED_DEPTH=0 \
    -DFFX_FSR2_OPTION_APPLY_SHARPENING=$sharpen -DFFX_FSR2_OPTION_REPROJECT_USE_LANCZOS_TYPE=0 \
    -DFFX_FSR2_OPTION_UPSAMPLE_USE_LANCZOS_TYPE=2 -I"$fsr2" -o "$out/fsr2-$pass.spv" \
    "$fsr2/ffx_fsr2_${pass}_pass.glsl" > "$tmp/log" || { cat "$tmp/log" >&2; exit 1; }
done
glslangValidator -V -S comp -o "$out/copy.spv" "$here/gpu/vk/shaders/copy.comp" > "$tmp/log" || { cat "$tmp/log" >&2; exit 1; }
echo "vk_shaders.sh: wrote $(ls "$out"/*.spv | wc -l) SPIR-V modules to $out"
