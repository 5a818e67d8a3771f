// What every ring node does with its link (docs/protocol.md 1.5, 1.10): decrement and forward, one message at a
// time, forwarded traffic before the node's own, and the liveness rules that stop a damaged message from
// holding a node or the ring.
//
//   receive side                          transmit side
//   header A>1 -> header A-1 ---\         between messages: forward buffer first, then the transmit queue;
//   data      -> data ----------+--> forward buffer --+--> link
//   EOM A     -> EOM A-1 ------/                      |
//   header A=1 or A=0, and what follows: local         |
//   own frames (PRINT#, SEND) ---------> transmit queue
//
// Forwarding is cut-through: a forwarded header goes out as soon as the transmitter is between messages,
// each data byte as soon as it arrives. Forwarders do not validate; the destination does. A forwarded message
// is lost (counted, NETSTAT bit 1) when
//   - the forward buffer overflows (`forwards_lost`),
//   - it carries more data than the longest legal message of its type (`forwards_cut`; type 1 and the
//     reserved types 5..7: the character maximum, type 2: 14, types 3 and 4: 1), or
//   - the line goes idle before its end of message (`forwards_ended_idle`, `line_idle`).
// A lost message is removed whole if none of it has gone out, otherwise cut short (the destination then sees
// a frame error); the rest of it is dropped.
//
// Capacity rule: bytes arrive at most one per byte-time, so while the node sends an own frame of L bytes at
// most L forwarded bytes arrive. The forward buffer therefore holds at least a direct variable transfer
// (16 bytes, checked at compile time) and the node never queues an own frame longer than the forward buffer
// (`max_own_frame`: long PRINT# text is split into several character messages): forwarded traffic is never
// lost to the node's own sending.
//
// Sides (docs/design.md, "Contexts"): `receive*`, `transmit*`, `relay` pieces, `line_idle` and the state
// queries belong to the link side (one interrupt context); `queue`, `queue_text` and `transmit_free` to the
// program side (one thread context). The transmit queue is a single-producer, single-consumer queue between
// them, NETSTAT a `netstat_register`, and every counter is written by one side only.
//
// The per-byte fast paths (a UART interrupt): a data byte of a forwarded message is appended to the forward
// buffer while a grant lasts (the room up to the end of the buffer, within the forwarding bound), and
// `transmit` takes the next forward-buffer byte. On hosts the next steps take the common bytes of traffic
// through the node that the fast path does not: the next grant at the buffer's end, a forwarded end of
// message, the header of a message to forward (`renew`, `next_*`); everything else (bytes for the node, drops,
// losses, the node's own frames) takes the general path of its kind (`route_data`, `route_control`: `take_*`
// then `refuse_*`; `transmit_slow`). While the node sends an own frame the forward buffer's indices are
// parked at its end, so the fast `transmit` finds nothing there and the bytes that arrive meanwhile wait in
// the buffer's wrapped-round part.
//
// This is the nodes' plumbing (`motion_coordinator` and `keypad` use it through `ring::node`), not an API.
// Cost: ForwardCapacity + TransmitCapacity bytes + about 40 bytes. Per byte O(1), the bulk calls with one copy
// per run of data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "trionet/attributes.hpp"
#include "trionet/fifo.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/netstat.hpp"
#include "trionet/single_writer.hpp"
#include "trionet/ring/variable_layout.hpp"

namespace trionet::ring {

/// Where a node's link sent a received byte.
enum class byte_route : std::uint8_t {
  local,      ///< for this node's own decoder (A = 1 or A = 0 messages, and bytes outside any message)
  forwarded,  ///< into the forward buffer
  dropped,    ///< discarded: forwarding is off, or the rest of a lost message
  lost,       ///< the byte on which a forwarded message was lost (buffer full, or longer than legal)
};

/// The route's name, as spelled in `byte_route`.
constexpr const char* to_string(byte_route r) noexcept {
  switch (r) {
    case byte_route::local:
      return "local";
    case byte_route::forwarded:
      return "forwarded";
    case byte_route::dropped:
      return "dropped";
    case byte_route::lost:
      return "lost";
  }
  return "unknown";
}

/// Counters of a node's link, as read at one moment; they only ever grow. The forwarding losses (wire
/// errors) wrap at 2^32, the traffic counts (messages forwarded, dropped, sent) at 2^16.
struct link_counters {
  std::uint32_t forwards_lost = 0;        ///< forwarded messages lost to a full forward buffer
  std::uint32_t forwards_cut = 0;         ///< ... longer than the longest legal message of their type
  std::uint32_t forwards_ended_idle = 0;  ///< ... whose end of message never came: the line went idle
  std::uint32_t messages_forwarded = 0;   ///< headers of messages passed on (A decremented); wraps at 2^16
  std::uint32_t messages_dropped = 0;     ///< messages dropped while forwarding was off; wraps at 2^16
  std::uint32_t messages_sent = 0;        ///< own messages whose end of message has gone out; wraps at 2^16

