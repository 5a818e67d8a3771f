// `trionet genius ...`: encode and decode Genius transmissions, and the bus-access timing analysis.
// Formats are documented in docs/genius.md.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <trionet/genius.hpp>

#include "capture_cli.hpp"
#include "cli.hpp"
#include "genius_bus_cli.hpp"
#include "learn_cli.hpp"
#include "profile_cli.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/capture_view.hpp"

namespace trionet::cli {
namespace {

namespace genius = trionet::genius;

constexpr const char* encode_usage =
    "usage: trionet genius encode --from S (--to D | --broadcast) [--words] [SEGMENT ...]\n"
    "Encodes a transmission. SEGMENT is plain data as hex bytes (\"1122\") or a block \"block:D:HEX\". Prints\n"
    "the characters: data \"XX\", control \"c:XX\" (--words: 11-bit words \"w:XXX\"). A transmission carries\n"
    "at most 256 data bytes in 16 segments (what `genius decode` takes).\n";

constexpr const char* decode_usage =
    "usage: trionet genius decode [TOKEN ...] [--write-pcap FILE [--rate R]]   tokens from the arguments,\n"
    "                                                                          else from standard input\n"
    "       trionet genius decode --raw [--write-pcap FILE [--rate R]]         2-byte words from standard input\n"
    "       trionet genius decode --pcap FILE [--json]                         the Genius records of a capture\n"
    "Tokens: a data character \"XX\", a control character \"c:XX\", an 11-bit word \"w:XXX\". --raw: each\n"
    "character as two bytes, the 11-bit word big-endian (as in a capture record, docs/wireshark.md).\n"
    "Prints each transmission and each error as soon as it is complete, with where it is (line and character,\n"
    "byte offset, or capture record), then a summary line. A token that is not a character is an error (the\n"
    "character is lost, as with a framing error) and decoding goes on. --write-pcap also writes every\n"
    "character to a capture, one record per transmission, timed at rate R (default 153.6s); a token that is\n"
    "not a character goes there as the word 0xFFFF (a framing error), so the capture keeps the loss.\n"
    "With --pcap, --json prints each record as the fields Wireshark shows (docs/wireshark.md).\n"
    "Exit status 0 when the input was read (wire errors included), 1 when reading or writing failed, 2 for\n"
    "bad arguments.\n";

constexpr const char* timing_usage =
    "usage: trionet genius timing --rate 153.6s|153.6e|76.8|38.4 --after S --device SBA@FEET ... [--skip-us U]\n"
    "                             [--prop-us-per-2000ft P] [--detect-us D] [--json] [--check]\n"
    "Turn start times and margins after the Stop of SBA S (docs/genius.md). FEET is 0..1000000; U (0.01 and\n"
    "up), P and D are microseconds up to 1000000. --check: exit status 3 when a margin is below the detection\n"
    "time (a collision risk) or the bus is longer or has more devices than the rate allows, so that a script\n"
    "or CI job can fail on it.\n";

constexpr const char* scan_time_usage =
    "usage: trionet genius scan-time --rate 153.6s|153.6e|76.8|38.4 --device BYTES[,BYTES...] ... [--minimum-ms M]\n"
    "                                [--json]\n"
    "       trionet genius scan-time --table\n"
    "The scan time of a Genius bus by GE's published figures (GFK-0825F): each device contributes a fixed\n"
    "term plus a term per byte of its inputs and outputs (BYTES, inputs + outputs together); the sum is over\n"
    "the devices, and the scan time is never below the bus controller's minimum, M ms (default 3, 0 for none).\n"
    "--device is repeatable and takes a comma-separated list. The results are exact (GE's figures in\n"
    "milliseconds); the computed 11-bit character time is shown beside them. --table prints GE's printed\n"
    "table beside the formula and marks the cells that are not the formula rounded to 0.01 ms.\n";

const char* const rate_names = "153.6s 153.6e 76.8 38.4";

const option_list encode_options = {
    {"SEGMENT", nullptr, "", "plain data as hex bytes (\"1122\"), or a block \"block:D:HEX\""},
    {"--from", "S", "", "the SBA that sends, 0..31"},
    {"--to", "D", "", "the SBA the transmission is directed to, 0..31"},
    {"--broadcast", nullptr, "", "a broadcast transmission (instead of --to)"},
    {"--words", nullptr, "", "print 11-bit words \"w:XXX\" instead of characters"},
};

const option_list decode_options = {
    {"TOKEN", nullptr, "", "a data character \"XX\", a control character \"c:XX\", an 11-bit word \"w:XXX\""},
    {"--raw", nullptr, "", "2-byte words from standard input, the 11-bit word big-endian"},
    {"--pcap", "FILE", "@file", "read the Genius records of a pcapng capture"},
    {"--json", nullptr, "", "with --pcap: each record as the fields Wireshark shows"},
    {"--write-pcap", "FILE", "@file", "also write every character to a capture, one record per transmission"},
    {"--rate", "R", rate_names, "with --write-pcap: the bit rate the records are timed at (default 153.6s)"},
};

const option_list timing_options = {
    {"--rate", "R", rate_names, "the bus's bit rate: 153.6s, 153.6e, 76.8 or 38.4"},
    {"--after", "S", "", "the SBA whose Stop just ended, 0..31"},
    {"--device", "SBA@FEET", "", "a device and its position on the cable, 0..1000000 feet", true},
    {"--skip-us", "U", "", "the skip time in microseconds"},
    {"--prop-us-per-2000ft", "P", "", "the propagation delay per 2000 feet in microseconds"},
    {"--detect-us", "D", "", "the detection time in microseconds"},
    {"--json", nullptr, "", "the results as JSON"},
    {"--check", nullptr, "", "exit status 3 on a collision risk, or a bus longer or with more devices than the rate allows"},
};

const option_list scan_time_options = {
    {"--rate", "R", rate_names, "the bus's bit rate: 153.6s, 153.6e, 76.8 or 38.4"},
    {"--device", "BYTES[,BYTES...]", "", "devices with their bytes of inputs and outputs together", true},
    {"--minimum-ms", "M", "", "the bus controller's minimum scan time in ms (default 3, 0 for none)"},
    {"--json", nullptr, "", "the results as JSON"},
    {"--table", nullptr, "", "GE's printed table beside the formula (no other option)"},
};

std::string hex2(unsigned value) {
  char text[8];
  std::snprintf(text, sizeof text, "%02x", value & 0xffu);
  return text;
}

// Whole hex number of 1..max_digits digits.
bool parse_hex(const std::string& text, std::size_t max_digits, unsigned& out) {
  std::uint32_t value = 0;
  if (!host::parse_hex_number(text, max_digits, value)) return false;
  out = value;
  return true;
}

bool parse_sba(const std::string& text, std::uint8_t& out) {
  long long value = 0;
  if (!parse_integer(text, 0, genius::max_sba, value)) return false;
  out = static_cast<std::uint8_t>(value);
  return true;
}

// The parser `genius decode` uses (the library's capacities, the profile's CRC-6): what `encode` checks its
// output against.
using decode_parser = genius::transmission_parser<256, 16, genius::crc6_runtime>;

genius::crc6_runtime profile_crc() {
  return genius::crc6_runtime(active_profile().genius.crc);
}

const genius::control_layout& profile_control() {
  return active_profile().genius.control;
}

// ---------------------------------------------------------------------------------------------------
// encode

int encode_main(const std::vector<std::string>& words) {
  arguments args;
  std::string error;
  if (!parse_arguments(words, encode_options, args, error))
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
      if (colon == std::string::npos) return fail("block segment '" + host::printable(text) + "' must be block:SBA:HEX");
      segments[i].block = true;
      if (!parse_sba(text.substr(6, colon - 6), segments[i].destination)) {
        return fail("block segment '" + host::printable(text) + "': destination must be an SBA 0..31");
      }
      if (!host::parse_hex_bytes(std::string_view(text).substr(colon + 1), bytes[i]) || bytes[i].empty()) {
        return fail("block segment '" + host::printable(text) + "': data must be one or more hex bytes");
      }
    } else if (!host::parse_hex_bytes(text, bytes[i]) || bytes[i].empty()) {
      return fail("data segment '" + host::printable(text) + "' must be one or more hex bytes (e.g. 1122)");
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
      genius::encode_transmission(span<genius::character>(out.data(), out.size()), t, profile_crc(), profile_control());
  if (!written) return fail("cannot encode this transmission");
  // What is printed must be what `genius decode` accepts: parse it with the same parser.
  decode_parser check(profile_crc(), profile_control());
  genius::parse_status parsed = genius::parse_status::in_progress;
  for (const genius::character& c : out) {
    parsed = check.push(c);
    if (parsed != genius::parse_status::in_progress) break;
  }
  if (parsed != genius::parse_status::ok) {
    return fail(std::string("cannot encode: the decoder would report ") + genius::to_string(parsed) + " (at most " +
                std::to_string(decode_parser::data_capacity) + " data bytes in " +
                std::to_string(decode_parser::segment_capacity) + " segments)");
  }

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
  return write_stdout(line + "\n") ? exit_ok : fail_output();
}

// ---------------------------------------------------------------------------------------------------
// decode

// A token as an 11-bit word: "XX" data, "c:XX" control, "w:XXX" any word (framing errors included).
bool parse_token(std::string_view text, std::uint16_t& word) {
  unsigned value = 0;
  if (text.substr(0, 2) == "w:") {
    // Any 3 hex digits: bits above bit 10 are a framing error, as the same word read with --raw.
    if (!parse_hex(std::string(text.substr(2)), 3, value)) return false;
    word = static_cast<std::uint16_t>(value);
    return true;
  }
  const bool control = text.substr(0, 2) == "c:";
  const std::string_view digits = control ? text.substr(2) : text;
  if (digits.size() != 2 || !parse_hex(std::string(digits), 2, value)) return false;
  word = genius::encode_character(genius::character{static_cast<std::uint8_t>(value), control});
  return true;
}


// Characters in, transmissions and errors out, each line printed with where it is. Optionally every
// character also goes to a capture.
class genius_stream {
 public:
  explicit genius_stream(std::string& out)
      : out_(out),
        parser_(profile_crc(), profile_control()),
        splitter_(host::genius_record_splitter::default_max_characters, profile_control()) {}

