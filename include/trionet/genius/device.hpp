// A Genius device node (docs/protocol.md 3.4): one station on a Genius bus that takes its turn, as firmware
// runs it behind a 9-bit UART and one timer, and as the host simulator runs many of on one modelled bus.
//
//   UART word in --> receive ----+--> its own word read back: compare (a difference is a collision)
//   framing error -> framing_error+--> others' transmissions: parse, CRC-6, deliver (broadcast, directed
//   start bit ---> start_bit --> cancels the timer              to it, blocks to it) --> delivery queue
//   timer -------> timer_expired --> its turn: turn data or a directed transmission --> transmit --> UART
//                                    or the bus went quiet: a lost transmission, an idle restart
//   program: set_turn_data, queue_directed, read, counters, netstat
//
// Bus access (3.3, 3.4). At the end of every Stop from SBA s (s is the sender of the Start heard before it)
// the device arms its timer for skip x ((d - s) mod 32) and takes its turn when it expires, unless a start
// bit comes first. Its turn sends a queued one-shot directed transmission if there is one, else its turn
// data (a broadcast, every turn until changed), else nothing (the turn passes in silence). It reads back
// every character it sends: one that comes back different, or another device's start bit before its first
// character goes out, is a collision: it stops after that character and waits for the next Stop.
// Liveness: silence of `idle_characters` character times inside a transmission loses it (counted), and every
// device acts as if its sender's Stop had ended then; silence of 32 skip times + `idle_characters`
// character times with no transmission at all is an idle restart: every device acts as if the Stop of SBA 31
// had ended, so turns resume from SBA 0.
//
// The link driver. Every link-side call returns a `link_request`: what to do with the device's one-shot
// timer (keep it, arm it for `ticks`, cancel it) and whether a word is ready (`transmit`: call `transmit`
// and give the UART the word). A timer armed by `receive` or `framing_error` runs from the END of the
// character just received (a UART that reports a word at the middle of its stop bit adds half a bit); one
// armed by any other call runs from the moment of the call. Ticks are the unit of `device_timing`: by
// default one bit time. A firmware driver:
//
//   void UART_RX_IRQHandler() {                         // a word (or a framing error) received
//     const auto request = uart_framing_error() ? node.framing_error() : node.receive(uart_read());
//     apply(request, /*from_end_of_character=*/true);
//   }
//   void RX_EDGE_IRQHandler() { apply(node.start_bit(), false); }   // a start bit detected on the line
//   void TIMER_IRQHandler()   { apply(node.timer_expired(), false); }
//   void apply(genius::link_request r, bool from_end) {
//     if (r.timer == genius::timer_action::arm) timer_start(r.ticks, from_end);
//     if (r.timer == genius::timer_action::cancel) timer_stop();
//     std::uint16_t word;
//     if (r.transmit && node.transmit(word)) uart_write(word);   // 9-bit word: bit 0 the control bit
//   }
//   // at power-up: apply(node.power_on(), false);
//
// Characters follow each other without a gap as long as the next word reaches the UART within the rest of
// the stop bit of the one read back (a UART with a transmit holding register has it then).
//
// Two sides, no lock and no interrupt masking (docs/design.md, "Contexts"):
//   link side (one interrupt context, or ISRs of one priority): power_on, receive, framing_error,
//     start_bit, timer_expired, transmit, and everything that a delivery does
//   program side (one thread context: the main loop or one RTOS task): set_turn_data, clear_turn_data,
//     queue_directed, directed_waiting, read, deliveries_waiting, netstat, clear_netstat
//   either side: counters, sba
//   link side only (plain link-side state, for drivers, monitors and tests; the program side may call them
//     only while the link side is stopped): sending, in_transmission, turn_armed
// Deliveries cross in a single-producer, single-consumer queue (a transmission's records published whole,
// at its Stop); a directed transmission in a ring of slots (one producer index, one consumer index); the
// turn data in three buffers (the program writes one that the link side neither sends from nor can start
// to); counters are `single_writer`s; NETSTAT is a register whose two bytes have one writer each.
//
// Cost (Cortex-M0+, default capacities): 368 bytes of RAM: 3 x (TurnCapacity + 1) for the turn data,
// DeliveryCapacity + 2 for the delivery queue, DirectedSlots x (DirectedCapacity + 4) for directed
// transmissions, 60 bytes of counters and the broadcast mask, and about 70 of state and configuration. Every
// link-side call is O(1) (the turn's start O(1) too: no copy); `set_turn_data` is O(its bytes); `read` O(the
// record's bytes). No heap.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "trionet/detail/crc_holder.hpp"
#include "trionet/detail/fifo.hpp"
#include "trionet/detail/single_writer.hpp"
#include "trionet/genius/bus_access.hpp"
#include "trionet/genius/character.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/genius/transmission.hpp"
#include "trionet/span.hpp"

namespace trionet::genius {

/// What a link-side call asks the driver to do with the device's one-shot timer.
enum class timer_action : std::uint8_t {
  keep,    ///< leave the timer as it is (armed or not)
  arm,     ///< (re)arm it for `link_request::ticks`
  cancel,  ///< stop it
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(timer_action value) noexcept {
  switch (value) {
    case timer_action::keep:
      return "keep";
    case timer_action::arm:
      return "arm";
    case timer_action::cancel:
      return "cancel";
  }
  return "unknown";
}

/// What the link driver does after a link-side call (see the file comment). Eight bytes, `ticks` first, so that
/// it is built and returned in one register on a 64-bit host (no store of its bytes read back as a word).
struct [[nodiscard]] link_request {
  std::uint32_t ticks = 0;                  ///< `arm`: ticks from the end of the character received
                                            ///< (receive, framing_error) or from now (other calls)
  timer_action timer = timer_action::keep;  ///< the timer: keep, arm for `ticks`, or cancel
  bool transmit = false;                    ///< a word is ready: call `transmit` and send it
};
static_assert(sizeof(link_request) == 8, "a link request is one 64-bit word");

/// A device's timing in timer ticks (docs/protocol.md 3.3, 3.4). With one tick per bit time (the default,
/// `bit_timing`), `skip_ticks` is the rule's 1 (2 at 153.6e) and a character 11. A host model may count in
/// finer ticks (the simulator counts picoseconds, so that any skip time, GE's example's 26 us included, is
/// exact).
struct device_timing {
  std::uint32_t skip_ticks = 1;        ///< one skip time
  std::uint32_t character_ticks = 11;  ///< one character (11 bit times)
  std::uint8_t idle_characters = 2;    ///< silence that ends a transmission (configurable, default 2)

