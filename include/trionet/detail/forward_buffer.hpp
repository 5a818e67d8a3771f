// The forward buffer of a ring node (docs/protocol.md 1.5): the bytes of the message passing through, on their
// way from the link's receiver to its transmitter, and the bound on the data that message may still carry.
// The node's forwarding rule (ring/node.hpp) uses it through a small interface: a message `begin`s, its data
// are `append`ed, it `end`s, or it is `lose`d or `close`d; the transmitter `take`s.
//
// The fast path: a data byte of the message passing through is one comparison and one store (`put_fast`)
// while a *grant* lasts, and the next byte to send one comparison and one load (`ready`, `take`). The grant is
// the room up to the end of the buffer, within the bound: the part of the bound handed to the fast path. The
// buffer keeps both (`remaining_ + granted`), so the bound is always exact and no caller has to settle it. No
// grant is open between messages (a message's `end`, `close` or `lose` ends it).
//
//   data_:  [ 0 ........ o_ )  ...  [ r_ ........ w_ )[ w_ ... lim_ )  ... Capacity
//            wrapped-round part      goes out first     the grant
//
// [r_, w_) goes out first, then [0, o_), which fills once w_ has reached the end while bytes were still
// waiting (o_ > 0 only when w_ == Capacity, and o_ <= r_): so neither fast path tests for a wrap. While the
// node sends an own frame (`park`), r_ = w_ = Capacity: everything that arrives waits in [0, o_), and the
// transmitter's fast path finds nothing.
//
// Link side only (one context: no synchronisation). Cost: Capacity bytes, four indices, the bound and a flag.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/detail/attributes.hpp"
#include "trionet/detail/fifo.hpp"
#include "trionet/detail/single_writer.hpp"
#include "trionet/ring/bytes.hpp"

namespace trionet::detail {

/// Why `forward_buffer::append` did not take a data byte.
enum class append_status : std::uint8_t {
  ok,          ///< appended
  past_bound,  ///< the message already carries the longest legal data of its type
  full,        ///< no room
};

template <std::size_t Capacity>
class forward_buffer {
  static_assert(Capacity >= 1 && Capacity < 65535, "a forward buffer holds 1..65534 bytes");

 public:
  /// An index into the buffer (0 .. Capacity): a machine word on 64-bit hosts (no zero-extension on the fast
  /// paths), the smallest type that holds Capacity on 32-bit cores (RAM).
#if UINTPTR_MAX > 0xFFFFFFFFu
  using index = std::size_t;
#else
  using index = index_for<Capacity>;
#endif

  // ---- the receive side: the message passing through ----

  /// The fast path: appends a data byte of the open message while the grant lasts; false (nothing done) when
  /// it has run out (then `append`).
  TRIONET_ALWAYS_INLINE bool put_fast(std::uint8_t byte) noexcept {
    if (w_ == lim_) return false;
    data_[w_] = byte;
    ++w_;  // after the store: one add to memory
    return true;
  }
  /// The fast path in bulk: appends the data bytes of [first, last) up to the first control byte, while the
  /// grant lasts, in one copy. Returns the first byte not taken.
  const std::uint8_t* put_run(const std::uint8_t* first, const std::uint8_t* last) noexcept {
    const std::size_t granted = std::size_t{lim_} - w_;
    const std::size_t available = static_cast<std::size_t>(last - first);
    const std::uint8_t* const stop = ring::find_control(first, first + (available < granted ? available : granted));
    const auto n = static_cast<std::size_t>(stop - first);
    copy_bytes(data_ + w_, first, n);
    w_ = static_cast<index>(w_ + n);
    return stop;
  }

  /// A message begins: its header (already passed on with A - 1) is appended, and its data may come to
  /// `longest` bytes. Any message open before it is over. False, with nothing done, when there is no room.
  [[nodiscard]] bool begin(std::uint8_t header, std::uint16_t longest) noexcept {
    if (!push(header)) return false;
    remaining_ = longest;
    regrant();
    return true;
  }
  /// A data byte of the open message that `put_fast` (or `put_run`) did not take: appended, or why not
  /// (nothing done then). Precondition: the grant is used up.
  [[nodiscard]] append_status append(std::uint8_t byte) noexcept {
    TRIONET_ASSERT(lim_ == w_);
    if (remaining_ == 0) return append_status::past_bound;  // (the grant is used up: remaining_ is the bound)
    if (!push(byte)) return append_status::full;
    --remaining_;
    regrant();
    return append_status::ok;
  }
  /// The open message's end of message (already with A - 1) appended: the message is over. False, with nothing
  /// done, when there is no room (then `lose` it).
  [[nodiscard]] bool end(std::uint8_t end_of_message) noexcept {
    return push(end_of_message);  // (fails only without a grant: remaining_ is then the bound, for `lose`)
  }
  /// The open message ends here without its end of message (a header cut in, or the line went idle): no more
  /// data for it.
  void close() noexcept {
    remaining_ = 0;
    lim_ = w_;
  }
  /// The open message, whose data may come to `longest` bytes, is lost: its header and data so far are removed
  /// if none of it has gone out yet (else it stays cut short), and it is closed.
  void lose(std::uint16_t longest) noexcept {
    const std::size_t incoming = std::size_t{longest} - bound() + 1u;  // its header and data so far
    close();
    if (incoming <= size()) drop_back(incoming);
  }
  /// The data the open message may still carry (meaningful while a message is open).
  std::size_t bound() const noexcept { return std::size_t{remaining_} + (std::size_t{lim_} - w_); }

