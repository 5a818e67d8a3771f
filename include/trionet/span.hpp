// A minimal non-owning view of contiguous elements (C++17 has no std::span).
// Cost: two words; no allocation. Safe to use from an ISR.
#pragma once

#include <cstddef>
#include <cstdint>

namespace trionet {

/// A non-owning view of `size()` contiguous elements of type `T` starting at `data()` (C++17 has no
/// std::span). Cost: two words; safe in an ISR.
template <class T>
class span {
 public:
  constexpr span() noexcept = default;
  /// A view of `size` elements starting at `data`.
  constexpr span(T* data, std::size_t size) noexcept : data_(data), size_(size) {}
  template <std::size_t N>
  /// A view of a whole array (implicit, so that an array can be passed where a span is expected).
  constexpr span(T (&array)[N]) noexcept : data_(array), size_(N) {}  // NOLINT: implicit by design
  /// A span of const T from a span of T.
  template <class U>
  constexpr span(span<U> other) noexcept : data_(other.data()), size_(other.size()) {}  // NOLINT

  constexpr T* data() const noexcept { return data_; }           ///< the first element
  constexpr std::size_t size() const noexcept { return size_; }  ///< the number of elements
  constexpr bool empty() const noexcept { return size_ == 0; }   ///< true when there is no element
  constexpr T& operator[](std::size_t i) const noexcept { return data_[i]; }  ///< element `i` (unchecked)
  constexpr T* begin() const noexcept { return data_; }        ///< for range-for: the first element
  constexpr T* end() const noexcept { return data_ + size_; }  ///< for range-for: one past the last

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

using byte_view = span<const std::uint8_t>;  ///< bytes to read
using byte_buffer = span<std::uint8_t>;      ///< bytes to write

}  // namespace trionet