  /// Forwarded messages lost for any reason (each sets NETSTAT bit 1).
  constexpr std::uint32_t forwards_failed() const noexcept {
    return forwards_lost + forwards_cut + forwards_ended_idle;
  }
};

namespace detail {

/// The forward buffer of a node's link: link side only (no synchronisation). A buffer of Capacity bytes in
/// two parts: [r_, w_) goes out first, then [0, o_), which fills once w_ has reached the end while bytes
/// were still waiting (o_ > 0 only when w_ == Capacity, and o_ <= r_). The fast paths are `put_fast` (while
/// w_ < lim_: the link's grant) and `ready` + `take` (while r_ < w_): one comparison each, no wrap test.
/// While the node sends an own frame (`parked`), r_ = w_ = Capacity: every received byte goes to [0, o_).
template <std::size_t Capacity>
class forward_buffer {
 public:
  /// An index into the buffer (0 .. Capacity): a machine word on 64-bit hosts (no zero-extension on the fast
  /// paths), the smallest type that holds Capacity on 32-bit cores (RAM).
#if UINTPTR_MAX > 0xFFFFFFFFu
  using index = std::size_t;
#else
  using index = trionet::detail::index_for<Capacity>;
#endif

  /// Appends a byte while the grant lasts; false (nothing done) when it has run out.
  TRIONET_ALWAYS_INLINE bool put_fast(std::uint8_t byte) noexcept {
    if (w_ == lim_) return false;
    data_[w_] = byte;
    ++w_;  // after the store: one add to memory
    return true;
  }
  /// True when [r_, w_) holds a byte: `take` may take it.
  TRIONET_ALWAYS_INLINE bool ready() const noexcept { return r_ != w_; }
  /// Takes the next byte of [r_, w_). Precondition: ready().
  TRIONET_ALWAYS_INLINE std::uint8_t take() noexcept { return data_[r_++]; }

  /// Bytes in the buffer.
  std::size_t size() const noexcept { return std::size_t{w_} - r_ + o_; }
  /// True when it holds no byte.
  bool empty() const noexcept { return r_ == w_ && o_ == 0; }
  /// Room for this many more bytes.
  std::size_t free() const noexcept { return Capacity - size(); }

  /// The grant still open: bytes `put_fast` may still append.
  std::size_t granted() const noexcept { return std::size_t{lim_} - w_; }
  /// Ends the grant.
  void revoke() noexcept { lim_ = w_; }
  /// Opens a grant of up to `most` bytes: as many as fit before the end of the buffer (none while parked or
  /// wrapped round). Returns the grant.
  std::size_t grant(std::size_t most) noexcept {
    const std::size_t room = Capacity - w_;  // 0 while parked or wrapped round (w_ == Capacity)
    const std::size_t n = most < room ? most : room;
    lim_ = static_cast<index>(w_ + n);
    return n;
  }

  /// Appends a byte; false (nothing done) when full. Ends any grant.
  [[nodiscard]] TRIONET_ALWAYS_INLINE bool push(std::uint8_t byte) noexcept {
    if (!reserve()) return push_wrapped(byte);
    put_reserved(byte);
    return true;
  }
  /// Appends as many of `n` bytes as fit (all or a prefix); returns how many. Ends any grant.
  std::size_t push(const std::uint8_t* bytes, std::size_t n) noexcept {
    std::size_t room = Capacity - w_;
    if (TRIONET_LIKELY(n <= room)) {  // the common case: all of it before the end
      trionet::detail::copy_bytes(data_ + w_, bytes, n);
      lim_ = w_ = static_cast<index>(w_ + n);
      return n;
    }
    std::size_t done = 0;
    if (room == 0 && r_ == Capacity && o_ == 0 && !parked_) {  // drained at the end: start again
      r_ = w_ = 0;
      room = Capacity;
    }
    if (room != 0) {
      done = n < room ? n : room;
      trionet::detail::copy_bytes(data_ + w_, bytes, done);
      lim_ = w_ = static_cast<index>(w_ + done);
      if (done == n || w_ != Capacity) return done;
    }
    std::size_t more = n - done;  // then the wrapped-round part, up to the next byte to send
    const std::size_t wrapped_room = std::size_t{r_} - o_;
    if (more > wrapped_room) more = wrapped_room;
    trionet::detail::copy_bytes(data_ + o_, bytes + done, more);
    o_ = static_cast<index>(o_ + more);
    return done + more;
  }
  /// Removes the `n` most recently appended bytes. Precondition: n <= size(). Ends any grant.
  void drop_back(std::size_t n) noexcept {
    const std::size_t wrapped = n < o_ ? n : o_;
    o_ = static_cast<index>(o_ - wrapped);
    lim_ = w_ = static_cast<index>(w_ - (n - wrapped));
  }
  /// The byte `i` places from the oldest. Precondition: i < size().
  std::uint8_t& at(std::size_t i) noexcept {
    const std::size_t first = std::size_t{w_} - r_;
    return i < first ? data_[r_ + i] : data_[i - first];
  }
  /// The most recently appended byte. Precondition: !empty().
  std::uint8_t& back() noexcept { return o_ != 0 ? data_[o_ - 1u] : data_[w_ - 1u]; }

