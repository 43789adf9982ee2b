// Vectors of per-body, per-joint and per-contact records on transparent huge pages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace softstep {

// The size of a transparent huge page on x86-64 Linux.
inline constexpr std::size_t kHugePage = std::size_t{2} << 20;

// Allocates blocks of at least one huge page aligned to it and asks Linux to back them with
// huge pages (madvise MADV_HUGEPAGE, honoured where /sys/kernel/mm/transparent_hugepage/enabled
// is "madvise" or "always", as on Debian 12) before anything touches them; smaller blocks as
// std::allocator. Why: a step walks every body's, joint's and contact's record, and with 4 KB
// pages a 100,000-link chain's 130 MB miss the TLB on nearly every record (each miss a page
// walk, a long one in a VM). The same binary with every allocation on huge pages
// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1) stepped the README's main job 7-16 % faster
// (5 runs alternated, one thread, a Zen 4 VM).
// A block wastes less than one huge page; where madvise fails the block is an ordinary one.
template <class T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  // Below PTRDIFF_MAX with room to round up to a whole huge page.
  static constexpr std::size_t kMostBytes =
      std::size_t{PTRDIFF_MAX} / kHugePage * kHugePage - kHugePage;

  static bool paged(std::size_t n) { return n * sizeof(T) >= kHugePage; }

  T* allocate(std::size_t n) {
    if (!paged(n)) return std::allocator<T>{}.allocate(n);
    if (n > kMostBytes / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = (n * sizeof(T) + kHugePage - 1) / kHugePage * kHugePage;
    void* block = std::aligned_alloc(kHugePage, bytes);
    if (block == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(block, bytes, MADV_HUGEPAGE);  // advice: an ordinary block where refused
#endif
    return static_cast<T*>(block);
  }

  void deallocate(T* block, std::size_t n) noexcept {
    if (!paged(n)) {
      std::allocator<T>{}.deallocate(block, n);
      return;
    }
    std::free(block);
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using PagedVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace softstep
