// The byte queue between the two sides of a node: one side produces, the other consumes, with no lock and no
// interrupt masking (single producer, single consumer). A ring node's transmit queue (the program side
// queues own frames, the link side sends them) and a Motion Coordinator's receive buffer (the link side
// stores characters, the program side reads them with GET#) are such queues.
//
// The producer owns `tail_`, the consumer owns `head_` (`single_writer`, see detail/single_writer.hpp). The producer
// may stage bytes past the tail without publishing them, and publishes a whole frame or message at once with
// `publish`, so the consumer never sees part of one. Cost: Capacity (+ Extra) bytes and two indices (one byte
// each up to a capacity of 128, else two bytes); every operation O(1), the bulk ones O(n). No heap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "trionet/detail/attributes.hpp"
#include "trionet/detail/single_writer.hpp"

namespace trionet::detail {

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

/// The smallest unsigned type that holds 0..Max.
template <std::size_t Max>
using index_for = std::conditional_t<Max <= 0xFFu, std::uint8_t, std::uint16_t>;

/// A single-producer, single-consumer byte queue of `Capacity` bytes (see the file comment). `Extra` bytes
/// after the queue's own (`slots()[Capacity ..]`) belong to the producer as scratch space.
template <std::size_t Capacity, std::size_t Extra = 0>
class spsc_fifo {
  static_assert(Capacity >= 1 && Capacity <= 32767, "a queue holds 1..32767 bytes");
  // A power-of-two capacity lets the indices run freely (wrapping at 2^8 or 2^16) and a slot be an index's
  // low bits; any other capacity runs them over 0 .. 2 * Capacity - 1. Either way full and empty differ.
  static constexpr bool power_of_two = (Capacity & (Capacity - 1)) == 0;

 public:
  /// An index of the queue (see above).
  using index = std::conditional_t<power_of_two, index_for<(Capacity <= 128 ? 255 : 65535)>,
                                   index_for<2 * Capacity - 1>>;

  /// How many bytes the queue holds.
  static constexpr std::size_t capacity() noexcept { return Capacity; }

  // ---- the consumer's side ----

  /// Consumer: true when nothing published waits.
  bool empty() const noexcept { return head_.load() == tail_.acquire(); }
  /// Consumer: bytes published and not yet taken.
  std::size_t available() const noexcept { return distance(head_.load(), tail_.acquire()); }
  /// Consumer: takes the oldest byte; false when there is none.
  [[nodiscard]] bool pop(std::uint8_t& byte) noexcept {
    const index head = head_.load();
    if (head == tail_.acquire()) return false;
    byte = data_[slot(head)];
    head_.release(advance(head, 1));
    return true;
  }
  /// Consumer: takes up to `n` of the oldest bytes into `bytes`; returns how many.
  std::size_t pop(std::uint8_t* bytes, std::size_t n) noexcept {
    const index head = head_.load();
    const std::size_t ready = distance(head, tail_.acquire());
    if (n > ready) n = ready;
    const std::size_t at = slot(head);
    const std::size_t first = n < Capacity - at ? n : Capacity - at;
    copy_bytes(bytes, data_ + at, first);
    if (n != first) copy_bytes(bytes + first, data_, n - first);
    head_.release(advance(head, n));
    return n;
  }
  /// Consumer: the oldest bytes that lie contiguously in the buffer; `front_size()` says how many.
  const std::uint8_t* front() const noexcept { return data_ + slot(head_.load()); }
  /// Consumer: how many bytes `front()` shows.
  std::size_t front_size() const noexcept {
    const index head = head_.load();
    const std::size_t ready = distance(head, tail_.acquire());
    const std::size_t to_end = Capacity - slot(head);
    return ready < to_end ? ready : to_end;
  }
  /// Consumer: removes the `n` oldest bytes. Precondition: n <= available().
  void consume(std::size_t n) noexcept {
    TRIONET_ASSERT(n <= available());
    head_.release(advance(head_.load(), n));
  }

  // ---- the producer's side ----

  /// Producer: room for this many more bytes.
  std::size_t free() const noexcept { return Capacity - distance(head_.acquire(), tail_.load()); }
  /// Producer: writes `byte` `k` places after the last published byte, without publishing it.
  /// Precondition: k < free().
  void stage(std::size_t k, std::uint8_t byte) noexcept {
    TRIONET_ASSERT(k < free());
    data_[slot(advance(tail_.load(), k))] = byte;
  }
  /// Producer: writes `n` bytes from `k` places after the last published byte on, without publishing them.
  /// Precondition: k + n <= free(). (A byte at a time: own frames are short, and the code stays small.)
  void stage(std::size_t k, const std::uint8_t* bytes, std::size_t n) noexcept {
    TRIONET_ASSERT(k + n <= free());
    const index tail = tail_.load();
    for (std::size_t i = 0; i < n; ++i) data_[slot(advance(tail, k + i))] = bytes[i];
  }
  /// Producer: hands the next `n` staged bytes to the consumer, all at once. Precondition: n <= free().
  void publish(std::size_t n) noexcept {
    TRIONET_ASSERT(n <= free());
    tail_.release(advance(tail_.load(), n));
  }
  /// Producer: appends a byte; false (and nothing changes) when full.
  [[nodiscard]] bool push(std::uint8_t byte) noexcept {
    if (free() == 0) return false;
    stage(0, byte);
    publish(1);
    return true;
  }

  // ---- raw access for a producer that writes slots itself (the decoder's character window) ----

  /// The buffer: slots 0 .. Capacity - 1 are the queue's, Capacity .. Capacity + Extra - 1 the producer's.
  std::uint8_t* slots() noexcept { return data_; }
  /// The buffer, read-only.
  const std::uint8_t* slots() const noexcept { return data_; }
  /// Producer: the slot that the byte `k` places after the last published one goes into.
  std::size_t staging_slot(std::size_t k) const noexcept { return slot(advance(tail_.load(), k)); }

 private:
  static constexpr std::size_t slot(std::size_t position) noexcept {
    if constexpr (power_of_two) {
      return position & (Capacity - 1);
    } else {
      return position < Capacity ? position : position - Capacity;
    }
  }
  static constexpr index advance(std::size_t position, std::size_t n) noexcept {
    if constexpr (power_of_two) {
      return static_cast<index>(position + n);
    } else {
      const std::size_t next = position + n;
      return static_cast<index>(next < 2 * Capacity ? next : next - 2 * Capacity);
    }
  }
  static constexpr std::size_t distance(std::size_t from, std::size_t to) noexcept {
    if constexpr (power_of_two) {
      return static_cast<index>(to - from);
    } else {
      return to >= from ? to - from : to + 2 * Capacity - from;
    }
  }

  single_writer<index> head_;  // the consumer's
  single_writer<index> tail_;  // the producer's
  std::uint8_t data_[Capacity + Extra] = {};
};

}  // namespace trionet::detail
