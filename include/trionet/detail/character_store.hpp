// Where a ring decoder keeps the data of the message it is receiving (ring/decoder.hpp): the character stores.
//
// A character store holds the data of the message being received, in slots that the decoder writes itself
// (so that the decoder's per-byte path is one comparison and one store), and keeps a character transfer's
// characters only if the message turns out valid:
//   std::uint8_t* slots();                      // the store's bytes
//   static constexpr std::size_t payload_at;    // slots [payload_at, payload_at + 14): the data of a message
//                                               // of another type (at most 14 bytes are kept)
//   store_window begin();                       // a character transfer begins: where its characters go
//   store_window next(std::size_t stored);      // the window is used up after `stored` characters: where the
//                                               // next go (the store may wrap round), or no room
//   byte_view commit(std::size_t length);       // the message is valid: keep it (a view of it, or empty if the
//                                               // characters are not contiguous)
//   byte_view text(std::size_t length) const;   // the message just committed, as `commit` returned it
//   void abort();                               // the message is discarded
// `character_buffer` is a plain array (a decoded message's text is contiguous); a Motion Coordinator's
// `receive_buffer` stages characters straight into the queue GET# reads, so no message is held twice.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/detail/fifo.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/span.hpp"

namespace trionet::detail {

/// Where a character store lets the decoder write: slots [first, end) of the store's `slots()`.
struct store_window {
  std::uint16_t first = 0;  ///< the first slot
  std::uint16_t end = 0;    ///< one past the last slot (first == end: no room)
};

/// The default character store: a plain array of N characters (at least the 14 bytes of a direct variable
/// transfer's data).
template <std::size_t N>
class character_buffer {
  static_assert(N >= 1 && N < 65535, "a character buffer holds 1..65534 characters");

 public:
  /// Where the data of a message of type 2..7 goes.
  static constexpr std::size_t payload_at = 0;
  /// The store's bytes.
  std::uint8_t* slots() noexcept { return data_; }
  /// The store's bytes, read-only.
  const std::uint8_t* slots() const noexcept { return data_; }
  /// A character transfer begins: all N slots.
  store_window begin() noexcept { return {0, static_cast<std::uint16_t>(N)}; }
  /// The N slots are used up: no more room.
  static store_window next(std::size_t) noexcept { return {}; }
  /// The first `length` slots hold the message.
  byte_view commit(std::size_t length) noexcept { return text(length); }
  /// The message just committed.
  byte_view text(std::size_t length) const noexcept { return byte_view(data_, length); }
  /// Nothing to forget: the next message starts again at slot 0.
  static void abort() noexcept {}

 private:
  std::uint8_t data_[N < ring::variable_data_length ? ring::variable_data_length : N] = {};
  static_assert(payload_at + ring::variable_data_length <= sizeof data_, "a variable transfer's data fits the store");
};

/// A Motion Coordinator's receive buffer as the decoder's character store: a single-producer, single-consumer
/// queue from the link side (the decoder stages a message's characters past its tail and publishes them only
/// if the whole message is valid and fits: all or nothing) to the program side (KEY#, GET#). The 14 bytes
/// after the queue hold the data of the other message types.
template <std::size_t Capacity>
class receive_buffer {
 public:
  /// Where the data of a message of type 2..7 goes.
  static constexpr std::size_t payload_at = Capacity;

  /// Link side: the store's bytes.
  std::uint8_t* slots() noexcept { return fifo_.slots(); }
  /// Link side: the store's bytes, read-only.
  const std::uint8_t* slots() const noexcept { return fifo_.slots(); }
  /// Link side: a character transfer begins: the free slots from the queue's tail up to its wrap.
  store_window begin() const noexcept { return window(0); }
  /// Link side: `stored` characters are staged: the free slots after them (the program side may have made
  /// more room meanwhile).
  store_window next(std::size_t stored) const noexcept { return window(stored); }
  /// Link side: the message's `length` characters go to the program side, all at once.
  byte_view commit(std::size_t length) noexcept {
    fifo_.publish(length);
    return {};  // the characters may wrap round the buffer: no contiguous view
  }
  /// The committed characters are not one contiguous view.
  static byte_view text(std::size_t) noexcept { return {}; }
  /// Link side: nothing was published, so there is nothing to take back.
  static void abort() noexcept {}

  /// Program side: characters of whole messages waiting to be read.
  std::size_t waiting() const noexcept { return fifo_.available(); }
  /// Program side: takes the oldest character; false when there is none.
  bool take(std::uint8_t& c) noexcept { return fifo_.pop(c); }

 private:
  store_window window(std::size_t stored) const noexcept {
    const std::size_t free = fifo_.free();
    if (stored >= free) return {};
    const std::size_t first = fifo_.staging_slot(stored);
    const std::size_t room = free - stored;
    const std::size_t end = room < Capacity - first ? first + room : Capacity;
    return {static_cast<std::uint16_t>(first), static_cast<std::uint16_t>(end)};
  }

  spsc_fifo<Capacity, ring::variable_data_length> fifo_;
};

}  // namespace trionet::detail