  void capture_to(host::pcapng_writer* writer, std::uint32_t interface, double character_ns) {
    writer_ = writer;
    interface_ = interface;
    character_ns_ = character_ns;
  }

  // One word, and where it is ("line 1, character 3"); `token` is the text it came from, for messages.
  void word(std::uint16_t w, const std::string& where, std::string_view token) {
    record(w);
    const genius::character_result decoded = genius::decode_character(w);
    genius::parse_status status;
    std::string detail;
    if (decoded) {
      if (decoded.value.control && genius::read_control(decoded.value.byte, profile_control()).kind == genius::control_kind::start) {
        start_ = where;
      }
      status = parser_.push(decoded.value);
    } else {
      status = parser_.push_framing_error();
      detail = decoded.status == genius::character_status::start_bit_not_0  ? " (start bit not 0)"
               : decoded.status == genius::character_status::stop_bit_not_1 ? " (stop bit not 1)"
                                                                             : " (more than 11 bits)";
    }
    if (status == genius::parse_status::ok) {
      ++transmissions_;
      print_transmission(parser_.received());
    } else if (genius::is_error(status)) {
      out_ += "error at " + where + " (" + host::printable(token) + "): " + genius::to_string(status) + detail + "\n";
    }
  }

  // A token that is no character: the character is lost, as with a framing error. A capture gets the word
  // 0xFFFF in its place (a framing error: bits above bit 10), so that it holds no transmission the decoder
  // rejected.
  void bad_token(const std::string& where, std::string_view token) {
    record(lost_word);
    if (parser_.in_transmission()) {
      (void)parser_.push_framing_error();  // counted by the parser
    } else {
      ++bad_tokens_;
    }
    out_ += "error at " + where + " (" + host::printable(token) + "): not a character (XX, c:XX or w:XXX)\n";
  }

