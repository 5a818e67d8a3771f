// The library's view of capture records as named fields (see trionet/host/capture_view.hpp). This is the one
// place of the host library that reads the decoders' result types for captures.
#include "trionet/host/capture_view.hpp"

#include <cinttypes>
#include <cstdio>
#include <map>

#include "trionet/can/frame.hpp"
#include "trionet/can/identifiers.hpp"
#include "trionet/can/vr_codec.hpp"
#include "trionet/genius/transmission.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/text.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/q32.hpp"

namespace trionet::host {
namespace {

// ---------------------------------------------------------------------------------------------------------
// building fields

void add_unsigned(capture_fields& out, std::string name, std::uint64_t value) {
  capture_field field;
  field.name = std::move(name);
  field.kind = capture_field::type::unsigned_integer;
  field.unsigned_value = value;
  out.push_back(std::move(field));
}
void add_signed(capture_fields& out, std::string name, std::int64_t value) {
  capture_field field;
  field.name = std::move(name);
  field.kind = capture_field::type::signed_integer;
  field.signed_value = value;
  out.push_back(std::move(field));
}
void add_boolean(capture_fields& out, std::string name, bool value) {
  capture_field field;
  field.name = std::move(name);
  field.kind = capture_field::type::boolean;
  field.boolean = value;
  out.push_back(std::move(field));
}
void add_real(capture_fields& out, std::string name, double value) {
  capture_field field;
  field.name = std::move(name);
  field.kind = capture_field::type::real;
  field.real = value;
  out.push_back(std::move(field));
}
void add_text(capture_fields& out, std::string name, std::string value) {
  capture_field field;
  field.name = std::move(name);
  field.kind = capture_field::type::text;
  field.text = std::move(value);
  out.push_back(std::move(field));
}
void add_marker(capture_fields& out, std::string name) {
  capture_field field;
  field.name = std::move(name);
  out.push_back(std::move(field));
}

// Bytes as Wireshark prints a byte string: "48:01:00".
std::string colon_hex(const std::uint8_t* data, std::size_t size) {
  std::string out;
  char pair[4];
  for (std::size_t i = 0; i < size; ++i) {
    std::snprintf(pair, sizeof pair, i == 0 ? "%02x" : ":%02x", data[i]);
    out += pair;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// ring

// One message, stray run or stray end of message: the bytes, then what a fresh decoder makes of them (with
// the message cut short at the end of the record reported as `interrupted`, as the next header would).
void ring_unit_fields(byte_view unit, capture_fields& out) {
  const std::uint8_t first = unit[0];
  const bool message = ring::classify(first) == ring::byte_class::header;
  const bool ends = ring::classify(unit[unit.size() - 1]) == ring::byte_class::end_of_message;
  const std::size_t data_at = message ? 1 : 0;
  const std::size_t data_end = unit.size() - (ends ? 1 : 0);
  const std::size_t length = data_end > data_at ? data_end - data_at : 0;
  const std::uint8_t* data = unit.data() + data_at;
  if (message) {
    add_unsigned(out, "trionet_ring.header", first);
    add_unsigned(out, "trionet_ring.hops", ring::hops_of(first));
    add_unsigned(out, "trionet_ring.type", ring::type_of(first));
  }
  if (message || length > 0) add_unsigned(out, "trionet_ring.length", length);
  if (length > 0) add_text(out, "trionet_ring.data", colon_hex(data, length));
  if (ends) {
    add_unsigned(out, "trionet_ring.eom", unit[unit.size() - 1]);
    add_unsigned(out, "trionet_ring.eom_hops", ring::hops_of(unit[unit.size() - 1]));
  }
  if (message && ring::hops_of(first) != 0) {
    const std::uint8_t type = ring::type_of(first);
    if (type == 1 && length > 0) add_text(out, "trionet_ring.text", escaped_text(byte_view(data, length)));
    if (type == 2 && length == ring::variable_data_length) {
      std::uint16_t vr = 0;
      std::int64_t value = 0;
      ring::read_variable_data(data, vr, value);
      const std::uint16_t computed =
          ring::crc_wire_bits(ring::crc_of<ring::crc16_ccitt_false, ring::variable_crc_length>(data));
      const auto received = static_cast<std::uint16_t>(data[12] | data[13] << 8);
      add_unsigned(out, "trionet_ring.vr", vr);
      add_signed(out, "trionet_ring.value_raw", value);
      add_real(out, "trionet_ring.value", trionet::q32_to_double(value));
      add_unsigned(out, "trionet_ring.crc", received);
      add_unsigned(out, "trionet_ring.crc_computed", computed);
      add_boolean(out, "trionet_ring.crc_good", received == computed);
    }
    if (type == 3 && length == 1) add_unsigned(out, "trionet_ring.offset", data[0]);
    if (type == 4 && length == 1) add_unsigned(out, "trionet_ring.mode", data[0]);
  }

  ring::decoder<> decoder;
  std::vector<ring::decode_result> results;
  for (std::uint8_t byte : unit) {
    const ring::decode_result result = decoder.push(byte);
    if (result.status != ring::decode_status::incomplete) results.push_back(result);
  }
  if (decoder.in_message()) results.push_back(decoder.interrupt());
  for (const ring::decode_result& result : results) {
    add_text(out, "trionet_ring.status",
             result.status == ring::decode_status::ok ? "message" : ring::to_string(result.status));
    if (result.status == ring::decode_status::frame_error) {
      add_text(out, "trionet_ring.frame_error", ring::to_string(result.error));
      add_marker(out, std::string("trionet_ring.expert.") + ring::to_string(result.error));
    } else if (result.status == ring::decode_status::crc_error) {
      add_marker(out, "trionet_ring.expert.crc_error");
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// Genius

using genius_parser = genius::transmission_parser<>;

const char* character_status_name(genius::character_status status) {
  switch (status) {
    case genius::character_status::ok:
      return "ok";
    case genius::character_status::start_bit_not_0:
      return "start_bit_not_0";
    case genius::character_status::stop_bit_not_1:
      return "stop_bit_not_1";
    case genius::character_status::not_11_bits:
      return "not_11_bits";
  }
  return "unknown";
}

const char* control_kind_name(genius::control_kind kind) {
  switch (kind) {
    case genius::control_kind::start:
      return "start";
    case genius::control_kind::stop:
      return "stop";
    case genius::control_kind::start_of_block:
      return "start_of_block";
    case genius::control_kind::end_of_block:
      return "end_of_block";
    case genius::control_kind::unknown:
      return "unknown";
  }
  return "unknown";
}

// One transmission (or run of characters outside one, or one badly framed word), through a fresh parser.
// Beside the parser, the CRC-6 registers are kept as the parser keeps them, to show the CRC it compared.
void genius_unit_fields(const std::vector<std::uint16_t>& words, capture_fields& out) {
  using crc = genius::crc6_g704;
  genius_parser parser;
  crc::register_type stop_crc = crc::begin();
  crc::register_type block_crc = crc::begin();
  bool in_block = false;
  bool need_destination = false;
  const char* outcome = nullptr;
  for (const std::uint16_t word : words) {
    add_unsigned(out, "trionet_genius.word", word);
    add_unsigned(out, "trionet_genius.start_bit", word & genius::start_bit_mask);
    add_boolean(out, "trionet_genius.control", (word & genius::control_bit_mask) != 0);
    add_unsigned(out, "trionet_genius.byte", (word >> 2) & 0xFFu);
    add_unsigned(out, "trionet_genius.stop_bit", (word & genius::stop_bit_mask) >> 10);
    const genius::character_result decoded = genius::decode_character(word);
    genius::parse_status status;
    if (!decoded) {
      add_text(out, "trionet_genius.character_status", character_status_name(decoded.status));
      status = parser.push_framing_error();
    } else {
      const genius::character c = decoded.value;
      const bool open = parser.in_transmission();
      if (!c.control) {
        add_text(out, "trionet_genius.kind", "data");
        if (open && need_destination) add_unsigned(out, "trionet_genius.destination", c.byte);
        if (open) {
          stop_crc = crc::update(stop_crc, c.byte);
          if (in_block) block_crc = crc::update(block_crc, c.byte);
        }
        need_destination = false;
        status = parser.push(c);
      } else {
        const genius::control_fields fields = genius::read_control(c.byte);
        add_text(out, "trionet_genius.kind", control_kind_name(fields.kind));
        switch (fields.kind) {
          case genius::control_kind::start:
            add_boolean(out, "trionet_genius.broadcast", fields.broadcast);
            add_unsigned(out, "trionet_genius.sender", fields.sba);
            break;
          case genius::control_kind::stop:
            add_unsigned(out, "trionet_genius.crc", fields.crc);
            break;
          case genius::control_kind::start_of_block:
            add_unsigned(out, "trionet_genius.block_destination", fields.sba);
            break;
          case genius::control_kind::end_of_block:
            add_unsigned(out, "trionet_genius.block_crc", fields.crc);
            break;
          case genius::control_kind::unknown:
            break;
        }
        status = parser.push(c);
        if (fields.kind == genius::control_kind::start) {
          stop_crc = crc::begin();
          in_block = false;
          need_destination = !fields.broadcast;
        } else if (fields.kind == genius::control_kind::start_of_block &&
                   status == genius::parse_status::in_progress) {
          block_crc = crc::begin();
          in_block = true;
        } else if (fields.kind == genius::control_kind::end_of_block &&
                   (status == genius::parse_status::in_progress ||
                    status == genius::parse_status::block_crc_mismatch)) {
          add_unsigned(out, "trionet_genius.block_crc_computed", crc::finish(block_crc));
          add_boolean(out, "trionet_genius.block_crc_good", status == genius::parse_status::in_progress);
          in_block = false;
        } else if (fields.kind == genius::control_kind::stop &&
                   (status == genius::parse_status::ok ||
                    status == genius::parse_status::stop_crc_mismatch)) {
          add_unsigned(out, "trionet_genius.crc_computed", crc::finish(stop_crc));
          add_boolean(out, "trionet_genius.crc_good", status == genius::parse_status::ok);
        }
      }
    }
    if (status != genius::parse_status::in_progress) {
      add_text(out, "trionet_genius.parse_status", genius::to_string(status));
    }
    if (genius::is_error(status)) {
      add_marker(out, std::string("trionet_genius.expert.") + genius::to_string(status));
    }
    const bool decisive = status == genius::parse_status::ok || genius::is_error(status);
    if (outcome == nullptr && decisive) outcome = genius::to_string(status);
  }
  if (outcome == nullptr && parser.in_transmission()) {
    outcome = "incomplete";
    add_marker(out, "trionet_genius.expert.incomplete");
  }
  if (outcome != nullptr) add_text(out, "trionet_genius.status", outcome);
}

// ---------------------------------------------------------------------------------------------------------
// CAN

}  // namespace

capture_fields ring_record_fields(byte_view record) {
  capture_fields out;
  ring_record_splitter units(record.size() + 1);
  for (std::uint8_t byte : record) {
    units.push(byte, 0, [&](byte_view unit, std::uint64_t) { ring_unit_fields(unit, out); });
  }
  units.flush([&](byte_view unit, std::uint64_t) { ring_unit_fields(unit, out); });
  return out;
}

capture_fields genius_record_fields(byte_view record) {
  capture_fields out;
  const std::vector<std::uint16_t> words = genius_record_words(record);
  genius_record_splitter units(words.size() + 1);
  const auto fields_of = [&](byte_view unit, std::uint64_t) { genius_unit_fields(genius_record_words(unit), out); };
  for (std::uint16_t word : words) units.push(word, 0, fields_of);
  units.flush(fields_of);
  if (record.size() % 2 != 0) {
    add_unsigned(out, "trionet_genius.odd_byte", record[record.size() - 1]);
    add_marker(out, "trionet_genius.expert.odd_length");
  }
  return out;
}

capture_fields can_record_fields(byte_view record, std::uint8_t node_count) {
  capture_fields out;
  const socketcan_record_result read = read_socketcan_record(record);
  // The fields Wireshark's SocketCAN dissector shows for a CAN FD frame and an error frame (tshark 4.0).
  if (read.status == socketcan_record_status::not_classic && (record[5] & 0x80U) == 0 &&
      (record[0] & 0x20U) == 0) {
    const bool extended = (record[0] & 0x80U) != 0;
    const std::uint32_t id = std::uint32_t{record[0]} << 24 | std::uint32_t{record[1]} << 16 |
                             std::uint32_t{record[2]} << 8 | record[3];
    add_unsigned(out, "can.id", id & (extended ? can::frame::extended_mask : 0x7FFU));
    add_boolean(out, "can.flags.xtd", extended);
    add_unsigned(out, "can.len", record[4]);
    add_boolean(out, "canfd.flags.brs", (record[5] & 0x01U) != 0);
    add_boolean(out, "canfd.flags.esi", (record[5] & 0x02U) != 0);
    return out;
  }
  if (read.status == socketcan_record_status::error_frame) {
    add_boolean(out, "can.flags.err", true);
    add_unsigned(out, "can.len", record[4]);
    return out;
  }
  if (!read) return out;
  const can::frame& frame = read.frame;
  add_unsigned(out, "can.id", frame.identifier());
  add_unsigned(out, "can.len", record[4]);
  add_boolean(out, "can.flags.xtd", frame.extended());
  add_boolean(out, "can.flags.rtr", frame.remote());
  add_boolean(out, "can.flags.err", false);
  if (frame.extended() || frame.remote() || frame.dlc != can::vr_message_size) return out;
  const can::route_result route = can::route_of(node_count, frame.identifier());
  if (!route) return out;
  add_unsigned(out, "trionet_can.sender", route.value.sender);
  add_unsigned(out, "trionet_can.receiver", route.value.receiver);
  add_unsigned(out, "trionet_can.receive_channel", route.value.receive_channel);
  const std::uint8_t* d = frame.data;
  add_unsigned(out, "trionet_can.vr", d[0]);
  add_unsigned(out, "trionet_can.sign", d[1]);
  add_unsigned(out, "trionet_can.integer",
               std::uint32_t{d[2]} << 24 | std::uint32_t{d[3]} << 16 | std::uint32_t{d[4]} << 8 | d[5]);
  add_unsigned(out, "trionet_can.fraction", static_cast<std::uint16_t>(d[6] << 8 | d[7]));
  const can::decode_result decoded = can::decode_vr_frame(frame);
  if (decoded) {
    add_real(out, "trionet_can.value", trionet::to_double(decoded.message.value));
  } else {
    add_text(out, "trionet_can.error", can::to_string(decoded.status));
    add_marker(out, std::string("trionet_can.expert.") + can::to_string(decoded.status));
  }
  return out;
}

capture_fields record_fields(const pcapng_reader& reader, const pcapng_record& record,
                             const capture_view_options& options) {
  capture_fields out;
  add_unsigned(out, "frame.interface_id", record.interface);
  if (record.interface < reader.interfaces().size() && !reader.interfaces()[record.interface].name.empty()) {
    add_text(out, "frame.interface_name", reader.interfaces()[record.interface].name);
  }
  char time[48];
  std::snprintf(time, sizeof time, "%" PRIu64 ".%09" PRIu64, record.time_ns / 1000000000u,
                record.time_ns % 1000000000u);
  add_text(out, "frame.time_epoch", time);
  if (!record.dissector.empty()) add_text(out, "exported_pdu.prot_name", std::string(record.dissector));
  capture_fields network;
  switch (record.network) {
    case capture_network::ring:
      network = ring_record_fields(record.bytes);
      break;
    case capture_network::genius:
      network = genius_record_fields(record.bytes);
      break;
    case capture_network::can:
      network = can_record_fields(record.bytes, options.can_node_count);
      break;
    case capture_network::other:
      break;
  }
  out.insert(out.end(), network.begin(), network.end());
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// JSON

namespace {

void append_json_value(std::string& out, const capture_field& field) {
  char number[40];
  switch (field.kind) {
    case capture_field::type::unsigned_integer:
      std::snprintf(number, sizeof number, "%" PRIu64, field.unsigned_value);
      out += number;
      return;
    case capture_field::type::signed_integer:
      std::snprintf(number, sizeof number, "%" PRId64, field.signed_value);
      out += number;
      return;
    case capture_field::type::boolean:
      out += field.boolean ? "true" : "false";
      return;
    case capture_field::type::real:
    {
      // The shortest plain decimal that gives the double back, never an exponent, and always a fraction so
      // that a JSON reader keeps it a floating-point number (-0.0 stays negative zero).
      const std::string text = format_real(field.real);
      out += text;
      if (text.find_first_of(".n") == std::string::npos) out += ".0";
      return;
    }
    case capture_field::type::text:
      append_json_string(out, field.text);
      return;
    case capture_field::type::marker:
      out += "\"\"";
      return;
  }
}

}  // namespace

std::string fields_json(const capture_fields& fields) {
  std::vector<std::string_view> order;                            // names, in order of first appearance
  std::map<std::string_view, std::vector<const capture_field*>> values;  // each name's values, in order
  for (const capture_field& field : fields) {
    std::vector<const capture_field*>& list = values[field.name];
    if (list.empty()) order.push_back(field.name);
    list.push_back(&field);
  }
  std::string out = "{";
  for (const std::string_view name : order) {
    const std::vector<const capture_field*>& list = values[name];
    if (out.size() > 1) out += ',';
    append_json_string(out, name);
    out += ':';
    if (list.size() > 1) out += '[';
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (i != 0) out += ',';
      append_json_value(out, *list[i]);
    }
    if (list.size() > 1) out += ']';
  }
  out += '}';
  return out;
}

}  // namespace trionet::host
