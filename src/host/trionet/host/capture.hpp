// What one capture record is, per network (docs/wireshark.md): cutting a link's bytes or a line's characters
// into records, and the record layouts that the Wireshark dissectors read.
//
//   ring    one message as it crossed one link, header .. end of message; a message cut short (by the next
//           header, an idle line, the end of the capture), a run of stray data bytes and a stray end of
//           message are records of their own, so every byte that crossed is in exactly one record.
//   Genius  one transmission, Start .. Stop, each character a 16-bit big-endian word holding the 11-bit wire
//           word (bit 0 start, bit 1 control, bits 9..2 the byte, bit 10 stop); a transmission cut short
//           (by the next Start, a framing error, the end) and characters outside a transmission are records of
//           their own, and so is every character with a framing error.
//   CAN     one frame, as the 16-byte Linux SocketCAN frame of LINKTYPE_CAN_SOCKETCAN:
//             | can_id u32 big-endian (flags in bits 31..29) | len | flags 0 | len8_dlc | 0 | data[8] |
//
// A record's time is the time of its first byte (character, frame). Host code (std::vector).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "trionet/can/frame.hpp"
#include "trionet/genius/character.hpp"
#include "trionet/genius/transmission.hpp"
#include "trionet/host/candump.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/span.hpp"

namespace trionet::host {

namespace detail {
/// The record a splitter is building: its bytes and the time of the first. `flush` hands it to the sink.
class open_record {
 public:
  [[nodiscard]] bool open() const noexcept { return open_; }
  [[nodiscard]] std::size_t size() const noexcept { return bytes_.size(); }
  void begin(std::uint64_t time_ns) {
    open_ = true;
    time_ns_ = time_ns;
    bytes_.clear();
  }
  void put(std::uint8_t byte) { bytes_.push_back(byte); }
  template <class Sink>
  void flush(Sink&& sink) {
    if (!open_) return;
    open_ = false;
    sink(byte_view(bytes_.data(), bytes_.size()), time_ns_);
  }

 private:
  bool open_ = false;
  std::uint64_t time_ns_ = 0;
  std::vector<std::uint8_t> bytes_;
};
}  // namespace detail

/// Cuts the bytes that crossed one ring link into records. Feed every byte with the time it was sent; call
/// `flush` on an idle line and at the end of the capture. `sink(byte_view record, std::uint64_t time_ns)`
/// receives each record (the view is valid during the call).
///
/// A record never exceeds `max_record_length` bytes: a message that does is cut there, and its further data
/// bytes make a stray-data record. The default holds the longest message any decoder accepts (a header,
/// 65534 characters and the end of message) with room to spare.
class ring_record_splitter {
 public:
  static constexpr std::size_t default_max_record_length = 65536;

  explicit ring_record_splitter(std::size_t max_record_length = default_max_record_length)
      : max_(max_record_length < 1 ? 1 : max_record_length) {}

  template <class Sink>
  void push(std::uint8_t byte, std::uint64_t time_ns, Sink&& sink) {
    if (ring::is_data(byte)) {
      if (record_.open() && record_.size() == max_) flush(sink);
      if (!record_.open()) begin(unit::stray, time_ns);
      record_.put(byte);
    } else if (ring::type_of(byte) != 0) {  // a header begins a message
      flush(sink);
      begin(unit::message, time_ns);
      record_.put(byte);
    } else if (kind_ == unit::message && record_.open() && record_.size() < max_) {  // its end of message
      record_.put(byte);
      flush(sink);
    } else {  // an end of message outside a message (or past the limit) stands alone
      flush(sink);
      begin(unit::stray, time_ns);
      record_.put(byte);
      flush(sink);
    }
  }

  /// Emits the open record, if any (a message cut short or a run of stray data).
  template <class Sink>
  void flush(Sink&& sink) {
    record_.flush(sink);
  }

  /// True while a record is open.
  [[nodiscard]] bool open() const noexcept { return record_.open(); }

 private:
  enum class unit : std::uint8_t { message, stray };