  // Another error of the input (e.g. an odd byte at the end of raw input).
  void input_error(const std::string& text) {
    ++bad_tokens_;
    out_ += "error at " + text + "\n";
  }

  // The end of a unit of input (the whole input, or one capture record): an open transmission is unfinished.
  void end(const std::string& what) {
    if (parser_.in_transmission()) {
      ++unfinished_;
      out_ += "error at end of " + what + ": transmission not finished (its Start at " + start_ + ")\n";
    }
    parser_.reset();
    if (writer_ != nullptr) splitter_.flush(sink{this});
  }

  void summary() {
    const std::uint64_t errors = parser_.errors() + bad_tokens_ + unfinished_;
    const std::uint32_t skipped = parser_.count(genius::parse_status::skipped);
    out_ += std::to_string(transmissions_) + " transmission" + (transmissions_ == 1 ? "" : "s") + ", " +
            std::to_string(errors) + " error" + (errors == 1 ? "" : "s") + ", " + std::to_string(skipped) +
            " character" + (skipped == 1 ? "" : "s") + " skipped\n";
  }

  bool capture_ok() const { return written_ == host::pcapng_write_status::ok; }
  int write_errno() const { return write_errno_; }  // the system's cause of the first failed write (0: none)

 private:
  void print_transmission(const genius::transmission& t) {
    out_ += "transmission from SBA " + std::to_string(t.sender);
    out_ += t.broadcast ? ", broadcast" : ", directed to SBA " + std::to_string(t.destination);
    out_ += " (" + start_ + ")\n";
    for (const genius::segment& s : t.segments) {
      out_ += s.block ? "  block to SBA " + std::to_string(s.destination) + ":" : "  data";
      for (std::uint8_t byte : s.data) out_ += " " + hex2(byte);
      out_ += '\n';
    }
  }

  struct sink {
    genius_stream* self;
    void operator()(byte_view record, std::uint64_t time_ns) const {
      errno = 0;
      const host::pcapng_write_status status = self->writer_->write(self->interface_, time_ns, record);
      if (self->written_ == host::pcapng_write_status::ok) {
        self->written_ = status;
        if (status != host::pcapng_write_status::ok) self->write_errno_ = errno;
      }
    }
  };