  /// The longest timer a device arms: 32 skip times + `idle_characters` character times (the idle restart).
  [[nodiscard]] constexpr std::uint64_t longest_ticks() const noexcept {
    return 32u * std::uint64_t{skip_ticks} + std::uint64_t{idle_characters} * character_ticks;
  }
  /// True when every timer fits the 32-bit tick count and the parameters are not 0.
  [[nodiscard]] constexpr bool valid() const noexcept {
    return skip_ticks != 0 && character_ticks != 0 && idle_characters != 0 && longest_ticks() <= 0xFFFFFFFFu;
  }
};

/// The timing of `r` counted in bit times: the rule's skip time, 11 ticks a character, 2 idle characters.
[[nodiscard]] constexpr device_timing bit_timing(rate r) noexcept {
  return device_timing{properties(r).skip_bits, 11, 2};
}

/// A device's NETSTAT bits: errors since the program last cleared them (`device::netstat`).
enum netstat_bit : std::uint8_t {
  netstat_collision = 1,           ///< a character it sent came back different (or a start bit beat its turn)
  netstat_crc_error = 2,           ///< a Stop or End of block whose CRC-6 did not match
  netstat_framing_error = 4,       ///< a character with a framing error
  netstat_lost_transmission = 8,   ///< a transmission ended by silence before its Stop
  netstat_wire_error = 16,         ///< a transmission discarded for its structure (docs/protocol.md 3.2)
  netstat_delivery_overflow = 32,  ///< a transmission for it did not fit the delivery queue (dropped whole)
  netstat_idle_restart = 64,       ///< the bus was quiet for the idle time: turns restarted from SBA 0
};

/// The bit's name, as spelled in `netstat_bit`.
constexpr const char* to_string(netstat_bit bit) noexcept {
  switch (bit) {
    case netstat_collision:
      return "netstat_collision";
    case netstat_crc_error:
      return "netstat_crc_error";
    case netstat_framing_error:
      return "netstat_framing_error";
    case netstat_lost_transmission:
      return "netstat_lost_transmission";
    case netstat_wire_error:
      return "netstat_wire_error";
    case netstat_delivery_overflow:
      return "netstat_delivery_overflow";
    case netstat_idle_restart:
      return "netstat_idle_restart";
  }
  return "unknown";
}

/// A device's counts since power-up, each read whole (not all at one instant). Each wraps at 2^32.
struct device_counters {
  std::uint32_t turns_taken = 0;          ///< turns in which it began a transmission
  std::uint32_t turns_passed = 0;         ///< turns it let pass in silence (nothing to send)
  std::uint32_t transmissions_sent = 0;   ///< its transmissions read back whole, Stop included
  std::uint32_t collisions = 0;           ///< its transmissions cut by a collision
  std::uint32_t characters = 0;           ///< well-framed characters received (its own read back included)
  std::uint32_t framing_errors = 0;       ///< characters received with a framing error
  std::uint32_t transmissions_heard = 0;  ///< others' transmissions received whole with a good CRC-6
  std::uint32_t crc_errors = 0;           ///< others' transmissions discarded for a CRC-6 mismatch
  std::uint32_t wire_errors = 0;          ///< others' transmissions (or strays) discarded for their structure
  std::uint32_t lost_transmissions = 0;   ///< transmissions ended by silence before their Stop
  std::uint32_t deliveries = 0;           ///< records put in the delivery queue
  std::uint32_t delivery_overflows = 0;   ///< transmissions for it dropped whole for lack of room
  std::uint32_t idle_restarts = 0;        ///< idle restarts (the quiet bus, power-up included)
  std::uint32_t skipped = 0;  ///< characters skipped to the next Start (after an error, at power-up)
};

/// What a delivery is.
enum class delivery_kind : std::uint8_t {
  broadcast,  ///< the plain data of a broadcast transmission
  directed,   ///< the plain data of a transmission directed to this device (destination SBA not included)
  block,      ///< a block addressed to this device (Start of block), inside any transmission
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(delivery_kind value) noexcept {
  switch (value) {
    case delivery_kind::broadcast:
      return "broadcast";
    case delivery_kind::directed:
      return "directed";
    case delivery_kind::block:
      return "block";
  }
  return "unknown";
}

/// What `device::read` found.
enum class delivery_status : std::uint8_t {
  ok,                ///< a delivery was copied out (and removed)
  none_waiting,      ///< the delivery queue is empty
  buffer_too_small,  ///< the next delivery is longer than the buffer: nothing copied, it stays (`length`)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(delivery_status value) noexcept {
  switch (value) {
    case delivery_status::ok:
      return "ok";
    case delivery_status::none_waiting:
      return "none_waiting";
    case delivery_status::buffer_too_small:
      return "buffer_too_small";
  }
  return "unknown";
}

/// One delivery: its kind, its sender and its length (the bytes copied out for `ok`, the bytes needed for
/// `buffer_too_small`).
struct [[nodiscard]] delivery_result {
  delivery_status status = delivery_status::none_waiting;  ///< `ok`, or why nothing was copied
  delivery_kind kind = delivery_kind::broadcast;           ///< what it is
  std::uint8_t sender = 0;                                 ///< the sender's SBA
  std::size_t length = 0;                                  ///< its data bytes
  /// True when a delivery was copied out.
  constexpr explicit operator bool() const noexcept { return status == delivery_status::ok; }
};

/// What became of new turn data (misuse of the API; on anything but `ok` the turn data is unchanged).
enum class turn_data_status : std::uint8_t {
  ok,                        ///< the next turn sends it
  too_long,                  ///< more than the device's turn-data capacity (or a block of over 255 bytes)
  empty_block,               ///< a block with no data
  destination_out_of_range,  ///< a block's destination > 31
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(turn_data_status value) noexcept {
  switch (value) {
    case turn_data_status::ok:
      return "ok";
    case turn_data_status::too_long:
      return "too_long";
    case turn_data_status::empty_block:
      return "empty_block";
    case turn_data_status::destination_out_of_range:
      return "destination_out_of_range";
  }
  return "unknown";
}

/// What became of a directed transmission queued (misuse of the API; nothing is queued unless `ok`).
enum class queue_status : std::uint8_t {
  ok,                        ///< queued: it goes first at one of the next turns
  full,                      ///< every slot holds a transmission not yet sent
  too_long,                  ///< more data than a slot holds
  destination_out_of_range,  ///< destination > 31
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(queue_status value) noexcept {
  switch (value) {
    case queue_status::ok:
      return "ok";
    case queue_status::full:
      return "full";
    case queue_status::too_long:
      return "too_long";
    case queue_status::destination_out_of_range:
      return "destination_out_of_range";
  }
  return "unknown";
}

/// Bytes a delivery record takes in the delivery queue besides its data (kind, sender, length).
constexpr std::size_t delivery_header_bytes = 3;

namespace detail {

// The turn data and a directed transmission are kept as the body of a transmission: segments, each a header
// byte (a block's destination 0..31, or `plain_segment`), a length byte (1..255) and the data.
constexpr std::uint8_t plain_segment = 0xFF;

// The encoded size of `segments` (0 when there is no data at all), or a status.
struct body_size {
  turn_data_status status;
  std::size_t bytes;
};

// The encoded size of plain data of `n` bytes: segments of up to 255 bytes.
constexpr std::size_t plain_body_size(std::size_t n) noexcept {
  return 2 * ((n + 254) / 255) + n;
}

constexpr body_size measure_body(span<const segment> segments) noexcept {
  std::size_t bytes = 0;
  for (const segment& s : segments) {
    if (s.block) {
      if (s.destination > max_sba) return {turn_data_status::destination_out_of_range, 0};
      if (s.data.empty()) return {turn_data_status::empty_block, 0};
      if (s.data.size() > 255) return {turn_data_status::too_long, 0};
      bytes += 2 + s.data.size();
    } else {
      bytes += plain_body_size(s.data.size());
    }
  }
  return {turn_data_status::ok, bytes};
}

// Writes `data` as segments with the header `header` (a block's destination, or `plain_segment`: a plain
// segment holds up to 255 bytes, a block all of `data`); returns the end of what it wrote.
constexpr std::uint8_t* write_segments(std::uint8_t* out, std::uint8_t header, byte_view data) noexcept {
  std::size_t from = 0;
  while (from < data.size()) {
    const std::size_t n = header != plain_segment || data.size() - from <= 255 ? data.size() - from : 255;
    *out++ = header;
    *out++ = static_cast<std::uint8_t>(n);
    for (std::size_t i = 0; i < n; ++i) *out++ = data[from + i];
    from += n;
  }
  return out;
}

constexpr void write_body(std::uint8_t* out, span<const segment> segments) noexcept {
  for (const segment& s : segments)
    out = write_segments(out, s.block ? s.destination : plain_segment, s.data);
}

// A control layout (transmission.hpp) as a device encodes and decodes it, worked out once: the shifts of the
// tag and the fields, the tag of each kind (start, stop, start of block, end of block), and the kind of each
// tag (`control_kind::unknown` for none; a tag shared by two kinds reads as the first, as `read_control`).
struct control_code {
  std::uint8_t tag_shift;
  std::uint8_t field_shift;
  std::uint8_t tag[4];
  control_kind kind[4];

