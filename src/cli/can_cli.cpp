// `trionet can ...`: encode a VR message as candump text, decode candump text or captures as they arrive,
// print the note's tables; the command table of the part.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include <trionet/can.hpp>

#include "capture_cli.hpp"
#include "cli.hpp"
#include "can_cli.hpp"
#include "profile_cli.hpp"
#include "trionet/host/candump.hpp"
#include "trionet/host/capture.hpp"

namespace trionet::cli {
namespace {

constexpr const char* encode_usage =
    "usage: trionet can encode --from I --to J --vr V --value X [--nodes K]\n"
    "Prints the frame node I sends to node J to set VR(V) = X, as compact candump text (3 hex digits of\n"
    "identifier, '#', 16 hex digits of data). K is the number of controllers, 2..11 (default 5).\n";

constexpr const char* decode_usage =
    "usage: trionet can decode [--nodes K]                 candump text from standard input\n"
    "       trionet can decode --pcap FILE [--json] [--nodes K]   the CAN records of a pcapng capture\n"
    "Reads every form of candump text that can-utils reads or writes (docs/protocol.md 2.3): log lines\n"
    "\"(1700000000.123456) can0 028#...\" with 6 or 9 fraction digits and an optional direction R/T, compact\n"
    "frames \"028#...\", and candump's screen format \"  can0  028   [8]  01 00 ...\" with or without its\n"
    "timestamp. Prints one JSON object per line as soon as the line is complete:\n"
    "  {\"event\":\"vr\",...}      a TN20-17 VR message (id, from, to, vr, negative, int, frac, value)\n"
    "  {\"event\":\"frame\",...}   a valid CAN frame that is no VR message; \"kind\" says what it is: remote,\n"
    "                          error_frame, fd, xl, extended, bad_identifier (standard id above 7FF),\n"
    "                          foreign_id (not an exchange identifier for K nodes)\n"
    "  {\"event\":\"error\",...}   a frame on an exchange identifier that is no VR message (reason bad_dlc,\n"
    "                          bad_sign, bad_fraction), or a line that is not candump text (reason syntax,\n"
    "                          detail: where the line goes wrong, e.g. identifier, data, too_long)\n"
    "Every event has \"line\" (blank lines are skipped but counted), and \"time\", \"interface\" and\n"
    "\"direction\" where the line has them; from a capture, \"record\", \"interface\" and \"time\".\n"
    "With --pcap, --json prints each record as the fields Wireshark shows (docs/wireshark.md).\n"
    "Exit status 0 when the input was read, 1 when reading or writing failed, 2 for bad arguments.\n";

constexpr const char* table_usage =
    "usage: trionet can table [--nodes K]\n"
    "Prints the note's receive-identifier table, a blank line, then its transmit-identifier table, in aligned\n"
    "columns.\n";

const option_list decode_options = joined(node_count_option(), {
    {"--pcap", "FILE", "@file", "read the CAN records of a pcapng capture (else candump text from standard input)"},
    {"--json", nullptr, "", "with --pcap: each record as the fields Wireshark shows"},
});

bool parse_args(const words& all, const option_list& options, arguments& parsed, std::string& error) {
  if (!parse_arguments(all, options, parsed, error)) return false;
  if (!parsed.positionals.empty()) {
    error = "unexpected argument '" + host::printable(parsed.positionals.front()) + "'";
    return false;
  }
  return true;
}

int encode_command(const words& all) {
  arguments parsed;
  std::string error;
  if (!parse_args(all, can_message_options(), parsed, error)) return fail(error);
  can::frame out;
  if (!can_message_frame(parsed, out, error)) return fail(error);
  return write_stdout(host::format_candump_frame(out) + "\n") ? exit_ok : fail_output();
}

// ---------------------------------------------------------------------------------------------------------
// decode

// Lines of candump text, read in pieces, one event per line that is not blank.
class candump_reader {
 public:
  candump_reader(std::string& out, std::uint8_t nodes) : out_(out), nodes_(nodes) {}