  static constexpr std::uint16_t lost_word = 0xFFFF;

  void record(std::uint16_t w) {
    if (writer_ == nullptr) return;
    const auto time_ns = static_cast<std::uint64_t>(static_cast<double>(characters_++) * character_ns_ + 0.5);
    splitter_.push(w, time_ns, sink{this});
  }

  std::string& out_;
  decode_parser parser_;
  std::string start_ = "the start";
  std::uint64_t transmissions_ = 0;
  std::uint64_t bad_tokens_ = 0;
  std::uint64_t unfinished_ = 0;
  host::pcapng_writer* writer_ = nullptr;
  std::uint32_t interface_ = 0;
  double character_ns_ = 0;
  std::uint64_t characters_ = 0;
  int write_errno_ = 0;
  host::genius_record_splitter splitter_;
  host::pcapng_write_status written_ = host::pcapng_write_status::ok;
};

// Tokens of text, read in pieces: words separated by blanks, each kept to at most 41 bytes (no valid token
// is longer, and a longer one is only echoed in part).
class token_reader {
 public:
  explicit token_reader(genius_stream& stream) : stream_(stream) {}

  void push(std::string_view text) {
    for (const char c : text) {
      if (host::is_blank(c)) {
        end_token();
        if (c == '\n') ++line_;
      } else if (token_.size() <= 40) {
        token_ += c;
      } else {
        long_ = true;
      }
    }
  }

  void finish() {
    end_token();
    stream_.end("input");
  }

 private:
  void end_token() {
    if (token_.empty()) return;
    ++number_;
    const std::string where = "line " + std::to_string(line_) + ", character " + std::to_string(number_);
    std::uint16_t w = 0;
    if (!long_ && parse_token(token_, w)) {
      stream_.word(w, where, token_);
    } else {
      stream_.bad_token(where, token_);
    }
    token_.clear();
    long_ = false;
  }

