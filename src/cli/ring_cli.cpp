// `trionet ring ...`: encode and decode fibre-ring frames from the shell; the command table of the part.
#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

#include "capture_cli.hpp"
#include "cli.hpp"
#include "learn_cli.hpp"
#include "profile_cli.hpp"
#include "ring_cli.hpp"
#include "ring_live.hpp"
#include "ring_message_arguments.hpp"
#include "ring_wire_cli.hpp"
#include "trionet/host/ring_events.hpp"
#include "trionet/ring.hpp"

namespace trionet::cli {
namespace {

constexpr const char* encode_usage =
    "usage: trionet ring encode print  --to N TEXT\n"
    "       trionet ring encode var    --to N --vr V --value X\n"
    "       trionet ring encode offset --to N --offset M\n"
    "       trionet ring encode mode   --to N --mode 0|127\n"
    "Prints the frame as hex bytes. N and M are BASIC addresses 10..24 (hops + 9); TEXT is 1..256 characters\n"
    "of 7 bits (what a decoder accepts); V is 0..16383; X is a real number in the Q32.32 range.\n";

constexpr const char* decode_usage =
    "usage: trionet ring decode [HEX...]               hex bytes from the arguments, else from standard input\n"
    "       trionet ring decode --raw                  raw bytes from standard input (a serial port, a file)\n"
    "       trionet ring decode --pcap FILE [--json]   the ring records of a pcapng capture\n"
    "Prints one JSON object per event as soon as it is complete:\n"
    "  {\"event\":\"message\",...}, {\"event\":\"crc_error\",...}, {\"event\":\"frame_error\",\"reason\":R,...},\n"
    "  {\"event\":\"unfinished\",...} (a message still open at the end of the input),\n"
    "  {\"event\":\"error\",\"reason\":\"not_hex\"|\"odd_digits\",...} (hex text that is not a byte; the rest of\n"
    "  that word is skipped and decoding goes on).\n"
    "Every event says where it is: \"line\" for hex text, \"offset\" (of the message's first byte) for --raw,\n"
    "\"record\", \"interface\" and \"time\" for --pcap. Hex text: pairs of hex digits, words separated by blanks.\n"
    "With --pcap, --json prints each record as the fields Wireshark's dissector shows (docs/wireshark.md).\n"
    "Exit status 0 when the input was read, 1 when reading or writing failed, 2 for bad arguments.\n";

const option_list encode_options = joined(
    {
        {"KIND", nullptr, "print var offset mode", "the message: print (characters), var (a VR), offset, mode"},
        {"TEXT", nullptr, "", "print: the characters, 1..256 of 7 bits"},
    },
    ring_message_options());

const option_list decode_options = {
    {"HEX", nullptr, "", "hex bytes (else standard input is read)"},
    {"--raw", nullptr, "", "read raw bytes from standard input (a serial port, a file)"},
    {"--pcap", "FILE", "@file", "read the ring records of a pcapng capture"},
    {"--json", nullptr, "", "with --pcap: each record as the fields Wireshark's dissector shows"},
};

int encode_main(const words& all) {
  if (all.empty()) return fail("ring encode needs a message kind: print, var, offset or mode");
  const int capacities = check_ring_capacities("ring encode", ring_capacity_use::text_limit);
  if (capacities != exit_ok) return capacities;
  const words rest(all.begin() + 1, all.end());
  arguments args;
  std::string error;
  if (!parse_arguments(rest, encode_options, args, error)) return fail(error);
  std::vector<std::uint8_t> frame;
  if (!ring_message_frame(all[0], args, frame, error)) return fail(error);
  return write_stdout(hex_line(frame.data(), frame.size()) + "\n") ? exit_ok : fail_output();
}

// ---------------------------------------------------------------------------------------------------------
// decode

// How an event says where it is.
enum class where_kind : std::uint8_t { line, position };

// A decoder over a stream of bytes that knows where each byte came from, printing events to `out`.
class ring_stream {
 public:
  ring_stream(std::string& out, where_kind kind) : out_(out), kind_(kind) {}

  void push(std::uint8_t byte, std::uint64_t at) { stream_.push(byte, at, printer{this}); }
  void push(const std::uint8_t* first, const std::uint8_t* last, std::uint64_t at) {
    stream_.push(first, last, at, printer{this});
  }

  // The end of the input: a message still open is reported.
  void finish() {
    std::uint64_t at = 0;
    if (!stream_.unfinished(at)) return;
    event e(out_, "unfinished");
    e.number(key(), at);
  }

 private:
  const char* key() const { return kind_ == where_kind::line ? "line" : "position"; }
  struct printer {
    ring_stream* self;
    void operator()(const ring::decode_result& r, std::uint64_t at) const {
      append_ring_event(self->out_, r, [&](event& e) { e.number(self->key(), at); });
    }
  };

  std::string& out_;
  where_kind kind_;
  host::ring_event_stream<profile_decoder> stream_;
};

// Hex text, read in pieces: pairs of hex digits in words separated by blanks. A character that is not hex is
// an error event and the rest of its word is skipped; a word with an odd number of digits loses its last
// digit (an error event too).
class hex_reader {
 public:
  hex_reader(std::string& out, ring_stream& bytes) : out_(out), bytes_(bytes) {}

