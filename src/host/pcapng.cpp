// pcapng writer and reader (see trionet/host/pcapng.hpp for the block layouts).
#include "trionet/host/pcapng.hpp"

#include <istream>
#include <ostream>

namespace trionet::host {
namespace {

constexpr std::uint32_t section_header_type = 0x0A0D0D0A;
constexpr std::uint32_t interface_description_type = 1;
constexpr std::uint32_t enhanced_packet_type = 6;
constexpr std::uint32_t byte_order_magic = 0x1A2B3C4D;
constexpr std::uint32_t byte_order_magic_swapped = 0x4D3C2B1A;

constexpr std::uint16_t opt_endofopt = 0;
constexpr std::uint16_t shb_userappl = 4;
constexpr std::uint16_t if_name = 2;
constexpr std::uint16_t if_tsresol = 9;
constexpr std::uint16_t if_tsoffset = 14;

constexpr std::uint16_t exp_pdu_tag_end_of_opt = 0;
constexpr std::uint16_t exp_pdu_tag_dissector_name = 12;

constexpr std::uint8_t nanosecond_resolution = 9;  // if_tsresol: 10^-9 s
constexpr std::uint64_t nanoseconds_per_second = 1000000000u;

std::size_t padded(std::size_t size) {
  return (size + 3u) & ~std::size_t{3};
}

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t value) {
  out.push_back(static_cast<std::uint8_t>(value));
  out.push_back(static_cast<std::uint8_t>(value >> 8));
}
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<std::uint8_t>(value >> shift));
}
void put_bytes(std::vector<std::uint8_t>& out, const std::uint8_t* data, std::size_t size) {
  out.insert(out.end(), data, data + size);
  out.resize(padded(out.size()), 0);
}
void put_option(std::vector<std::uint8_t>& out, std::uint16_t code, std::string_view value) {
  put_u16(out, code);
  put_u16(out, static_cast<std::uint16_t>(value.size()));
  put_bytes(out, reinterpret_cast<const std::uint8_t*>(value.data()), value.size());
}
// Starts a block in `out`: type and a length that `end_block` fills in.
void begin_block(std::vector<std::uint8_t>& out, std::uint32_t type) {
  out.clear();
  put_u32(out, type);
  put_u32(out, 0);
}
void end_block(std::vector<std::uint8_t>& out) {
  const auto length = static_cast<std::uint32_t>(out.size() + 4);
  for (std::size_t i = 0; i < 4; ++i) out[4 + i] = static_cast<std::uint8_t>(length >> (8 * i));
  put_u32(out, length);
}

// The exported-PDU tags in front of every record of `network`: the dissector's name, NUL-padded to four
// bytes as Wireshark itself writes it, then the end tag. All exported-PDU integers are big-endian.
void put_exported_pdu_tags(std::vector<std::uint8_t>& out, const char* dissector) {
  const std::string_view name(dissector);
  const std::size_t length = padded(name.size());
  out.push_back(0);
  out.push_back(exp_pdu_tag_dissector_name);
  out.push_back(static_cast<std::uint8_t>(length >> 8));
  out.push_back(static_cast<std::uint8_t>(length));
  put_bytes(out, reinterpret_cast<const std::uint8_t*>(name.data()), name.size());
  for (int i = 0; i < 4; ++i) out.push_back(0);  // EXP_PDU_TAG_END_OF_OPT, length 0
}

std::uint16_t link_type_of(capture_network network) {
  return network == capture_network::can ? linktype_can_socketcan : linktype_wireshark_upper_pdu;
}

