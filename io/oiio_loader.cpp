// dlopen() of io/'s OpenImageIO module (io/oiio_loader.h).
#include "io/oiio_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "core/error.h"

#ifndef AALAB_IO_OIIO_MODULE_BUILD_PATH
#define AALAB_IO_OIIO_MODULE_BUILD_PATH ""
#endif

namespace aalab::io_detail {
namespace {

std::atomic<bool> g_loaded{false};

std::string ExeDir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

/// The module's entry points, or nullptr with `tried` listing what failed.
const OiioModuleApi* Load(std::string* tried) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv(kOiioModuleVariable); env && *env) {
    candidates.push_back(env);  // set: the only place looked in
  } else {
    if (const std::string dir = ExeDir(); !dir.empty()) candidates.push_back(dir + "/" + kOiioModuleFile);
    if (*AALAB_IO_OIIO_MODULE_BUILD_PATH) candidates.push_back(AALAB_IO_OIIO_MODULE_BUILD_PATH);
  }
  for (const auto& path : candidates) {
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = ::dlerror();
      *tried += (tried->empty() ? "" : "; ") + path + ": " + (why ? why : "cannot be loaded");
      continue;
    }
    using Entry = const OiioModuleApi* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, kOiioModuleSymbol));
    const OiioModuleApi* api = entry ? entry() : nullptr;
    if (!api || api->abi_version != kOiioModuleAbi) {
      *tried += (tried->empty() ? "" : "; ") + path + ": not this aalab's module (rebuild it)";
      continue;  // the handle stays open: harmless, and unloading code is never safe here
    }
    return api;
  }
  return nullptr;
}

}  // namespace

const OiioModuleApi& OiioModule(const std::string& what) {
  static std::once_flag once;
  static const OiioModuleApi* api = nullptr;
  static std::string tried;
  std::call_once(once, [] {
    api = Load(&tried);
    g_loaded = api != nullptr;
  });
  if (!api) {
    throw UserError(what + " needs OpenImageIO, which aalab loads from its module " + kOiioModuleFile +
                    " (built with aalab, beside the executable); it could not be loaded (" +
                    (tried.empty() ? std::string("no place to look") : tried) + "); set " + kOiioModuleVariable +
                    "=PATH to name it, or rebuild aalab (PNG files need no module)");
  }
  return *api;
}

bool OiioModuleLoaded() { return g_loaded.load(); }

}  // namespace aalab::io_detail
