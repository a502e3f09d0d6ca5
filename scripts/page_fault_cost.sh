#!/usr/bin/env bash
# What a first-touch page fault costs on this machine (docs/performance.md, #41): maps 64 MiB
# of anonymous memory and writes one byte per 4 KiB page, then memsets the mapped memory, five
# rounds; then the same first touch after madvise(MADV_HUGEPAGE). Prints µs per 4 KiB page.
# Usage: scripts/page_fault_cost.sh   (needs cc)
set -euo pipefail
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cat > "$dir/probe.c" <<'C'
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>
static double ms(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}
int main(void) {
  const size_t n = (size_t)64 << 20, huge = (size_t)2 << 20;
  for (int huge_pages = 0; huge_pages <= 1; ++huge_pages) {
    for (int r = 0; r < 5; ++r) {
      char* q = mmap(0, n + huge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (q == MAP_FAILED) return 1;
      char* p = (char*)(((uintptr_t)q + huge - 1) & ~(uintptr_t)(huge - 1));
      if (huge_pages) madvise(p, n, MADV_HUGEPAGE);
      const double t0 = ms();
      for (size_t i = 0; i < n; i += 4096) p[i] = 1;
      const double t1 = ms();
      memset(p, 2, n);
      const double t2 = ms();
      munmap(q, n + huge);
      printf("%s round %d: first touch of 64 MiB %.1f ms (%.2f us per 4 KiB page); memset once mapped %.1f ms\n",
             huge_pages ? "MADV_HUGEPAGE" : "4 KiB pages  ", r + 1, t1 - t0, (t1 - t0) * 1e3 / (double)(n / 4096),
             t2 - t1);
    }
  }
  return 0;
}
C
cc -O2 -o "$dir/probe" "$dir/probe.c"
uname -r
"$dir/probe"
