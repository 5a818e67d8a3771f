// `trionet ring ...`: encode and decode fibre-ring frames from the shell.
#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

#include "cli.hpp"
#include "ring_cli.hpp"
#include "ring_live.hpp"
#include "trionet/ring.hpp"

namespace trionet::cli {
namespace {

constexpr const char* ring_usage =
    "usage:\n"
    "  trionet ring encode print  --to N TEXT\n"
    "  trionet ring encode var    --to N --vr V --value X\n"
    "  trionet ring encode offset --to N --offset M\n"
    "  trionet ring encode mode   --to N --mode 0|127\n"
    "  trionet ring decode [HEX...]          (no HEX: read standard input)\n"
    "  trionet ring simulate example1|example2|example3|example3-fixed [options]\n"
    "  trionet ring simulate --node mc:FILE.bas|mc|keypad ... [options]   (trionet ring simulate --help)\n"
    "  trionet ring monitor|send|join PORT ...   live ports (trionet ring monitor --help)\n"
    "N and M are BASIC addresses 10..24 (hops + 9); V is 0..16383; X is a real number.\n";

std::string hex_line(const std::uint8_t* bytes, std::size_t length) {
  std::string line;
  char text[4];
  for (std::size_t i = 0; i < length; ++i) {
    std::snprintf(text, sizeof text, "%02x", bytes[i]);
    if (i != 0) line += ' ';
    line += text;
  }
  return line;
}

bool basic_address(const arguments& args, const std::string& name, std::uint8_t& hops, std::string& error) {
  auto found = args.options.find(name);
  if (found == args.options.end()) {
    error = "missing " + name + " (a BASIC address 10..24)";
    return false;
  }
  long long n = 0;
  if (!parse_integer(found->second, ring::first_basic_address, ring::last_basic_address, n)) {
    error = name + " must be a BASIC address 10..24, got '" + found->second + "'";
    return false;
  }
  hops = *ring::hops_from_basic_address(static_cast<int>(n));
  return true;
}

int encode_main(const std::vector<std::string>& words) {
  if (words.empty()) return fail("ring encode needs a message kind: print, var, offset or mode");
  const std::string kind = words[0];
  const std::vector<std::string> rest(words.begin() + 1, words.end());
  arguments args;
  std::string error;
  if (!parse_arguments(rest, {"--to", "--vr", "--value", "--offset", "--mode"}, {}, args, error))
    return fail(error);
  const std::vector<std::string> allowed_for = [&]() -> std::vector<std::string> {
    if (kind == "print") return {"--to"};
    if (kind == "var") return {"--to", "--vr", "--value"};
    if (kind == "offset") return {"--to", "--offset"};
    if (kind == "mode") return {"--to", "--mode"};
    return {};
  }();
  if (allowed_for.empty())
    return fail("unknown message kind '" + kind + "' (expected print, var, offset or mode)");
  for (const auto& option : args.options) {
    bool allowed = false;
    for (const auto& name : allowed_for) allowed = allowed || option.first == name;
    if (!allowed) return fail("option " + option.first + " does not apply to 'ring encode " + kind + "'");
  }
  if (kind != "print" && !args.positionals.empty())
    return fail("unexpected argument '" + args.positionals[0] + "'");

  std::uint8_t hops = 0;
  if (!basic_address(args, "--to", hops, error)) return fail(error);

  ring::message m;
  std::string text;
  if (kind == "print") {
    if (args.positionals.size() != 1) return fail("ring encode print takes exactly one TEXT argument");
    text = args.positionals[0];
    if (text.empty()) return fail("TEXT is empty: a character transfer needs at least one character");
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (static_cast<unsigned char>(text[i]) > 127) {
        return fail("TEXT has a character above 127 at byte " + std::to_string(i) +
                    " (the ring carries 7-bit characters)");
      }
    }
    m = ring::message::characters(hops,
                                  byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  } else if (kind == "var") {
    if (!args.has("--vr")) return fail("missing --vr (a VR number 0..16383)");
    if (!args.has("--value")) return fail("missing --value (a real number)");
    long long vr = 0;
    if (!parse_integer(args.options.at("--vr"), 0, ring::max_vr, vr)) {
      return fail("--vr must be a VR number 0..16383, got '" + args.options.at("--vr") + "'");
    }
    double value = 0;
    if (!parse_real(args.options.at("--value"), value)) {
      return fail("--value must be a real number, got '" + args.options.at("--value") + "'");
    }
    const trionet::q32_result q = trionet::q32_from_double(value);
    if (!q)
      return fail("--value " + args.options.at("--value") +
                  " is outside the Q32.32 range [-2147483648, 2147483647.9999999998]");
    m = ring::message::variable(hops, static_cast<std::uint16_t>(vr), q.raw);
  } else if (kind == "offset") {
    std::uint8_t offset = 0;
    if (!basic_address(args, "--offset", offset, error)) return fail(error);
    m = ring::message::keypad_offset(hops, offset);
  } else {
    if (!args.has("--mode")) return fail("missing --mode (0 or 127)");
    long long mode = 0;
    if (!parse_integer(args.options.at("--mode"), 0, 127, mode) || (mode != 0 && mode != 127)) {
      return fail("--mode must be 0 (key ON) or 127 (key ON and OFF), got '" + args.options.at("--mode") +
                  "'");
    }
    m = ring::message::keypad_mode(hops, static_cast<std::uint8_t>(mode));
  }

  std::vector<std::uint8_t> frame(ring::frame_length(m));
  const ring::encode_result result = ring::encode(byte_buffer(frame.data(), frame.size()), m);
  if (!result) return fail(std::string("cannot encode: ") + ring::to_string(result.status));
  std::printf("%s\n", hex_line(frame.data(), result.length).c_str());
  return exit_ok;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

}  // namespace

bool parse_hex_bytes(const std::string& text, std::vector<std::uint8_t>& bytes, std::string& error) {
  int high = -1;
  std::size_t high_at = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (is_space(c)) {
      continue;
    }
    const int digit = hex_digit(c);
    if (digit < 0) {
      const auto byte = static_cast<unsigned char>(c);
      char shown[8];
      if (byte >= 0x20 && byte < 0x7f) {
        std::snprintf(shown, sizeof shown, "'%c'", c);
      } else {
        std::snprintf(shown, sizeof shown, "0x%02x", byte);
      }
      error = std::string("not hex: ") + shown + " at offset " + std::to_string(i);
      return false;
    }
    if (high < 0) {
      high = digit;
      high_at = i;
    } else {
      bytes.push_back(static_cast<std::uint8_t>(high * 16 + digit));
      high = -1;
    }
  }
  if (high >= 0) {
    error = "odd number of hex digits: the last byte (offset " + std::to_string(high_at) + ") has one digit";
    return false;
  }
  return true;
}

std::string ring_result_json(const ring::decode_result& result) {
  std::string line;
  if (result.status == ring::decode_status::frame_error) {
    return std::string("{\"event\":\"frame_error\",\"reason\":\"") + ring::to_string(result.error) + "\"}";
  }
  const ring::message& m = result.msg;
  const std::string hops = std::to_string(m.hops);
  if (result.status == ring::decode_status::no_room) {  // only with a store smaller than the maximum
    return "{\"event\":\"no_room\",\"hops\":" + hops + "}";
  }
  if (result.status == ring::decode_status::crc_error) {
    return "{\"event\":\"crc_error\",\"hops\":" + hops + ",\"vr\":" + std::to_string(m.vr) + "}";
  }
  switch (m.type) {
    case ring::message_type::character:
      return "{\"event\":\"message\",\"type\":\"char\",\"hops\":" + hops + ",\"text\":" +
             json_string(std::string(reinterpret_cast<const char*>(m.text.data()), m.text.size())) + "}";
    case ring::message_type::variable: {
      char raw[24];
      std::snprintf(raw, sizeof raw, "0x%016" PRIx64, trionet::q32_to_raw(m.value));
      return "{\"event\":\"message\",\"type\":\"var\",\"hops\":" + hops + ",\"vr\":" + std::to_string(m.vr) +
             ",\"raw\":\"" + raw + "\",\"value\":" + format_real(trionet::q32_to_double(m.value)) + "}";
    }
    case ring::message_type::keypad_offset:
      return "{\"event\":\"message\",\"type\":\"offset\",\"hops\":" + hops +
             ",\"offset\":" + std::to_string(m.offset) + "}";
    case ring::message_type::keypad_mode:
      return "{\"event\":\"message\",\"type\":\"mode\",\"hops\":" + hops +
             ",\"mode\":" + std::to_string(m.mode) + "}";
  }
  return "{}";
}

namespace {

int decode_main(const std::vector<std::string>& words) {
  std::string text;
  if (words.empty()) {
    text = read_stdin();
  } else {
    for (const auto& word : words) {
      text += word;
      text += ' ';
    }
  }
  std::vector<std::uint8_t> bytes;
  std::string error;
  if (!parse_hex_bytes(text, bytes, error)) return fail("ring decode: " + error);
  ring::decoder<> decoder;
  std::string out;
  decoder.push(byte_view(bytes.data(), bytes.size()), [&](const ring::decode_result& result) {
    out += ring_result_json(result);
    out += '\n';
  });
  std::fwrite(out.data(), 1, out.size(), stdout);
  return exit_ok;
}

}  // namespace

int ring_main(const std::vector<std::string>& words) {
  if (words.empty()) {
    std::fputs(ring_usage, stderr);
    return exit_usage;
  }
  if (words[0] == "--help" || words[0] == "-h") {
    std::fputs(ring_usage, stdout);
    return exit_ok;
  }
  const std::vector<std::string> rest(words.begin() + 1, words.end());
  if (words[0] == "encode") return encode_main(rest);
  if (words[0] == "decode") return decode_main(rest);
  if (words[0] == "simulate") return ring_simulate_main(rest);
  if (words[0] == "monitor" || words[0] == "send" || words[0] == "join") return ring_live_main(words[0], rest);
  return fail("unknown ring command '" + words[0] + "' (expected encode, decode, simulate, monitor, send or join)");
}

}  // namespace trionet::cli