  void begin(unit kind, std::uint64_t time_ns) {
    kind_ = kind;
    record_.begin(time_ns);
  }

  std::size_t max_;
  unit kind_ = unit::stray;
  detail::open_record record_;
};

/// Records the bytes that cross one ring link into one interface of a capture: byte-times become
/// nanoseconds at the link's bit rate, records are cut by a ring_record_splitter, and a gap of more than
/// `idle_byte_times` byte-times between two bytes is an idle line that ends the open record (docs/protocol.md
/// 1.10). Call `flush` at the end.
class ring_link_recorder {
 public:
  /// `interface` is the writer's id for this link; `bit_rate` in bits per second, `bits_per_byte` on the
  /// line (start, 8 data, stop: 10); record times start at `epoch_ns`.
  ring_link_recorder(pcapng_writer& writer, std::uint32_t interface, double bit_rate, unsigned bits_per_byte = 10,
                     std::uint64_t epoch_ns = 0, std::uint64_t idle_byte_times = 2)
      : writer_(writer),
        interface_(interface),
        ns_per_byte_(1e9 * bits_per_byte / bit_rate),
        epoch_ns_(epoch_ns),
        idle_(idle_byte_times) {}

  /// The byte sent at byte-time `byte_time` (non-decreasing).
  void byte_at(std::uint64_t byte_time, std::uint8_t byte) {
    if (started_ && byte_time > last_ + idle_) flush();
    started_ = true;
    last_ = byte_time;
    splitter_.push(byte, epoch_ns_ + static_cast<std::uint64_t>(static_cast<double>(byte_time) * ns_per_byte_ + 0.5),
                   sink{this});
  }

  /// Writes the open record, if any.
  void flush() { splitter_.flush(sink{this}); }

  /// The first write status that was not ok, else ok.
  [[nodiscard]] pcapng_write_status status() const noexcept { return status_; }

 private:
  struct sink {
    ring_link_recorder* self;
    void operator()(byte_view record, std::uint64_t time_ns) const {
      const pcapng_write_status written = self->writer_.write(self->interface_, time_ns, record);
      if (self->status_ == pcapng_write_status::ok) self->status_ = written;
    }
  };

  pcapng_writer& writer_;
  std::uint32_t interface_;
  double ns_per_byte_;
  std::uint64_t epoch_ns_;
  std::uint64_t idle_;
  ring_record_splitter splitter_;
  std::uint64_t last_ = 0;
  bool started_ = false;
  pcapng_write_status status_ = pcapng_write_status::ok;
};

/// Bytes per Genius character in a record: the 11-bit word, big-endian.
constexpr std::size_t genius_record_bytes_per_character = 2;

/// True if `word` is a character with its start bit 0, its stop bit 1 and nothing above bit 10.
constexpr bool well_framed(std::uint16_t word) noexcept {
  return (word & ~genius::word_mask) == 0 && (word & genius::start_bit_mask) == 0 &&
         (word & genius::stop_bit_mask) != 0;
}

/// Cuts the 11-bit words of one Genius line into records (see the top of this header). `sink(byte_view
/// record, std::uint64_t time_ns)` receives each record, two bytes per character. A record never exceeds
/// `max_characters` characters: a longer one is cut there and goes on in a record of its own.
class genius_record_splitter {
 public:
  static constexpr std::size_t default_max_characters = 4096;

  /// A splitter that finds Start and Stop in the control layout `layout` (genius/transmission.hpp).
  explicit genius_record_splitter(std::size_t max_characters = default_max_characters,
                                  const genius::control_layout& layout = genius::control_layout{})
      : max_(max_characters < 1 ? 1 : max_characters), layout_(layout) {}