// if_tsresol: bit 7 clear = 10^-n s per tick, set = 2^-n s. Finer than 10^-19 s or 2^-63 s a 64-bit tick
// count does not even span a second: no capture uses that.
// Ticks at any if_tsresol to whole nanoseconds (a time finer than 1 ns rounds down, as far as 0); false if that
// does not fit 64 bits.
bool ticks_to_nanoseconds(std::uint64_t ticks, std::uint8_t tsresol, std::uint64_t& out) {
  const unsigned exponent = tsresol & 0x7Fu;
  if ((tsresol & 0x80u) == 0) {
    std::uint64_t scale = 1;
    if (exponent <= 9) {
      for (unsigned i = exponent; i < 9; ++i) scale *= 10;
      if (ticks > UINT64_MAX / scale) return false;
      out = ticks * scale;
    } else if (exponent <= 28) {
      for (unsigned i = 9; i < exponent; ++i) scale *= 10;  // at most 10^19, within 64 bits
      out = ticks / scale;
    } else {
      out = 0;  // 10^20 and more ticks to a nanosecond: no 64-bit count reaches one
    }
    return true;
  }
  // ticks x 10^9 < 2^94: exact in 128 bits, then shifted down by the exponent (0..127), rounding down.
  __extension__ typedef unsigned __int128 wide;  // GCC's and Clang's 128-bit integer (host code only)
  const wide nanoseconds = (static_cast<wide>(ticks) * nanoseconds_per_second) >> exponent;
  if (nanoseconds > UINT64_MAX) return false;
  out = static_cast<std::uint64_t>(nanoseconds);
  return true;
}

