// A fixed-capacity byte FIFO: the buffers of the ring nodes (forward buffer, transmit queue, receive buffer).
// Cost: Capacity bytes + 4 bytes of indices; every operation O(1) except `drop_back` (O(1) too). No heap.
// Not synchronised: the owner decides which context (ISR or main loop) touches it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace trionet {

namespace detail {
/// std::memcpy for the short runs a node moves (part of a message, a variable transfer, a DMA chunk): on
/// 64-bit cores, 8 to 16 bytes as two overlapping words inline, which beats a library call. `to` and `from`
/// do not overlap.
inline void copy_bytes(std::uint8_t* to, const std::uint8_t* from, std::size_t n) noexcept {
#if UINTPTR_MAX > 0xFFFFFFFFu
  if (n >= 8 && n <= 16) {
    std::uint64_t first;
    std::uint64_t last;
    std::memcpy(&first, from, sizeof first);
    std::memcpy(&last, from + (n - 8), sizeof last);
    std::memcpy(to, &first, sizeof first);
    std::memcpy(to + (n - 8), &last, sizeof last);
    return;
  }
#endif
  std::memcpy(to, from, n);
}
}  // namespace detail

template <std::size_t Capacity>
class byte_fifo {
  static_assert(Capacity >= 1 && Capacity <= 65535, "a byte FIFO holds 1..65535 bytes");

 public:
  static constexpr std::size_t capacity() noexcept { return Capacity; }
  std::size_t size() const noexcept { return size_; }
  std::size_t free() const noexcept { return Capacity - size_; }
  bool empty() const noexcept { return size_ == 0; }

  /// Appends a byte; false (and nothing changes) when full.
  [[nodiscard]] bool push(std::uint8_t byte) noexcept {
    if (size_ == Capacity) return false;
    data_[wrap(head_ + size_)] = byte;
    ++size_;
    return true;
  }

  /// Takes the oldest byte; false when empty.
  [[nodiscard]] bool pop(std::uint8_t& byte) noexcept {
    if (size_ == 0) return false;
    byte = data_[head_];
    head_ = static_cast<std::uint16_t>(wrap(head_ + 1u));
    --size_;
    return true;
  }

  /// Appends as many of `n` bytes as fit (all or a prefix); returns how many. O(n).
  std::size_t push(const std::uint8_t* bytes, std::size_t n) noexcept {
    if (n > Capacity - size_) n = Capacity - size_;
    const std::size_t tail = wrap(head_ + size_);
    const std::size_t first = n < Capacity - tail ? n : Capacity - tail;
    detail::copy_bytes(data_ + tail, bytes, first);
    if (n != first) detail::copy_bytes(data_, bytes + first, n - first);
    size_ = static_cast<std::uint16_t>(size_ + n);
    return n;
  }

  /// Takes up to `n` of the oldest bytes into `bytes`; returns how many. O(n).
  std::size_t pop(std::uint8_t* bytes, std::size_t n) noexcept {
    if (n > size_) n = size_;
    const std::size_t first = n < Capacity - head_ ? n : Capacity - head_;
    detail::copy_bytes(bytes, data_ + head_, first);
    if (n != first) detail::copy_bytes(bytes + first, data_, n - first);
    consume(n);
    return n;
  }

  /// The oldest bytes that lie contiguously in the buffer (all of them unless they wrap round).
  const std::uint8_t* front() const noexcept { return data_ + head_; }
  std::size_t front_size() const noexcept { return size_ < Capacity - head_ ? size_ : Capacity - head_; }
  /// Removes the `n` oldest bytes. Precondition: n <= size().
  void consume(std::size_t n) noexcept {
    head_ = static_cast<std::uint16_t>(wrap(head_ + n));
    size_ = static_cast<std::uint16_t>(size_ - n);
  }

  /// The byte `i` places from the oldest (0 = the oldest). Precondition: i < size().
  std::uint8_t& at(std::size_t i) noexcept { return data_[wrap(head_ + i)]; }
  /// The most recently pushed byte. Precondition: !empty().
  std::uint8_t& back() noexcept { return at(size_ - 1u); }

  /// Removes the `n` most recently pushed bytes (at most size()).
  void drop_back(std::size_t n) noexcept { size_ = static_cast<std::uint16_t>(n >= size_ ? 0 : size_ - n); }

 private:
  static std::size_t wrap(std::size_t index) noexcept { return index >= Capacity ? index - Capacity : index; }

  std::uint8_t data_[Capacity] = {};
  std::uint16_t head_ = 0;
  std::uint16_t size_ = 0;
};

}  // namespace trionet