  constexpr explicit control_code(const control_layout& layout) noexcept
      : tag_shift(layout.position == tag_position::high ? 6 : 0),
        field_shift(layout.position == tag_position::high ? 0 : 2),
        tag{static_cast<std::uint8_t>(layout.start & 3u), static_cast<std::uint8_t>(layout.stop & 3u),
            static_cast<std::uint8_t>(layout.start_of_block & 3u),
            static_cast<std::uint8_t>(layout.end_of_block & 3u)},
        kind{kind_of(layout, 0), kind_of(layout, 1), kind_of(layout, 2), kind_of(layout, 3)} {}

  static constexpr control_kind kind_of(const control_layout& layout, std::uint8_t tag) noexcept {
    if (tag == layout.start) return control_kind::start;
    if (tag == layout.stop) return control_kind::stop;
    if (tag == layout.start_of_block) return control_kind::start_of_block;
    if (tag == layout.end_of_block) return control_kind::end_of_block;
    return control_kind::unknown;
  }
  // The control character of `kind` (not unknown) carrying the 6 field bits `fields`.
  constexpr character encode(control_kind which, unsigned fields) const noexcept {
    const unsigned tag_bits = tag[static_cast<unsigned>(which)];
    return control_character(static_cast<std::uint8_t>(tag_bits << tag_shift | (fields & 0x3fu) << field_shift));
  }
  // The same as a 9-bit UART word (`to_uart_word(encode(which, fields))`).
  constexpr std::uint16_t encode_word(control_kind which, unsigned fields) const noexcept {
    return to_uart_word(encode(which, fields));
  }
  // The fields of a control character's byte (as `read_control`).
  constexpr control_fields decode(std::uint8_t byte) const noexcept {
    const auto fields = static_cast<std::uint8_t>((byte >> field_shift) & 0x3fu);
    control_fields f;
    f.kind = kind[(byte >> tag_shift) & 3u];
    f.sba = static_cast<std::uint8_t>(fields & 0x1fu);
    f.broadcast = (fields & 0x20u) != 0;
    f.crc = fields;
    if (f.kind == control_kind::start_of_block && f.broadcast) f.kind = control_kind::unknown;
    return f;
  }
};

// NETSTAT for two writers: the link side raises bits by flipping them in `raised_` (when not raised
// already); the program side clears by copying `raised_` into `cleared_`. A bit is raised while the two
// bytes differ in it.
class netstat_bits {
 public:
  void raise(std::uint8_t bits) noexcept {
    const std::uint8_t raised = raised_.load();
    const auto pending = static_cast<std::uint8_t>(bits & ~(raised ^ cleared_.load()));
    raised_.store(static_cast<std::uint8_t>(raised ^ pending));  // its own value again when none is pending
  }
  std::uint8_t read() const noexcept { return static_cast<std::uint8_t>(raised_.load() ^ cleared_.load()); }
  void clear() noexcept { cleared_.store(raised_.load()); }

