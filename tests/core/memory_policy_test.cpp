// core/memory_policy: after KeepFreedMemory, buffers freed by one "call" are reused by the
// next without fresh page faults (the pattern of SMAA's per-call buffers: three blocks of
// 8 MiB live at once, 24 MiB in all, more than glibc's default trims).
#include "core/memory_policy.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <memory>
#include <string>

#include <sys/resource.h>

namespace aalab {
namespace {

long ThreadMinorFaults() {
  rusage u{};
  getrusage(RUSAGE_THREAD, &u);
  return u.ru_minflt;
}

// Allocates `blocks` blocks of `bytes`, writes one byte per 4 KiB page of each, frees them
// (last first); returns the minor page faults this thread took meanwhile.
long FaultsOfOneCall(int blocks, std::size_t bytes) {
  const long before = ThreadMinorFaults();
  std::unique_ptr<std::unique_ptr<char[]>[]> held(new std::unique_ptr<char[]>[static_cast<std::size_t>(blocks)]);
  for (int b = 0; b < blocks; ++b) {
    held[static_cast<std::size_t>(b)].reset(new char[bytes]);
    char* p = held[static_cast<std::size_t>(b)].get();
    for (std::size_t i = 0; i < bytes; i += 4096) p[i] = static_cast<char>(i >> 12);
    asm volatile("" : : "r"(p) : "memory");  // the writes are observable: no elided allocation
  }
  for (int b = blocks - 1; b >= 0; --b) held[static_cast<std::size_t>(b)].reset();
  return ThreadMinorFaults() - before;
}

TEST(MemoryPolicy, TunablesStringCarriesTheSameThresholds) {
  const std::string t = KeepFreedMemoryTunables();
  EXPECT_NE(t.find("glibc.malloc.mmap_threshold=" + std::to_string(kMmapThresholdBytes)), std::string::npos) << t;
  EXPECT_NE(t.find("glibc.malloc.trim_threshold=" + std::to_string(kTrimThresholdBytes)), std::string::npos) << t;
  EXPECT_EQ(kMmapThresholdBytes, std::size_t{33554432});  // glibc's largest M_MMAP_THRESHOLD on 64-bit
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define AALAB_TEST_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define AALAB_TEST_ASAN 1
#endif

// glibc's malloc only: a sanitizer's allocator replaces it (and answers mallopt with 0).
#if defined(__GLIBC__) && !defined(AALAB_TEST_ASAN)
TEST(MemoryPolicy, FreedBuffersAreReusedWithoutFreshPageFaults) {
  ASSERT_TRUE(KeepFreedMemory());
  constexpr int kBlocks = 3;
  constexpr std::size_t kBytes = std::size_t{8} << 20;
  const long pages = static_cast<long>(kBlocks * (kBytes / 4096));  // 6144
  (void)FaultsOfOneCall(kBlocks, kBytes);                           // the first call maps the memory
  for (int call = 0; call < 3; ++call) {
    // glibc's default returns the 24 MiB to the kernel on every free (then ~6144 faults a call).
    EXPECT_LT(FaultsOfOneCall(kBlocks, kBytes), pages / 20) << "call " << call;
  }
}
#endif

}  // namespace
}  // namespace aalab
