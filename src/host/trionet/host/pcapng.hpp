// pcapng capture files, as Wireshark and tshark read them: a writer for the records trionet captures and a
// reader that validates every file it is given (docs/wireshark.md says what one record is per network).
//
//   file     = section header block, then blocks: interface descriptions, enhanced packets, others
//   block    = | type u32 | total length u32 | body, padded to 4 bytes | total length u32 again |
//   section  | 0x0A0D0D0A | len | byte-order magic 0x1A2B3C4D | major 1 | minor 0 | section length -1 | options |
//   interface| 1 | len | link type u16 | reserved u16 | snap length u32 | options: if_name, if_tsresol ... |
//   packet   | 6 | len | interface u32 | timestamp high u32 | low u32 | captured u32 | original u32 | bytes |
//   option   | code u16 | length u16 | value, padded to 4 bytes |   ... | 0 | 0 | (end of options)
//
// The writer writes little-endian, one interface per link (its name in if_name, e.g. "link 0: MC1 -> keypad"),
// timestamps in nanoseconds (if_tsresol 9). Ring and Genius records go out as LINKTYPE_WIRESHARK_UPPER_PDU
// (252): each record starts with exported-PDU tags that name the Lua dissector ("trionet_ring",
// "trionet_genius"), so stock Wireshark calls it without any preference; CAN records as
// LINKTYPE_CAN_SOCKETCAN (227), which Wireshark's own SocketCAN dissector reads.
//
// The reader takes any pcapng file, in either byte order, with several sections, and stops with a status at
// the first thing that is not pcapng; it never reads outside a block, never trusts a length it has not
// checked against the block and its limits, and skips block types it has no use for (counted). Host code
// (std::istream, std::string, std::vector); not for firmware.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "trionet/span.hpp"

namespace trionet::host {

constexpr std::uint16_t linktype_can_socketcan = 227;        ///< LINKTYPE_CAN_SOCKETCAN
constexpr std::uint16_t linktype_wireshark_upper_pdu = 252;  ///< LINKTYPE_WIRESHARK_UPPER_PDU (exported PDU)

/// The networks whose records a trionet capture holds; `other` for any record that is none of them.
enum class capture_network : std::uint8_t { ring, can, genius, other };

constexpr const char* to_string(capture_network network) noexcept {
  switch (network) {
    case capture_network::ring:
      return "ring";
    case capture_network::can:
      return "can";
    case capture_network::genius:
      return "genius";
    case capture_network::other:
      return "other";
  }
  return "unknown";
}

/// The Wireshark dissector that a ring or Genius record names in its exported-PDU tags; nullptr for the
/// others (CAN records are read by Wireshark's SocketCAN dissector).
constexpr const char* dissector_name(capture_network network) noexcept {
  switch (network) {
    case capture_network::ring:
      return "trionet_ring";
    case capture_network::genius:
      return "trionet_genius";
    case capture_network::can:
    case capture_network::other:
      return nullptr;
  }
  return nullptr;
}

/// What a writer call did. Nothing is written unless the status is `ok`.
enum class pcapng_write_status : std::uint8_t {
  ok,
  bad_network,      ///< add_interface with `capture_network::other`
  name_too_long,    ///< an interface name longer than `pcapng_writer::max_name_length`
  bad_interface,    ///< write to an interface id that add_interface did not return
  record_too_long,  ///< a record longer than `pcapng_writer::max_record_length`
  write_failed,     ///< the stream reported an error (this and every later call fail)
};

constexpr const char* to_string(pcapng_write_status status) noexcept {
  switch (status) {
    case pcapng_write_status::ok:
      return "ok";
    case pcapng_write_status::bad_network:
      return "bad_network";
    case pcapng_write_status::name_too_long:
      return "name_too_long";
    case pcapng_write_status::bad_interface:
      return "bad_interface";
    case pcapng_write_status::record_too_long:
      return "record_too_long";
    case pcapng_write_status::write_failed:
      return "write_failed";
  }
  return "unknown";
}

/// An added interface: its id for `write`, or why there is none.
struct [[nodiscard]] pcapng_interface_result {
  pcapng_write_status status = pcapng_write_status::ok;
  std::uint32_t id = 0;
  constexpr explicit operator bool() const noexcept { return status == pcapng_write_status::ok; }
};

/// Writes a pcapng capture to a binary stream. The section header goes out in the constructor; then
/// interfaces and records in any order (an interface before its first record). Each call writes whole
/// blocks; call `flush` to make what was written visible to a reader (e.g. Wireshark following a live file).
/// Cost: one small block per record, no buffering beyond the stream's.
class pcapng_writer {
 public:
  static constexpr std::size_t max_record_length = 262144;  ///< Wireshark's largest standard packet
  static constexpr std::size_t max_name_length = 65000;     ///< an option value is at most 65535 bytes

