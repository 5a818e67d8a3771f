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
// This is the nodes' plumbing (`motion_coordinator` and `keypad` use it through `ring::node`), not an API.
// Cost: ForwardCapacity + TransmitCapacity bytes + about 24 bytes. Per byte O(1), the bulk calls with one copy
// per run of data; ISR-safe.
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
#include "trionet/ring/variable_layout.hpp"

namespace trionet::ring {

/// Where a node's link sent a received byte.
enum class byte_route : std::uint8_t {
  local,      ///< for this node's own decoder (A = 1 or A = 0 messages, and bytes outside any message)
  forwarded,  ///< into the forward buffer
  dropped,    ///< discarded: forwarding is off, or the rest of a lost message
  lost,       ///< the byte on which a forwarded message was lost (buffer full, or longer than legal)
};

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

/// Counters of a node's link; they only ever grow (and wrap at 2^32).
struct link_counters {
  /// Received bytes by where they went, indexed by `byte_route`: their sum is every byte received.
  std::uint32_t bytes[4] = {};
  std::uint32_t messages_forwarded = 0;   ///< headers of messages passed on (A decremented)
  std::uint32_t forwards_lost = 0;        ///< forwarded messages lost to a full forward buffer
  std::uint32_t forwards_cut = 0;         ///< ... longer than the longest legal message of their type
  std::uint32_t forwards_ended_idle = 0;  ///< ... whose end of message never came: the line went idle
  std::uint32_t messages_dropped = 0;     ///< messages through this node dropped while forwarding was off
  std::uint32_t messages_sent = 0;        ///< own messages whose end of message has gone out

