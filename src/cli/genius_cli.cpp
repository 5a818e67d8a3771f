// `trionet genius ...`: encode and decode Genius transmissions, and the bus-access timing analysis.
// Formats are documented in docs/genius.md.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <trionet/genius.hpp>

#include "cli.hpp"

namespace trionet::cli {
namespace {

namespace genius = trionet::genius;

constexpr const char* genius_usage =
    "usage: trionet genius <command> [options]\n"
    "\n"
    "commands:\n"
    "  encode --from S (--to D | --broadcast) [--words] [SEGMENT ...]\n"
    "      Encode a transmission. SEGMENT is plain data as hex bytes (\"1122\") or a block\n"
    "      \"block:D:HEX\". Prints the characters: data \"XX\", control \"c:XX\" (--words: 11-bit words\n"
    "      \"w:XXX\").\n"
    "  decode [TOKEN ...]\n"
    "      Decode characters (\"XX\", \"c:XX\" or \"w:XXX\"; from standard input if none are given).\n"
    "      Exit 0 if every character belonged to a good transmission, 1 on wire errors.\n"
    "  timing --rate 153.6s|153.6e|76.8|38.4 --after S --device SBA@FEET ... [--skip-us U]\n"
    "         [--prop-us-per-2000ft P] [--detect-us D] [--json]\n"
    "      Turn start times and margins after the Stop of SBA S.\n"
    "  scan-time --rate 153.6s|153.6e|76.8|38.4 --device BYTES[,BYTES...] ... [--json]\n"
    "      The bus scan time by GE's published figures, per device and in total.\n";

std::string hex2(unsigned value) {
  char text[8];
  std::snprintf(text, sizeof text, "%02x", value & 0xffu);
  return text;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Whole hex number of 1..max_digits digits.
bool parse_hex(const std::string& text, std::size_t max_digits, unsigned& out) {
  if (text.empty() || text.size() > max_digits) return false;
  unsigned value = 0;
  for (char c : text) {
    const int digit = hex_digit(c);
    if (digit < 0) return false;
    value = value * 16u + static_cast<unsigned>(digit);
  }
  out = value;
  return true;
}

// An even number of hex digits ("", "11", "1122") as bytes.
bool parse_hex_bytes(const std::string& text, std::vector<std::uint8_t>& out) {
  if (text.size() % 2 != 0) return false;
  for (std::size_t i = 0; i < text.size(); i += 2) {
    unsigned byte = 0;
    if (!parse_hex(text.substr(i, 2), 2, byte)) return false;
    out.push_back(static_cast<std::uint8_t>(byte));
  }
  return true;
}

bool parse_sba(const std::string& text, std::uint8_t& out) {
  long long value = 0;
  if (!parse_integer(text, 0, genius::max_sba, value)) return false;
  out = static_cast<std::uint8_t>(value);
  return true;
}

std::vector<std::string> split_lines(const std::string& joined) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  while (true) {
    const std::size_t at = joined.find('\n', from);
    parts.push_back(joined.substr(from, at == std::string::npos ? std::string::npos : at - from));
    if (at == std::string::npos) break;
    from = at + 1;
  }
  return parts;
}

std::vector<std::string> split_words(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      if (!word.empty()) words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) words.push_back(word);
  return words;
}

// ---------------------------------------------------------------------------------------------------
// encode

int encode_main(const std::vector<std::string>& words) {
  arguments args;
  std::string error;
  if (!parse_arguments(words, {"--from", "--to"}, {"--broadcast", "--words"}, args, error))
    return fail(error);
  if (!args.has("--from")) return fail("encode needs --from SBA");
  genius::transmission t;
  if (!parse_sba(args.options["--from"], t.sender)) return fail("--from must be an SBA 0..31");
  const bool broadcast = args.flags.count("--broadcast") != 0;
  if (broadcast == args.has("--to")) return fail("encode needs exactly one of --to SBA and --broadcast");
  t.broadcast = broadcast;
  if (!broadcast && !parse_sba(args.options["--to"], t.destination)) return fail("--to must be an SBA 0..31");

  // Byte storage first, views second: the vectors must not move once views point into them.
  std::vector<std::vector<std::uint8_t>> bytes(args.positionals.size());
  std::vector<genius::segment> segments(args.positionals.size());
  for (std::size_t i = 0; i < args.positionals.size(); ++i) {
    const std::string& text = args.positionals[i];
    if (text.compare(0, 6, "block:") == 0) {
      const std::size_t colon = text.find(':', 6);
      if (colon == std::string::npos) return fail("block segment '" + text + "' must be block:SBA:HEX");
      segments[i].block = true;
      if (!parse_sba(text.substr(6, colon - 6), segments[i].destination)) {
        return fail("block segment '" + text + "': destination must be an SBA 0..31");
      }
      if (!parse_hex_bytes(text.substr(colon + 1), bytes[i]) || bytes[i].empty()) {
        return fail("block segment '" + text + "': data must be one or more hex bytes");
      }
    } else if (!parse_hex_bytes(text, bytes[i]) || bytes[i].empty()) {
      return fail("data segment '" + text + "' must be one or more hex bytes (e.g. 1122)");
    }
    segments[i].data = byte_view(bytes[i].data(), bytes[i].size());
  }
  t.segments = span<const genius::segment>(segments.data(), segments.size());

  const genius::encode_result length = genius::encoded_length(t);
  if (length.status == genius::encode_status::empty_transmission) {
    return fail("a broadcast transmission needs at least one data byte");
  }
  if (!length) return fail("cannot encode this transmission");
  std::vector<genius::character> out(length.length);
  const genius::encode_result written =
      genius::encode_transmission(span<genius::character>(out.data(), out.size()), t);
  if (!written) return fail("cannot encode this transmission");

  const bool as_words = args.flags.count("--words") != 0;
  std::string line;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (i != 0) line += ' ';
    if (as_words) {
      char text[8];
      std::snprintf(text, sizeof text, "w:%03x", static_cast<unsigned>(genius::encode_character(out[i])));
      line += text;
    } else {
      line += (out[i].control ? "c:" : "") + hex2(out[i].byte);
    }
  }
  std::printf("%s\n", line.c_str());
  return exit_ok;
}