// Adds if_tsoffset seconds; false if the time leaves 0 .. 2^64 - 1 ns.
bool add_offset(std::uint64_t& time_ns, std::int64_t offset_seconds) {
  if (offset_seconds == 0) return true;
  const std::uint64_t magnitude = offset_seconds < 0 ? 0u - static_cast<std::uint64_t>(offset_seconds)
                                                     : static_cast<std::uint64_t>(offset_seconds);
  if (magnitude > UINT64_MAX / nanoseconds_per_second) return false;
  const std::uint64_t shift = magnitude * nanoseconds_per_second;
  if (offset_seconds < 0) {
    if (time_ns < shift) return false;
    time_ns -= shift;
  } else {
    if (time_ns > UINT64_MAX - shift) return false;
    time_ns += shift;
  }
  return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// writer

pcapng_writer::pcapng_writer(std::ostream& out, std::string_view application) : out_(out) {
  begin_block(block_, section_header_type);
  put_u32(block_, byte_order_magic);
  put_u16(block_, 1);  // major version
  put_u16(block_, 0);  // minor version
  put_u32(block_, 0xFFFFFFFFu);  // section length: not given (-1)
  put_u32(block_, 0xFFFFFFFFu);
  if (application.size() > max_name_length) application = application.substr(0, max_name_length);
  put_option(block_, shb_userappl, application);
  put_option(block_, opt_endofopt, {});
  end_block(block_);
  (void)put(block_);
}

pcapng_interface_result pcapng_writer::add_interface(std::string_view name, capture_network network) {
  if (failed_) return {pcapng_write_status::write_failed, 0};
  if (network == capture_network::other) return {pcapng_write_status::bad_network, 0};
  if (name.size() > max_name_length) return {pcapng_write_status::name_too_long, 0};
  begin_block(block_, interface_description_type);
  put_u16(block_, link_type_of(network));
  put_u16(block_, 0);  // reserved
  put_u32(block_, 0);  // snap length: no limit
  if (!name.empty()) put_option(block_, if_name, name);
  const char resolution = static_cast<char>(nanosecond_resolution);
  put_option(block_, if_tsresol, std::string_view(&resolution, 1));
  put_option(block_, opt_endofopt, {});
  end_block(block_);
  if (!put(block_)) return {pcapng_write_status::write_failed, 0};
  networks_.push_back(network);
  return {pcapng_write_status::ok, static_cast<std::uint32_t>(networks_.size() - 1)};
}

pcapng_write_status pcapng_writer::write(std::uint32_t interface, std::uint64_t time_ns, byte_view bytes) {
  if (failed_) return pcapng_write_status::write_failed;
  if (interface >= networks_.size()) return pcapng_write_status::bad_interface;
  if (bytes.size() > max_record_length) return pcapng_write_status::record_too_long;
  begin_block(block_, enhanced_packet_type);
  put_u32(block_, interface);
  put_u32(block_, static_cast<std::uint32_t>(time_ns >> 32));
  put_u32(block_, static_cast<std::uint32_t>(time_ns));
  const std::size_t length_at = block_.size();
  put_u32(block_, 0);  // captured and original length, filled in below
  put_u32(block_, 0);
  const std::size_t data_at = block_.size();
  if (const char* dissector = dissector_name(networks_[interface])) put_exported_pdu_tags(block_, dissector);
  block_.insert(block_.end(), bytes.begin(), bytes.end());
  const auto captured = static_cast<std::uint32_t>(block_.size() - data_at);
  for (std::size_t i = 0; i < 4; ++i) {
    block_[length_at + i] = static_cast<std::uint8_t>(captured >> (8 * i));
    block_[length_at + 4 + i] = static_cast<std::uint8_t>(captured >> (8 * i));
  }
  block_.resize(padded(block_.size()), 0);
  end_block(block_);
  return put(block_) ? pcapng_write_status::ok : pcapng_write_status::write_failed;
}

pcapng_write_status pcapng_writer::flush() {
  if (failed_) return pcapng_write_status::write_failed;
  out_.flush();
  if (!out_) failed_ = true;
  return failed_ ? pcapng_write_status::write_failed : pcapng_write_status::ok;
}

bool pcapng_writer::put(const std::vector<std::uint8_t>& block) {
  out_.write(reinterpret_cast<const char*>(block.data()), static_cast<std::streamsize>(block.size()));
  if (!out_) failed_ = true;
  return !failed_;
}

// ---------------------------------------------------------------------------------------------------------
// reader

pcapng_reader::pcapng_reader(std::istream& in, limits limit) : in_(in), limits_(limit) {}

std::uint16_t pcapng_reader::u16(const std::uint8_t* at) const noexcept {
  return big_endian_ ? static_cast<std::uint16_t>(at[0] << 8 | at[1])
                     : static_cast<std::uint16_t>(at[1] << 8 | at[0]);
}

std::uint32_t pcapng_reader::u32(const std::uint8_t* at) const noexcept {
  const std::uint32_t high = u16(big_endian_ ? at : at + 2);
  const std::uint32_t low = u16(big_endian_ ? at + 2 : at);
  return high << 16 | low;
}

pcapng_read_status pcapng_reader::stop(pcapng_read_status status) {
  state_ = read_state::stopped;
  stopped_ = status;
  return status;
}

// Reads exactly `size` bytes: `end_of_file` if none were left at a block start, `truncated` if some were.
pcapng_read_status pcapng_reader::read_exact(std::uint8_t* to, std::size_t size, bool at_block_start) {
  if (size == 0) return pcapng_read_status::ok;
  in_.read(reinterpret_cast<char*>(to), static_cast<std::streamsize>(size));
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (got == size) return pcapng_read_status::ok;
  if (in_.bad()) return pcapng_read_status::read_failed;
  return got == 0 && at_block_start ? pcapng_read_status::end_of_file : pcapng_read_status::truncated;
}

// Reads `size` bytes into block_, growing it as they arrive, so that a block length that lies about a short
// file costs no more memory than the file holds (plus one step).
pcapng_read_status pcapng_reader::read_body(std::size_t size) {
  constexpr std::size_t step = 65536;
  block_.clear();
  while (block_.size() < size) {
    const std::size_t at = block_.size();
    const std::size_t chunk = size - at < step ? size - at : step;
    block_.resize(at + chunk);
    const pcapng_read_status status = read_exact(block_.data() + at, chunk, false);
    if (status != pcapng_read_status::ok) return status;
  }
  return pcapng_read_status::ok;
}

pcapng_read_result pcapng_reader::next() {
  pcapng_read_result result;
  for (;;) {
    if (state_ == read_state::stopped) {
      result.status = stopped_;
      return result;
    }
    std::uint8_t head[8];
    pcapng_read_status status = read_exact(head, 8, true);
    if (status == pcapng_read_status::end_of_file && state_ == read_state::start) {
      status = pcapng_read_status::not_pcapng;
    }
    if (status != pcapng_read_status::ok) {
      result.status = stop(status);
      return result;
    }
    // The section header's type reads the same in both byte orders; its magic says which one follows.
    const bool section = head[0] == 0x0A && head[1] == 0x0D && head[2] == 0x0D && head[3] == 0x0A;
    if (section) {
      status = read_section_header(head);
      if (status != pcapng_read_status::ok) {
        result.status = stop(status);
        return result;
      }
      continue;
    }
    if (state_ == read_state::start) {
      result.status = stop(pcapng_read_status::not_pcapng);
      return result;
    }
    const std::uint32_t type = u32(head);
    const std::uint32_t length = u32(head + 4);
    if (length < 12 || length % 4 != 0) {
      result.status = stop(pcapng_read_status::bad_block_length);
      return result;
    }
    if (length > limits_.max_block_length) {
      result.status = stop(pcapng_read_status::block_too_long);
      return result;
    }
    status = read_body(length - 8);
    if (status == pcapng_read_status::ok && u32(block_.data() + block_.size() - 4) != length) {
      status = pcapng_read_status::bad_block_length;
    }
    if (status != pcapng_read_status::ok) {
      result.status = stop(status);
      return result;
    }
    block_.resize(block_.size() - 4);  // the body alone
    if (type == interface_description_type) {
      status = read_interface();
      if (status != pcapng_read_status::ok) {
        result.status = stop(status);
        return result;
      }
    } else if (type == enhanced_packet_type) {
      result.status = read_packet(result.record);
      if (ends_reading(result.status)) stop(result.status);
      return result;
    } else {
      ++skipped_blocks_;
    }
  }
}

pcapng_read_status pcapng_reader::read_section_header(const std::uint8_t* head) {
  std::uint8_t magic[4];
  pcapng_read_status status = read_exact(magic, 4, false);
  if (status != pcapng_read_status::ok) return status;
  big_endian_ = false;
  const std::uint32_t order = u32(magic);
  if (order == byte_order_magic_swapped) {
    big_endian_ = true;
  } else if (order != byte_order_magic) {
    return pcapng_read_status::bad_byte_order;
  }
  const std::uint32_t length = u32(head + 4);
  if (length < 28 || length % 4 != 0) return pcapng_read_status::bad_block_length;
  if (length > limits_.max_block_length) return pcapng_read_status::block_too_long;
  status = read_body(length - 12);
  if (status != pcapng_read_status::ok) return status;
  if (u32(block_.data() + block_.size() - 4) != length) return pcapng_read_status::bad_block_length;
  if (u16(block_.data()) != 1) return pcapng_read_status::unsupported_version;
  // Options (shb_userappl, ...) are not used, but they must be well formed.
  std::size_t at = 12;
  const std::size_t end = block_.size() - 4;
  while (at + 4 <= end) {
    const std::uint16_t code = u16(block_.data() + at);
    const std::size_t size = u16(block_.data() + at + 2);
    at += 4;
    if (code == opt_endofopt) break;
    if (padded(size) > end - at) return pcapng_read_status::bad_option;
    at += padded(size);
  }
  interfaces_.clear();
  ++sections_;
  state_ = read_state::in_section;
  return pcapng_read_status::ok;
}

pcapng_read_status pcapng_reader::read_interface() {
  if (block_.size() < 8) return pcapng_read_status::bad_block;
  if (interfaces_.size() >= limits_.max_interfaces) return pcapng_read_status::too_many_interfaces;
  pcapng_interface interface;
  interface.link_type = u16(block_.data());
  interface.snap_length = u32(block_.data() + 4);
  std::size_t at = 8;
  while (at + 4 <= block_.size()) {
    const std::uint16_t code = u16(block_.data() + at);
    const std::size_t size = u16(block_.data() + at + 2);
    at += 4;
    if (code == opt_endofopt) break;
    if (padded(size) > block_.size() - at) return pcapng_read_status::bad_option;
    const std::uint8_t* value = block_.data() + at;
    if (code == if_name) {
      std::size_t used = size;
      while (used > 0 && value[used - 1] == 0) --used;
      interface.name.assign(reinterpret_cast<const char*>(value), used);
    } else if (code == if_tsresol) {
      if (size != 1) return pcapng_read_status::bad_option;
      interface.tsresol = value[0];
    } else if (code == if_tsoffset) {
      if (size != 8) return pcapng_read_status::bad_option;
      const std::uint64_t first = u32(value);
      const std::uint64_t second = u32(value + 4);
      const std::uint64_t bits = big_endian_ ? first << 32 | second : second << 32 | first;
      interface.tsoffset = static_cast<std::int64_t>(bits);  // two's complement (C++20; every C++17 target)
    }
    at += padded(size);
  }
  interfaces_.push_back(std::move(interface));
  return pcapng_read_status::ok;
}

pcapng_read_status pcapng_reader::read_packet(pcapng_record& out) {
  if (block_.size() < 20) return pcapng_read_status::bad_block;
  const std::uint32_t interface = u32(block_.data());
  const std::uint64_t ticks = std::uint64_t{u32(block_.data() + 4)} << 32 | u32(block_.data() + 8);
  const std::uint32_t captured = u32(block_.data() + 12);
  if (captured > block_.size() - 20) return pcapng_read_status::bad_block;
  // Packet options (after the padded bytes) are not used, but they must be well formed.
  std::size_t at = 20 + padded(captured);
  if (at > block_.size()) return pcapng_read_status::bad_block;
  while (at + 4 <= block_.size()) {
    const std::uint16_t code = u16(block_.data() + at);
    const std::size_t size = u16(block_.data() + at + 2);
    at += 4;
    if (code == opt_endofopt) break;
    if (padded(size) > block_.size() - at) return pcapng_read_status::bad_option;
    at += padded(size);
  }
  if (interface >= interfaces_.size()) return pcapng_read_status::unknown_interface;
  const pcapng_interface& description = interfaces_[interface];
  out.interface = interface;
  out.original_length = u32(block_.data() + 16);
  if (!ticks_to_nanoseconds(ticks, description.tsresol, out.time_ns) || !add_offset(out.time_ns, description.tsoffset)) return pcapng_read_status::timestamp_out_of_range;
  byte_view bytes(block_.data() + 20, captured);
  out.dissector = {};
  out.network = capture_network::other;
  if (description.link_type == linktype_can_socketcan) {
    out.network = capture_network::can;
  } else if (description.link_type == linktype_wireshark_upper_pdu) {
    // Tags: type u16, length u16 (big-endian), value; until the end tag. The first name tag counts.
    std::size_t tag_at = 0;
    bool ended = false;
    while (!ended) {
      if (bytes.size() - tag_at < 4) return pcapng_read_status::bad_exported_pdu;
      const std::uint8_t* tag = bytes.data() + tag_at;
      const auto type = static_cast<std::uint16_t>(tag[0] << 8 | tag[1]);
      const std::size_t size = static_cast<std::size_t>(tag[2] << 8 | tag[3]);
      tag_at += 4;
      if (size > bytes.size() - tag_at) return pcapng_read_status::bad_exported_pdu;
      if (type == exp_pdu_tag_dissector_name && out.dissector.empty()) {
        // The name ends at its first NUL, as Wireshark reads it: what follows is padding, whatever it holds.
        std::size_t used = 0;
        while (used < size && tag[4 + used] != 0) ++used;
        out.dissector = std::string_view(reinterpret_cast<const char*>(tag + 4), used);
      }
      ended = type == exp_pdu_tag_end_of_opt;
      tag_at += size;
    }
    bytes = byte_view(bytes.data() + tag_at, bytes.size() - tag_at);
    if (out.dissector == dissector_name(capture_network::ring)) out.network = capture_network::ring;
    if (out.dissector == dissector_name(capture_network::genius)) out.network = capture_network::genius;
  }
  out.bytes = bytes;
  return pcapng_read_status::ok;
}

}  // namespace trionet::host