  /// Forwarded messages lost for any reason (each sets NETSTAT bit 1).
  constexpr std::uint32_t forwards_failed() const noexcept {
    return forwards_lost + forwards_cut + forwards_ended_idle;
  }
};

namespace detail {

/// `Crc` and `Layout` are the CRC policy and field layout the node's own direct variable transfers are sent
/// with (crc.hpp, variable_layout.hpp); `MaxCharacters` the character maximum of docs/protocol.md 1.4 (the
/// forwarding bound of type 1 and the reserved types).
template <std::size_t ForwardCapacity, std::size_t TransmitCapacity, std::size_t MaxCharacters,
          class Crc = crc16_ccitt_false, class Layout = default_variable_layout>
class link : private crc_holder<Crc> {
  static_assert(ForwardCapacity >= framing_length + variable_data_length && ForwardCapacity < 65535,
                "the forward buffer must hold a whole direct variable transfer (16 bytes): while a node sends "
                "an own frame, as many forwarded bytes arrive as the frame has, and they must not be lost");
  static_assert(TransmitCapacity >= framing_length + 1 && TransmitCapacity < 65535,
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

  /// Takes one received byte and says where it went.
  [[nodiscard]] byte_route receive(std::uint8_t byte) noexcept { return receive(byte, forward_); }

  /// A run of data bytes (no header or end of message among them): the same as `receive` for each, with one
  /// copy. Returns where they went; if a forwarded message is lost part-way, the byte it was lost on is
  /// `lost`, the rest `dropped`, and the result is `lost`.
  [[nodiscard]] byte_route receive_data(const std::uint8_t* data, std::size_t n) noexcept {
    return receive_data(data, n, forward_);
  }

  /// The line has been idle (docs/protocol.md 1.10): a message being forwarded has lost the rest of its bytes. It
  /// is ended and counted (`forwards_ended_idle`; true is returned) and any later byte of it is stray data;
  /// the transmitter then goes on to the node's own messages. The rest of a lost message, if being dropped,
  /// is over too.
  bool line_idle() noexcept {
    const receiving was = receiving_;
    receiving_ = receiving::local;
    if (was != receiving::forward) return false;
    ++counters_.forwards_ended_idle;
    return true;
  }

  /// True while a message through the node has begun and not ended (forwarded, or being dropped).
  bool passing_message() const noexcept { return receiving_ != receiving::local; }

  /// What `receive_passing` took (a forwarded message lost on the way shows in the counters).
  struct passing {
    const std::uint8_t* stop;  ///< the first byte not taken (one for the node itself), or the end
    bool header;               ///< a header was taken: a message the node was receiving ended
  };

  /// Takes bytes from [first, last) while they are not for the node itself: the same as `receive` for each,
  /// in order, with runs of data copied whole, stopping before the first byte `receive` would byte_route `local`.
  TRIONET_ALWAYS_INLINE [[nodiscard]] passing receive_passing(const std::uint8_t* first,
                                                              const std::uint8_t* last) noexcept {
    return receive_passing(first, last, forward_);
  }

  /// The caller's transmit buffer standing in for the forward buffer while the forward buffer is empty and
  /// nothing else is being sent: forwarded bytes go straight into it (see `straight_through`), one copy
  /// instead of two. It only ever receives part of the bytes `straight_through` was asked about, which fit in
  /// it by that check: so it never runs out of room, and says so (`free`), which keeps its pushes unchecked.
  class straight_out {
   public:
    std::size_t size() const noexcept { return size_; }
    // Never less than what comes: `straight_through` checked that all of it fits.
    static constexpr std::size_t free() noexcept { return static_cast<std::size_t>(-1); }
    [[nodiscard]] bool push(std::uint8_t byte) noexcept {
      data_[size_++] = byte;
      return true;
    }
    std::size_t push(const std::uint8_t* bytes, std::size_t n) noexcept {
      trionet::detail::copy_bytes(data_ + size_, bytes, n);
      size_ += n;
      return n;
    }
    std::uint8_t& at(std::size_t i) noexcept { return data_[i]; }
    std::uint8_t& back() noexcept { return data_[size_ - 1]; }
    void drop_back(std::size_t n) noexcept { size_ = n >= size_ ? 0 : size_ - n; }

   private:
    friend class link;
    explicit straight_out(std::uint8_t* data) noexcept : data_(data) {}
    std::uint8_t* data_;
    std::size_t size_ = 0;
  };

  /// Whether `received` bytes and then `transmit(out, capacity)` can go straight through: the forward buffer
  /// is empty, the node is not in the middle of its own message, and both the forward buffer and `out` have
  /// room for every received byte (so nothing received could be lost, and everything forwarded goes out
  /// first). If so, forwarded bytes are written into `out` (`receive_passing` with the returned stand-in),
  /// and `transmit_after` then adds what `transmit` would give after them.
  [[nodiscard]] bool straight_through(std::size_t received, std::size_t capacity) const noexcept {
    return forward_.empty() && sending_ != sending::own && received <= ForwardCapacity &&
           received <= capacity;
  }
  [[nodiscard]] static straight_out straight_buffer(std::uint8_t* out) noexcept { return straight_out(out); }
  TRIONET_ALWAYS_INLINE [[nodiscard]] passing receive_passing(const std::uint8_t* first,
                                                              const std::uint8_t* last,
                                                              straight_out& into) noexcept {
    return receive_passing<straight_out>(first, last, into);
  }
  /// The bytes `transmit(out, capacity)` gives after the forwarded bytes already in `straight` (= out[0..]).
  [[nodiscard]] std::size_t transmit_after(const straight_out& straight, std::uint8_t* out,
                                           std::size_t capacity) noexcept {
    const std::size_t n = straight.size();
    // Not sending an own message (`straight_through`), the transmitter is inside a forwarded message exactly
    // when one is open on the receive side; otherwise it is between messages.
    sending_ = receiving_ == receiving::forward ? sending::forward : sending::idle;
    if (queue_.empty()) return n;  // the forward buffer is empty too: nothing more (`transmit` would say so)
    return n + transmit(out + n, capacity - n);
  }

  /// Fills `out` with up to `capacity` bytes for the link: the same bytes as that many calls of `transmit`,
  /// with the forward buffer's bytes copied whole (they go out first, in order, whatever they are) and runs
  /// of the node's own message data too.
  [[nodiscard]] std::size_t transmit(std::uint8_t* out, std::size_t capacity) noexcept {
    std::size_t n = 0;
    while (n < capacity) {
      if (sending_ != sending::own && !forward_.empty()) {
        n += forward_.pop(out + n, capacity - n);
        sending_ = classify(out[n - 1]) == byte_class::end_of_message ? sending::idle : sending::forward;
        continue;
      }
      if (queue_.empty()) {  // and the forward buffer too: nothing to send (as `transmit` would find)
        if (sending_ == sending::forward && receiving_ != receiving::forward) sending_ = sending::idle;
        break;
      }
      if (sending_ == sending::own) {  // a run of own message data up to its next control byte
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
      if (!transmit(out[n])) break;  // control bytes of own messages, message boundaries, waiting
      ++n;
    }
    return n;
  }

  /// The next byte for the link, if any.
  [[nodiscard]] bool transmit(std::uint8_t& byte) noexcept {
    if (sending_ == sending::forward) {
      if (forward_.pop(byte)) {
        if (classify(byte) == byte_class::end_of_message) sending_ = sending::idle;
        return true;
      }
      if (receiving_ == receiving::forward) return false;  // cut-through: the next byte has not arrived yet
      sending_ = sending::idle;         // the message was cut short upstream or here
    } else if (sending_ == sending::own) {
      if (!queue_.pop(byte)) {  // cannot happen: own frames are queued whole
        sending_ = sending::idle;
        return false;
      }
      if (classify(byte) == byte_class::end_of_message) {
        sending_ = sending::idle;
        ++counters_.messages_sent;
      }
      return true;
    }
    if (forward_.pop(byte)) {
      sending_ = classify(byte) == byte_class::end_of_message ? sending::idle : sending::forward;
      return true;
    }
    if (queue_.pop(byte)) {
      sending_ = sending::own;
      return true;
    }
    return false;
  }

  /// True when `transmit` would give a byte now.
  bool transmit_pending() const noexcept {
    if (!forward_.empty()) return true;
    if (queue_.empty()) return false;
    return !(sending_ == sending::forward && receiving_ == receiving::forward);
  }

  /// Queues one of the node's own messages whole. `encode_status::buffer_too_small` if the transmit queue has
  /// no room for all of it or the frame is longer than `max_own_frame` (nothing is queued), or the message's
  /// own field error.
  [[nodiscard]] encode_result queue(const message& m) noexcept {
    const encode_status status = check(m);
    if (status != encode_status::ok) return {status, 0};
    const std::size_t length = frame_length(m);
    if (length > queue_.free() || length > max_own_frame) return {encode_status::buffer_too_small, 0};
    if (m.type == message_type::character) {  // straight into the queue: no staging copy of the text
      (void)queue_.push(make_header(m.hops, static_cast<std::uint8_t>(m.type)));
      (void)queue_.push(m.text.data(), m.text.size());
      (void)queue_.push(make_end_of_message(m.hops));
    } else {
      std::uint8_t frame[framing_length + variable_data_length];
      const encode_result encoded = encode<Crc, Layout>(frame, m, this->crc());
      (void)queue_.push(frame, encoded.length);
    }
    return {encode_status::ok, length};
  }

  /// Queues `text` (checked: 0..127 each) as consecutive character messages to `hops`, each as long as an own
  /// message may be (docs/protocol.md 1.6: `max_own_characters`, the last one shorter), as many whole messages as
  /// the transmit queue has room for. Returns how many characters were queued. The split depends on the text
  /// only, so a caller that goes on with the rest later sends the same messages.
  std::size_t queue_text(std::uint8_t hops, byte_view text) noexcept {
    std::size_t done = 0;
    while (done < text.size()) {
      std::size_t n = text.size() - done;
      if (n > max_own_characters) n = max_own_characters;
      if (n + framing_length > queue_.free()) break;
      (void)queue_.push(make_header(hops, static_cast<std::uint8_t>(message_type::character)));
      (void)queue_.push(text.data() + done, n);
      (void)queue_.push(make_end_of_message(hops));
      done += n;
    }
    return done;
  }

  /// Free bytes in the transmit queue (a frame is its message plus header and end of message).
  std::size_t transmit_free() const noexcept { return queue_.free(); }
  /// Bytes waiting in the forward buffer.
  std::size_t forward_backlog() const noexcept { return forward_.size(); }

  /// Forwarding on (a Motion Coordinator, a keypad in network mode) or off (a keypad in local mode: messages
  /// through the node are dropped and counted).
  constexpr void set_forwarding(bool on) noexcept { forwarding_ = on; }

  const link_counters& counters() const noexcept { return counters_; }

  static constexpr std::size_t forward_capacity = ForwardCapacity;
  static constexpr std::size_t transmit_capacity = TransmitCapacity;

 private:
  enum class receiving : std::uint8_t { local, forward, discard };

  // The receive side, forwarding `into` the forward buffer or a `straight_out`.
  template <class Into>
  byte_route receive(std::uint8_t byte, Into& into) noexcept {
    const byte_route r = route_byte(byte, into);
    ++counters_.bytes[static_cast<std::size_t>(r)];
    return r;
  }

  template <class Into>
  byte_route receive_data(const std::uint8_t* data, std::size_t n, Into& into) noexcept {
    const auto count = [this](byte_route r, std::size_t k) {
      counters_.bytes[static_cast<std::size_t>(r)] += static_cast<std::uint32_t>(k);
    };
    switch (receiving_) {
      case receiving::local:
        count(byte_route::local, n);
        return byte_route::local;
      case receiving::discard:
        count(byte_route::dropped, n);
        return byte_route::dropped;
      case receiving::forward:
        break;
    }
    const std::size_t allowed = remaining_;
    if (TRIONET_LIKELY(n <= allowed)) {  // the common case: not longer than legal
      const std::size_t pushed = into.push(data, n);
      count(byte_route::forwarded, pushed);
      remaining_ = static_cast<std::uint16_t>(allowed - pushed);
      if (pushed == n) return byte_route::forwarded;
      count(lose(into), 1);
      count(byte_route::dropped, n - pushed - 1);
      return byte_route::lost;
    }
    const std::size_t pushed = into.push(data, allowed);
    count(byte_route::forwarded, pushed);
    remaining_ = static_cast<std::uint16_t>(allowed - pushed);
    count(pushed == allowed ? cut(into) : lose(into), 1);  // cut: the first byte past the longest legal message
    count(byte_route::dropped, n - pushed - 1);
    return byte_route::lost;
  }

  template <class Into>
  TRIONET_ALWAYS_INLINE passing receive_passing(const std::uint8_t* first, const std::uint8_t* last,
                                                Into& into) noexcept {
    passing result{first, false};
    const std::uint8_t* p = first;
    while (p != last) {
      if (receiving_ != receiving::local) {
        const std::uint8_t* const run = find_control(p, last);
        if (receiving_ == receiving::forward && run != last && type_of(*run) == 0 &&
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
        if (forwarding_ && receiving_ == receiving::local) {  // a whole message to forward?
          const std::uint8_t* const end = find_control(p + 1, last);
          if (end != last && type_of(*end) == 0 && forward_whole(p, end, into)) {
            p = end + 1;
            continue;
          }
        }
      }
      (void)receive(byte, into);
      ++p;
    }
    result.stop = p;
    return result;
  }

  template <class Into>
  byte_route route_byte(std::uint8_t byte, Into& into) noexcept {
    if (is_data(byte)) {
      switch (receiving_) {
        case receiving::forward:
          if (remaining_ == 0) return cut(into);
          if (!into.push(byte)) return lose(into);
          --remaining_;
          return byte_route::forwarded;
        case receiving::discard:
          return byte_route::dropped;
        case receiving::local:
          return byte_route::local;
      }
      return byte_route::local;
    }
    const receiving was = receiving_;
    receiving_ = receiving::local;  // any header or end of message ends the message being forwarded
    if (type_of(byte) == 0) {  // end of message
      if (was == receiving::forward) {
        if (!into.push(decrement_hops(byte))) return lose(into);
        return byte_route::forwarded;
      }
      return was == receiving::discard ? byte_route::dropped : byte_route::local;
    }
    const std::uint8_t hops = hops_of(byte);
    if (hops <= 1) return byte_route::local;
    if (!forwarding_) {
      receiving_ = receiving::discard;
      ++counters_.messages_dropped;
      return byte_route::dropped;
    }
    ++counters_.messages_forwarded;
    if (!into.push(decrement_hops(byte))) {  // nothing of it is in the buffer: nothing to remove
      ++counters_.forwards_lost;
      receiving_ = receiving::discard;
      return byte_route::lost;
    }
    receiving_ = receiving::forward;
    limit_ = remaining_ = longest_data[static_cast<std::size_t>(byte & 0x07)];
    return byte_route::forwarded;
  }

  enum class sending : std::uint8_t { idle, forward, own };


  // The rest of a forwarded message, [data, end_of_message]: data then the end of message, in one copy if it
  // all fits and is not longer than legal (the same as `receive` for each byte); false, and nothing done, if
  // not.
  template <class Into>
  bool forward_end(const std::uint8_t* data, const std::uint8_t* end_of_message, Into& into) noexcept {
    const auto n = static_cast<std::size_t>(end_of_message - data) + 1;
    if (n > into.free() || n - 1 > remaining_) return false;
    (void)into.push(data, n);
    into.back() = decrement_hops(*end_of_message);
    counters_.bytes[static_cast<std::size_t>(byte_route::forwarded)] += static_cast<std::uint32_t>(n);
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
    counters_.bytes[static_cast<std::size_t>(byte_route::forwarded)] += static_cast<std::uint32_t>(n);
    ++counters_.messages_forwarded;
    return true;
  }

  // The forwarded message being received does not fit: it is lost.
  template <class Into>
  byte_route lose(Into& into) noexcept {
    ++counters_.forwards_lost;
    return end_forward(into);
  }

  // The forwarded message being received is longer than any legal message of its type: it is lost.
  template <class Into>
  byte_route cut(Into& into) noexcept {
    ++counters_.forwards_cut;
    return end_forward(into);
  }

  template <class Into>
  byte_route end_forward(Into& into) noexcept {
    // Its header and data so far are in the buffer, if none of it has gone out.
    const std::size_t incoming = std::size_t{limit_} - remaining_ + 1u;
    if (incoming <= into.size()) into.drop_back(incoming);
    receiving_ = receiving::discard;
    return byte_route::lost;
  }

  byte_fifo<ForwardCapacity> forward_;
  byte_fifo<TransmitCapacity> queue_;
  link_counters counters_;
  std::uint16_t limit_ = 0;      // the most data the message being forwarded may carry: longest_data
  std::uint16_t remaining_ = 0;  // ... of which it has not carried yet
  receiving receiving_ = receiving::local;  // `forward`: a forwarded message has begun and not yet ended
  sending sending_ = sending::idle;
  bool forwarding_ = true;
};

}  // namespace detail
}  // namespace trionet::ring