  /// At the end of the buffer (w_ == Capacity): when everything has gone out, starts again at its beginning
  /// (not while parked: an own frame is going out). True if so.
  TRIONET_ALWAYS_INLINE bool restart() noexcept {
    if (r_ != Capacity || o_ != 0 || parked_) return false;
    r_ = w_ = 0;
    return true;
  }
  /// Room for one byte after [r_, w_) (restarting the buffer if it has drained at its end): then
  /// `put_reserved` appends it. False when only the wrapped-round part is left (`push` takes it there).
  TRIONET_ALWAYS_INLINE bool reserve() noexcept { return w_ != Capacity || restart(); }
  /// Appends a byte after `reserve`. Ends any grant.
  TRIONET_ALWAYS_INLINE void put_reserved(std::uint8_t byte) noexcept {
    data_[w_] = byte;
    lim_ = w_ = static_cast<index>(w_ + 1u);
  }
  /// `push(byte)` then a grant of the rest of the buffer, when the buffer has drained at its end (as
  /// `restart`); false, with nothing done, otherwise.
  TRIONET_ALWAYS_INLINE bool restart_with(std::uint8_t byte) noexcept {
    if (r_ != Capacity || o_ != 0 || parked_) return false;  // (r_ at the end: so is w_)
    data_[0] = byte;
    r_ = 0;
    w_ = 1;
    lim_ = static_cast<index>(Capacity);
    return true;
  }
  /// Appends a byte to the wrapped-round part, up to the next byte to send (w_ == Capacity); false when full.
  /// (Inlined on hosts: a node forwarding while it sends its own frames appends there often.)
  TRIONET_FAST_PATH bool push_wrapped(std::uint8_t byte) noexcept {
    if (o_ == r_) return false;
    data_[o_] = byte;
    o_ = static_cast<index>(o_ + 1u);
    return true;
  }

  /// When [r_, w_) is used up and bytes wait in [0, o_): they become [r_, w_). True if so.
  bool next_part() noexcept {
    if (r_ != w_ || o_ == 0 || parked_) return false;
    r_ = 0;
    lim_ = w_ = o_;
    o_ = 0;
    return true;
  }
  /// Takes up to `n` bytes into `out` (both parts); returns how many. Takes nothing while parked. A buffer it
  /// drains starts again at its beginning (with any grant).
  std::size_t pop(std::uint8_t* out, std::size_t n) noexcept {
    if (parked_) return 0;
    std::size_t done = 0;
    for (;;) {
      const std::size_t ready = std::size_t{w_} - r_;
      const std::size_t k = n - done < ready ? n - done : ready;
      trionet::detail::copy_bytes(out + done, data_ + r_, k);
      r_ = static_cast<index>(r_ + k);
      done += k;
      if (r_ != w_) return done;
      if (o_ == 0) {  // drained
        lim_ = static_cast<index>(lim_ - w_);
        r_ = w_ = 0;
        return done;
      }
      if (done == n) return done;
      r_ = 0;  // on to the wrapped-round part
      lim_ = w_ = o_;
      o_ = 0;
    }
  }

  /// The node starts an own frame (the buffer is empty): the indices go to the end, so that the bytes that
  /// arrive meanwhile wait in [0, o_) and the fast `transmit` finds nothing.
  void park() noexcept {
    r_ = w_ = lim_ = static_cast<index>(Capacity);
    parked_ = true;
  }
  /// The own frame has gone out.
  void unpark() noexcept { parked_ = false; }
  /// True while the node sends an own frame.
  bool parked() const noexcept { return parked_; }

 private:
  // The indices first: near the node's start, one instruction away on a Cortex-M0+.
  index r_ = 0;    // the next byte to send
  index w_ = 0;    // the end of the first part, where `put_fast` appends
  index o_ = 0;    // the end of the wrapped-round part [0, o_)
  index lim_ = 0;  // the end of the grant: `put_fast` appends while w_ != lim_
  bool parked_ = false;
  std::uint8_t data_[Capacity] = {};
};

/// Whether a link forwards, and the messages it dropped while it did not: only a link whose forwarding can be
/// turned off (a keypad's) keeps them.
template <bool Switchable>
class forwarding_switch {
 protected:
  bool forwarding() const noexcept { return on_; }
  void turn(bool on) noexcept { on_ = on; }
  void count_drop() noexcept { dropped_.increment(); }
  std::uint16_t drops() const noexcept { return dropped_.load(); }

 private:
  single_writer<std::uint16_t> dropped_;
  bool on_ = true;
};
/// A link that always forwards (a Motion Coordinator's): nothing to keep.
template <>
class forwarding_switch<false> {
 protected:
  static constexpr bool forwarding() noexcept { return true; }
  static constexpr std::uint16_t drops() noexcept { return 0; }
};

/// `Crc` and `Layout` are the CRC policy and field layout the node's own direct variable transfers are sent
/// with (crc.hpp, variable_layout.hpp); `MaxCharacters` the character maximum of docs/protocol.md 1.4 (the
/// forwarding bound of type 1 and the reserved types).
/// `Switchable`: whether forwarding can be turned off (a keypad); a Motion Coordinator always forwards.
template <std::size_t ForwardCapacity, std::size_t TransmitCapacity, std::size_t MaxCharacters,
          class Crc = crc16_ccitt_false, class Layout = default_variable_layout, bool Switchable = false>
class link : private forwarding_switch<Switchable>, private crc_holder<Crc> {
  static_assert(ForwardCapacity >= framing_length + variable_data_length && ForwardCapacity < 65535,
                "the forward buffer must hold a whole direct variable transfer (16 bytes): while a node sends "
                "an own frame, as many forwarded bytes arrive as the frame has, and they must not be lost");
  static_assert(TransmitCapacity >= framing_length + 1 && TransmitCapacity <= 32767,
                "the transmit queue must hold at least a one-character message (3 bytes)");
  static_assert(MaxCharacters >= 1 && MaxCharacters < 65535, "a character transfer holds 1..65534 characters");

 public:
  constexpr link() noexcept = default;
  /// With a CRC object (`crc16_runtime`, a CRC chosen at run time): own direct variable transfers get it.
  constexpr explicit link(const Crc& crc) noexcept : crc_holder<Crc>(crc) {}

