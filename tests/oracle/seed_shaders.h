// The original FXAA shaders, read at test time from the project's source documents
// (../shared/seeds): never copied into the repository.
#pragma once
#include <optional>
#include <string>

namespace aalab::oracle {

/// Where the seeds are: $AALAB_SEEDS_DIR if set, else <source dir>/../shared/seeds.
std::string SeedsDir();

/// True when SeedsDir() is a directory.
bool SeedsPresent();

/// The fragment shader "FXAA-interactive.fs" of FrostKiwi's "Analytical Anti-Aliasing"
/// (seed 004): the full FXAA 3.11 PC quality shader with every preset, GLSL ES 1.00 style,
/// expecting FXAA_QUALITY_PRESET / FXAA_GREEN_AS_LUMA / FXAA_ENABLE / FXAA_LUMA defines.
/// Found by its markers in whichever seed file holds it; throws std::runtime_error naming
/// the missing marker when no seed file has it.
std::string Fxaa311InteractiveShader();

/// The GLSL "FXAA with 12 iterations" of seed 003 (#version 430 core, from "#version" to
/// the closing brace of main). Throws std::runtime_error naming the missing marker.
std::string Iter12Shader();

}  // namespace aalab::oracle
