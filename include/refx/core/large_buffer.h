// Storage for the large surfaces a frame walks over (render targets, depth buffers,
// decoded texture levels): allocations of 2 MiB and more are mapped on their own,
// aligned to 2 MiB and advised as transparent huge pages, so a frame's accesses to
// them need far fewer TLB entries. Where the kernel gives no huge pages the memory is
// ordinary pages; the contents and the layout are the same either way.
#pragma once
#include <cstddef>
#include <new>
#include <vector>

namespace refx {

namespace detail {
constexpr size_t kHugePageBytes = size_t(2) << 20;
// Maps `bytes` (a multiple of kHugePageBytes), zeroed, aligned to kHugePageBytes.
void* mapHugePages(size_t bytes);
void unmapHugePages(void* p, size_t bytes);
constexpr size_t roundToHugePages(size_t bytes) { return (bytes + kHugePageBytes - 1) & ~(kHugePageBytes - 1); }
}  // namespace detail

template <class T>
struct LargeBufferAllocator {
  using value_type = T;
  LargeBufferAllocator() = default;
  template <class U>
  LargeBufferAllocator(const LargeBufferAllocator<U>&) {}

  T* allocate(size_t n) {
    if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const size_t bytes = n * sizeof(T);
    if (bytes < detail::kHugePageBytes) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(detail::mapHugePages(detail::roundToHugePages(bytes)));
  }
  void deallocate(T* p, size_t n) {
    const size_t bytes = n * sizeof(T);
    if (bytes < detail::kHugePageBytes) ::operator delete(p);
    else detail::unmapHugePages(p, detail::roundToHugePages(bytes));
  }
  template <class U>
  bool operator==(const LargeBufferAllocator<U>&) const { return true; }
};

template <class T>
using LargeBuffer = std::vector<T, LargeBufferAllocator<T>>;

}  // namespace refx
