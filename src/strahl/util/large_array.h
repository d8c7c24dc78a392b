#pragma once
// The large arrays of a scene's way to the renderer — a mesh file's text and its vertices and
// faces, the scene's triangles, and what an acceleration structure's build fills once and keeps
// (nodes, leaf blocks) or throws away (the primitives' boxes): std::vectors whose blocks of 1 MiB
// or more are mapped in 2 MiB pages (util/large_pages.h, allocate_array_bytes()) — one page fault
// per 2 MiB instead of 512: in a virtual machine whose 4 KiB faults cost 10 µs each, a million
// triangles' BVH build spent a fifth of its time in them and built 40 % faster so — and whose
// resize() leaves the new elements default-initialised (no zeroing pass: the build writes every
// element it keeps; a type with member initialisers gets them, hence none in TriangleBlock).

#include <cstddef>
#include <limits>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "strahl/util/large_pages.h"

namespace strahl {

template <class T>
struct LargeArrayAllocator {
  using value_type = T;

  LargeArrayAllocator() = default;
  template <class U>
  LargeArrayAllocator(const LargeArrayAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor): as std::allocator

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_array_bytes(n * sizeof(T), alignof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { free_array_bytes(p, n * sizeof(T), alignof(T)); }

  // resize(n) and the like: default-initialisation (a trivial T keeps whatever the block holds).
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  friend bool operator==(const LargeArrayAllocator&, const LargeArrayAllocator&) { return true; }
};

template <class T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

}  // namespace strahl
