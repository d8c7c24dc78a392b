#include "strahl/util/large_pages.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif
#if defined(__GLIBC__)
#include <malloc.h>
#endif

// Whether this build maps large blocks itself: Linux with transparent huge pages, not under a
// sanitizer (whose checks need its own allocator's blocks).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define STRAHL_SANITIZED_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define STRAHL_SANITIZED_ALLOCATOR 1
#endif
#endif
#if defined(__linux__) && defined(MADV_HUGEPAGE) && !defined(STRAHL_SANITIZED_ALLOCATOR)
#define STRAHL_MAPS_LARGE_PAGES 1
#endif

namespace strahl {

namespace {

#if defined(STRAHL_MAPS_LARGE_PAGES)
// The block's length rounded up to whole large pages.
std::size_t mapped_length(std::size_t bytes) { return (bytes + kLargePage - 1) / kLargePage * kLargePage; }
#endif

}  // namespace

bool large_pages_supported() {
#if defined(STRAHL_MAPS_LARGE_PAGES)
  return true;
#else
  return false;
#endif
}

bool large_pages_enabled() {
  static const bool enabled = [] {
    const char* v = std::getenv("STRAHL_LARGE_PAGES");
    return v == nullptr || !(std::strcmp(v, "0") == 0 || std::strcmp(v, "off") == 0);
  }();
  return enabled;
}

bool maps_large_pages(std::size_t bytes) {
#if defined(STRAHL_MAPS_LARGE_PAGES)
  return bytes >= kLargeBlock && bytes <= std::size_t(-1) - 2 * kLargePage && large_pages_enabled();
#else
  (void)bytes;
  return false;
#endif
}

void* allocate_zeroed_bytes(std::size_t bytes) {
#if defined(STRAHL_MAPS_LARGE_PAGES)
  if (maps_large_pages(bytes)) {
    // One large page more than needed, then the part before the first aligned address and the
    // part after the block given back: an aligned block of whole large pages.
    const std::size_t length = mapped_length(bytes);
    void* raw = mmap(nullptr, length + kLargePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (start + kLargePage - 1) & ~std::uintptr_t(kLargePage - 1);
    if (aligned > start) munmap(raw, aligned - start);
    const std::uintptr_t end = start + length + kLargePage;
    if (end > aligned + length) munmap(reinterpret_cast<void*>(aligned + length), end - (aligned + length));
    void* p = reinterpret_cast<void*>(aligned);
    madvise(p, length, MADV_HUGEPAGE);  // advice: without it (THP off) the block is 4 KiB pages
    return p;
  }
#endif
  void* p = std::calloc(bytes, 1);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

void free_zeroed_bytes(void* p, std::size_t bytes) noexcept {
  if (p == nullptr) return;
#if defined(STRAHL_MAPS_LARGE_PAGES)
  if (maps_large_pages(bytes)) {
    munmap(p, mapped_length(bytes));
    return;
  }
#endif
  (void)bytes;
  std::free(p);
}

namespace {

// Whether allocate_array_bytes(bytes) maps the block (and free_array_bytes unmaps it): one rule for both.
bool maps_array(std::size_t bytes) { return maps_large_pages(bytes); }

}  // namespace

void* allocate_array_bytes(std::size_t bytes, std::size_t align) {
  if (maps_array(bytes)) return allocate_zeroed_bytes(bytes);
  return ::operator new(bytes, std::align_val_t(align));
}

void free_array_bytes(void* p, std::size_t bytes, std::size_t align) noexcept {
  if (p == nullptr) return;
  if (maps_array(bytes)) return free_zeroed_bytes(p, bytes);
  ::operator delete(p, std::align_val_t(align));
}

void give_back_free_heap() noexcept {
#if defined(__GLIBC__) && !defined(STRAHL_SANITIZED_ALLOCATOR)
  malloc_trim(0);
#endif
}

}  // namespace strahl
