// `trionet can ...`: encode a VR message as candump text, decode candump text, print the note's tables.
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include <trionet/can.hpp>

#include "trionet/host/candump.hpp"
#include "cli.hpp"
#include "live.hpp"

namespace trionet::cli {
namespace {

constexpr const char* can_usage =
    "usage: trionet can <command> [options]\n"
    "\n"
    "commands (TN20-17 VR exchange over CANbus):\n"
    "  encode --from I --to J --vr V --value X [--nodes K]\n"
    "      print the frame node I sends to node J to set VR(V) = X, as compact candump text\n"
    "      (3 hex digits of identifier, '#', 16 hex digits of data)\n"
    "  decode [--nodes K]\n"
    "      read candump lines (\"(secs.micros) can0 028#...\" or \"028#...\") from stdin, print one JSON\n"
    "      object per line: {\"event\":\"vr\",...} or {\"event\":\"error\",\"line\":L,\"reason\":R} with R "
    "one of\n"
    "      syntax, dlc, sign, fraction, unknown_id; blank lines are skipped (but counted in L)\n"
    "  table [--nodes K]\n"
    "      print the note's receive and transmit identifier tables\n"
    "  monitor|send|node IFACE ...\n"
    "      a live bus: SocketCAN or candump text (trionet can monitor --help)\n"
    "\n"
    "K is the number of controllers, 2..11 (default 5, the note's limit).\n";

bool parse_node_count(const arguments& parsed, std::uint8_t& out, std::string& error) {
  out = can::default_node_count;
  if (!parsed.has("--nodes")) return true;
  long long value = 0;
  if (!parse_integer(parsed.options.at("--nodes"), can::min_node_count, can::max_node_count, value)) {
    error = "--nodes must be an integer from 2 to 11, got '" + parsed.options.at("--nodes") + "'";
    return false;
  }
  out = static_cast<std::uint8_t>(value);
  return true;
}

bool parse_args(const std::vector<std::string>& words, const std::set<std::string>& options,
                arguments& parsed, std::string& error) {
  if (!parse_arguments(words, options, {}, parsed, error)) return false;
  if (!parsed.positionals.empty()) {
    error = "unexpected argument '" + parsed.positionals.front() + "'";
    return false;
  }
  return true;
}

int encode_command(const std::vector<std::string>& words) {
  arguments parsed;
  std::string error;
  if (!parse_args(words, {"--nodes", "--from", "--to", "--vr", "--value"}, parsed, error)) return fail(error);
  std::uint8_t nodes = 0;
  if (!parse_node_count(parsed, nodes, error)) return fail(error);
  for (const char* required : {"--from", "--to", "--vr", "--value"}) {
    if (!parsed.has(required)) return fail(std::string("encode needs ") + required);
  }
  long long from = 0;
  long long to = 0;
  long long vr = 0;
  double value = 0;
  const std::string node_range = "an integer from 1 to " + std::to_string(nodes);
  if (!parse_integer(parsed.options.at("--from"), 1, nodes, from)) {
    return fail("--from must be " + node_range + ", got '" + parsed.options.at("--from") + "'");
  }
  if (!parse_integer(parsed.options.at("--to"), 1, nodes, to)) {
    return fail("--to must be " + node_range + ", got '" + parsed.options.at("--to") + "'");
  }
  if (from == to) return fail("--from and --to are the same node; a node does not send to itself");
  if (!parse_integer(parsed.options.at("--vr"), 0, can::max_message_vr, vr)) {
    return fail("--vr must be an integer from 0 to 255, got '" + parsed.options.at("--vr") + "'");
  }
  if (!parse_real(parsed.options.at("--value"), value)) {
    return fail("--value must be a finite decimal number, got '" + parsed.options.at("--value") + "'");
  }
  const can::identifier_result id =
      can::exchange_identifier(nodes, static_cast<std::uint8_t>(from), static_cast<std::uint8_t>(to));
  can::frame out;
  out.id = id.identifier;
  out.dlc = can::vr_message_size;
  const can::encode_status encoded = can::encode_vr(static_cast<std::uint16_t>(vr), value, out.data);
  if (encoded == can::encode_status::too_large) {
    return fail("--value magnitude must round to less than 4294967296, got '" + parsed.options.at("--value") +
                "'");
  }
  if (encoded != can::encode_status::ok || id.status != can::scheme_status::ok) {
    return fail("cannot encode this message");  // unreachable: every input was checked above
  }
  std::printf("%s\n", host::format_candump_frame(out).c_str());
  return exit_ok;
}

std::string error_event(std::size_t line, const char* reason) {
  return "{\"event\":\"error\",\"line\":" + std::to_string(line) + ",\"reason\":\"" + reason + "\"}";
}

std::string decode_line(std::uint8_t nodes, std::size_t line_number, std::string_view line) {
  const host::candump_result parsed = host::parse_candump_line(line);
  if (parsed.status != host::candump_status::ok) return error_event(line_number, "syntax");
  const can::frame& frame = parsed.record.frame;
  const can::route_result route = can::route_of(nodes, frame.id);
  if (route.status != can::scheme_status::ok) return error_event(line_number, "unknown_id");
  const can::decode_result decoded = can::decode_vr_frame(frame);
  if (!decoded) return error_event(line_number, can::to_string(decoded.status));
  const can::vr_message& message = decoded.message;
  return "{\"event\":\"vr\",\"id\":" + std::to_string(frame.identifier()) +
         ",\"from\":" + std::to_string(route.value.sender) +
         ",\"to\":" + std::to_string(route.value.receiver) + ",\"vr\":" + std::to_string(message.vr) +
         ",\"negative\":" + (message.value.negative ? "true" : "false") +
         ",\"int\":" + std::to_string(message.value.integer_part) +
         ",\"frac\":" + std::to_string(message.value.fraction) +
         ",\"value\":" + format_real(trionet::to_double(message.value)) + "}";
}

int decode_command(const std::vector<std::string>& words) {
  arguments parsed;
  std::string error;
  if (!parse_args(words, {"--nodes"}, parsed, error)) return fail(error);
  std::uint8_t nodes = 0;
  if (!parse_node_count(parsed, nodes, error)) return fail(error);
  const std::string input = read_stdin();
  std::string_view rest = input;
  std::size_t line_number = 0;
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    const std::string_view line = rest.substr(0, newline);
    rest = newline == std::string_view::npos ? std::string_view() : rest.substr(newline + 1);
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;  // blank line: skipped
    std::printf("%s\n", decode_line(nodes, line_number, line).c_str());
  }
  return exit_ok;
}

int table_command(const std::vector<std::string>& words) {
  arguments parsed;
  std::string error;
  if (!parse_args(words, {"--nodes"}, parsed, error)) return fail(error);
  std::uint8_t nodes = 0;
  if (!parse_node_count(parsed, nodes, error)) return fail(error);
  std::string out = "Node Base address";
  for (unsigned channel = 1; channel < nodes; ++channel) out += "\tRx #" + std::to_string(channel);
  out += '\n';
  for (std::uint8_t node = 1; node <= nodes; ++node) {
    out += std::to_string(can::base_identifier(nodes, node).identifier);
    for (std::uint8_t channel = 1; channel < nodes; ++channel) {
      out += '\t' + std::to_string(can::receive_identifier(nodes, node, channel).identifier);
    }
    out += '\n';
  }
  out += "\nNode Base address";
  for (unsigned channel = can::first_transmit_channel; channel <= nodes + 3U; ++channel) {
    out += "\tTx #" + std::to_string(channel);
  }
  out += '\n';
  for (std::uint8_t node = 1; node <= nodes; ++node) {
    out += std::to_string(can::base_identifier(nodes, node).identifier);
    for (auto channel = can::first_transmit_channel; channel <= nodes + 3U; ++channel) {
      out += '\t' + std::to_string(can::transmit_identifier(nodes, node, channel).identifier);
    }
    out += '\n';
  }
  std::fputs(out.c_str(), stdout);
  return exit_ok;
}

}  // namespace

int can_main(const std::vector<std::string>& args) {
  if (args.empty()) {
    std::fputs(can_usage, stderr);
    return exit_usage;
  }
  const std::string& command = args.front();
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(can_usage, stdout);
    return exit_ok;
  }
  if (command == "encode") return encode_command(rest);
  if (command == "decode") return decode_command(rest);
  if (command == "table") return table_command(rest);
  if (command == "monitor" || command == "send" || command == "node") return can_live_main(command, rest);
  return fail("unknown can command '" + command + "' (expected encode, decode, table, monitor, send or node)");
}

}  // namespace trionet::cli