 private:
  trionet::detail::single_writer<std::uint8_t> raised_;   // link side
  trionet::detail::single_writer<std::uint8_t> cleared_;  // program side
};

// A turn-data buffer's index, shared by the two sides: sequentially consistent, so that of the program side's
// look at `reading_` after publishing and the link side's look at `published_` after claiming, one sees the
// other's store (set_turn_data). A load and a store each (a `dmb` on Cortex-M), never a read-modify-write.
class shared_index {
 public:
  constexpr shared_index() noexcept = default;
  shared_index(const shared_index& other) noexcept : value_(other.load()) {}
  shared_index& operator=(const shared_index& other) noexcept {
    store(other.load());
    return *this;
  }
  ~shared_index() = default;
  std::uint8_t load() const noexcept { return value_.load(std::memory_order_seq_cst); }
  // A look that orders nothing (no `dmb`): its writer's own look, or the other side's look at a candidate
  // that a sequentially consistent load then confirms.
  std::uint8_t load_relaxed() const noexcept { return value_.load(std::memory_order_relaxed); }
  void store(std::uint8_t value) noexcept { value_.store(value, std::memory_order_seq_cst); }

 private:
  std::atomic<std::uint8_t> value_{0};
};

}  // namespace detail

/// A Genius device node (see the file comment). `TurnCapacity` bytes hold the turn data's body (a plain
/// broadcast of n <= 253 bytes takes n + 2), three times over; `DeliveryCapacity` bytes the delivery queue
/// (each delivery takes its data + 3); `DirectedSlots` directed transmissions of up to `DirectedCapacity`
/// data bytes may wait. `Crc` is the CRC-6 policy (crc6.hpp).
///
/// Defaults (32 turn-data bytes, a 96-byte delivery queue, two directed transmissions of 16 bytes): 368 bytes
/// of RAM on a Cortex-M0+ (`sizeof`). Copy a device only while neither side runs.
template <std::size_t TurnCapacity = 32, std::size_t DeliveryCapacity = 96, std::size_t DirectedCapacity = 16,
          std::size_t DirectedSlots = 2, class Crc = crc6_g704>
class device : private trionet::detail::crc_holder<Crc> {
  static_assert(TurnCapacity >= 3 && TurnCapacity <= 65535,
                "turn data holds 3..65535 bytes (a body of 1 byte takes 3)");
  static_assert(DeliveryCapacity >= delivery_header_bytes + 1,
                "the delivery queue must hold at least one delivery of one byte (4 bytes)");
  static_assert(DirectedCapacity <= 253, "a directed transmission carries at most 253 data bytes");
  static_assert(DirectedSlots >= 1 && DirectedSlots <= 127, "1..127 directed slots");

 public:
  static constexpr std::size_t turn_capacity = TurnCapacity;          ///< bytes of a turn-data body
  static constexpr std::size_t delivery_capacity = DeliveryCapacity;  ///< bytes of the delivery queue
  static constexpr std::size_t directed_capacity = DirectedCapacity;  ///< data bytes of one directed slot
  static constexpr std::size_t directed_slots = DirectedSlots;  ///< directed transmissions that may wait

  /// A device with SBA `sba` (0..31; higher values are masked to 5 bits), timing `timing` (`valid()`; counted
  /// in the ticks of its timer), the CRC `crc` and the control-character layout `layout`. constexpr, so that
  /// a device at namespace scope in firmware needs no start-up code.
  constexpr explicit device(std::uint8_t sba, device_timing timing = bit_timing(rate::standard_153k6),
                            const Crc& crc = Crc{}, const control_layout& layout = control_layout{}) noexcept
      : trionet::detail::crc_holder<Crc>(crc),
        sba_(static_cast<std::uint8_t>(sba & max_sba)),
        code_(layout),
        skip_ticks_(timing.skip_ticks),
        gap_ticks_(static_cast<std::uint32_t>(timing.idle_characters * timing.character_ticks)),
        character_ticks_(timing.character_ticks) {}

  /// This device's SBA.
  [[nodiscard]] constexpr std::uint8_t sba() const noexcept { return sba_; }
  /// Its timing.
  [[nodiscard]] constexpr device_timing timing() const noexcept {
    return device_timing{skip_ticks_, character_ticks_, static_cast<std::uint8_t>(gap_ticks_ / character_ticks_)};
  }

  // ---- the link side ----

  /// Link side: power-up. The device listens; with no transmission heard for the idle time it restarts
  /// the turns (arms that timer now).
  link_request power_on() noexcept { return arm(armed::quiet, quiet_ticks()); }

  /// Link side: a start bit was detected on the bus (its own included). Cancels the timer: a turn not yet
  /// due is given up to whoever is sending; a turn due whose first word has not gone out is a collision.
  link_request start_bit() noexcept {
    if (state_ == state::turn_due) collided();
    armed_ = armed::none;
    return link_request{0, timer_action::cancel, false};
  }

  /// Link side: a 9-bit UART word received (bit 0 the control bit, bits 8..1 the data byte; bits above 8
  /// are ignored). A timer it arms runs from the end of this character.
  TRIONET_ALWAYS_INLINE link_request receive(std::uint16_t word) noexcept {
    characters_.increment();
    word &= uart_word_mask;
    if (state_ == state::sending) {
      if (word == sent_) return read_back();
      collided();  // it may be another device's Start: follow it
    }
    return hear(word);
  }

  /// Link side: a character was received with a framing error (start bit not 0 or stop bit not 1). A timer
  /// it arms runs from the end of this character.
  link_request framing_error() noexcept {
    count(error::framing);
    if (state_ == state::sending) {
      collided();
    } else if (rx_open_) {
      discard();
    }
    return after_character();
  }

  /// Link side: the timer expired: its turn (it sends, or the turn passes), silence inside a transmission
  /// (lost: as if its sender's Stop had ended now), or the quiet bus (an idle restart). A timer it arms runs
  /// from now.
  TRIONET_ALWAYS_INLINE link_request timer_expired() noexcept {
    const armed what = armed_;
    armed_ = armed::none;
    if (what == armed::none) return link_request{};
    if (what == armed::turn) return take_turn();
    std::uint8_t sender = max_sba;  // the quiet bus: as if the Stop of SBA 31 had ended
    if (what == armed::quiet) {
      count(error::idle_restart);
    } else {
      // Silence inside a transmission: its rest is lost.
      // Its own read-back stopped coming: the transmission is over as far as it can tell.
      const bool own = sending();
      if (own || rx_open_) {
        count(error::lost_transmission);
        if (own) {
          state_ = state::listening;
        } else {
          discard();
        }
      }
      sender = bus_sender_;
      bus_sender_ = no_sender;
    }
    return after_stop_of(sender, what == armed::quiet);
  }

