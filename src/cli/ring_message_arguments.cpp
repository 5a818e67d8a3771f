// The arguments that describe one ring message: see ring_message_arguments.hpp.
#include "ring_message_arguments.hpp"

#include <algorithm>

#include "profile_cli.hpp"
#include "trionet/host/q32_text.hpp"

#include "trionet/ring.hpp"

namespace trionet::cli {
namespace {

bool basic_address(const arguments& args, const std::string& name, std::uint8_t& hops, std::string& error) {
  auto found = args.options.find(name);
  if (found == args.options.end()) {
    error = "missing " + name + " (a BASIC address 10..24)";
    return false;
  }
  long long n = 0;
  if (!parse_integer(found->second, ring::first_basic_address, ring::last_basic_address, n)) {
    error = name + " must be a BASIC address 10..24, got '" + host::printable(found->second) + "'";
    return false;
  }
  hops = *ring::hops_from_basic_address(static_cast<int>(n));
  return true;
}

bool message_of(const std::string& kind, const arguments& args, ring::message& m, std::string& text,
                std::string& error) {
  std::uint8_t hops = 0;
  if (!basic_address(args, "--to", hops, error)) return false;
  if (kind == "print") {
    if (args.positionals.size() != 1) {
      error = "print takes exactly one TEXT argument";
      return false;
    }
    text = args.positionals[0];
    if (text.empty()) {
      error = "TEXT is empty: a character transfer needs at least one character";
      return false;
    }
    const std::size_t max_characters = std::min(active_profile().ring.max_characters, ring::default_max_characters);
    if (text.size() > max_characters) {
      error = "TEXT has " + std::to_string(text.size()) + " characters; a character transfer carries at most " +
              std::to_string(max_characters) + " (docs/protocol.md 1.4" +
              (max_characters == ring::default_max_characters ? ")" : ", the profile's ring.max_characters)");
      return false;
    }
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (static_cast<unsigned char>(text[i]) > 127) {
        error = "TEXT has a character above 127 at byte " + std::to_string(i) + " (the ring carries 7-bit characters)";
        return false;
      }
    }
    m = ring::message::characters(hops, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    return true;
  }
  if (kind == "var") {
    if (!args.has("--vr")) {
      error = "missing --vr (a VR number 0..16383)";
      return false;
    }
    if (!args.has("--value")) {
      error = "missing --value (a real number)";
      return false;
    }
    const std::string& vr_text = args.options.at("--vr");
    const std::string& value_text = args.options.at("--value");
    long long vr = 0;
    if (!parse_integer(vr_text, 0, ring::max_vr, vr)) {
      error = "--vr must be a VR number 0..16383, got '" + host::printable(vr_text) + "'";
      return false;
    }
    // Read exactly, not through a double (53 bits against Q32.32's 64): see q32_text.hpp.
    const host::q32_text_result q = host::parse_q32(value_text);
    if (q.status == host::q32_text_status::too_long) {
      error = "--value has " + std::to_string(value_text.size()) + " characters; a value has at most " +
              std::to_string(host::max_q32_text);
      return false;
    }
    if (q.status == host::q32_text_status::not_a_number) {
      error = "--value must be a real number, got '" + host::printable(value_text) + "'";
      return false;
    }
    if (!q) {
      error = "--value " + host::printable(value_text) + " is outside the Q32.32 range " + host::q32_range_text;
      return false;
    }
    m = ring::message::variable(hops, static_cast<std::uint16_t>(vr), q.raw);
    return true;
  }
  if (kind == "offset") {
    std::uint8_t offset = 0;
    if (!basic_address(args, "--offset", offset, error)) return false;
    m = ring::message::keypad_offset(hops, offset);
    return true;
  }
  if (!args.has("--mode")) {
    error = "missing --mode (0 or 127)";
    return false;
  }
  long long mode = 0;
  if (!parse_integer(args.options.at("--mode"), 0, 127, mode) || (mode != 0 && mode != 127)) {
    error = "--mode must be 0 (key ON) or 127 (key ON and OFF), got '" + host::printable(args.options.at("--mode")) + "'";
    return false;
  }
  m = ring::message::keypad_mode(hops, static_cast<std::uint8_t>(mode));
  return true;
}

}  // namespace

const option_list& ring_message_options() {
  static const option_list options = {
      {"--to", "N", "10 11 12 13 14 15 16 17 18 19 20 21 22 23 24",
       "the BASIC address the message goes to, 10..24 (hops + 9)"},
      {"--vr", "V", "", "var: the VR number, 0..16383"},
      {"--value", "X", "", "var: the value, a real number in the Q32.32 range"},
      {"--offset", "M", "10 11 12 13 14 15 16 17 18 19 20 21 22 23 24",
       "offset: the keypad offset, a BASIC address 10..24"},
      {"--mode", "0|127", "0 127", "mode: the keypad mode, 0 or 127"},
  };
  return options;
}

bool ring_message_frame(const std::string& kind, const arguments& args, std::vector<std::uint8_t>& frame,
                        std::string& error) {
  const std::vector<std::string> allowed_for = [&]() -> std::vector<std::string> {
    if (kind == "print") return {"--to"};
    if (kind == "var") return {"--to", "--vr", "--value"};
    if (kind == "offset") return {"--to", "--offset"};
    if (kind == "mode") return {"--to", "--mode"};
    return {};
  }();
  if (allowed_for.empty()) {
    error = "unknown message kind '" + host::printable(kind) + "' (expected print, var, offset or mode)";
    return false;
  }
  for (const auto& option : args.options) {
    bool message_option = false;
    for (const cli::option& o : ring_message_options()) message_option = message_option || option.first == o.name;
    if (!message_option) continue;  // the command's own options
    bool allowed = false;
    for (const auto& name : allowed_for) allowed = allowed || option.first == name;
    if (!allowed) {
      error = "option " + option.first + " does not apply to a " + kind + " message";
      return false;
    }
  }
  if (kind != "print" && !args.positionals.empty()) {
    error = "unexpected argument '" + host::printable(args.positionals[0]) + "'";
    return false;
  }
  ring::message m;
  std::string text;
  if (!message_of(kind, args, m, text, error)) return false;
  frame.assign(ring::frame_length(m), 0);
  const ring::encode_result result = encode_with_profile(byte_buffer(frame.data(), frame.size()), m);
  if (!result) {
    error = std::string("cannot encode: ") + ring::to_string(result.status);
    return false;
  }
  frame.resize(result.length);
  // What is written must be what `ring decode` accepts: decode it with the same decoder.
  profile_decoder check;
  ring::decode_status decoded = ring::decode_status::incomplete;
  check.push(byte_view(frame.data(), frame.size()), [&decoded](const ring::decode_result& r) { decoded = r.status; });
  if (decoded != ring::decode_status::ok) {
    error = std::string("cannot encode: the decoder would report ") + ring::to_string(decoded);
    return false;
  }
  return true;
}

}  // namespace trionet::cli