  /// Writes the section header (shb_userappl = `application`) to `out`, which must be open in binary mode.
  explicit pcapng_writer(std::ostream& out, std::string_view application = "trionet");

  /// Describes one link, bus or line; records of `network` are written with its link type. Returns the id
  /// that `write` takes (0, 1, 2, ... in the order added).
  pcapng_interface_result add_interface(std::string_view name, capture_network network);

  /// One record: `bytes` as they crossed interface `interface`, the first of them at `time_ns` nanoseconds
  /// since 1970-01-01 00:00 UTC (or since the start of a simulation). Ring and Genius records get their
  /// exported-PDU tags in front; CAN records are 16-byte SocketCAN frames (see socketcan_record).
  [[nodiscard]] pcapng_write_status write(std::uint32_t interface, std::uint64_t time_ns, byte_view bytes);

  /// Flushes the stream.
  [[nodiscard]] pcapng_write_status flush();

  /// Interfaces added so far.
  [[nodiscard]] std::uint32_t interfaces() const noexcept { return static_cast<std::uint32_t>(networks_.size()); }

 private:
  bool put(const std::vector<std::uint8_t>& block);

  std::ostream& out_;
  std::vector<capture_network> networks_;
  std::vector<std::uint8_t> block_;
  bool failed_ = false;
};

/// What a reader call found. From `not_pcapng` to `read_failed` the file cannot be read on: that call and
/// every later one return the same status. From `unknown_interface` on, only this record is bad: the next
/// call goes on with the next block.
enum class pcapng_read_status : std::uint8_t {
  ok,                   ///< a record
  end_of_file,          ///< the file ends after a whole block
  not_pcapng,           ///< the file does not start with a section header block (or is empty)
  bad_byte_order,       ///< a section header whose byte-order magic is neither 0x1A2B3C4D nor swapped
  unsupported_version,  ///< a section header whose major version is not 1
  bad_block_length,     ///< a block length below 12 or not a multiple of 4, or its trailing copy differs
  block_too_long,       ///< a block longer than the reader's `max_block_length`
  truncated,            ///< the file ends inside a block
  bad_block,            ///< a block too short for its fixed fields, or packet bytes beyond the block
  bad_option,           ///< an option running past its block, or if_tsresol/if_tsoffset of the wrong size
  too_many_interfaces,  ///< more interfaces in a section than the reader's `max_interfaces`
  read_failed,          ///< the stream reported an error
  unknown_interface,       ///< a packet names an interface that its section does not describe
  timestamp_out_of_range,  ///< the packet's time is before 1970 or does not fit 64-bit nanoseconds
  bad_exported_pdu,        ///< a link type 252 packet whose tags run past it or do not end
};

constexpr const char* to_string(pcapng_read_status status) noexcept {
  switch (status) {
    case pcapng_read_status::ok:
      return "ok";
    case pcapng_read_status::end_of_file:
      return "end_of_file";
    case pcapng_read_status::not_pcapng:
      return "not_pcapng";
    case pcapng_read_status::bad_byte_order:
      return "bad_byte_order";
    case pcapng_read_status::unsupported_version:
      return "unsupported_version";
    case pcapng_read_status::bad_block_length:
      return "bad_block_length";
    case pcapng_read_status::block_too_long:
      return "block_too_long";
    case pcapng_read_status::truncated:
      return "truncated";
    case pcapng_read_status::bad_block:
      return "bad_block";
    case pcapng_read_status::bad_option:
      return "bad_option";
    case pcapng_read_status::too_many_interfaces:
      return "too_many_interfaces";
    case pcapng_read_status::read_failed:
      return "read_failed";
    case pcapng_read_status::unknown_interface:
      return "unknown_interface";
    case pcapng_read_status::timestamp_out_of_range:
      return "timestamp_out_of_range";
    case pcapng_read_status::bad_exported_pdu:
      return "bad_exported_pdu";
  }
  return "unknown";
}

/// True for the statuses after which the reader cannot go on.
constexpr bool ends_reading(pcapng_read_status status) noexcept {
  return status != pcapng_read_status::ok && status < pcapng_read_status::unknown_interface;
}

/// One interface description of the current section.
struct pcapng_interface {
  std::string name;              ///< if_name, without trailing NULs (empty if absent)
  std::uint16_t link_type = 0;   ///< LINKTYPE_...
  std::uint32_t snap_length = 0;
  std::uint8_t tsresol = 6;      ///< if_tsresol as in the file: bit 7 clear = 10^-n s, set = 2^-n s
  std::int64_t tsoffset = 0;     ///< if_tsoffset, seconds added to every timestamp
};

/// One packet. `bytes` points into the reader and is valid until its next call.
struct pcapng_record {
  std::uint32_t interface = 0;  ///< index into `pcapng_reader::interfaces()`
  std::uint64_t time_ns = 0;    ///< nanoseconds since 1970 (truncated to whole nanoseconds)
  std::uint32_t original_length = 0;  ///< the length on the wire, as the file states it
  capture_network network = capture_network::other;  ///< from the link type and the exported-PDU dissector
  std::string_view dissector;  ///< link type 252: the dissector the tags name, else empty
  byte_view bytes;             ///< the captured bytes (link type 252: after the tags)
};

struct [[nodiscard]] pcapng_read_result {
  pcapng_read_status status = pcapng_read_status::ok;
  pcapng_record record{};  ///< meaningful when status is ok
  constexpr explicit operator bool() const noexcept { return status == pcapng_read_status::ok; }
};

/// Reads a pcapng file block by block from a binary stream. Memory: one block (at most `max_block_length`)
/// and the interfaces of the current section (at most `max_interfaces`, each with a name of at most 64 KiB).
class pcapng_reader {
 public:
  struct limits {
    std::uint32_t max_block_length = 16u << 20;  ///< longer blocks end reading (`block_too_long`)
    std::size_t max_interfaces = 1024;           ///< per section
  };