  /// Link side: the next word to send (9-bit UART word), if one is due now: the first word of its turn, or
  /// the next one after the last was read back unchanged. False leaves `word` untouched.
  [[nodiscard]] bool transmit(std::uint16_t& word) noexcept {
    if (state_ == state::turn_due) {
      state_ = state::sending;
    } else if (state_ != state::sending || !next_ready_) {
      return false;
    }
    next_ready_ = false;
    sent_ = next_word();
    word = sent_;
    return true;
  }

  /// Link side: true while its own transmission is under way (its turn taken, the Stop not yet read back).
  /// Not for the program side while the link side runs: it reads link-side state that is not shared.
  [[nodiscard]] bool sending() const noexcept {
    return state_ == state::sending || state_ == state::turn_due;
  }
  /// Link side: true while its turn timer is armed (its turn due after the last Stop, not yet cancelled).
  [[nodiscard]] bool turn_armed() const noexcept { return armed_ == armed::turn; }
  /// Link side: true while another device's transmission is being received (a Start heard, no Stop yet).
  [[nodiscard]] bool in_transmission() const noexcept { return rx_open_; }

  // ---- the program side ----

  /// Program side: the turn data, a broadcast of `data` sent at every turn from the next on until changed.
  /// Empty: no turn data (its turns pass, unless a directed transmission waits).
  turn_data_status set_turn_data(byte_view data) noexcept {
    const std::size_t bytes = detail::plain_body_size(data.size());
    if (bytes > TurnCapacity) return turn_data_status::too_long;
    const std::uint8_t free = free_turn_buffer();
    detail::write_segments(turn_[free], detail::plain_segment, data);
    publish_turn_data(free, bytes);
    return turn_data_status::ok;
  }
  /// Program side: the turn data as plain data and blocks (a bus controller's outputs, one block per
  /// device), in order. No data at all: no turn data.
  turn_data_status set_turn_data(span<const segment> segments) noexcept {
    const detail::body_size size = detail::measure_body(segments);
    if (size.status != turn_data_status::ok) return size.status;
    if (size.bytes > TurnCapacity) return turn_data_status::too_long;
    const std::uint8_t free = free_turn_buffer();
    detail::write_body(turn_[free], segments);
    publish_turn_data(free, size.bytes);
    return turn_data_status::ok;
  }
  /// Program side: no turn data (its turns pass, unless a directed transmission waits).
  void clear_turn_data() noexcept { (void)set_turn_data(byte_view{}); }

  /// Program side: queues a one-shot transmission directed to SBA `destination` carrying `data` (may be
  /// empty: the destination SBA is a data character). It goes out at one of the next turns, before the turn
  /// data; cut by a collision, it is sent again at the next turn.
  queue_status queue_directed(std::uint8_t destination, byte_view data) noexcept {
    if (destination > max_sba) return queue_status::destination_out_of_range;
    if (data.size() > DirectedCapacity) return queue_status::too_long;
    const std::uint8_t queued = queued_.load();
    if (static_cast<std::uint8_t>(queued - directed_sent_.acquire()) >= DirectedSlots)
      return queue_status::full;
    directed_slot& slot = slots_[queued % DirectedSlots];
    slot.body[0] = destination;
    detail::write_segments(slot.body + 1, detail::plain_segment, data);
    slot.length = static_cast<length_type>(1 + detail::plain_body_size(data.size()));
    queued_.release(static_cast<std::uint8_t>(queued + 1));
    return queue_status::ok;
  }
  /// Program side: directed transmissions queued and not yet sent whole.
  [[nodiscard]] std::size_t directed_waiting() const noexcept {
    return static_cast<std::uint8_t>(queued_.load() - directed_sent_.acquire());
  }

  /// Program side: takes the oldest delivery, copying its data into `out`. A delivery longer than `out`
  /// stays (`buffer_too_small`, with its length).
  delivery_result read(byte_buffer out) noexcept {
    delivery_result result;
    if (deliveries_.available() < delivery_header_bytes) return result;  // records are published whole
    std::uint8_t header[delivery_header_bytes];
    const std::size_t at = copy_out(header, static_cast<std::size_t>(deliveries_.front() - deliveries_.slots()),
                                    delivery_header_bytes);
    result.kind = static_cast<delivery_kind>(header[0]);
    result.sender = header[1];
    result.length = header[2];
    if (result.length > out.size()) {
      result.status = delivery_status::buffer_too_small;
      return result;
    }
    (void)copy_out(out.data(), at, result.length);
    deliveries_.consume(delivery_header_bytes + result.length);
    result.status = delivery_status::ok;
    return result;
  }
  /// Program side: which senders' broadcasts are delivered: bit s of `senders` for SBA s (default: every
  /// sender). A device that wants only its outputs (blocks) and directed transmissions clears them all, so
  /// that the other devices' inputs, broadcast every scan, do not fill its delivery queue. Blocks and
  /// directed transmissions are delivered whatever the mask. Takes effect from the next Start heard.
  void deliver_broadcasts_from(std::uint32_t senders) noexcept { broadcast_senders_.store(senders); }

  /// Program side: true when a delivery waits.
  [[nodiscard]] bool deliveries_waiting() const noexcept { return !deliveries_.empty(); }

  /// Program side: NETSTAT, the `netstat_bit`s raised since it was last cleared.
  [[nodiscard]] std::uint8_t netstat() const noexcept { return netstat_.read(); }
  /// Program side: clears NETSTAT.
  void clear_netstat() noexcept { netstat_.clear(); }

  /// Either side: the counters now (each read whole, not all at one instant).
  [[nodiscard]] device_counters counters() const noexcept {
    device_counters c;
    c.turns_taken = turns_taken_.load();
    c.turns_passed = turns_passed_.load();
    c.transmissions_sent = transmissions_sent_.load();
    c.collisions = errors_[error::collision].load();
    c.characters = characters_.load();
    c.framing_errors = errors_[error::framing].load();
    c.transmissions_heard = transmissions_heard_.load();
    c.crc_errors = errors_[error::crc].load();
    c.wire_errors = errors_[error::wire].load();
    c.lost_transmissions = errors_[error::lost_transmission].load();
    c.deliveries = delivered_.load();
    c.delivery_overflows = errors_[error::delivery_overflow].load();
    c.idle_restarts = errors_[error::idle_restart].load();
    c.skipped = skipped_.load();
    return c;
  }