  void push(std::string_view text) {
    for (const char c : text) {
      const int digit = hex_digit(c);
      if (digit >= 0) {
        if (skipping_) continue;
        if (high_ < 0) {
          high_ = digit;
        } else {
          bytes_.push(static_cast<std::uint8_t>(high_ << 4 | digit), line_);
          high_ = -1;
        }
      } else if (host::is_blank(c)) {
        end_word();
        if (c == '\n') ++line_;
      } else if (!skipping_) {
        event(out_, "error").number("line", line_).text("reason", "not_hex").text("character", std::string_view(&c, 1));
        skipping_ = true;
        high_ = -1;
      }
    }
  }

  void finish() {
    end_word();
    bytes_.finish();
  }

 private:
  void end_word() {
    if (high_ >= 0) event(out_, "error").number("line", line_).text("reason", "odd_digits");
    high_ = -1;
    skipping_ = false;
  }

  std::string& out_;
  ring_stream& bytes_;
  int high_ = -1;
  bool skipping_ = false;
  std::uint64_t line_ = 1;
};

int decode_capture(const arguments& args) {
  return read_capture(args.options.at("--pcap"), host::capture_network::ring, args.flag("--json"), 5,
                      [](const host::pcapng_record& record, const capture_position& where, std::string& out) {
                        // Each record on its own, through a fresh decoder, as the dissector sees it.
                        profile_decoder decoder;
                        const auto here = [&where](event& e) { add_position(e, where); };
                        bool any = false;
                        for (std::uint8_t byte : record.bytes) {
                          const ring::decode_result r = decoder.push(byte);
                          if (r.status == ring::decode_status::incomplete) continue;
                          append_ring_event(out, r, here);
                          any = true;
                        }
                        if (decoder.in_message() || !any) {
                          event e(out, "unfinished");
                          add_position(e, where);
                        }
                      });
}

int decode_main(const words& all) {
  arguments args;
  std::string error;
  if (!parse_arguments(all, decode_options, args, error)) return fail(error);
  const int capacities = check_ring_capacities("ring decode", ring_capacity_use::decoder);
  if (capacities != exit_ok) return capacities;
  const bool raw = args.flag("--raw");
  if (args.has("--pcap")) {
    if (raw || !args.positionals.empty()) return fail("--pcap reads a capture file: no --raw and no HEX with it");
    return decode_capture(args);
  }
  if (args.flag("--json")) return fail("--json applies to --pcap (the output is JSON already)");
  output out;
  if (raw) {
    if (!args.positionals.empty()) return fail("--raw reads standard input: no HEX arguments with it");
    ring_stream bytes(out.text(), where_kind::position);
    std::uint64_t offset = 0;
    const int status = stream_stdin(out, [&](std::string_view chunk) {
      const auto* first = reinterpret_cast<const std::uint8_t*>(chunk.data());
      bytes.push(first, first + chunk.size(), offset);
      offset += chunk.size();
    });
    if (status != exit_ok) return status;
    bytes.finish();
    return out.flush() ? exit_ok : fail_output();
  }
  ring_stream bytes(out.text(), where_kind::line);
  hex_reader hex(out.text(), bytes);
  if (!args.positionals.empty()) {
    for (const std::string& word : args.positionals) {
      hex.push(word);
      hex.push(" ");
    }
  } else {
    const int status = stream_stdin(out, [&](std::string_view chunk) { hex.push(chunk); });
    if (status != exit_ok) return status;
  }
  hex.finish();
  return out.flush() ? exit_ok : fail_output();
}

const command ring_commands[] = {
    {"encode", "print, var, offset or mode: print one frame as hex bytes", encode_usage, encode_main, encode_options},
    {"decode", "read hex, raw bytes or a capture; print one JSON event per message or error", decode_usage,
     decode_main, decode_options},
    {"simulate", "a ring of Motion Coordinators running BASIC programs and keypads", simulate_usage,
     ring_simulate_main, ring_simulate_options()},
    {"monitor", "watch a live ring port: one event per message as it arrives", ring_live_usage, ring_monitor_main,
     ring_monitor_options()},
    {"send", "put one message on a live ring port", ring_live_usage, ring_send_main, ring_send_options()},
    {"join", "be a node on a live ring: a Motion Coordinator (--as mc) or a keypad (--as keypad)", ring_live_usage,
     ring_join_main, ring_join_options()},
    {"wire", "connect byte endpoints (ports, sockets, ptys) into one ring, with faults on its links", ring_wire_usage, ring_wire_main,
     ring_wire_options()},
    {"learn", "crc or layout: find the wire parameters from captured frames, write them into a profile",
     ring_learn_usage, ring_learn_main, ring_learn_options()},
};

}  // namespace

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

void append_ring_event_body(event& e, const ring::decode_result& result) { host::ring_event_fields(e, result); }

const char* ring_event_kind(const ring::decode_result& result) { return host::ring_event_kind(result); }

const part ring_part = {"ring", "Trio Motion Coordinator fibre-optic ring (encode, decode, simulate, monitor, send, join, learn)",
                        ring_commands, sizeof ring_commands / sizeof ring_commands[0], ""};

}  // namespace trionet::cli