  genius_stream& stream_;
  std::string token_;
  bool long_ = false;
  std::uint64_t line_ = 1;
  std::uint64_t number_ = 0;
};

int decode_capture(const arguments& args) {
  // One parser per record, as the dissector sees it; the summary covers every record.
  std::string pending;
  genius_stream stream(pending);
  const int status = read_capture(
      args.options.at("--pcap"), host::capture_network::genius, args.flag("--json"), 5,
      [&](const host::pcapng_record& record, const capture_position& where, std::string& out) {
        std::string place = "record " + std::to_string(where.record);
        if (!where.interface_name.empty()) place += " (" + host::escaped_text(byte_view(
            reinterpret_cast<const std::uint8_t*>(where.interface_name.data()), where.interface_name.size())) + ")";
        place += " at " + epoch_text(where.time_ns) + ", character ";
        std::size_t n = 0;
        for (std::uint16_t w : host::genius_record_words(record.bytes)) {
          char token[8];
          std::snprintf(token, sizeof token, "w:%03x", static_cast<unsigned>(w & 0xFFFFU));
          stream.word(w, place + std::to_string(++n), token);
        }
        if (record.bytes.size() % 2 != 0) stream.input_error(place + std::to_string(n + 1) + ": an odd byte at the end");
        stream.end("record " + std::to_string(where.record));
        out += pending;
        pending.clear();
      },
      args.flag("--json") ? capture_note{} : [&](std::uint64_t record, std::string_view what, bool error, std::string& out) {
        // In text, as the other errors are, and counted in the summary; a record of another network is
        // not an error of this one.
        const std::string place = "record " + std::to_string(record);
        if (error) {
          stream.input_error(place + ": the capture cannot be read there (" + std::string(what) + ")");
        } else {
          pending += place + ": not a Genius record (" + std::string(what) + "), not decoded\n";
        }
        out += pending;
        pending.clear();
      });
  if (status != exit_ok || args.flag("--json")) return status;
  stream.summary();
  output out;
  out.text() = pending;
  return out.flush() ? exit_ok : fail_output();
}

int decode_main(const std::vector<std::string>& all) {
  arguments args;
  std::string error;
  if (!parse_arguments(all, decode_options, args, error)) return fail(error);
  const bool raw = args.flag("--raw");
  if (args.has("--pcap")) {
    if (raw || !args.positionals.empty() || args.has("--write-pcap") || args.has("--rate")) {
      return fail("--pcap reads a capture: no --raw, --write-pcap, --rate or TOKEN with it");
    }
    return decode_capture(args);
  }
  if (args.flag("--json")) return fail("--json applies to --pcap");
  if (raw && !args.positionals.empty()) return fail("--raw reads standard input: no TOKEN arguments with it");
  if (args.has("--rate") && !args.has("--write-pcap")) return fail("--rate sets the times of --write-pcap");
  genius::rate rate = genius::rate::standard_153k6;
  if (args.has("--rate") && !genius::rate_from_name(args.options.at("--rate"), rate)) {
    return fail("unknown rate '" + host::printable(args.options.at("--rate")) +
                "' (expected 153.6s, 153.6e, 76.8 or 38.4)");
  }

  output out;
  genius_stream stream(out.text());
  std::ofstream capture_file;
  std::unique_ptr<host::pcapng_writer> writer;
  if (args.has("--write-pcap")) {
    const std::string& path = args.options.at("--write-pcap");
    capture_file.open(path, std::ios::binary | std::ios::trunc);
    if (!capture_file) return fail_io("cannot write the capture " + host::printable(path) + ": " + std::strerror(errno));
    writer = std::make_unique<host::pcapng_writer>(capture_file, version_line());
    const host::pcapng_interface_result line =
        writer->add_interface(std::string("genius ") + genius::properties(rate).name, host::capture_network::genius);
    if (!line) return fail_io("cannot write the capture " + host::printable(path));
    stream.capture_to(writer.get(), line.id, genius::character_time_us(rate) * 1000.0);
  }

  token_reader tokens(stream);
  std::uint64_t offset = 0;
  int odd = -1;  // --raw: the first byte of a word whose second has not come yet
  if (!args.positionals.empty()) {
    for (const std::string& token : args.positionals) {
      tokens.push(token);
      tokens.push(" ");
    }
  } else {
    const int status = stream_stdin(out, [&](std::string_view chunk) {
      if (!raw) {
        tokens.push(chunk);
        return;
      }
      for (const char c : chunk) {
        const auto byte = static_cast<std::uint8_t>(c);
        if (odd < 0) {
          odd = byte;
        } else {
          const auto w = static_cast<std::uint16_t>(odd << 8 | byte);
          char token[8];
          std::snprintf(token, sizeof token, "w:%03x", static_cast<unsigned>(w));
          stream.word(w, "offset " + std::to_string(offset), token);
          offset += 2;
          odd = -1;
        }
      }
    });
    if (status != exit_ok) return status;
  }
  if (raw) {
    if (odd >= 0) stream.input_error("offset " + std::to_string(offset) + ": an odd byte at the end of the input");
    stream.end("input");
  } else {
    tokens.finish();
  }
  stream.summary();
  if (writer) {
    errno = 0;
    capture_file.flush();
    const int cause = stream.write_errno() != 0 ? stream.write_errno() : errno;
    if (!stream.capture_ok() || !capture_file) {
      out.flush();
      return fail_io("cannot write the capture " + host::printable(args.options.at("--write-pcap")) + ": " +
                     std::strerror(cause != 0 ? cause : EIO));
    }
  }
  return out.flush() ? exit_ok : fail_output();
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

// The largest position and time the analysis takes: far beyond any real bus, small enough that every
// result is a finite number (JSON has no infinity).
constexpr double max_feet = 1e6;
constexpr double max_us = 1e6;

bool parse_bounded(const std::string& text, double min, double max, double& out) {
  return host::parse_real(text, min, max, out);
}

int timing_main(const std::vector<std::string>& words) {
  arguments args;
  std::string error;
  if (!parse_arguments(words, timing_options, args, error)) return fail(error);
  if (!args.positionals.empty()) return fail("unexpected argument '" + host::printable(args.positionals[0]) + "'");
  if (!args.has("--rate")) return fail("timing needs --rate 153.6s|153.6e|76.8|38.4");
  genius::rate rate{};
  if (!genius::rate_from_name(args.options["--rate"], rate)) {
    return fail("unknown rate '" + host::printable(args.options["--rate"]) + "' (expected 153.6s, 153.6e, 76.8 or 38.4)");
  }
  genius::bus_timing timing = genius::default_timing(rate);
  if (!args.has("--after")) return fail("timing needs --after SBA (the SBA whose Stop just ended)");
  std::uint8_t after = 0;
  if (!parse_sba(args.options["--after"], after)) return fail("--after must be an SBA 0..31");
  if (!args.has("--device")) return fail("timing needs at least one --device SBA@FEET");
  std::vector<genius::device_position> devices;
  for (const std::string& text : values_of(args.options["--device"])) {
    const std::size_t at = text.find('@');
    genius::device_position d;
    double feet = 0;
    if (at == std::string::npos || !parse_sba(text.substr(0, at), d.sba) ||
        !parse_bounded(text.substr(at + 1), 0, max_feet, feet)) {
      return fail("--device '" + host::printable(text) + "' must be SBA@FEET with SBA 0..31 and FEET 0..1000000");
    }
    d.position_ft = feet;
    for (const genius::device_position& other : devices) {
      if (other.sba == d.sba) return fail("SBA " + std::to_string(d.sba) + " is given twice");
    }
    devices.push_back(d);
  }
  const bool explicit_skip = args.has("--skip-us");
  // Below 0.01 us a skip time would print as 0.00: the figures are given to the hundredth of a microsecond.
  if (explicit_skip && !parse_bounded(args.options["--skip-us"], 0.01, max_us, timing.skip_us)) {
    return fail("--skip-us must be a number of microseconds from 0.01 (the resolution of the results) to 1000000");
  }
  if (args.has("--prop-us-per-2000ft") &&
      !parse_bounded(args.options["--prop-us-per-2000ft"], 0, max_us, timing.propagation_us_per_2000ft)) {
    return fail("--prop-us-per-2000ft must be a number of microseconds 0..1000000");
  }
  if (args.has("--detect-us") && !parse_bounded(args.options["--detect-us"], 0, max_us, timing.detection_us)) {
    return fail("--detect-us must be a number of microseconds 0..1000000");
  }

  const genius::turn_analysis analysis =
      genius::analyse_turns(span<const genius::device_position>(devices.data(), devices.size()), timing, after);
  if (analysis.status == genius::layout_status::sender_not_on_bus) {
    return fail("--after " + std::to_string(after) + " is not one of the --device entries");
  }
  if (analysis.status != genius::layout_status::ok) return fail(layout_problem(analysis.status));
  const genius::rate_properties props = genius::properties(rate);
  // --check: a margin below the detection time (a negative one included) is a collision risk.
  // A layout the rate does not allow (longer, or more devices) fails the check too: its margins are a model's.
  const bool problem = analysis.too_small_count != 0 || analysis.longer_than_rate_allows ||
                       analysis.more_devices_than_rate_allows;
  const int verdict = args.flag("--check") && problem ? exit_check : exit_ok;

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
    return write_stdout(out + "\n") ? verdict : fail_output();
  }

  std::string text;
  const genius::device_position* sender = nullptr;
  for (const genius::device_position& d : devices) {
    if (d.sba == after) sender = &d;
  }
  appendf(text, "rate %s (%s): bit time %s us, skip time %s us (%s)\n", props.name, props.description,
              fixed2(timing.bit_time_us).c_str(), fixed2(timing.skip_us).c_str(),
              explicit_skip ? "explicit" : "rule");
  appendf(text, "propagation %s us per 2000 ft, detection time %s us\n",
              format_real(timing.propagation_us_per_2000ft).c_str(), fixed2(timing.detection_us).c_str());
  appendf(text, "after the Stop of SBA %u at %s ft:\n", static_cast<unsigned>(after),
              format_real(sender->position_ft).c_str());
  if (analysis.turn_count == 0) appendf(text, "  no other device\n");
  if (analysis.turn_count != 0) appendf(text, "  SBA  position_ft  turn_start_us\n");
  for (std::size_t i = 0; i < analysis.turn_count; ++i) {
    const genius::turn& t = analysis.turns[i];
    appendf(text, "  %s  %s  %s\n", pad_left(std::to_string(t.sba), 3).c_str(),
                pad_left(format_real(t.position_ft), 11).c_str(), pad_left(fixed2(t.start_us), 13).c_str());
  }
  if (analysis.margin_count != 0)
    appendf(text, "margins (second's turn minus the arrival of first's start bit at second):\n");
  if (analysis.margin_count != 0) appendf(text, "  first  second  margin_us\n");
  for (std::size_t i = 0; i < analysis.margin_count; ++i) {
    const genius::turn_margin& m = analysis.margins[i];
    appendf(text, "  %s  %s  %s  %s\n", pad_left(std::to_string(m.first), 5).c_str(),
                pad_left(std::to_string(m.second), 6).c_str(), pad_left(fixed2(m.margin_us), 9).c_str(),
                m.margin_us < 0 ? "COLLISION (negative margin)"
                : m.too_small   ? "TOO SMALL"
                                : "ok");
  }
  if (analysis.too_small_count != 0) {
    appendf(text, "%zu margin%s below the detection time: collision risk\n", analysis.too_small_count,
                analysis.too_small_count == 1 ? "" : "s");
  }
  if (analysis.longer_than_rate_allows) {
    appendf(text, "warning: the bus is %s ft long; %s allows %u ft\n",
                format_real(analysis.bus_length_ft).c_str(), props.name,
                static_cast<unsigned>(props.max_length_ft));
  }
  if (analysis.more_devices_than_rate_allows) {
    appendf(text, "warning: %zu devices; %s allows %u\n", devices.size(), props.name,
                static_cast<unsigned>(props.max_devices));
  }
  return write_stdout(text) ? verdict : fail_output();
}

// ---------------------------------------------------------------------------------------------------
// scan-time: GE's published scan-time figures (docs/protocol.md 3.3), per device and for the bus.

// Milliseconds as exact decimal text from nanoseconds ("0.943", "0.0715", "4.831"), no floating point.
std::string exact_ms(std::uint64_t ns) {
  std::string text = std::to_string(ns / 1000000u);
  std::string fraction = std::to_string(ns % 1000000u);
  fraction.insert(0, 6 - fraction.size(), '0');
  while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
  return fraction.empty() ? text : text + "." + fraction;
}

// GE's printed table beside the formula (docs/genius.md, "Scan time").
int scan_time_table() {
  constexpr genius::rate rates[] = {genius::rate::standard_153k6, genius::rate::extended_153k6,
                                    genius::rate::baud_76k8, genius::rate::baud_38k4};
  std::printf("GE's printed scan-time table (GFK-0825F) beside GE's formula, one device, ms\n");
  std::string header = "  bytes";
  for (const genius::rate r : rates) {
    const std::string name = genius::properties(r).name;
    header += "  " + name + std::string(15 - name.size(), ' ');
  }
  while (header.back() == ' ') header.pop_back();
  std::printf("%s\n", header.c_str());
  unsigned differ = 0;
  std::uint64_t worst_us = 0;
  for (std::size_t row = 0; row < 5; ++row) {
    const std::uint32_t bytes = genius::published_table_bytes[row];
    std::string line = pad_left(std::to_string(bytes), 7);
    for (std::size_t col = 0; col < 4; ++col) {
      const unsigned printed = genius::published_table_centi_ms[row][col];
      const std::uint64_t formula_ns = genius::device_scan_time_ns(rates[col], bytes);
      const bool same = genius::formula_centi_ms(rates[col], bytes) == printed;
      char cell[48];
      std::snprintf(cell, sizeof cell, "%u.%02u", printed / 100, printed % 100);
      line += "  " + pad_left(cell, 5) + " " + pad_left(exact_ms(formula_ns), 7) + (same ? "  " : " *");
      if (!same) {
        ++differ;
        const std::uint64_t printed_ns = std::uint64_t{printed} * 10000u;
        const std::uint64_t gap_ns = printed_ns > formula_ns ? printed_ns - formula_ns : formula_ns - printed_ns;
        if (gap_ns / 1000u > worst_us) worst_us = gap_ns / 1000u;
      }
    }
    while (line.back() == ' ') line.pop_back();
    std::printf("%s\n", line.c_str());
  }
  std::printf("* the printed cell is not the formula rounded to 0.01 ms: %u cells, by up to %s ms\n", differ,
              exact_ms(worst_us * 1000u).c_str());
  return exit_ok;
}

int scan_time_main(const std::vector<std::string>& words) {
  arguments args;
  std::string error;
  if (!parse_arguments(words, scan_time_options, args, error)) return fail(error);
  if (!args.positionals.empty()) return fail("unexpected argument '" + host::printable(args.positionals[0]) + "'");
  if (args.flag("--table")) {
    if (args.has("--rate") || args.has("--device") || args.has("--minimum-ms") || args.flag("--json"))
      return fail("--table takes no other option");
    return scan_time_table();
  }
  if (!args.has("--rate")) return fail("scan-time needs --rate 153.6s|153.6e|76.8|38.4");
  genius::rate rate{};
  if (!genius::rate_from_name(args.options["--rate"], rate)) {
    return fail("unknown rate '" + host::printable(args.options["--rate"]) + "' (expected 153.6s, 153.6e, 76.8 or 38.4)");
  }
  if (!args.has("--device")) return fail("scan-time needs at least one --device BYTES");
  std::vector<std::uint32_t> bytes;
  for (const std::string& list : values_of(args.options["--device"])) {
    std::size_t from = 0;
    while (true) {
      const std::size_t comma = list.find(',', from);
      const std::string item = list.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
      long long value = 0;
      if (!parse_integer(item, 0, 4294967295LL, value)) {
        return fail("--device '" + host::printable(list) + "': each BYTES must be a whole number 0..4294967295");
      }
      bytes.push_back(static_cast<std::uint32_t>(value));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
  }
  std::uint64_t minimum_ns = genius::default_minimum_scan_ns;
  if (args.has("--minimum-ms")) {
    // Up to three decimals (whole microseconds), so that the figure stays exact.
    double ms = 0;
    if (!host::parse_real(args.options["--minimum-ms"], 0, 1000, ms) ||
        std::fabs(ms * 1000 - std::round(ms * 1000)) > 1e-6) {
      return fail("--minimum-ms must be 0..1000 with at most three decimals (0: no minimum)");
    }
    minimum_ns = static_cast<std::uint64_t>(std::llround(ms * 1000)) * 1000u;
  }
  const genius::rate_properties props = genius::properties(rate);
  const genius::scan_time_result bus =
      genius::bus_scan_time(rate, span<const std::uint32_t>(bytes.data(), bytes.size()), minimum_ns);
  if (bus.status == genius::scan_time_status::too_many_devices) {
    return fail(std::to_string(bytes.size()) + " devices; " + props.name + " allows " +
                std::to_string(props.max_devices));
  }
  if (!bus) return fail(genius::to_string(bus.status));

  const genius::scan_time_terms terms = genius::published_scan_time_terms(rate);
  // The computed character time, rounded to the nanosecond: a separate figure, not used in the sums.
  const auto character_ns = static_cast<std::uint64_t>(std::llround(genius::character_time_us(rate) * 1000.0));

  if (args.flags.count("--json") != 0) {
    std::string out = "{\"rate\":" + json_string(props.name) + ",\"fixed_ms\":" + exact_ms(terms.fixed_ns) +
                      ",\"per_byte_ms\":" + exact_ms(terms.per_byte_ns) + ",\"devices\":[";
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      if (i != 0) out += ',';
      out += "{\"io_bytes\":" + std::to_string(bytes[i]) +
             ",\"scan_time_ms\":" + exact_ms(genius::device_scan_time_ns(rate, bytes[i])) + "}";
    }
    out += "],\"io_bytes\":" + std::to_string(bus.io_bytes) + ",\"sum_ms\":" + exact_ms(bus.sum_ns) +
           ",\"minimum_ms\":" + exact_ms(minimum_ns) + ",\"scan_ms\":" + exact_ms(bus.scan_ns) +
           ",\"minimum_applies\":" + (bus.minimum_applies ? "true" : "false") +
           ",\"character_time_ms\":" + exact_ms(character_ns) + "}";
    std::printf("%s\n", out.c_str());
    return exit_ok;
  }
  std::printf("rate %s (%s): %s ms per device + %s ms per byte of inputs and outputs (GE GFK-0825F)\n",
              props.name, props.description, exact_ms(terms.fixed_ns).c_str(), exact_ms(terms.per_byte_ns).c_str());
  std::printf("  device  io_bytes  scan_time_ms\n");
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::printf("  %6zu  %8u  %12s\n", i + 1, static_cast<unsigned>(bytes[i]),
                exact_ms(genius::device_scan_time_ns(rate, bytes[i])).c_str());
  }
  std::printf("bus: %zu device%s, %llu byte%s: sum %s ms, scan time %s ms", bus.devices, bus.devices == 1 ? "" : "s",
              static_cast<unsigned long long>(bus.io_bytes), bus.io_bytes == 1 ? "" : "s",
              exact_ms(bus.sum_ns).c_str(), exact_ms(bus.scan_ns).c_str());
  if (bus.minimum_applies) {
    std::printf(" (the bus controller's minimum of %s ms applies)\n", exact_ms(minimum_ns).c_str());
  } else if (minimum_ns != 0) {
    std::printf(" (%s the minimum of %s ms)\n", bus.sum_ns == minimum_ns ? "equal to" : "above",
                exact_ms(minimum_ns).c_str());
  } else {
    std::printf(" (no minimum)\n");
  }
  std::printf("computed character time (11 bits at %u bit/s): %s ms, not used above\n",
              static_cast<unsigned>(props.baud), exact_ms(character_ns).c_str());
  return exit_ok;
}

const command genius_commands[] = {
    {"encode", "encode a transmission as characters", encode_usage, encode_main, encode_options},
    {"decode", "read characters, raw words or a capture; print transmissions and errors", decode_usage,
     decode_main, decode_options},
    {"timing", "turn start times and margins after a Stop (bus access)", timing_usage, timing_main, timing_options},
    {"scan-time", "the bus scan time by GE's published figures, per device and in total", scan_time_usage,
     scan_time_main, scan_time_options},
    {"simulate", "a bus of device nodes taking their turns: collisions, deliveries, scan time", genius_simulate_usage,
     genius_simulate_main, genius_simulate_option_list()},
    {"plan", "SBAs without collision risk for devices along a bus (or a check of SBAs given)", genius_plan_usage,
     genius_plan_main, genius_plan_option_list()},
    {"learn", "crc: find the CRC-6 from captured transmissions, write it into a profile", genius_learn_usage,
     genius_learn_main, genius_learn_options()},
};

}  // namespace

bool parse_genius_token(std::string_view text, std::uint16_t& word) {
  return parse_token(text, word);
}

const part genius_part = {"genius", "GE Genius bus (encode, decode, timing, scan-time, simulate, plan, learn)", genius_commands,
                          sizeof genius_commands / sizeof genius_commands[0], ""};

}  // namespace trionet::cli
