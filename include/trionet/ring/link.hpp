// What every ring node does with its link (PROTOCOL.md 1.5): decrement and forward, one message at a time,
// forwarded traffic before the node's own.
//
//   receive side                          transmit side
//   header A>1 -> header A-1 ---\         between messages: forward buffer first, then the transmit queue;
//   data      -> data ----------+--> forward buffer --+--> link
//   EOM A     -> EOM A-1 ------/                      |
//   header A=1 or A=0, and what follows: local         |
//   own frames (PRINT#, SEND) ---------> transmit queue
//
// Forwarding is cut-through: a forwarded header goes out as soon as the transmitter is between messages,
// each data byte as soon as it arrives. Forwarders do not validate; the destination does.
// If the forward buffer overflows, the forwarded message is lost: removed whole if none of it has gone out,
// otherwise cut short (the destination then sees it interrupted); the rest of it is dropped.
//
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

namespace trionet::ring {

/// Where `link::receive` sent a byte.
enum class route : std::uint8_t {
  local,      ///< for this node's own decoder (A = 1 or A = 0 messages, and bytes outside any message)
  forwarded,  ///< into the forward buffer
  dropped,    ///< discarded: forwarding is off, or the rest of a lost message
  lost,       ///< the forward buffer overflowed on this byte: the forwarded message is lost
};

/// Counters of a link; they only ever grow (and wrap at 2^32).
struct link_counters {
  /// Received bytes by where they went, indexed by `route`: their sum is every byte received.
  std::uint32_t bytes[4] = {};
  std::uint32_t messages_forwarded = 0;  ///< headers of messages passed on (A decremented)
  std::uint32_t forwards_lost = 0;       ///< forwarded messages lost to a full forward buffer
  std::uint32_t messages_dropped = 0;    ///< messages through this node dropped while forwarding was off
  std::uint32_t messages_sent = 0;       ///< own messages whose end of message has gone out
};

/// `Crc` and `Layout` are the CRC policy and field layout the node's own direct variable transfers are sent
/// with (crc.hpp, variable_layout.hpp).
template <std::size_t ForwardCapacity, std::size_t TransmitCapacity, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
class link {
  static_assert(ForwardCapacity < 65535, "the forward buffer holds up to 65534 bytes");

 public:
  /// Takes one received byte and says where it went.
  [[nodiscard]] route receive(std::uint8_t byte) noexcept { return receive(byte, forward_); }

  /// A run of data bytes (no header or end of message among them): the same as `receive` for each, with one
  /// copy. Returns where they went; if a forwarded message overflows part-way, the byte that did not fit is
  /// `lost`, the rest `dropped`, and the result is `lost`.
  [[nodiscard]] route receive_data(const std::uint8_t* data, std::size_t n) noexcept {
    return receive_data(data, n, forward_);
  }

  /// What `receive_passing` took.
  struct passing {
    static constexpr std::uint8_t header = 1;  ///< a header was taken: a message the node was receiving ended
    static constexpr std::uint8_t lost = 2;    ///< a forwarded message was lost
    const std::uint8_t* stop;  ///< the first byte not taken (one for the node itself), or the end
    std::uint8_t events;       ///< `header` and `lost` bits: what happened on the way
  };

  /// Takes bytes from [first, last) while they are not for the node itself: the same as `receive` for each,
  /// in order, with runs of data copied whole, stopping before the first byte `receive` would route `local`.
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
    static constexpr std::size_t free() noexcept { return ForwardCapacity; }  // never less than what comes
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
    if (n != 0)
      sending_ = classify(out[n - 1]) == byte_class::end_of_message ? sending::idle : sending::forward;
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
        if (sending_ == sending::forward && !forward_open_) sending_ = sending::idle;
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
      if (forward_open_) return false;  // cut-through: the next byte has not arrived yet
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
    return !(sending_ == sending::forward && forward_open_);
  }