  /// The longest own frame the node queues: it fits in the transmit queue, and the forward buffer can absorb
  /// everything that arrives while it is sent.
  static constexpr std::size_t max_own_frame =
      ForwardCapacity < TransmitCapacity ? ForwardCapacity : TransmitCapacity;
  /// The longest legal data of a message by its header's type field (docs/protocol.md 1.5): the forwarding bound.
  /// Type 1 and the reserved types 5..7: the character maximum; 2: a direct variable transfer; 3, 4: one.
  static constexpr std::uint16_t longest_data[8] = {0,
                                                    MaxCharacters,
                                                    variable_data_length,
                                                    1,
                                                    1,
                                                    MaxCharacters,
                                                    MaxCharacters,
                                                    MaxCharacters};
  /// The same as whole frames, header and end of message included.
  static constexpr std::uint16_t longest_frame[8] = {0,
                                                     MaxCharacters + framing_length,
                                                     variable_data_length + framing_length,
                                                     1 + framing_length,
                                                     1 + framing_length,
                                                     MaxCharacters + framing_length,
                                                     MaxCharacters + framing_length,
                                                     MaxCharacters + framing_length};
  /// The most characters one own character message carries.
  static constexpr std::size_t max_own_characters =
      max_own_frame - framing_length < MaxCharacters ? max_own_frame - framing_length : MaxCharacters;

  // ---- link side: receive ----

  /// Link side, the per-byte fast path: a data byte of a forwarded message while the grant lasts (room in
  /// the forward buffer up to its end, within the forwarding bound). True if taken; otherwise call `receive`.
  TRIONET_ALWAYS_INLINE bool forward_fast(std::uint8_t byte) noexcept {
    return is_data(byte) && forward_.put_fast(byte);
  }

  // After the fast path, on hosts, the next steps take the common bytes of traffic through the node that it
  // does not (`renew`, `next_data`, `next_control`: exactly as `receive` would, when nothing is lost and no
  // byte is for the node); `receive` takes everything. Precondition of each: `forward_fast(byte)` was false.

  /// Link side: a data byte of a forwarded message when the grant has run out (the end of the forward
  /// buffer, or its wrapped-round part while the node sends an own frame): appended, and a new grant opened
  /// where there is one. False, with nothing done, otherwise.
  TRIONET_ALWAYS_INLINE bool next_data(std::uint8_t byte) noexcept {
    if (!take_data(byte, forward_)) return false;
    regrant();
    return true;
  }
  /// Link side: the commonest case of `next_data`, in a few instructions: the forward buffer has drained at
  /// its end and the bound is not near, so the byte starts it again with a grant of the whole buffer. False,
  /// with nothing done, otherwise.
  TRIONET_ALWAYS_INLINE bool renew(std::uint8_t byte) noexcept {
    if (remaining_ < ForwardCapacity || !forwarding_message() || !forward_.restart_with(byte)) return false;
    remaining_ = static_cast<std::uint16_t>(remaining_ - ForwardCapacity);
    return true;
  }
  /// Link side: the end of message of a forwarded message, or a header with A > 1 on a forwarding link (a
  /// new message to forward: a grant is opened), passed on with A - 1. False, with nothing done, otherwise.
  /// A header ends any message passing through; the node's decoder must end its own. Not into the
  /// wrapped-round part (`receive` takes those), which keeps this step small.
  TRIONET_ALWAYS_INLINE bool next_control(std::uint8_t byte) noexcept {
    unwrapped into{forward_};
    if (!take_control(byte, into)) return false;
    regrant();
    return true;
  }

  /// Link side: true when `byte` is data for the node's own decoder (`receive` would route it `local`).
  bool local_data(std::uint8_t byte) const noexcept { return is_data(byte) && receiving_ == receiving::local; }

  /// Link side: takes one received byte that `forward_fast` refused, and says where it went.
  [[nodiscard]] byte_route receive(std::uint8_t byte) noexcept {
    return is_data(byte) ? route_data(byte) : route_control(byte);
  }
  /// Link side: `receive` of a data byte.
  [[nodiscard]] TRIONET_ALWAYS_INLINE byte_route route_data(std::uint8_t byte) noexcept {
    if (!take_data(byte, forward_)) return refuse_data(byte, forward_);
    regrant();
    return byte_route::forwarded;
  }
  /// Link side: `receive` of a header or end of message. (A grant still open needs no settling first: a
  /// control byte that ends its message either appends, which revokes it, or is refused, which settles it.)
  [[nodiscard]] TRIONET_ALWAYS_INLINE byte_route route_control(std::uint8_t byte) noexcept {
    if (!take_control(byte, forward_)) return refuse_control(byte, forward_);
    regrant();
    return byte_route::forwarded;
  }

  /// Link side: a run of data bytes (no header or end of message among them): the same as `receive` for
  /// each, with one copy. Returns where they went; if a forwarded message is lost part-way, the result is
  /// `lost` (the byte it was lost on; the rest are dropped).
  [[nodiscard]] byte_route receive_data(const std::uint8_t* data, std::size_t n) noexcept {
    settle();  // (no new grant after a bulk call: the next byte at a time renews it on the general path)
    return receive_data(data, n, forward_);
  }

  /// Link side: the line has been idle (docs/protocol.md 1.10): a message being forwarded has lost the rest of
  /// its bytes. It is ended and counted (`forwards_ended_idle`, NETSTAT bit 1; true is returned) and any later
  /// byte of it is stray data; the transmitter then goes on to the node's own messages. The rest of a lost
  /// message, if being dropped, is over too.
  bool line_idle() noexcept {
    settle();
    const bool was_forwarding = forwarding_message();
    receiving_ = receiving::local;
    if (!was_forwarding) return false;
    forwards_ended_idle_.increment();
    netstat_.raise(netstat_tx_buffer_error);
    return true;
  }

