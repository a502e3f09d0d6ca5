/// The allocator policy of the bench programs: aalab's own (core/memory_policy.h, freed memory
/// kept for reuse), so that a figure is what the filter or metric costs inside `aalab run`;
/// AALAB_BENCH_DEFAULT_MALLOC=1 in the environment keeps glibc's default instead (for an A/B
/// of the policy itself). Call first thing in main().
#pragma once
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/memory_policy.h"

namespace aalab::bench {

/// Applies the policy unless AALAB_BENCH_DEFAULT_MALLOC=1; returns which, in words.
inline const char* ApplyBenchMemoryPolicy() {
  const char* env = std::getenv("AALAB_BENCH_DEFAULT_MALLOC");
  if (env != nullptr && std::strcmp(env, "1") == 0)
    return "glibc's default malloc policy (AALAB_BENCH_DEFAULT_MALLOC=1)";
  return KeepFreedMemory() ? "aalab's malloc policy (freed memory kept: core/memory_policy.h)"
                           : "glibc's default malloc policy (the C library refused aalab's)";
}

/// The environment a peer process (scikit-image, NVIDIA's FLIP tool) runs with: the same
/// allocator policy as aalab's side ("GLIBC_TUNABLES=... "), so that the comparison is of
/// the computations and not of how often each side makes the kernel map fresh pages; empty
/// under AALAB_BENCH_DEFAULT_MALLOC=1.
inline std::string PeerEnvPrefix() {
  const char* env = std::getenv("AALAB_BENCH_DEFAULT_MALLOC");
  if (env != nullptr && std::strcmp(env, "1") == 0) return "";
  return std::string("GLIBC_TUNABLES=") + KeepFreedMemoryTunables() + " ";
}

}  // namespace aalab::bench