  void push(std::string_view text) {
    while (!text.empty()) {
      const void* found = std::memchr(text.data(), '\n', text.size());
      if (found == nullptr) {
        keep(text);
        return;
      }
      const std::size_t end = static_cast<std::size_t>(static_cast<const char*>(found) - text.data());
      if (pending_.empty() && !too_long_) {
        line(text.substr(0, end));  // the whole line is in this piece: no copy
      } else {
        keep(text.substr(0, end));
        line(pending_);
      }
      pending_.clear();
      too_long_ = false;
      text.remove_prefix(end + 1);
    }
  }

  void finish() {
    if (!pending_.empty() || too_long_) line(pending_);
    pending_.clear();
    too_long_ = false;
  }

 private:
  // Part of a line that goes on in the next piece; past the longest line only the fact is kept.
  void keep(std::string_view part) {
    if (too_long_) return;
    if (pending_.size() + part.size() > host::candump_max_line_length) {
      too_long_ = true;
      pending_.clear();
      return;
    }
    pending_.append(part.data(), part.size());
  }

  void line(std::string_view text) {
    ++number_;
    const host::candump_status status =
        too_long_ ? host::candump_status::too_long : host::parse_candump_line(text, record_);
    if (status == host::candump_status::empty) return;
    const auto where = [this](event& e) {
      e.number("line", number_);
      if (!record_.timestamp.empty()) e.text("time", record_.timestamp);
      if (!record_.interface_name.empty()) e.text("interface", record_.interface_name);
      if (record_.direction != 0) e.text("direction", std::string_view(&record_.direction, 1));
    };
    if (status != host::candump_status::ok) {
      event e(out_, "error");
      e.number("line", number_).text("reason", "syntax").text("detail", host::to_string(status));
      return;
    }
    append_can_frame_event(out_, nodes_, record_, where);
  }

  std::string& out_;
  std::uint8_t nodes_;
  std::string pending_;
  bool too_long_ = false;
  std::uint64_t number_ = 0;
  host::candump_record record_;
};

// A SocketCAN record of a capture as the fields of a candump record.
bool record_of(const host::pcapng_record& record, host::candump_record& out, host::socketcan_record_status& status) {
  const host::socketcan_record_result read = host::read_socketcan_record(record.bytes);
  status = read.status;
  out = host::candump_record{};
  if (record.bytes.size() >= 8) {
    out.can_id = std::uint32_t{record.bytes[0]} << 24U | std::uint32_t{record.bytes[1]} << 16U |
                 std::uint32_t{record.bytes[2]} << 8U | record.bytes[3];
    out.length = record.bytes[4];
  }
  switch (read.status) {
    case host::socketcan_record_status::ok:
      out.frame = read.frame;
      out.can_id = read.frame.id;
      out.length = read.frame.remote() ? std::uint16_t{read.frame.dlc > 8 ? std::uint8_t{8} : read.frame.dlc}
                                       : read.frame.data_length();  // a remote frame: the length it asks for
      return true;
    case host::socketcan_record_status::not_classic:
      if ((record.bytes[5] & 0x80U) != 0) {
        out.type = host::candump_frame_type::xl;
      } else {
        // The error flag makes an error frame of a CAN FD frame too, as candump text reads it (`20000080##0`).
        out.type = (out.can_id & host::can_error_flag) != 0 ? host::candump_frame_type::error
                                                            : host::candump_frame_type::fd;
      }
      return true;
    case host::socketcan_record_status::error_frame:
      out.type = host::candump_frame_type::error;
      return true;
    case host::socketcan_record_status::bad_identifier:
      return true;  // classic, identifier out of range: reported as bad_identifier
    case host::socketcan_record_status::too_short:
    case host::socketcan_record_status::bad_length:
      break;
  }
  return false;
}

int decode_command(const words& all) {
  arguments parsed;
  std::string error;
  if (!parse_args(all, decode_options, parsed, error)) return fail(error);
  std::uint8_t nodes = 0;
  if (!parse_node_count(parsed, nodes, error)) return fail(error);
  if (parsed.has("--pcap")) {
    return read_capture(parsed.options.at("--pcap"), host::capture_network::can, parsed.flag("--json"), nodes,
                        [nodes](const host::pcapng_record& record, const capture_position& where, std::string& out) {
                          host::candump_record frame;
                          host::socketcan_record_status status{};
                          const auto here = [&where](event& e) { add_position(e, where); };
                          if (record_of(record, frame, status)) {
                            append_can_frame_event(out, nodes, frame, here);
                          } else {
                            event e(out, "error");
                            here(e);
                            e.text("reason", host::to_string(status));
                          }
                        });
  }
  if (parsed.flag("--json")) return fail("--json applies to --pcap (the output is JSON already)");
  output out;
  candump_reader reader(out.text(), nodes);
  const int status = stream_stdin(out, [&reader](std::string_view chunk) { reader.push(chunk); });
  if (status != exit_ok) return status;
  reader.finish();
  return out.flush() ? exit_ok : fail_output();
}

// A table as text: columns left-aligned, two blanks between them, no blank at the end of a line.
std::string aligned(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> widths;
  for (const auto& row : rows) {
    if (widths.size() < row.size()) widths.resize(row.size(), 0);
    for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  }
  std::string out;
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size()) line += std::string(widths[c] - row[c].size() + 2, ' ');
    }
    out += line + '\n';
  }
  return out;
}