// ---------------------------------------------------------------------------------------------------
// decode

struct token {
  std::string text;
  bool is_word = false;
  std::uint16_t word = 0;
  genius::character value{};
};

bool parse_token(const std::string& text, token& out, std::string& error) {
  out.text = text;
  unsigned value = 0;
  if (text.compare(0, 2, "w:") == 0) {
    if (!parse_hex(text.substr(2), 3, value) || value > genius::word_mask) {
      error = "token '" + text + "': an 11-bit word is w: and 1..3 hex digits up to 7ff";
      return false;
    }
    out.is_word = true;
    out.word = static_cast<std::uint16_t>(value);
    return true;
  }
  const bool control = text.compare(0, 2, "c:") == 0;
  const std::string digits = control ? text.substr(2) : text;
  if (digits.size() != 2 || !parse_hex(digits, 2, value)) {
    error = "token '" + text + "' is not a character (XX, c:XX or w:XXX)";
    return false;
  }
  out.value = genius::character{static_cast<std::uint8_t>(value), control};
  return true;
}

void print_transmission(const genius::transmission& t) {
  std::string line = "transmission from SBA " + std::to_string(t.sender);
  line += t.broadcast ? ", broadcast" : ", directed to SBA " + std::to_string(t.destination);
  std::printf("%s\n", line.c_str());
  for (const genius::segment& s : t.segments) {
    std::string text = s.block ? "  block to SBA " + std::to_string(s.destination) + ":" : "  data";
    for (std::uint8_t byte : s.data) text += " " + hex2(byte);
    std::printf("%s\n", text.c_str());
  }
}