  /// Link side: true while a message through the node has begun and not ended (forwarded, or being dropped).
  bool passing_message() const noexcept { return receiving_ != receiving::local; }

  /// What `receive_passing` took (a forwarded message lost on the way shows in the counters).
  struct passing {
    const std::uint8_t* stop;  ///< the first byte not taken (one for the node itself), or the end
    bool header;               ///< a header was taken: a message the node was receiving ended
  };

  /// Link side: takes bytes from [first, last) while they are not for the node itself: the same as `receive`
  /// for each, in order, with runs of data copied whole, stopping before the first byte `receive` would
  /// route `local`.
  TRIONET_ALWAYS_INLINE [[nodiscard]] passing receive_passing(const std::uint8_t* first,
                                                              const std::uint8_t* last) noexcept {
    settle();
    return receive_passing(first, last, forward_);
  }

  /// The caller's transmit buffer standing in for the forward buffer while the forward buffer is empty and
  /// nothing else is being sent: forwarded bytes go straight into it (see `straight_through`), one copy
  /// instead of two. It only ever receives part of the bytes `straight_through` was asked about, which fit in
  /// it by that check: so it never runs out of room, and says so (`free`), which keeps its pushes unchecked.
  class straight_out {
   public:
    /// Bytes written so far.
    std::size_t size() const noexcept { return size_; }
    /// Never less than what comes: `straight_through` checked that all of it fits.
    static constexpr std::size_t free() noexcept { return static_cast<std::size_t>(-1); }
    /// Appends a byte (always room).
    [[nodiscard]] bool push(std::uint8_t byte) noexcept {
      data_[size_++] = byte;
      return true;
    }
    /// Appends `n` bytes (always room); returns n.
    std::size_t push(const std::uint8_t* bytes, std::size_t n) noexcept {
      trionet::detail::copy_bytes(data_ + size_, bytes, n);
      size_ += n;
      return n;
    }
    /// The byte `i` places from the first.
    std::uint8_t& at(std::size_t i) noexcept { return data_[i]; }
    /// The last byte written.
    std::uint8_t& back() noexcept { return data_[size_ - 1]; }
    /// Removes the `n` last bytes (at most size()).
    void drop_back(std::size_t n) noexcept { size_ = n >= size_ ? 0 : size_ - n; }

   private:
    friend class link;
    explicit straight_out(std::uint8_t* data) noexcept : data_(data) {}
    std::uint8_t* data_;
    std::size_t size_ = 0;
  };

  /// Link side: whether `received` bytes and then `transmit(out, capacity)` can go straight through: the
  /// forward buffer is empty, the node is not in the middle of its own message, and both the forward buffer
  /// and `out` have room for every received byte (so nothing received could be lost, and everything
  /// forwarded goes out first). If so, forwarded bytes are written into `out` (`receive_passing` with the
  /// returned stand-in), and `transmit_after` then adds what `transmit` would give after them.
  [[nodiscard]] bool straight_through(std::size_t received, std::size_t capacity) const noexcept {
    return received <= ForwardCapacity && received <= capacity && forward_.empty() && !forward_.parked();
  }
  /// The stand-in for the forward buffer that writes into `out`.
  [[nodiscard]] static straight_out straight_buffer(std::uint8_t* out) noexcept { return straight_out(out); }
  /// Link side: `receive_passing` into the stand-in.
  TRIONET_ALWAYS_INLINE [[nodiscard]] passing receive_passing(const std::uint8_t* first,
                                                              const std::uint8_t* last,
                                                              straight_out& into) noexcept {
    settle();
    return receive_passing<straight_out>(first, last, into);
  }
  /// Link side: the bytes `transmit(out, capacity)` gives after the forwarded bytes already in `straight`
  /// (= out[0..]).
  [[nodiscard]] std::size_t transmit_after(const straight_out& straight, std::uint8_t* out,
                                           std::size_t capacity) noexcept {
    const std::size_t n = straight.size();
    // The forward buffer is empty too: nothing more while a forwarded message is open or no own one waits.
    if (forwarding_message() || queue_.empty()) return n;
    return n + transmit_own(out + n, capacity - n);
  }

  // ---- link side: transmit ----

  /// Link side: fills `out` with up to `capacity` bytes for the link: the same bytes as that many calls of
  /// `transmit`, with the forward buffer's bytes copied whole (they go out first, in order, whatever they
  /// are) and runs of the node's own message data too.
  [[nodiscard]] std::size_t transmit(std::uint8_t* out, std::size_t capacity) noexcept {
    std::size_t n = 0;
    while (n < capacity) {
      if (!forward_.parked()) {
        n += forward_.pop(out + n, capacity - n);
        if (n == capacity) break;
        // The forward buffer is empty: nothing more unless an own message may start (as `transmit` finds).
        if (forwarding_message() || queue_.empty()) break;
      } else {  // a run of own message data up to its next control byte
        const std::size_t room = capacity - n;
        const std::size_t contiguous = queue_.front_size();
        const std::uint8_t* const front = queue_.front();
        const std::size_t available = contiguous < room ? contiguous : room;
        const auto k = static_cast<std::size_t>(find_control(front, front + available) - front);
        if (k != 0) {
          std::memcpy(out + n, front, k);
          queue_.consume(k);
          n += k;
          continue;
        }
      }
      const int next = transmit_slow();  // control bytes of own messages, message boundaries, waiting
      if (next < 0) break;
      out[n++] = static_cast<std::uint8_t>(next);
    }
    return n;
  }