int table_command(const words& all) {
  arguments parsed;
  std::string error;
  if (!parse_args(all, node_count_option(), parsed, error)) return fail(error);
  std::uint8_t nodes = 0;
  if (!parse_node_count(parsed, nodes, error)) return fail(error);
  std::vector<std::vector<std::string>> receive(1, {"Node Base address"});
  std::vector<std::vector<std::string>> transmit(1, {"Node Base address"});
  for (unsigned channel = 1; channel < nodes; ++channel) receive[0].push_back("Rx #" + std::to_string(channel));
  for (unsigned channel = can::first_transmit_channel; channel <= nodes + 3U; ++channel) {
    transmit[0].push_back("Tx #" + std::to_string(channel));
  }
  for (std::uint8_t node = 1; node <= nodes; ++node) {
    const std::string base = std::to_string(can::base_identifier(nodes, node).identifier);
    receive.push_back({base});
    transmit.push_back({base});
    for (std::uint8_t channel = 1; channel < nodes; ++channel) {
      receive.back().push_back(std::to_string(can::receive_identifier(nodes, node, channel).identifier));
    }
    for (auto channel = can::first_transmit_channel; channel <= nodes + 3U; ++channel) {
      transmit.back().push_back(std::to_string(can::transmit_identifier(nodes, node, channel).identifier));
    }
  }
  output out;
  out.text() += aligned(receive) + "\n" + aligned(transmit);
  return out.flush() ? exit_ok : fail_output();
}

const command can_commands[] = {
    {"encode", "print the frame that sets a VR on another node, as candump text", encode_usage, encode_command,
     can_message_options()},
    {"decode", "read candump text or a capture; print one JSON event per frame", decode_usage, decode_command,
     decode_options},
    {"table", "print the note's receive and transmit identifier tables", table_usage, table_command,
     node_count_option()},
    {"monitor", "watch a live bus (SocketCAN, or candump text with -): one event per frame", can_live_usage,
     can_monitor_main, can_monitor_options()},
    {"send", "put one VR message on a live bus", can_live_usage, can_send_main, can_send_options()},
    {"node", "be a TN20-17 VR-exchange node on a live bus, commands on stdin", can_live_usage, can_node_main,
     can_node_options()},
};

}  // namespace

bool parse_node_count(const arguments& parsed, std::uint8_t& out, std::string& error) {
  out = active_profile().can.node_count;
  if (!parsed.has("--nodes")) return true;
  long long value = 0;
  if (!parse_integer(parsed.options.at("--nodes"), can::min_node_count, can::max_node_count, value)) {
    error = "--nodes must be an integer from 2 to 11, got '" + host::printable(parsed.options.at("--nodes")) + "'";
    return false;
  }
  out = static_cast<std::uint8_t>(value);
  return true;
}