  /// Queues one of the node's own messages whole. `encode_error::buffer_too_small` if the transmit queue has
  /// no room for all of it (nothing is queued), or the message's own field error.
  [[nodiscard]] encode_result queue(const message& m) noexcept {
    const encode_error error = check(m);
    if (error != encode_error::none) return {0, error};
    const std::size_t length = frame_length(m);
    if (length > queue_.free()) return {0, encode_error::buffer_too_small};
    if (m.type == message_type::character) {  // straight into the queue: no staging copy of the text
      (void)queue_.push(make_header(m.hops, static_cast<std::uint8_t>(m.type)));
      for (std::uint8_t c : m.text) (void)queue_.push(c);
      (void)queue_.push(make_end_of_message(m.hops));
    } else {
      std::uint8_t frame[framing_length + variable_data_length];
      const encode_result encoded = encode<Crc, Layout>(frame, m);
      for (std::size_t i = 0; i < encoded.length; ++i) (void)queue_.push(frame[i]);
    }
    return {length, encode_error::none};
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
  route receive(std::uint8_t byte, Into& into) noexcept {
    const route r = route_byte(byte, into);
    ++counters_.bytes[static_cast<std::size_t>(r)];
    return r;
  }

  template <class Into>
  route receive_data(const std::uint8_t* data, std::size_t n, Into& into) noexcept {
    const auto count = [this](route r, std::size_t k) {
      counters_.bytes[static_cast<std::size_t>(r)] += static_cast<std::uint32_t>(k);
    };
    switch (receiving_) {
      case receiving::local:
        count(route::local, n);
        return route::local;
      case receiving::discard:
        count(route::dropped, n);
        return route::dropped;
      case receiving::forward:
        break;
    }
    const std::size_t pushed = into.push(data, n);
    count(route::forwarded, pushed);
    const std::size_t incoming = incoming_ + pushed;
    incoming_ = static_cast<std::uint16_t>(incoming <= ForwardCapacity ? incoming : ForwardCapacity + 1);
    if (pushed == n) return route::forwarded;
    count(lose(into), 1);
    count(route::dropped, n - pushed - 1);
    return route::lost;
  }

  template <class Into>
  TRIONET_ALWAYS_INLINE passing receive_passing(const std::uint8_t* first, const std::uint8_t* last,
                                                Into& into) noexcept {
    passing result{first, 0};
    const std::uint8_t* p = first;
    while (p != last) {
      if (receiving_ != receiving::local) {
        const std::uint8_t* const run = find_control(p, last);
        if (receiving_ == receiving::forward && run != last && type_of(*run) == 0 &&
            forward_end(p, run, into)) {
          p = run + 1;
          continue;
        }
        if (run != p && receive_data(p, static_cast<std::size_t>(run - p), into) == route::lost) {
          result.events |= passing::lost;
        }
        p = run;
        if (p == last) break;
      }
      const std::uint8_t byte = *p;  // a control byte, or data for the node
      if (is_data(byte)) break;
      if (type_of(byte) == 0) {
        if (receiving_ == receiving::local) break;  // the end of the node's own message
      } else {
        if (hops_of(byte) <= 1) break;  // a message for the node
        result.events |= passing::header;
        if (forwarding_ && receiving_ == receiving::local) {  // a whole message to forward?
          const std::uint8_t* const end = find_control(p + 1, last);
          if (end != last && type_of(*end) == 0 && forward_whole(p, end, into)) {
            p = end + 1;
            continue;
          }
        }
      }
      if (receive(byte, into) == route::lost) result.events |= passing::lost;
      ++p;
    }
    result.stop = p;
    return result;
  }

  template <class Into>
  route route_byte(std::uint8_t byte, Into& into) noexcept {
    if (is_data(byte)) {
      switch (receiving_) {
        case receiving::forward:
          return forward(byte, into);
        case receiving::discard:
          return route::dropped;
        case receiving::local:
          return route::local;
      }
      return route::local;
    }
    const receiving was = receiving_;
    receiving_ = receiving::local;
    forward_open_ = false;     // any header or end of message ends the message being forwarded
    if (type_of(byte) == 0) {  // end of message
      if (was == receiving::forward) {
        return forward(decrement_hops(byte), into);
      }
      return was == receiving::discard ? route::dropped : route::local;
    }
    const std::uint8_t hops = hops_of(byte);
    if (hops <= 1) return route::local;
    if (!forwarding_) {
      receiving_ = receiving::discard;
      ++counters_.messages_dropped;
      return route::dropped;
    }
    receiving_ = receiving::forward;
    forward_open_ = true;
    incoming_ = 0;
    ++counters_.messages_forwarded;
    return forward(decrement_hops(byte), into);
  }

  enum class sending : std::uint8_t { idle, forward, own };

  template <class Into>
  route forward(std::uint8_t byte, Into& into) noexcept {
    if (into.push(byte)) {
      if (incoming_ <= ForwardCapacity) ++incoming_;  // ForwardCapacity < 65535: never wraps
      return route::forwarded;
    }
    return lose(into);
  }

  // The rest of a forwarded message, [data, end_of_message]: data then the end of message, in one copy if it
  // all fits (the same as `receive` for each byte); false, and nothing done, if it does not.
  template <class Into>
  bool forward_end(const std::uint8_t* data, const std::uint8_t* end_of_message, Into& into) noexcept {
    const auto n = static_cast<std::size_t>(end_of_message - data) + 1;
    if (n > into.free()) return false;
    (void)into.push(data, n);
    into.back() = decrement_hops(*end_of_message);
    counters_.bytes[static_cast<std::size_t>(route::forwarded)] += static_cast<std::uint32_t>(n);
    receiving_ = receiving::local;
    forward_open_ = false;
    return true;
  }

  // A whole message to forward, [header, end_of_message] (header A > 1, forwarding on, between messages): in
  // one copy if it all fits (the same as `receive` for each byte); false, and nothing done, if it does not.
  template <class Into>
  bool forward_whole(const std::uint8_t* header, const std::uint8_t* end_of_message, Into& into) noexcept {
    const auto n = static_cast<std::size_t>(end_of_message - header) + 1;
    if (n > into.free()) return false;
    const std::size_t header_at = into.size();
    (void)into.push(header, n);
    into.at(header_at) = decrement_hops(*header);
    into.back() = decrement_hops(*end_of_message);
    counters_.bytes[static_cast<std::size_t>(route::forwarded)] += static_cast<std::uint32_t>(n);
    ++counters_.messages_forwarded;
    return true;
  }

  // The forwarded message being received does not fit: it is lost.
  template <class Into>
  route lose(Into& into) noexcept {
    ++counters_.forwards_lost;
    if (incoming_ <= into.size()) into.drop_back(incoming_);  // none of it has gone out yet
    forward_open_ = false;
    receiving_ = receiving::discard;
    return route::lost;
  }

  byte_fifo<ForwardCapacity> forward_;
  byte_fifo<TransmitCapacity> queue_;
  link_counters counters_;
  std::uint16_t incoming_ = 0;  // bytes of the message being forwarded now in the buffer (saturates)
  receiving receiving_ = receiving::local;
  sending sending_ = sending::idle;
  bool forward_open_ = false;  // a forwarded message has begun and not ended on the receive side
  bool forwarding_ = true;
};

}  // namespace trionet::ring
