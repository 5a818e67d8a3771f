// A minimal non-owning view of contiguous elements (C++17 has no std::span).
// Cost: two words; no allocation. Safe to use from an ISR.
#pragma once

#include <cstddef>
#include <cstdint>

namespace trionet {

template <class T>
class span {
 public:
  constexpr span() noexcept = default;
  constexpr span(T* data, std::size_t size) noexcept : data_(data), size_(size) {}
  template <std::size_t N>
  constexpr span(T (&array)[N]) noexcept : data_(array), size_(N) {}  // NOLINT: implicit by design
  /// A span of const T from a span of T.
  template <class U>
  constexpr span(span<U> other) noexcept : data_(other.data()), size_(other.size()) {}  // NOLINT

  constexpr T* data() const noexcept { return data_; }
  constexpr std::size_t size() const noexcept { return size_; }
  constexpr bool empty() const noexcept { return size_ == 0; }
  constexpr T& operator[](std::size_t i) const noexcept { return data_[i]; }
  constexpr T* begin() const noexcept { return data_; }
  constexpr T* end() const noexcept { return data_ + size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

using byte_view = span<const std::uint8_t>;
using byte_buffer = span<std::uint8_t>;

}  // namespace trionet