  /// One received word; a framing error is a word whose start or stop bit is wrong (genius/character.hpp).
  template <class Sink>
  void push(std::uint16_t word, std::uint64_t time_ns, Sink&& sink) {
    if (!well_framed(word)) {
      flush(sink);
      begin(unit::stray, time_ns);
      put(word);
      flush(sink);
      return;
    }
    const bool control = (word & genius::control_bit_mask) != 0;
    const genius::control_kind kind = genius::read_control(static_cast<std::uint8_t>(word >> 2), layout_).kind;
    if (control && kind == genius::control_kind::start) {
      flush(sink);
      begin(unit::transmission, time_ns);
    } else if (record_.open() && record_.size() == max_ * genius_record_bytes_per_character) {
      flush(sink);
      begin(unit::stray, time_ns);
    } else if (!record_.open()) {
      begin(unit::stray, time_ns);
    }
    put(word);
    if (control && kind == genius::control_kind::stop && kind_ == unit::transmission) flush(sink);
  }

  /// One received character (always well framed).
  template <class Sink>
  void push(genius::character c, std::uint64_t time_ns, Sink&& sink) {
    push(genius::encode_character(c), time_ns, sink);
  }

  /// Emits the open record, if any (a transmission cut short, or characters outside a transmission).
  template <class Sink>
  void flush(Sink&& sink) {
    record_.flush(sink);
  }

  [[nodiscard]] bool open() const noexcept { return record_.open(); }

 private:
  enum class unit : std::uint8_t { transmission, stray };

  void begin(unit kind, std::uint64_t time_ns) {
    kind_ = kind;
    record_.begin(time_ns);
  }
  void put(std::uint16_t word) {
    record_.put(static_cast<std::uint8_t>(word >> 8));
    record_.put(static_cast<std::uint8_t>(word));
  }

  std::size_t max_;
  genius::control_layout layout_;
  unit kind_ = unit::stray;
  detail::open_record record_;
};

/// The words of a Genius record (a trailing odd byte is not a word and is left out).
std::vector<std::uint16_t> genius_record_words(byte_view record);

/// The bytes of a SocketCAN record.
constexpr std::size_t socketcan_record_length = 16;

/// `frame` as a LINKTYPE_CAN_SOCKETCAN record: identifier word big-endian (extended and remote flags as in
/// `frame.id`), len = the data bytes on the wire, len8_dlc = the DLC when it is 9..15, data padded with 0.
std::array<std::uint8_t, socketcan_record_length> socketcan_record(const can::frame& frame);

enum class socketcan_record_status : std::uint8_t {
  ok,
  too_short,       ///< fewer than 8 header bytes, or fewer data bytes than len says
  not_classic,     ///< a CAN FD or CAN XL frame (flags byte, or the 72-byte FD length)
  error_frame,     ///< CAN_ERR_FLAG: a controller error report, not a frame on the bus
  bad_length,      ///< len above 8
  bad_identifier,  ///< a standard identifier with bits above bit 10
};

constexpr const char* to_string(socketcan_record_status status) noexcept {
  switch (status) {
    case socketcan_record_status::ok:
      return "ok";
    case socketcan_record_status::too_short:
      return "too_short";
    case socketcan_record_status::not_classic:
      return "not_classic";
    case socketcan_record_status::error_frame:
      return "error_frame";
    case socketcan_record_status::bad_length:
      return "bad_length";
    case socketcan_record_status::bad_identifier:
      return "bad_identifier";
  }
  return "unknown";
}

struct [[nodiscard]] socketcan_record_result {
  socketcan_record_status status = socketcan_record_status::ok;
  can::frame frame{};  ///< meaningful when ok
  constexpr explicit operator bool() const noexcept { return status == socketcan_record_status::ok; }
};

/// Reads a LINKTYPE_CAN_SOCKETCAN record (as Linux, dumpcap and `socketcan_record` write it).
socketcan_record_result read_socketcan_record(byte_view record);

/// The frame of `record` as a LINKTYPE_CAN_SOCKETCAN capture record, as Linux delivers it to a raw socket:
/// a classic frame as `socketcan_record` writes it (16 bytes); an error frame with the error flag and its
/// class bits and 8 data bytes (16 bytes); a CAN FD frame as a struct canfd_frame (72 bytes: the FDF flag
/// with its BRS and ESI flags, 64 data bytes). Empty for a CAN XL frame (not written).
std::vector<std::uint8_t> socketcan_record_of(const candump_record& record);

}  // namespace trionet::host
