/// Registry rows of each method family, one function per family file. registry.cpp joins
/// them in listing order.
#pragma once
#include <vector>

#include "methods/method.h"

namespace aalab {

/// `none`, `ssaa-2x2`, `ssaa-4x4`, `ssaa-rgss`, `ssaa-jitter` (methods/supersample.cpp).
std::vector<MethodEntry> SupersampleMethods();

/// `msaa-2x`, `msaa-4x`, `msaa-8x`, `msaa-16x`: coverage samples at the standard positions,
/// one shading per primitive and pixel (methods/msaa.cpp).
std::vector<MethodEntry> MsaaMethods();

/// `fxaa1-p0` … `fxaa1-p5`: FXAA 1.0 whitepaper presets (methods/fxaa1.cpp).
std::vector<MethodEntry> Fxaa1Methods();
/// `fxaa311-p10` .. `-p15`, `-p20` .. `-p29`, `-p39`, `fxaa-low`, `fxaa-medium`,
/// `fxaa-high`, `fxaa-iter12` (methods/fxaa311.cpp).
std::vector<MethodEntry> Fxaa311Methods();

/// `smaa-low`, `smaa-medium`, `smaa-high`, `smaa-ultra`: SMAA 1x with the reference's
/// presets (methods/smaa.cpp).
std::vector<MethodEntry> SmaaMethods();

/// `cmaa2-low`, `cmaa2-medium`, `cmaa2-high`, `cmaa2-ultra`: Intel CMAA2 quality presets
/// (methods/cmaa2.cpp).
std::vector<MethodEntry> Cmaa2Methods();

/// `scale43`, `scale43-fxaa-high`: render scale with bilinear / bicubic rescale
/// (methods/render_scale.cpp).
std::vector<MethodEntry> RenderScaleMethods();

/// `scale43-easu`, `scale43-easu-rcas`, `scale43-fxaa-high-easu-rcas`, `rcas`: AMD FSR 1
/// EASU upscaling and RCAS sharpening (methods/fsr1.cpp).
std::vector<MethodEntry> Fsr1Methods();

/// `aaa`, `aaa-length`, `aaa-fwidth`, `aaa-smoothstep`, `aaa-sqrt2`, `aaa-inside`,
/// `aaa-fwidth-inside`, `aaa-3d`: analytical AA presets (methods/aaa.cpp).
std::vector<MethodEntry> AaaMethods();
/// `taa`: temporal anti-aliasing with Halton(2,3) jitter, exact reprojection, YCoCg
/// variance clipping and an exponential blend (methods/taa.cpp).
std::vector<MethodEntry> TaaMethods();
/// `taa-prod`: the production TAA, each technique switchable (methods/taa_production.cpp).
std::vector<MethodEntry> TaaProdMethods();
/// `taau-77`, `taau-67`, `taau-59`, `taau-50`: temporal upscaling with the production TAA
/// (methods/taau.cpp).
std::vector<MethodEntry> TaauMethods();
/// Jitter phases of temporal upscaling at output/render `ratio`: ⌊8·ratio²⌋ (FSR 2).
int TaauJitterPhases(double ratio);
/// `fsr2-native`, `fsr2-quality`, `fsr2-balanced`, `fsr2-performance`, `fsr2-ultra-performance`:
/// AMD FSR 2.2.1 on jittered renders at 1/1 .. 1/3 of the output size (methods/fsr2_methods.cpp).
std::vector<MethodEntry> Fsr2Methods();
/// `gsaa`: geometric specular AA of glTF materials (methods/specular_aa.cpp).
std::vector<MethodEntry> SpecularAaMethods();

}  // namespace aalab
