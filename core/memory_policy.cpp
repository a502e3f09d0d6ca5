// The allocator policy of aalab's programs: freed memory kept for reuse.
//
// Why: by default glibc returns large freed blocks to the kernel (blocks of at least the
// dynamic mmap threshold are unmapped on free; the heap's top is trimmed once more than twice
// that threshold is free), so a filter that allocates its buffers per call (SMAA: an edge
// plane, a blend texture and the output, 18 MB for 1080p) gets freshly mapped pages every
// call, and the first write to each 4 KiB page is a page fault. On the machine `make bench`
// runs on (a Firecracker VM, kernel 6.18 "fc", paravirtualised MMU) one such fault costs
// about 12 µs (measured: /tmp-style probe touching 64 MiB of fresh anonymous memory, 196–318
// ms, i.e. 12–19 µs per page, against 3 ms to memset the same memory once mapped), so SMAA's
// 4.4k faults per 1080p call cost ~60 ms of its ~70 ms (docs/performance.md, the #41 table).
//
// What: M_MMAP_THRESHOLD = 32 MiB (glibc's maximum; fixed, which also turns off the dynamic
// threshold) and M_TRIM_THRESHOLD = 1 GiB. Cost: freed memory stays resident until the
// process ends, so the resident size stays at its high-water mark (which is what a peak
// measures anyway); the default run's peak was measured with and without (the #41 table).
#include "core/memory_policy.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace aalab {

bool KeepFreedMemory() {
#if defined(__GLIBC__)
  const bool mmap_ok = mallopt(M_MMAP_THRESHOLD, static_cast<int>(kMmapThresholdBytes)) == 1;
  const bool trim_ok = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kTrimThresholdBytes)) == 1;
  return mmap_ok && trim_ok;
#else
  return false;
#endif
}

const char* KeepFreedMemoryTunables() {
  return "glibc.malloc.mmap_threshold=33554432:glibc.malloc.trim_threshold=1073741824";
}

}  // namespace aalab