  /// Link side: the next byte for the link, if any. The fast path takes the next forwarded byte.
  [[nodiscard]] TRIONET_ALWAYS_INLINE bool transmit(std::uint8_t& byte) noexcept {
    // The two paths meet in a whole register, so a caller that widens `byte` does not widen it again after
    // the fast path (one instruction per byte); the general path's result stays in a register too.
    std::size_t next;
    if (TRIONET_LIKELY(forward_.ready())) {
      next = forward_.take();
    } else {
      const int slow = transmit_slow();
      if (slow < 0) return false;
      next = static_cast<std::uint8_t>(slow);
    }
    byte = static_cast<std::uint8_t>(next);
    return true;
  }

  /// Link side: true when `transmit` would give a byte now.
  bool transmit_pending() const noexcept {
    return !forward_.empty() || !(forwarding_message() || queue_.empty());  // (parked: the queue has the rest)
  }

  // ---- program side ----

  /// Program side: queues one of the node's own messages whole. `encode_status::buffer_too_small` if the
  /// transmit queue has no room for all of it or the frame is longer than `max_own_frame` (nothing is
  /// queued), or the message's own field error.
  [[nodiscard]] encode_result queue(const message& m) noexcept {
    const encode_status status = check(m);
    if (status != encode_status::ok) return {status, 0};
    const std::size_t length = frame_length(m);
    if (length > queue_.free() || length > max_own_frame) return {encode_status::buffer_too_small, 0};
    if (m.type == message_type::character) {  // straight into the queue: no staging copy of the text
      queue_.stage(0, make_header(m.hops, static_cast<std::uint8_t>(m.type)));
      queue_.stage(1, m.text.data(), m.text.size());
      queue_.stage(1 + m.text.size(), make_end_of_message(m.hops));
    } else {
      std::uint8_t frame[framing_length + variable_data_length];
      const encode_result encoded = encode<Crc, Layout>(frame, m, this->crc());
      queue_.stage(0, frame, encoded.length);
    }
    queue_.publish(length);
    return {encode_status::ok, length};
  }

  /// Program side: queues `text` (checked: 0..127 each) as consecutive character messages to `hops`, each as
  /// long as an own message may be (docs/protocol.md 1.6: `max_own_characters`, the last one shorter), as many
  /// whole messages as the transmit queue has room for. Returns how many characters were queued. The split
  /// depends on the text only, so a caller that goes on with the rest later sends the same messages.
  std::size_t queue_text(std::uint8_t hops, byte_view text) noexcept {
    std::size_t done = 0;
    while (done < text.size()) {
      std::size_t n = text.size() - done;
      if (n > max_own_characters) n = max_own_characters;
      if (n + framing_length > queue_.free()) break;
      queue_.stage(0, make_header(hops, static_cast<std::uint8_t>(message_type::character)));
      queue_.stage(1, text.data() + done, n);
      queue_.stage(1 + n, make_end_of_message(hops));
      queue_.publish(n + framing_length);
      done += n;
    }
    return done;
  }

  /// Program side: free bytes in the transmit queue (a frame is its message plus header and end of message).
  std::size_t transmit_free() const noexcept { return queue_.free(); }

  // ---- state ----

  /// Link side: bytes waiting in the forward buffer.
  std::size_t forward_backlog() const noexcept { return forward_.size(); }

  /// Link side: forwarding on (a Motion Coordinator, a keypad in network mode) or off (a keypad in local mode:
  /// messages through the node are dropped and counted).
  void set_forwarding(bool on) noexcept {
    static_assert(Switchable, "this link always forwards");
    this->turn(on);
  }

  /// Either side: the counters now (each read on its own: not one instant).
  link_counters counters() const noexcept {
    link_counters c;
    c.forwards_lost = forwards_lost_.load();
    c.forwards_cut = forwards_cut_.load();
    c.forwards_ended_idle = forwards_ended_idle_.load();
    c.messages_forwarded = messages_forwarded_.load();
    c.messages_dropped = this->drops();
    c.messages_sent = messages_sent_.load();
    return c;
  }

  /// NETSTAT: the link side raises bits 1..4 here, the program side reads, clears and raises bit 0.
  netstat_register& netstat() noexcept { return netstat_; }
  /// NETSTAT, read-only.
  const netstat_register& netstat() const noexcept { return netstat_; }

  /// The forward buffer's capacity.
  static constexpr std::size_t forward_capacity = ForwardCapacity;
  /// The transmit queue's capacity.
  static constexpr std::size_t transmit_capacity = TransmitCapacity;

 private:
  // The receive side's state in one byte: between or in messages for the node, dropping the rest of a
  // message, or forwarding one (its type in the low bits: the forwarding bound, and what a loss removes).
  enum class receiving : std::uint8_t { local = 0, discard = 1, forward = 0x80 };
  bool forwarding_message() const noexcept { return (static_cast<unsigned>(receiving_) & 0x80u) != 0; }
  std::uint8_t forward_type() const noexcept { return static_cast<std::uint8_t>(receiving_) & 0x07u; }