 private:
  using register_type = typename Crc::register_type;
  using length_type =
      std::conditional_t<(TurnCapacity <= 255 && DirectedCapacity <= 252), std::uint8_t, std::uint16_t>;
  static constexpr std::uint8_t no_sender = 0xFF;

  enum class state : std::uint8_t {
    listening,  // not sending (receiving others, or the bus quiet)
    turn_due,   // its turn came with something to send; the first word not out yet
    sending,    // its transmission under way: each word read back before the next
  };
  enum class armed : std::uint8_t {
    none,   // no timer
    turn,   // its turn, `turn_offset_` skip times after a Stop
    quiet,  // the idle restart
    gap,    // silence inside a transmission
  };
  enum class phase : std::uint8_t { start, segment, data, end_of_block, done };

  // A directed transmission: the destination SBA, then its body (segments, as the turn data's).
  struct directed_slot {
    length_type length;  // of `body`
    std::uint8_t body[1 + DirectedCapacity + 2];
  };

  // Copies `n` bytes of the delivery queue from slot `at` on (wrapping without a division: none on a
  // Cortex-M0+); returns the slot after them.
  TRIONET_NOINLINE std::size_t copy_out(std::uint8_t* to, std::size_t at, std::size_t n) const noexcept {
    const std::uint8_t* const base = deliveries_.slots();
    for (std::size_t k = 0; k < n; ++k) {
      to[k] = base[at];
      if (++at == DeliveryCapacity) at = 0;
    }
    return at;
  }

  // ---- turn data ----

  // Program side: a buffer that the link side neither reads nor can start to read: not the one published,
  // not the one it reads (docs/design.md; the two indices are sequentially consistent, so a stale `reading_`
  // is never seen once the link side has confirmed it).
  std::uint8_t free_turn_buffer() const noexcept {
    const std::uint8_t published = published_.load_relaxed();  // its own variable
    const std::uint8_t reading = reading_.load();
    std::uint8_t free = 0;
    while (free == published || free == reading) ++free;
    return free;
  }
  // Program side: buffer `index`, written with a body of `bytes`, is the newest turn data.
  void publish_turn_data(std::uint8_t index, std::size_t bytes) noexcept {
    turn_length_[index] = static_cast<length_type>(bytes);
    published_.store(index);
  }

  // ---- timers ----

  link_request arm(armed what, std::uint32_t ticks, bool transmit = false) noexcept {
    armed_ = what;
    return link_request{ticks, timer_action::arm, transmit};
  }
  std::uint32_t quiet_ticks() const noexcept {
    return 32u * skip_ticks_ + gap_ticks_;
  }
  std::uint32_t gap_ticks() const noexcept {
    return gap_ticks_;
  }

  // The Stop of `sender` ended (now, or at the end of the character just received): arm its turn, or (its own
  // Stop, or `no_sender`: a Stop whose Start it missed, silence with no transmission open) the idle restart.
  // An idle restart acts as if SBA 31's Stop ended; SBA 31 itself then waits a full round of 32 skip times, so
  // that a lone device takes its turns too.
  TRIONET_ALWAYS_INLINE link_request after_stop_of(std::uint8_t sender, bool idle_restart) noexcept {
    unsigned offset = sender == no_sender ? 0 : sba_offset(sender, sba_);
    if (offset == 0 && idle_restart) offset = 32;
    if (offset == 0) return arm(armed::quiet, quiet_ticks());
    turn_offset_ = static_cast<std::uint8_t>(offset);
    return arm(armed::turn, static_cast<std::uint32_t>(offset * skip_ticks_));
  }

  // After a character (received, or a framing error) that armed no turn: silence inside a transmission
  // heard, or the idle restart.
  link_request after_character() noexcept {
    if (bus_sender_ != no_sender) return arm(armed::gap, gap_ticks());
    return arm(armed::quiet, quiet_ticks());
  }

  // ---- its turn and its own transmission ----

  TRIONET_ALWAYS_INLINE link_request take_turn() noexcept {
    if (directed_sent_.load() != queued_.acquire()) {
      source_ = source::directed;
    } else if (claim_turn_data()) {
      source_ = source::turn_data;
    } else {
      turns_passed_.increment();
      // Nothing heard since the Stop: the idle restart comes 32 skip times + the idle characters after it.
      return arm(armed::quiet, (32u - turn_offset_) * skip_ticks_ + gap_ticks_);
    }
    turns_taken_.increment();
    if (rx_open_) discard();
    state_ = state::turn_due;
    phase_ = phase::start;
    next_ready_ = true;
    return arm(armed::gap, gap_ticks(), true);
  }

  // Claims the newest turn data for this turn (see set_turn_data); false when there is none.
  bool claim_turn_data() noexcept {
    std::uint8_t newest = published_.load_relaxed();  // a candidate: `confirm` looks again
    const std::uint8_t now = confirm(newest);
    if (now != newest) {
      newest = now;  // published again meanwhile: claim that one
      // The program side published twice meanwhile (never on one core): send it next turn.
      if (confirm(newest) != newest) return false;
    }
    body_ = turn_[newest];
    body_length_ = turn_length_[newest];
    return body_length_ != 0;
  }

  // Marks turn data buffer `index` as the one it reads, then returns the newest published (`index` is
  // claimed when they are the same). Out of line: a claim may take two.
  TRIONET_NOINLINE std::uint8_t confirm(std::uint8_t index) noexcept {
    reading_.store(index);
    return published_.load();
  }

  // The next character of its transmission, as a 9-bit UART word.
  std::uint16_t next_word() noexcept {
    if (phase_ == phase::start) {
      stop_crc_ = this->crc().begin();
      at_ = 0;
      const bool directed = source_ == source::directed;
      phase_ = phase::segment;
      if (directed) {  // the destination SBA first: a data character outside any segment
        const directed_slot& slot = slots_[directed_sent_.load() % DirectedSlots];
        body_ = slot.body;
        body_length_ = slot.length;
        left_ = 1;
        block_ = false;
        phase_ = phase::data;
      }
      return code_.encode_word(control_kind::start, (directed ? 0u : 0x20u) | sba_);
    }
    if (phase_ == phase::end_of_block) {
      phase_ = phase::segment;
      return code_.encode_word(control_kind::end_of_block, this->crc().finish(block_crc_));
    }
    if (phase_ != phase::data) {  // the next segment (or, at the end of the body, the Stop)
      if (at_ >= body_length_) {
        phase_ = phase::done;
        return code_.encode_word(control_kind::stop, this->crc().finish(stop_crc_));
      }
      const std::uint8_t header = body_[at_];
      left_ = body_[at_ + 1];
      at_ = static_cast<length_type>(at_ + 2);
      phase_ = phase::data;
      block_ = header != detail::plain_segment;
      if (block_) {
        block_crc_ = this->crc().begin();
        return code_.encode_word(control_kind::start_of_block, header & max_sba);
      }
    }
    const std::uint8_t byte = body_[at_];
    at_ = static_cast<length_type>(at_ + 1);
    if (block_) block_crc_ = this->crc().update(block_crc_, byte);
    if (--left_ == 0) phase_ = block_ ? phase::end_of_block : phase::segment;
    stop_crc_ = this->crc().update(stop_crc_, byte);
    return to_uart_word(data_character(byte));
  }