int decode_main(const std::vector<std::string>& words) {
  arguments args;
  std::string error;
  if (!parse_arguments(words, {}, {}, args, error)) return fail(error);
  const std::vector<std::string> texts =
      args.positionals.empty() ? split_words(read_stdin()) : args.positionals;
  std::vector<token> tokens(texts.size());
  for (std::size_t i = 0; i < texts.size(); ++i) {
    if (!parse_token(texts[i], tokens[i], error)) return fail(error);
  }

  // Plenty for any transmission given on a command line; a longer one is reported as overflow.
  genius::transmission_parser<4096, 256> parser;
  std::size_t transmissions = 0;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const token& t = tokens[i];
    genius::parse_status status;
    std::string detail;
    if (t.is_word) {
      const genius::character_result decoded = genius::decode_character(t.word);
      if (decoded) {
        status = parser.push(decoded.value);
      } else {
        status = parser.push_framing_error();
        detail = decoded.status == genius::character_status::start_bit_not_0 ? " (start bit not 0)"
                                                                             : " (stop bit not 1)";
      }
    } else {
      status = parser.push(t.value);
    }
    if (status == genius::parse_status::ok) {
      ++transmissions;
      print_transmission(parser.received());
    } else if (genius::is_error(status)) {
      std::printf("error at character %zu (%s): %s%s\n", i + 1, t.text.c_str(), genius::to_string(status),
                  detail.c_str());
    }
  }
  const bool unfinished = parser.in_transmission();
  if (unfinished) std::printf("error at end of input: transmission not finished\n");
  const std::uint32_t errors = parser.errors() + (unfinished ? 1u : 0u);
  std::printf("%zu transmission%s, %u error%s, %u character%s skipped\n", transmissions,
              transmissions == 1 ? "" : "s", static_cast<unsigned>(errors), errors == 1 ? "" : "s",
              static_cast<unsigned>(parser.count(genius::parse_status::skipped)),
              parser.count(genius::parse_status::skipped) == 1 ? "" : "s");
  return errors == 0 ? exit_ok : 1;
}

// ---------------------------------------------------------------------------------------------------
// timing

// JSON numbers: rounded to the nanosecond (0.001 us), shortest text that reads back.
std::string json_us(double value) {
  double rounded = std::round(value * 1000.0) / 1000.0;
  if (rounded == 0.0) rounded = 0.0;  // no "-0"
  return format_real(rounded);
}

