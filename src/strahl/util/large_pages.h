#pragma once
// Fresh, zeroed memory for large arrays (util/zeroed_array.h), in 2 MiB pages where the kernel
// offers them. A block of kLargeBlock bytes or more is mapped on its own, aligned to kLargePage,
// and advised for transparent huge pages (Linux's MADV_HUGEPAGE: the default "madvise" setting
// of /sys/kernel/mm/transparent_hugepage/enabled backs only such blocks with 2 MiB pages); its
// first touch then costs one page fault per 2 MiB. Smaller blocks, other systems and the
// sanitizer builds (whose checks need their allocator) take calloc's memory, and so does every
// block when the environment variable STRAHL_LARGE_PAGES is 0 or off (docs/cli.md, "Environment":
// a fresh large page can cost more than its 512 small ones on a host that has to back it anew).

#include <cstddef>

namespace strahl {

inline constexpr std::size_t kLargePage = std::size_t(2) << 20;
// The smallest block mapped in large pages: from here one large page costs less than the 4 KiB
// pages' faults (256 of them, 2.6 ms in a virtual machine where each costs 10 µs), and rounding up
// to whole large pages adds at most as much as the block holds.
inline constexpr std::size_t kLargeBlock = std::size_t(1) << 20;

// `bytes` (> 0) zeroed bytes, aligned to kLargePage when mapped on their own; throws
// std::bad_alloc when there is no memory.
void* allocate_zeroed_bytes(std::size_t bytes);

// Frees a block from allocate_zeroed_bytes(bytes) (nullptr: nothing).
void free_zeroed_bytes(void* p, std::size_t bytes) noexcept;

// Whether allocate_zeroed_bytes(bytes) maps the block on its own in large pages.
bool maps_large_pages(std::size_t bytes);

// `bytes` (> 0) bytes aligned to `align` (a power of two up to kLargePage), not initialised
// (a block mapped afresh reads as zeros): from kLargeBlock bytes on mapped in large pages like
// allocate_zeroed_bytes(), below from operator new. Throws std::bad_alloc.
// Until 2026-12-05 only blocks of 32 MiB or more were mapped, so that smaller ones would reuse
// the heap's warm, freed memory between builds; but a first build (the CLI's only one) faulted every 4 KiB
// page of them, at 10 µs a fault in a virtual machine: the dragon's load and build took 0.20 s, of
// which 0.14 s were page faults (docs/benchmark.md, "Twenty-fifth session"). A fresh 2 MiB page
// costs about 60 µs, so repeated builds lose little; a block's last large page is rounded up
// (at most 2 MiB resident beyond the block).
void* allocate_array_bytes(std::size_t bytes, std::size_t align);

// Frees a block from allocate_array_bytes(bytes, align) (nullptr: nothing).
void free_array_bytes(void* p, std::size_t bytes, std::size_t align) noexcept;

// Whether this build maps large blocks in large pages (Linux with transparent huge pages, no
// sanitizer), and whether the environment lets it (STRAHL_LARGE_PAGES, read once, at the first call).
bool large_pages_supported();
bool large_pages_enabled();

// Gives the heap's free memory back to the system (glibc's malloc_trim; elsewhere nothing). The
// scene loader calls it once the parser's trees are freed: the build's large arrays are mapped
// afresh (above), so without it they would stack on that garbage instead of reusing it, and the
// peak resident memory would grow by it (a YAML file of 50,000 spheres: ~4 MiB).
void give_back_free_heap() noexcept;

}  // namespace strahl