  // A character received while sending: its own, read back.
  link_request read_back() noexcept {
    // Its own Start heard: a transmission of its own is open on the bus. (Set again at each later character
    // read back, which finds it so: while it sends, nothing else changes the sender.)
    bus_sender_ = sba_;
    if (phase_ != phase::done) {
      next_ready_ = true;
      return arm(armed::gap, gap_ticks(), true);
    }
    // Its Stop came back: the transmission is whole. It arms no turn after its own Stop.
    state_ = state::listening;
    bus_sender_ = no_sender;
    transmissions_sent_.increment();
    if (source_ == source::directed)
      directed_sent_.release(static_cast<std::uint8_t>(directed_sent_.load() + 1));
    return arm(armed::quiet, quiet_ticks());
  }

  void collided() noexcept {
    count(error::collision);
    state_ = state::listening;
    next_ready_ = false;
    rx_open_ = false;
    resync_ = true;  // whatever is on the bus now began before it could follow it
  }

  // ---- others' transmissions ----

  // A 9-bit UART word (bits above 8 clear).
  TRIONET_ALWAYS_INLINE link_request hear(std::uint16_t word) noexcept {
    const auto byte = static_cast<std::uint8_t>(word >> 1);
    if ((word & 1u) == 0) {
      hear_data(byte);
    } else {
      const control_fields f = code_.decode(byte);
      if (f.kind == control_kind::stop) return hear_stop(f.crc);
      hear_control(f);
    }
    return after_character();
  }

  TRIONET_ALWAYS_INLINE void hear_control(const control_fields& f) noexcept {
    if (f.kind == control_kind::start) {
      if (rx_open_) wire_error();  // the old transmission ends without its Stop
      begin(f);
      return;
    }
    if (!rx_open_) return outside();
    if (f.kind == control_kind::start_of_block && part_ == part::plain) {
      part_ = part::block;
      block_length_ = 0;
      block_crc_ = this->crc().begin();
      if (f.sba == sba_) open_record(delivery_kind::block);
    } else if (f.kind == control_kind::end_of_block && part_ == part::block && block_length_ != 0) {
      if (this->crc().finish(block_crc_) != f.crc) return crc_error();
      part_ = part::plain;
      if (record_ == record_kind::block) close_record();  // a block for it
    } else {
      wire_error();  // a block where none may start or end, or an unknown control character
    }
  }

  TRIONET_ALWAYS_INLINE void hear_data(std::uint8_t byte) noexcept {
    if (!rx_open_) return outside();
    stop_crc_ = this->crc().update(stop_crc_, byte);
    ++data_characters_;
    if (part_ == part::destination) {
      part_ = part::plain;
      if (byte > max_sba) return wire_error();
      plain_ = byte == sba_ ? plain_for::it_directed : plain_for::others;
    } else if (part_ == part::block) {
      block_crc_ = this->crc().update(block_crc_, byte);
      ++block_length_;
      if (record_ == record_kind::block) stage(byte);  // a block for it
    } else if (plain_ != plain_for::others) {
      if (record_ != record_kind::plain) open_record(static_cast<delivery_kind>(plain_));
      stage(byte);
    }
  }

  void begin(const control_fields& f) noexcept {
    rx_open_ = true;
    resync_ = false;
    bus_sender_ = f.sba;
    rx_sender_ = f.sba;
    part_ = f.broadcast ? part::plain : part::destination;
    plain_ = f.broadcast && ((broadcast_senders_.load() >> f.sba) & 1u) != 0 ? plain_for::it_broadcast
                                                                             : plain_for::others;
    data_characters_ = 0;
    stop_crc_ = this->crc().begin();
    staged_ = 0;
    overflow_ = false;
    record_ = record_kind::none;
  }

  link_request hear_stop(std::uint8_t crc) noexcept {
    if (rx_open_) {
      if (part_ != part::plain || data_characters_ == 0) {
        wire_error();
      } else if (this->crc().finish(stop_crc_) != crc) {
        crc_error();
      } else {
        deliver();
      }
    } else {
      outside();  // (skipped: the end of a transmission it had dropped, or whose Start it missed)
    }
    const std::uint8_t sender = bus_sender_;
    bus_sender_ = no_sender;
    return after_stop_of(sender, false);
  }

  // A character outside any transmission it follows.
  void outside() noexcept {
    if (!resync_ && bus_sender_ == no_sender) {
      wire_error_outside();
    } else {
      skipped_.increment();
    }
  }

  // ---- deliveries: staged past the queue's tail while the transmission comes, published at its Stop ----

  enum class record_kind : std::uint8_t { none, plain, block };
  // What a data character of the transmission heard is: its destination SBA (a directed transmission's
  // first), plain data, or a block's.
  enum class part : std::uint8_t { destination, plain, block };
  // Whom the plain data of the transmission heard is for: it, as a broadcast (from a sender it delivers) or
  // as a transmission directed to it, whose records have that delivery kind; or others (also a directed
  // transmission's until its destination is heard).
  enum class plain_for : std::uint8_t {
    it_broadcast = static_cast<std::uint8_t>(delivery_kind::broadcast),
    it_directed = static_cast<std::uint8_t>(delivery_kind::directed),
    others,
  };
  // The errors NETSTAT shows, in the order of their bits: error e raises bit 1 << e.
  struct error {
    enum index : std::uint8_t {
      collision,          ///< NETSTAT bit 0: `netstat_collision`
      crc,                ///< bit 1: `netstat_crc_error`
      framing,            ///< bit 2: `netstat_framing_error`
      lost_transmission,  ///< bit 3: `netstat_lost_transmission`
      wire,               ///< bit 4: `netstat_wire_error`
      delivery_overflow,  ///< bit 5: `netstat_delivery_overflow`
      idle_restart,       ///< bit 6: `netstat_idle_restart`
      count               ///< how many there are
    };
  };
  static_assert(netstat_collision == 1u << error::collision && netstat_crc_error == 1u << error::crc &&
                    netstat_framing_error == 1u << error::framing &&
                    netstat_lost_transmission == 1u << error::lost_transmission &&
                    netstat_wire_error == 1u << error::wire &&
                    netstat_delivery_overflow == 1u << error::delivery_overflow &&
                    netstat_idle_restart == 1u << error::idle_restart,
                "error e raises NETSTAT bit 1 << e");
  enum class source : std::uint8_t { turn_data, directed };