  // The forward buffer for `next_control`: appends only after [r_, w_), or at the beginning of a buffer
  // drained at its end, leaving the wrapped-round part to `receive` (so the step needs no register saved).
  struct unwrapped {
    forward_buffer<ForwardCapacity>& buffer;
    TRIONET_ALWAYS_INLINE bool push(std::uint8_t byte) noexcept {
      if (!buffer.reserve()) return false;
      buffer.put_reserved(byte);
      return true;
    }
  };

  // The grant of the fast path goes back into the forwarding bound: `remaining_` is exact again.
  void settle() noexcept {
    const std::size_t granted = forward_.granted();
    if (granted == 0) return;
    remaining_ = static_cast<std::uint16_t>(remaining_ + granted);
    forward_.revoke();
  }
  // A new grant for the fast path, while a forwarded message is open.
  TRIONET_ALWAYS_INLINE void regrant() noexcept {
    if (!forwarding_message()) return;
    remaining_ = static_cast<std::uint16_t>(remaining_ - forward_.grant(remaining_));
  }

  // The general link side of transmit: own frames, the wrapped-round part of the forward buffer, message
  // boundaries. The next byte, or -1 for none.
  TRIONET_NOINLINE int transmit_slow() noexcept {
    std::uint8_t byte = 0;
    if (forward_.parked()) {  // in an own frame, which was queued whole
      if (!queue_.pop(byte)) {  // cannot happen
        forward_.unpark();
        return -1;
      }
      if (classify(byte) == byte_class::end_of_message) {
        forward_.unpark();
        messages_sent_.increment();
      }
      return byte;
    }
    if (forward_.next_part()) return forward_.take();  // bytes that arrived meanwhile
    // The forward buffer is empty. A forwarded message open on the receive side has gone out so far
    // (cut-through): its next byte has not arrived. Otherwise the transmitter is between messages.
    if (forwarding_message() || !queue_.pop(byte)) return -1;
    forward_.park();
    return byte;
  }

  // `transmit` after a straight-through relay, when an own message waits (out of line: the relay's common
  // path stays small).
  TRIONET_NOINLINE std::size_t transmit_own(std::uint8_t* out, std::size_t capacity) noexcept {
    return transmit(out, capacity);
  }

  // The receive side, forwarding `into` the forward buffer or a `straight_out`.
  template <class Into>
  byte_route receive_data(const std::uint8_t* data, std::size_t n, Into& into) noexcept {
    if (!forwarding_message()) return receiving_ == receiving::local ? byte_route::local : byte_route::dropped;
    const std::size_t allowed = remaining_;
    if (TRIONET_LIKELY(n <= allowed)) {  // the common case: not longer than legal
      const std::size_t pushed = into.push(data, n);
      remaining_ = static_cast<std::uint16_t>(allowed - pushed);
      if (pushed == n) return byte_route::forwarded;
      return lose(into);
    }
    const std::size_t pushed = into.push(data, allowed);
    remaining_ = static_cast<std::uint16_t>(allowed - pushed);
    return pushed == allowed ? cut(into) : lose(into);  // cut: the first byte past the longest legal message
  }

  template <class Into>
  TRIONET_ALWAYS_INLINE passing receive_passing(const std::uint8_t* first, const std::uint8_t* last,
                                                Into& into) noexcept {
    passing result{first, false};
    const std::uint8_t* p = first;
    while (p != last) {
      if (receiving_ != receiving::local) {
        const std::uint8_t* const run = find_control(p, last);
        if (forwarding_message() && run != last && type_of(*run) == 0 &&
            forward_end(p, run, into)) {
          p = run + 1;
          continue;
        }
        if (run != p) (void)receive_data(p, static_cast<std::size_t>(run - p), into);
        p = run;
        if (p == last) break;
      }
      const std::uint8_t byte = *p;  // a control byte, or data for the node
      if (is_data(byte)) break;
      if (type_of(byte) == 0) {
        if (receiving_ == receiving::local) break;  // the end of the node's own message
      } else {
        if (hops_of(byte) <= 1) break;  // a message for the node
        result.header = true;
        if (this->forwarding() && receiving_ == receiving::local) {  // a whole message to forward?
          const std::uint8_t* const end = find_control(p + 1, last);
          if (end != last && type_of(*end) == 0 && forward_whole(p, end, into)) {
            p = end + 1;
            continue;
          }
        }
      }
      (void)route_byte(byte, into);
      ++p;
    }
    result.stop = p;
    return result;
  }

  template <class Into>
  TRIONET_ALWAYS_INLINE byte_route route_byte(std::uint8_t byte, Into& into) noexcept {
    if (is_data(byte)) return take_data(byte, into) ? byte_route::forwarded : refuse_data(byte, into);
    return take_control(byte, into) ? byte_route::forwarded : refuse_control(byte, into);
  }

