/// The process's allocator policy: freed memory kept for the next allocation instead of
/// returned to the kernel (core/memory_policy.cpp says why and what it costs).
#pragma once
#include <cstddef>

namespace aalab {

/// glibc's malloc thresholds that KeepFreedMemory sets.
inline constexpr std::size_t kMmapThresholdBytes = std::size_t{32} << 20;  ///< glibc's largest allowed
inline constexpr std::size_t kTrimThresholdBytes = std::size_t{1} << 30;

/// Makes glibc's malloc serve every block below kMmapThresholdBytes (a 1080p RGBA8 image is
/// 8.3 MB) from its heaps and keep freed heap memory unless more than kTrimThresholdBytes is
/// free at the top, so that a buffer freed by one call is reused by the next without the
/// kernel mapping fresh zeroed pages again. Call once, first thing in main(), before threads
/// start. Returns false where the C library has no such setting (not glibc) or refused it.
/// Values and outputs never depend on it; only the time spent in page faults does.
bool KeepFreedMemory();

/// The GLIBC_TUNABLES value with the same policy, for child processes (make bench's peers).
const char* KeepFreedMemoryTunables();

}  // namespace aalab
