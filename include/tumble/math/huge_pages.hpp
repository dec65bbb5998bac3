#pragma once
// Large arrays on transparent huge pages, where the kernel offers them on request.
//
// The first touch of each fresh 4 KiB page costs a page fault: 0.1–0.3 µs on bare metal, but 2–16 µs
// on the virtual machines tumble is measured on (bench/scene_setup prints it), where a scene of 10⁵
// bodies touches ~40 000 pages and their faults cost more than reading the scene or stepping it.
// Linux's default is to give huge pages (one fault per 2 MiB) only to memory a program asks them for
// ("madvise" in /sys/kernel/mm/transparent_hugepage/enabled), so tumble asks for the large arrays a
// scene is read into and its outputs are made from, which are touched once or a few times. Not for
// the engine's columns, which every step reads: there huge pages made stepping 10⁵ bodies 5–20 %
// slower on the virtual machine measured (bench/results/amd-epyc-avx512/batch_throughput_stop3_ab.txt),
// more than their faults cost. A hint only: where the kernel lacks huge pages, nothing changes.
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tumble {

/// Advises the kernel to back the 2 MiB pages that [p, p + bytes) touches with huge pages, before they
/// are first touched; ranges under 1 MiB are left alone. The pages are rounded outwards: a large
/// allocation is malloc's own mapping, which the kernel aligns to 2 MiB, and its first page starts
/// just before p (malloc's header); where the range shares a page with other memory, that memory
/// gets the hint too, which changes nothing but how it is mapped.
inline void prefer_huge_pages(const void* p, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  if (bytes < kHuge / 2) return;
  const auto start = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t begin = start & ~(kHuge - 1);
  const std::uintptr_t end = (start + bytes + kHuge - 1) & ~(kHuge - 1);
  // A hint: where part of the range is not mapped, the rest still gets it (ENOMEM is ignored).
  ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

/// The same for a vector's reserved storage.
template <class T>
void prefer_huge_pages(const std::vector<T>& v) noexcept {
  prefer_huge_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace tumble