  // ---- the transmit side ----

  /// True when [r_, w_) holds a byte: `take` may take it.
  TRIONET_ALWAYS_INLINE bool ready() const noexcept { return r_ != w_; }
  /// Takes the next byte of [r_, w_). Precondition: ready().
  TRIONET_ALWAYS_INLINE std::uint8_t take() noexcept {
    TRIONET_ASSERT(ready());
    return data_[r_++];
  }
  /// Takes the bytes of [r_, w_), up to `n`, into `out`; returns how many.
  std::size_t take_run(std::uint8_t* out, std::size_t n) noexcept {
    const std::size_t ready = std::size_t{w_} - r_;
    if (n > ready) n = ready;
    copy_bytes(out, data_ + r_, n);
    r_ = static_cast<index>(r_ + n);
    return n;
  }
  /// When [r_, w_) is used up and bytes wait in [0, o_): they become [r_, w_). True if so.
  bool next_part() noexcept {
    if (r_ != w_ || o_ == 0 || parked_) return false;
    r_ = 0;
    lim_ = w_ = o_;  // (no grant while w_ was at the end: none now either)
    o_ = 0;
    return true;
  }

  /// The node starts an own frame (the buffer is empty): the indices go to the end, so that the bytes that
  /// arrive meanwhile wait in [0, o_) and `take` finds nothing. The rest of any grant goes back to the bound.
  void park() noexcept {
    TRIONET_ASSERT(empty());
    settle();
    r_ = w_ = lim_ = static_cast<index>(Capacity);
    parked_ = true;
  }
  /// The own frame has gone out.
  void unpark() noexcept { parked_ = false; }
  /// True while the node sends an own frame.
  bool parked() const noexcept { return parked_; }

  /// Bytes in the buffer.
  std::size_t size() const noexcept { return std::size_t{w_} - r_ + o_; }
  /// True when it holds no byte.
  bool empty() const noexcept { return r_ == w_ && o_ == 0; }

 private:
  // The grant goes back into the bound.
  void settle() noexcept {
    remaining_ = static_cast<std::uint16_t>(bound());
    lim_ = w_;
  }
  // The bound, as far as it reaches before the end of the buffer, becomes the grant (none while the buffer is
  // parked or wrapped round: w_ == Capacity).
  void regrant() noexcept {
    const std::size_t room = Capacity - w_;
    const std::size_t n = remaining_ < room ? remaining_ : room;
    lim_ = static_cast<index>(w_ + n);
    remaining_ = static_cast<std::uint16_t>(remaining_ - n);
  }
  // Appends a byte (after [r_, w_), starting the buffer again at its beginning if it has drained at its end,
  // else in the wrapped-round part); false when full, which happens only without a grant (a grant is room).
  // Ends any grant: its rest is dropped from the bound, so callers that go on with the message have none open
  // (`begin`, `append`) and regrant after; `end` ends the message anyway.
  TRIONET_ALWAYS_INLINE bool push(std::uint8_t byte) noexcept {
    if (w_ == Capacity && r_ == Capacity && o_ == 0 && !parked_) r_ = w_ = 0;  // drained at the end
    if (w_ != Capacity) {
      data_[w_] = byte;
      lim_ = w_ = static_cast<index>(w_ + 1u);
      return true;
    }
    if (o_ == r_) return false;
    data_[o_] = byte;
    o_ = static_cast<index>(o_ + 1u);
    return true;
  }
  // Removes the `n` most recently appended bytes. Precondition: n <= size(), and no grant.
  void drop_back(std::size_t n) noexcept {
    TRIONET_ASSERT(n <= size() && lim_ == w_);
    const std::size_t wrapped = n < o_ ? n : o_;
    o_ = static_cast<index>(o_ - wrapped);
    lim_ = w_ = static_cast<index>(w_ - (n - wrapped));
  }

  // The indices first: near the node's start, one instruction away on a Cortex-M0+.
  index r_ = 0;    // the next byte to send
  index w_ = 0;    // the end of the first part, where `put_fast` appends
  index o_ = 0;    // the end of the wrapped-round part [0, o_)
  index lim_ = 0;  // the end of the grant: `put_fast` appends while w_ != lim_
  std::uint16_t remaining_ = 0;  // the bound less the grant
  bool parked_ = false;
  std::uint8_t data_[Capacity] = {};
};

/// Whether a node forwards, and how many messages it dropped while it did not: a keypad's forwarding is off
/// in local mode (docs/protocol.md 1.7).
template <bool Switchable>
struct forwarding_switch {
  bool on = false;                     ///< link side
  single_writer<std::uint16_t> drops;  ///< link side: messages dropped while off (a traffic count: 2^16)

  bool forwarding() const noexcept { return on; }
  std::uint32_t dropped() const noexcept { return drops.load(); }
};
/// A node that always forwards (a Motion Coordinator): nothing to keep.
template <>
struct forwarding_switch<false> {
  static constexpr bool forwarding() noexcept { return true; }
  static constexpr std::uint32_t dropped() noexcept { return 0; }
};

}  // namespace trionet::detail
