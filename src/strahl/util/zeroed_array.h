#pragma once
// An array of n values that start as all-zero bytes, in fresh pages that the kernel supplies
// already zeroed on first touch, so creating the array writes nothing. The film's sums and
// statistics, the image and the render job's per-pixel counts (tens of MiB at 1080p) are such
// arrays: their page faults happen where the tiles are first merged and the image resolved, in
// the threads that do it, instead of all at once before the first tile.
//
// A block of 1 MiB or more is mapped in whole 2 MiB pages where the kernel offers them
// (util/large_pages.h): one page fault per 2 MiB instead of 512. In some virtual machines a 4 KiB
// page fault costs 10 µs: there a 1080p film's 66 MiB of sums took 178 ms of faults in 4 KiB
// pages and 3–6 ms in 2 MiB ones (docs/benchmark.md, "Seventeenth session").

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "strahl/util/large_pages.h"

namespace strahl {

template <class T>
class ZeroedArray {
  // Copies are memcpy, so T must be trivially copyable. That all-zero bytes are a value of T (and
  // the value zero) is the user's promise, which no trait can check: it holds for the arithmetic
  // types and the aggregates of them stored here (double, std::int64_t, Rgb, PixelStats).
  static_assert(std::is_trivially_copyable_v<T>, "ZeroedArray copies with memcpy: T must be trivially copyable");

 public:
  ZeroedArray() = default;
  explicit ZeroedArray(std::size_t n) : data_(allocate(n)), size_(n) {}
  ZeroedArray(const ZeroedArray& o) : data_(allocate(o.size_)), size_(o.size_) {
    if (size_ > 0) std::memcpy(data_.get(), o.data_.get(), size_ * sizeof(T));
  }
  // A moved-from array is empty, as a moved-from std::vector is.
  ZeroedArray(ZeroedArray&& o) noexcept : data_(std::move(o.data_)), size_(std::exchange(o.size_, 0)) {}
  ZeroedArray& operator=(const ZeroedArray& o) { return *this = ZeroedArray(o); }
  ZeroedArray& operator=(ZeroedArray&& o) noexcept {
    data_ = std::move(o.data_);
    size_ = std::exchange(o.size_, 0);
    return *this;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  T& operator[](std::size_t i) { return data_.get()[i]; }
  const T& operator[](std::size_t i) const { return data_.get()[i]; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }
  friend bool operator==(const ZeroedArray& a, const ZeroedArray& b) {
    if (a.size_ != b.size_) return false;
    for (std::size_t i = 0; i < a.size_; ++i)
      if (!(a[i] == b[i])) return false;
    return true;
  }
  const T& at(std::size_t i) const {
    if (i >= size_) throw std::out_of_range("ZeroedArray::at");
    return data_.get()[i];
  }

 private:
  // Frees a block of `bytes` bytes from allocate().
  struct Free {
    std::size_t bytes = 0;
    void operator()(T* p) const { free_zeroed_bytes(p, bytes); }
  };
  static std::unique_ptr<T, Free> allocate(std::size_t n) {
    if (n == 0) return {nullptr, Free{}};
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
    const std::size_t bytes = n * sizeof(T);
    return {static_cast<T*>(allocate_zeroed_bytes(bytes)), Free{bytes}};
  }
  std::unique_ptr<T, Free> data_;
  std::size_t size_ = 0;
};

}  // namespace strahl