  // A data byte of a forwarded message within its bound, appended (no grant is open: it ran out, or the
  // caller settled it). False, with nothing done, otherwise.
  template <class Into>
  TRIONET_ALWAYS_INLINE bool take_data(std::uint8_t byte, Into& into) noexcept {
    if (!forwarding_message() || remaining_ == 0 || !into.push(byte)) return false;
    remaining_ = static_cast<std::uint16_t>(remaining_ - 1u);
    return true;
  }
  // The end of message of a forwarded message, or the header of a message to forward, appended with A - 1.
  // False, with nothing done, otherwise. (An open grant needs no settling: its message ends, and its bound
  // with it; the append revokes it.)
  template <class Into>
  TRIONET_ALWAYS_INLINE bool take_control(std::uint8_t byte, Into& into) noexcept {
    std::uint8_t out;
    if (type_of(byte) == 0) {
      if (!forwarding_message()) return false;
      out = decrement_hops(byte);
    } else {
      // Any header ends the message passing through: the one before does not matter here.
      if (hops_of(byte) <= 1 || !this->forwarding()) return false;
      out = static_cast<std::uint8_t>(byte - 0x08);  // A > 1: decrement_hops without its check
    }
    if (!into.push(out)) return false;
    if (type_of(byte) == 0) {
      receiving_ = receiving::local;
      return true;
    }
    messages_forwarded_.increment();
    receiving_ = static_cast<receiving>(0x80u | (byte & 0x07u));
    remaining_ = longest_data[byte & 0x07u];
    return true;
  }
  // A data byte that `take_data` did not take: for the node, dropped, past the bound (cut), or no room (lost).
  template <class Into>
  byte_route refuse_data(std::uint8_t, Into& into) noexcept {
    if (!forwarding_message()) return receiving_ == receiving::local ? byte_route::local : byte_route::dropped;
    return remaining_ == 0 ? cut(into) : lose(into);
  }
  // A control byte that `take_control` did not take: an end of message for the node or of a dropped
  // message, one that found no room (lost), or a header: for the node, of a message dropped while
  // forwarding is off, or of one that found no room (nothing of it is in the buffer: nothing to remove).
  template <class Into>
  byte_route refuse_control(std::uint8_t byte, Into& into) noexcept {
    if (type_of(byte) == 0) {
      if (forwarding_message()) {
        const byte_route r = lose(into);
        receiving_ = receiving::local;  // it has ended, lost or not: nothing of it is left to drop
        return r;
      }
      const bool dropping = receiving_ == receiving::discard;
      receiving_ = receiving::local;
      return dropping ? byte_route::dropped : byte_route::local;
    }
    settle();  // any header ends the message being forwarded, and its grant
    receiving_ = receiving::local;
    if (hops_of(byte) <= 1) return byte_route::local;
    if constexpr (Switchable) {
      if (!this->forwarding()) {  // a keypad in local mode
        receiving_ = receiving::discard;
        this->count_drop();
        return byte_route::dropped;
      }
    }
    messages_forwarded_.increment();
    forwards_lost_.increment();
    netstat_.raise(netstat_tx_buffer_error);
    receiving_ = receiving::discard;
    return byte_route::lost;
  }

  // The rest of a forwarded message, [data, end_of_message]: data then the end of message, in one copy if it
  // all fits and is not longer than legal (the same as `receive` for each byte); false, and nothing done, if
  // not.
  template <class Into>
  bool forward_end(const std::uint8_t* data, const std::uint8_t* end_of_message, Into& into) noexcept {
    const auto n = static_cast<std::size_t>(end_of_message - data) + 1;
    if (n > into.free() || n - 1 > remaining_) return false;
    (void)into.push(data, n);
    into.back() = decrement_hops(*end_of_message);
    receiving_ = receiving::local;
    return true;
  }

  // A whole message to forward, [header, end_of_message] (header A > 1, forwarding on, between messages): in
  // one copy if it all fits and is not longer than legal (the same as `receive` for each byte); false, and
  // nothing done, if not.
  template <class Into>
  bool forward_whole(const std::uint8_t* header, const std::uint8_t* end_of_message, Into& into) noexcept {
    const auto n = static_cast<std::size_t>(end_of_message - header) + 1;
    if (n > into.free() || n > longest_frame[static_cast<std::size_t>(*header & 0x07)]) return false;
    const std::size_t header_at = into.size();
    (void)into.push(header, n);
    into.at(header_at) = static_cast<std::uint8_t>(*header - 0x08);  // A > 1: decrement_hops without its check
    into.back() = decrement_hops(*end_of_message);
    messages_forwarded_.increment();
    return true;
  }

  // The forwarded message being received does not fit: it is lost.
  template <class Into>
  byte_route lose(Into& into) noexcept {
    forwards_lost_.increment();
    return end_forward(into);
  }

  // The forwarded message being received is longer than any legal message of its type: it is lost.
  template <class Into>
  byte_route cut(Into& into) noexcept {
    forwards_cut_.increment();
    return end_forward(into);
  }

  template <class Into>
  byte_route end_forward(Into& into) noexcept {
    settle();  // (no grant is open when a message is lost; this keeps `remaining_` exact whatever the caller)
    netstat_.raise(netstat_tx_buffer_error);
    // Its header and data so far are in the buffer, if none of it has gone out.
    const std::size_t incoming = std::size_t{longest_data[forward_type()]} - remaining_ + 1u;
    if (incoming <= into.size()) into.drop_back(incoming);
    receiving_ = receiving::discard;
    return byte_route::lost;
  }

  // The small members first, the buffers last: a Cortex-M0+ reaches the first 32 bytes of the node with one
  // load or store, the next ones take an address computation more.
  std::uint16_t remaining_ = 0;  // data the forwarded message may still carry, less the grant
  netstat_register netstat_;
  single_writer<std::uint16_t> messages_forwarded_;
  single_writer<std::uint16_t> messages_sent_;
  single_writer<std::uint32_t> forwards_lost_;
  single_writer<std::uint32_t> forwards_cut_;
  single_writer<std::uint32_t> forwards_ended_idle_;
  receiving receiving_ = receiving::local;  // forward | type: a forwarded message has begun and not yet ended
  forward_buffer<ForwardCapacity> forward_;
  spsc_fifo<TransmitCapacity> queue_;  // the program side produces, the link side consumes
};

}  // namespace detail
}  // namespace trionet::ring
