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

// The smallest block allocate_array_bytes() maps in large pages: glibc's malloc maps every block
// this large afresh anyway (its mmap threshold grows with the blocks freed, but never past 32 MiB
// on 64-bit systems), so mapping it in large pages costs no reuse of warm freed memory — which
// smaller blocks would lose (docs/benchmark.md, "Nineteenth session" and "Twentieth session").
inline constexpr std::size_t kFreshBlock = std::size_t(32) << 20;

// `bytes` (> 0) bytes aligned to `align` (a power of two up to kLargePage), not initialised
// (a block mapped afresh reads as zeros): from kFreshBlock bytes on mapped in large pages like
// allocate_zeroed_bytes(), below from operator new. Throws std::bad_alloc.
void* allocate_array_bytes(std::size_t bytes, std::size_t align);

// Frees a block from allocate_array_bytes(bytes, align) (nullptr: nothing).
void free_array_bytes(void* p, std::size_t bytes, std::size_t align) noexcept;

// Whether this build maps large blocks in large pages (Linux with transparent huge pages, no
// sanitizer), and whether the environment lets it (STRAHL_LARGE_PAGES, read once, at the first call).
bool large_pages_supported();
bool large_pages_enabled();

}  // namespace strahl