  explicit pcapng_reader(std::istream& in) : pcapng_reader(in, limits{}) {}
  pcapng_reader(std::istream& in, limits limit);

  /// The next record, or why there is none.
  pcapng_read_result next();

  /// The interfaces described so far in the current section.
  [[nodiscard]] const std::vector<pcapng_interface>& interfaces() const noexcept { return interfaces_; }
  /// Section header blocks read so far.
  [[nodiscard]] std::uint32_t sections() const noexcept { return sections_; }
  /// Blocks of types the reader has no use for (name resolution, statistics, simple packets ...), skipped.
  [[nodiscard]] std::uint32_t skipped_blocks() const noexcept { return skipped_blocks_; }

 private:
  enum class read_state : std::uint8_t { start, in_section, stopped };

  pcapng_read_status stop(pcapng_read_status status);
  pcapng_read_status read_exact(std::uint8_t* to, std::size_t size, bool at_block_start);
  pcapng_read_status read_body(std::size_t size);
  pcapng_read_status read_section_header(const std::uint8_t* head);
  pcapng_read_status read_interface();
  pcapng_read_status read_packet(pcapng_record& out);
  std::uint16_t u16(const std::uint8_t* at) const noexcept;
  std::uint32_t u32(const std::uint8_t* at) const noexcept;

  std::istream& in_;
  limits limits_;
  read_state state_ = read_state::start;
  pcapng_read_status stopped_ = pcapng_read_status::ok;
  bool big_endian_ = false;
  std::vector<std::uint8_t> block_;  // body of the current block (after type and length)
  std::vector<pcapng_interface> interfaces_;
  std::uint32_t sections_ = 0;
  std::uint32_t skipped_blocks_ = 0;
};

}  // namespace trionet::host