const option_list& node_count_option() {
  static const option_list options = {
      {"--nodes", "K", "2 3 4 5 6 7 8 9 10 11", "the number of controllers, 2..11 (default 5, the note's limit)"}};
  return options;
}

const option_list& can_message_options() {
  static const option_list options = joined(node_count_option(), {
      {"--from", "I", "1 2 3 4 5 6 7 8 9 10 11", "the node that sends, 1..K"},
      {"--to", "J", "1 2 3 4 5 6 7 8 9 10 11", "the node that receives, 1..K"},
      {"--vr", "V", "", "the VR number"},
      {"--value", "X", "", "the value"},
  });
  return options;
}

bool can_message_frame(const arguments& parsed, can::frame& out, std::string& error) {
  std::uint8_t nodes = 0;
  if (!parse_node_count(parsed, nodes, error)) return false;
  for (const char* required : {"--from", "--to", "--vr", "--value"}) {
    if (!parsed.has(required)) {
      error = std::string("missing ") + required;
      return false;
    }
  }
  long long from = 0;
  long long to = 0;
  long long vr = 0;
  double value = 0;
  const std::string node_range = "an integer from 1 to " + std::to_string(nodes);
  const auto given = [&parsed](const char* name) { return "'" + host::printable(parsed.options.at(name)) + "'"; };
  if (!parse_integer(parsed.options.at("--from"), 1, nodes, from)) {
    error = "--from must be " + node_range + ", got " + given("--from");
    return false;
  }
  if (!parse_integer(parsed.options.at("--to"), 1, nodes, to)) {
    error = "--to must be " + node_range + ", got " + given("--to");
    return false;
  }
  if (from == to) {
    error = "--from and --to are the same node (own_node): a node does not send to itself";
    return false;
  }
  if (!parse_integer(parsed.options.at("--vr"), 0, can::max_message_vr, vr)) {
    error = "--vr must be an integer from 0 to 255, got " + given("--vr");
    return false;
  }
  if (!parse_real(parsed.options.at("--value"), value)) {
    error = "--value must be a finite decimal number, got " + given("--value");
    return false;
  }
  const can::identifier_result id =
      can::exchange_identifier(nodes, static_cast<std::uint8_t>(from), static_cast<std::uint8_t>(to));
  out = can::frame{};
  out.id = id.identifier;
  out.dlc = can::vr_message_size;
  const can::encode_status encoded = can::encode_vr(static_cast<std::uint16_t>(vr), value, out.data, active_profile().can.byte_order);
  if (encoded == can::encode_status::too_large) {
    error = "--value magnitude must round to less than 4294967296, got " + given("--value");
    return false;
  }
  // Every input was checked above; and what is written must be what `can decode` accepts.
  if (encoded != can::encode_status::ok || id.status != can::scheme_status::ok || !can::decode_vr_frame(out, active_profile().can.byte_order) ||
      !can::route_of(nodes, out.identifier())) {
    error = "cannot encode this message";
    return false;
  }
  return true;
}

host::candump_record candump_record_of(const can::frame& frame, bool error_frame) {
  host::candump_record r;
  r.type = error_frame ? host::candump_frame_type::error : host::candump_frame_type::classic;
  r.can_id = error_frame ? (frame.id & can::frame::extended_mask) | host::can_error_flag : frame.id;
  r.length = frame.remote() ? (frame.dlc > 8 ? std::uint8_t{8} : frame.dlc) : frame.data_length();
  r.frame = frame;
  return r;
}

const part can_part = {"can", "Trio TN20-17 CANbus VR exchange (encode, decode, table, monitor, send, node)", can_commands,
                       sizeof can_commands / sizeof can_commands[0],
                       "K (--nodes) is the number of controllers, 2..11 (default 5, the note's limit).\n"};

}  // namespace trionet::cli