std::string fixed2(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

std::string pad_left(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
}

const char* layout_problem(genius::layout_status status) {
  switch (status) {
    case genius::layout_status::ok:
      return "ok";
    case genius::layout_status::sba_out_of_range:
      return "an SBA is out of range 0..31";
    case genius::layout_status::duplicate_sba:
      return "two devices have the same SBA";
    case genius::layout_status::sender_not_on_bus:
      return "the --after SBA is not one of the --device entries";
    case genius::layout_status::bad_position:
      return "a device position is negative or not finite";
    case genius::layout_status::bad_timing:
      return "the timing parameters are out of range";
  }
  return "invalid layout";
}

int timing_main(const std::vector<std::string>& words) {
  arguments args;
  std::string error;
  if (!parse_arguments(words,
                       {"--rate", "--after", "--device", "--skip-us", "--prop-us-per-2000ft", "--detect-us"},
                       {"--json"}, args, error, {"--device"})) {
    return fail(error);
  }
  if (!args.positionals.empty()) return fail("unexpected argument '" + args.positionals[0] + "'");
  if (!args.has("--rate")) return fail("timing needs --rate 153.6s|153.6e|76.8|38.4");
  genius::rate rate{};
  if (!genius::rate_from_name(args.options["--rate"], rate)) {
    return fail("unknown rate '" + args.options["--rate"] + "' (expected 153.6s, 153.6e, 76.8 or 38.4)");
  }
  genius::bus_timing timing = genius::default_timing(rate);
  if (!args.has("--after")) return fail("timing needs --after SBA (the SBA whose Stop just ended)");
  std::uint8_t after = 0;
  if (!parse_sba(args.options["--after"], after)) return fail("--after must be an SBA 0..31");
  if (!args.has("--device")) return fail("timing needs at least one --device SBA@FEET");
  std::vector<genius::device> devices;
  for (const std::string& text : split_lines(args.options["--device"])) {
    const std::size_t at = text.find('@');
    genius::device d;
    double feet = 0;
    if (at == std::string::npos || !parse_sba(text.substr(0, at), d.sba) ||
        !parse_real(text.substr(at + 1), feet) || feet < 0) {
      return fail("--device '" + text + "' must be SBA@FEET with SBA 0..31 and FEET >= 0");
    }
    d.position_ft = feet;
    for (const genius::device& other : devices) {
      if (other.sba == d.sba) return fail("SBA " + std::to_string(d.sba) + " is given twice");
    }
    devices.push_back(d);
  }
  const bool explicit_skip = args.has("--skip-us");
  if (explicit_skip && (!parse_real(args.options["--skip-us"], timing.skip_us) || !(timing.skip_us > 0))) {
    return fail("--skip-us must be a number > 0");
  }
  if (args.has("--prop-us-per-2000ft") &&
      (!parse_real(args.options["--prop-us-per-2000ft"], timing.propagation_us_per_2000ft) ||
       timing.propagation_us_per_2000ft < 0)) {
    return fail("--prop-us-per-2000ft must be a number >= 0");
  }
  if (args.has("--detect-us") &&
      (!parse_real(args.options["--detect-us"], timing.detection_us) || timing.detection_us < 0)) {
    return fail("--detect-us must be a number >= 0");
  }

  const genius::turn_analysis analysis =
      genius::analyse_turns(span<const genius::device>(devices.data(), devices.size()), timing, after);
  if (analysis.status == genius::layout_status::sender_not_on_bus) {
    return fail("--after " + std::to_string(after) + " is not one of the --device entries");
  }
  if (analysis.status != genius::layout_status::ok) return fail(layout_problem(analysis.status));
  const genius::rate_properties props = genius::properties(rate);

  if (args.flags.count("--json") != 0) {
    std::string out =
        "{\"rate\":" + json_string(props.name) + ",\"skip_us\":" + json_us(timing.skip_us) + ",\"turns\":[";
    for (std::size_t i = 0; i < analysis.turn_count; ++i) {
      if (i != 0) out += ',';
      out += "{\"sba\":" + std::to_string(analysis.turns[i].sba) +
             ",\"start_us\":" + json_us(analysis.turns[i].start_us) + "}";
    }
    out += "],\"margins\":[";
    for (std::size_t i = 0; i < analysis.margin_count; ++i) {
      const genius::turn_margin& m = analysis.margins[i];
      if (i != 0) out += ',';
      out += "{\"first\":" + std::to_string(m.first) + ",\"second\":" + std::to_string(m.second) +
             ",\"margin_us\":" + json_us(m.margin_us) + "}";
    }
    out += "]}";
    std::printf("%s\n", out.c_str());
    return exit_ok;
  }

  const genius::device* sender = nullptr;
  for (const genius::device& d : devices) {
    if (d.sba == after) sender = &d;
  }
  std::printf("rate %s (%s): bit time %s us, skip time %s us (%s)\n", props.name, props.description,
              fixed2(timing.bit_time_us).c_str(), fixed2(timing.skip_us).c_str(),
              explicit_skip ? "explicit" : "rule");
  std::printf("propagation %s us per 2000 ft, detection time %s us\n",
              format_real(timing.propagation_us_per_2000ft).c_str(), fixed2(timing.detection_us).c_str());
  std::printf("after the Stop of SBA %u at %s ft:\n", static_cast<unsigned>(after),
              format_real(sender->position_ft).c_str());
  if (analysis.turn_count == 0) std::printf("  no other device\n");
  if (analysis.turn_count != 0) std::printf("  SBA  position_ft  turn_start_us\n");
  for (std::size_t i = 0; i < analysis.turn_count; ++i) {
    const genius::turn& t = analysis.turns[i];
    std::printf("  %s  %s  %s\n", pad_left(std::to_string(t.sba), 3).c_str(),
                pad_left(format_real(t.position_ft), 11).c_str(), pad_left(fixed2(t.start_us), 13).c_str());
  }
  if (analysis.margin_count != 0)
    std::printf("margins (second's turn minus the arrival of first's start bit at second):\n");
  if (analysis.margin_count != 0) std::printf("  first  second  margin_us\n");
  for (std::size_t i = 0; i < analysis.margin_count; ++i) {
    const genius::turn_margin& m = analysis.margins[i];
    std::printf("  %s  %s  %s  %s\n", pad_left(std::to_string(m.first), 5).c_str(),
                pad_left(std::to_string(m.second), 6).c_str(), pad_left(fixed2(m.margin_us), 9).c_str(),
                m.margin_us < 0 ? "COLLISION (negative margin)"
                : m.too_small   ? "TOO SMALL"
                                : "ok");
  }
  if (analysis.too_small_count != 0) {
    std::printf("%zu margin%s below the detection time: collision risk\n", analysis.too_small_count,
                analysis.too_small_count == 1 ? "" : "s");
  }
  if (analysis.longer_than_rate_allows) {
    std::printf("warning: the bus is %s ft long; %s allows %u ft\n",
                format_real(analysis.bus_length_ft).c_str(), props.name,
                static_cast<unsigned>(props.max_length_ft));
  }
  if (analysis.more_devices_than_rate_allows) {
    std::printf("warning: %zu devices; %s allows %u\n", devices.size(), props.name,
                static_cast<unsigned>(props.max_devices));
  }
  return exit_ok;
}

// ---------------------------------------------------------------------------------------------------
// scan-time: GE's published scan-time figures (docs/protocol.md 3.3), per device and for the bus.

int scan_time_main(const std::vector<std::string>& words) {
  static constexpr const char* usage =
      "usage: trionet genius scan-time --rate 153.6s|153.6e|76.8|38.4 --device BYTES[,BYTES...] ... [--json]\n"
      "\n"
      "The scan time of a Genius bus by GE's published figures (GFK-0825F): each device contributes a fixed\n"
      "term plus a term per byte of its inputs and outputs (BYTES, inputs + outputs together); the bus's scan\n"
      "time is the sum over its devices. --device is repeatable and takes a comma-separated list. The results\n"
      "are exact (GE's figures in milliseconds); the computed 11-bit character time is shown beside them.\n";
  for (const std::string& word : words) {
    if (word == "--") break;
    if (word == "--help" || word == "-h") {
      std::fputs(usage, stdout);
      return exit_ok;
    }
  }
  arguments args;
  std::string error;
  if (!parse_arguments(words, {"--rate", "--device"}, {"--json"}, args, error, {"--device"})) return fail(error);
  if (!args.positionals.empty()) return fail("unexpected argument '" + args.positionals[0] + "'");
  if (!args.has("--rate")) return fail("scan-time needs --rate 153.6s|153.6e|76.8|38.4");
  genius::rate rate{};
  if (!genius::rate_from_name(args.options["--rate"], rate)) {
    return fail("unknown rate '" + args.options["--rate"] + "' (expected 153.6s, 153.6e, 76.8 or 38.4)");
  }
  if (!args.has("--device")) return fail("scan-time needs at least one --device BYTES");
  std::vector<std::uint32_t> bytes;
  for (const std::string& list : split_lines(args.options["--device"])) {
    std::size_t from = 0;
    while (true) {
      const std::size_t comma = list.find(',', from);
      const std::string item = list.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
      long long value = 0;
      if (!parse_integer(item, 0, 4294967295LL, value)) {
        return fail("--device '" + list + "': each BYTES must be a whole number 0..4294967295");
      }
      bytes.push_back(static_cast<std::uint32_t>(value));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
  }
  const genius::rate_properties props = genius::properties(rate);
  const genius::scan_time_result bus =
      genius::bus_scan_time(rate, span<const std::uint32_t>(bytes.data(), bytes.size()));
  if (bus.status == genius::scan_time_status::too_many_devices) {
    return fail(std::to_string(bytes.size()) + " devices; " + props.name + " allows " +
                std::to_string(props.max_devices));
  }
  if (!bus) return fail(genius::to_string(bus.status));

  // Milliseconds as exact decimal text from nanoseconds ("0.943", "0.0715", "4.831"), no floating point.
  const auto ms = [](std::uint64_t ns) {
    std::string text = std::to_string(ns / 1000000u);
    std::string fraction = std::to_string(ns % 1000000u);
    fraction.insert(0, 6 - fraction.size(), '0');
    while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
    return fraction.empty() ? text : text + "." + fraction;
  };
  const genius::scan_time_terms terms = genius::published_scan_time_terms(rate);
  // The computed character time, rounded to the nanosecond: a separate figure, not used in the sums.
  const auto character_ns = static_cast<std::uint64_t>(std::llround(genius::character_time_us(rate) * 1000.0));

  if (args.flags.count("--json") != 0) {
    std::string out = "{\"rate\":" + json_string(props.name) + ",\"fixed_ms\":" + ms(terms.fixed_ns) +
                      ",\"per_byte_ms\":" + ms(terms.per_byte_ns) + ",\"devices\":[";
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      if (i != 0) out += ',';
      out += "{\"io_bytes\":" + std::to_string(bytes[i]) +
             ",\"scan_time_ms\":" + ms(genius::device_scan_time_ns(rate, bytes[i])) + "}";
    }
    out += "],\"io_bytes\":" + std::to_string(bus.io_bytes) + ",\"total_ms\":" + ms(bus.total_ns) +
           ",\"character_time_ms\":" + ms(character_ns) + "}";
    std::printf("%s\n", out.c_str());
    return exit_ok;
  }
  std::printf("rate %s (%s): %s ms per device + %s ms per byte of inputs and outputs (GE GFK-0825F)\n",
              props.name, props.description, ms(terms.fixed_ns).c_str(), ms(terms.per_byte_ns).c_str());
  std::printf("  device  io_bytes  scan_time_ms\n");
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::printf("  %6zu  %8u  %12s\n", i + 1, static_cast<unsigned>(bytes[i]),
                ms(genius::device_scan_time_ns(rate, bytes[i])).c_str());
  }
  std::printf("bus: %zu device%s, %llu byte%s, %s ms\n", bus.devices, bus.devices == 1 ? "" : "s",
              static_cast<unsigned long long>(bus.io_bytes), bus.io_bytes == 1 ? "" : "s",
              ms(bus.total_ns).c_str());
  std::printf("computed character time (11 bits at %u bit/s): %s ms, not used above\n",
              static_cast<unsigned>(props.baud), ms(character_ns).c_str());
  return exit_ok;
}

}  // namespace

int genius_main(const std::vector<std::string>& args) {
  if (args.empty())
    return fail("genius needs a command: encode, decode, timing or scan-time (see trionet genius --help)");
  const std::string& command = args[0];
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(genius_usage, stdout);
    return exit_ok;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (command == "encode") return encode_main(rest);
  if (command == "decode") return decode_main(rest);
  if (command == "timing") return timing_main(rest);
  if (command == "scan-time") return scan_time_main(rest);
  return fail("unknown genius command '" + command + "' (expected encode, decode, timing or scan-time)");
}

}  // namespace trionet::cli
