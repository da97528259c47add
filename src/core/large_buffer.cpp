#include "refx/core/large_buffer.h"

#include <cstdint>

#include <sys/mman.h>

namespace refx::detail {

void* mapHugePages(size_t bytes) {
  // One huge page more than asked, then the unaligned head and tail unmapped.
  const size_t mapped = bytes + kHugePageBytes;
  void* m = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t base = reinterpret_cast<uintptr_t>(m);
  const uintptr_t aligned = (base + kHugePageBytes - 1) & ~uintptr_t(kHugePageBytes - 1);
  if (aligned > base) munmap(m, aligned - base);
  const uintptr_t end = base + mapped, used = aligned + bytes;
  if (end > used) munmap(reinterpret_cast<void*>(used), end - used);
#ifdef MADV_HUGEPAGE
  // Advice only: without transparent huge pages the mapping keeps ordinary pages.
  madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
#endif
  return reinterpret_cast<void*>(aligned);
}

void unmapHugePages(void* p, size_t bytes) { munmap(p, bytes); }

}  // namespace refx::detail
