/// Loads io/'s OpenImageIO module (aalab_io_oiio, io/oiio_module.cpp) on first use. Internal
/// to io/. Where it looks, in order: the file named by AALAB_IO_OIIO_MODULE; next to the
/// running executable (/proc/self/exe's folder); the build tree's copy, a path compiled in
/// from CMake (AALAB_IO_OIIO_MODULE_BUILD_PATH), for the test executables in subfolders.
#pragma once
#include <string>

#include "io/image_decoder.h"

namespace aalab::io_detail {

/// The module's file name.
inline constexpr const char* kOiioModuleFile = "libaalab_io_oiio.so";
/// The environment variable that names the module's file, overriding the search.
inline constexpr const char* kOiioModuleVariable = "AALAB_IO_OIIO_MODULE";

/// The module's entry points, loaded once (thread-safe). `what` says what needs it, e.g.
/// "image 'a.exr' (.exr)"; UserError naming it, the module and the places looked in when the
/// module cannot be loaded.
const OiioModuleApi& OiioModule(const std::string& what);

/// Whether the module has been loaded by this process (tests: PNG work must not load it).
bool OiioModuleLoaded();

}  // namespace aalab::io_detail