  void open_record(delivery_kind kind) noexcept {
    close_record();
    record_at_ = staged_;
    record_ = kind == delivery_kind::block ? record_kind::block : record_kind::plain;
    stage(static_cast<std::uint8_t>(kind));
    stage(rx_sender_);
    stage(0);  // the length, when the record is closed
  }
  void close_record() noexcept {
    if (record_ == record_kind::none) return;
    const std::size_t length = staged_ - record_at_ - delivery_header_bytes;
    // (A record never outgrows a queue of up to 258 bytes: staging stops at the queue's room.)
    if constexpr (DeliveryCapacity > 255 + delivery_header_bytes) {
      if (length > 255) overflow_ = true;
    }
    if (!overflow_) deliveries_.stage(record_at_ + 2, static_cast<std::uint8_t>(length));
    ++records_;
    record_ = record_kind::none;
  }
  void stage(std::uint8_t byte) noexcept {
    if (overflow_ || staged_ >= deliveries_.free()) {
      overflow_ = true;
      return;
    }
    deliveries_.stage(staged_, byte);
    ++staged_;
  }
  void deliver() noexcept {
    close_record();
    rx_open_ = false;
    transmissions_heard_.increment();
    if (overflow_) {
      count(error::delivery_overflow);
    } else if (staged_ != 0) {
      deliveries_.publish(staged_);
      delivered_.add(records_);
    }
    staged_ = 0;
    records_ = 0;
  }
  // The open transmission is dropped (its staged records with it); characters are skipped to the next Start.
  TRIONET_NOINLINE void discard() noexcept {
    rx_open_ = false;
    resync_ = true;
    staged_ = 0;
    records_ = 0;
    record_ = record_kind::none;
  }
  void wire_error() noexcept {
    count(error::wire);
    discard();
  }
  void wire_error_outside() noexcept {
    count(error::wire);
    resync_ = true;
  }
  void crc_error() noexcept {
    count(error::crc);
    discard();
  }
  // A counted event that NETSTAT shows: one call site's code for every error (its counter is errors_[e], its
  // NETSTAT bit 1 << e).
  TRIONET_NOINLINE void count(std::uint8_t e) noexcept {
    errors_[e].increment();
    netstat_.raise(static_cast<std::uint8_t>(1u << e));
  }

  // ---- state ----
  // Ordered for small code on a Cortex-M0+ (a byte reaches 31 bytes past the object, a half-word 62, a word
  // 124): the link side's bytes first, then half-words, then words; the buffers last.

  // Link side only.
  std::uint8_t sba_;  // configuration
  state state_ = state::listening;
  armed armed_ = armed::none;
  phase phase_ = phase::done;
  source source_ = source::turn_data;
  record_kind record_ = record_kind::none;
  std::uint8_t turn_offset_ = 0;
  std::uint8_t bus_sender_ = no_sender;  // the sender of the Start heard last, until its Stop
  std::uint8_t rx_sender_ = 0;
  std::uint8_t left_ = 0;
  bool next_ready_ = false;
  bool block_ = false;
  bool rx_open_ = false;
  bool resync_ = true;  // skip to the first Start after power-up (a transmission joined half way)
  plain_for plain_ = plain_for::others;  // whom the plain data heard is for
  part part_ = part::plain;              // what the next data character heard is
  bool overflow_ = false;
  register_type stop_crc_{};
  register_type block_crc_{};
  length_type at_ = 0;
  length_type body_length_ = 0;
  std::uint16_t sent_ = 0;  // the UART word it sent last

  // Shared: one writer each.
  detail::netstat_bits netstat_;
  detail::shared_index published_;  // program side: the newest turn data (at first the empty buffer 0)
  detail::shared_index reading_;    // link side: the turn data it sends (or is claiming)
  trionet::detail::single_writer<std::uint8_t> queued_;  // program side: directed transmissions queued
  trionet::detail::single_writer<std::uint8_t>
      directed_sent_;  // link side: directed transmissions sent whole
  detail::control_code code_;  // configuration: the control layout

  // Link side only.
  std::uint16_t data_characters_ = 0;
  std::uint16_t block_length_ = 0;
  std::uint16_t staged_ = 0;
  std::uint16_t record_at_ = 0;
  std::uint16_t records_ = 0;
  const std::uint8_t* body_ = nullptr;

  // Configuration.
  std::uint32_t skip_ticks_;       // one skip time
  std::uint32_t gap_ticks_;        // the idle characters: silence that ends a transmission
  std::uint32_t character_ticks_;  // one character

  // Shared: one writer each.
  trionet::detail::single_writer<std::uint32_t> broadcast_senders_{
      0xFFFFFFFFu};  // program side: whose broadcasts to deliver
  trionet::detail::single_writer<std::uint32_t> turns_taken_;
  trionet::detail::single_writer<std::uint32_t> turns_passed_;
  trionet::detail::single_writer<std::uint32_t> transmissions_sent_;
  trionet::detail::single_writer<std::uint32_t> characters_;
  trionet::detail::single_writer<std::uint32_t> transmissions_heard_;
  trionet::detail::single_writer<std::uint32_t> delivered_;
  trionet::detail::single_writer<std::uint32_t> skipped_;
  trionet::detail::single_writer<std::uint32_t> errors_[error::count];  // the errors' counters, by `error`
  length_type turn_length_[3] = {};
  std::uint8_t turn_[3][TurnCapacity] = {};
  directed_slot slots_[DirectedSlots] = {};
  trionet::detail::spsc_fifo<DeliveryCapacity> deliveries_;
};

}  // namespace trionet::genius
