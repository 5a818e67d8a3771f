// `trionet ring learn crc|layout`, `trionet genius learn crc`: thin wrappers around the learning library
// (src/learn/, docs/profile.md). Each reads a capture, prints what it found as JSON events and, when it found
// exactly one answer, writes the profile in effect with that answer into `-o FILE`.
#include "learn_cli.hpp"

#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "capture_cli.hpp"
#include "learn/genius_crc_learn.hpp"
#include "learn/ring_capture.hpp"
#include "learn/ring_crc_learn.hpp"
#include "learn/ring_layout_learn.hpp"
#include "profile_cli.hpp"
#include "ring_cli.hpp"
#include "trionet/genius/character.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/files.hpp"
#include "trionet/host/progress.hpp"
#include "trionet/q32.hpp"

namespace trionet::cli {

const char* const ring_learn_usage =
    "usage: trionet ring learn crc    [FILE | --raw [FILE] | --pcap CAPTURE] [--even] [-o PROFILE]\n"
    "       trionet ring learn layout [FILE | --raw [FILE] | --pcap CAPTURE] --sent LIST [-o PROFILE]\n"
    "Finds the unpublished parameters of direct variable transfers (docs/profile.md) in captured frames: "
    "hex\n"
    "text as `ring decode` reads it (FILE, else standard input), raw ring bytes (--raw), or the ring records "
    "of\n"
    "a pcapng capture (--pcap). Every well-framed direct variable transfer is used; other bytes are "
    "skipped.\n"
    "crc: every 16-bit CRC (polynomial, initial value, reflections, final XOR) that gives the 14 "
    "transmitted\n"
    "  bits of every frame, one event per class of CRCs that agree on every frame (three frames usually\n"
    "  suffice; --even also tries polynomials without the x^0 term). The CRC covers the bytes as the "
    "profile's\n"
    "  layout says.\n"
    "layout: the group order of the VR number and of the value, and the bytes the CRC covers, from the "
    "frames\n"
    "  and LIST, the VR numbers and values the program sent, in order: one \"VR VALUE\" a line, # comments.\n"
    "  With --profile its CRC is used; else the CRC is learned both ways.\n"
    "With -o, the profile in effect (--profile, else the default) with what was found is written to "
    "PROFILE.\n"
    "Exit status 0 when exactly one answer was found, 3 when none or several fit (all are listed), 1 when\n"
    "reading or writing failed, 2 for bad arguments or input text that is not hex.\n";

const char* const genius_learn_usage =
    "usage: trionet genius learn crc [FILE | --raw [FILE] | --pcap CAPTURE] [--even] [-o PROFILE]\n"
    "Finds the CRC-6 (polynomial, initial value, reflections, final XOR) of captured Genius transmissions:\n"
    "tokens as `genius decode` reads them (FILE, else standard input), 2-byte words (--raw), or the Genius\n"
    "records of a pcapng capture (--pcap). Each Stop with the data since its Start, and each End of block "
    "with\n"
    "the data since its Start of block, is one sample; four samples of different lengths usually suffice.\n"
    "One event per class of CRCs that agree on every message of 1..257 bytes, then a result event.\n"
    "With -o, the profile in effect (--profile, else the default) with the CRC found is written to PROFILE.\n"
    "Exit status 0 when exactly one class fits, 3 when none or several fit, 1 when reading or writing\n"
    "failed, 2 for bad arguments or input that is not tokens.\n";

namespace {

// The options every kind of learning shares, after the kind and the input.
option_list learn_options(const char* kinds) {
  return {
      {"KIND", nullptr, kinds, "what to learn"},
      {"FILE", nullptr, "@file", "the input (else standard input)"},
      {"--raw", nullptr, "", "raw bytes, not text"},
      {"--pcap", "CAPTURE", "@file", "the records of a pcapng capture"},
      {"--even", nullptr, "", "also try polynomials without the x^0 term"},
      {"-o", "PROFILE", "@file", "write the profile in effect, with what was found, to PROFILE"},
  };
}

}  // namespace

const option_list& ring_learn_options() {
  static const option_list options = joined(
      learn_options("crc layout"),
      {{"--sent", "LIST", "@file", "layout: the VR numbers and values the program sent, one \"VR VALUE\" a line"}});
  return options;
}

const option_list& genius_learn_options() {
  static const option_list options = learn_options("crc");
  return options;
}

namespace {

// Learning needs a few frames: more input than this is refused rather than held in memory.
constexpr std::size_t max_input = std::size_t{64} << 20U;

int too_much_input() {
  return fail_io("the capture holds more than 64 MiB of frames: a few frames suffice for learning (docs/profile.md)");
}

// The whole of FILE, or of standard input when there is none (or it is "-"), at most 64 MiB; `what` names
// the command on the progress line.
int read_input(const std::vector<std::string>& positionals, std::string& text, const char* what) {
  if (positionals.size() > 1) return fail("unexpected argument '" + host::printable(positionals[1]) + "'");
  const bool from_file = !positionals.empty() && positionals[0] != "-";
  host::progress shown(what, "bytes read", 0);
  const host::file_result read = from_file ? host::read_bounded_file(positionals[0], max_input, text, &shown)
                                           : host::read_bounded_fd(STDIN_FILENO, max_input, text, &shown);
  if (read) return exit_ok;
  std::string message = read.message(from_file ? positionals[0] : "standard input");
  if (read.status == host::file_status::too_large) message += " (64 MiB): a few frames suffice for learning";
  return fail_io(message);
}

// The bytes of every record of `network` in a capture (events for records of other networks are printed).
int read_capture_bytes(const std::string& path, host::capture_network network, const char* what,
                       std::vector<std::uint8_t>& out, std::vector<std::uint16_t>* genius_words = nullptr) {
  bool too_much = false;
  host::progress shown(what, "bytes of records read", 0);
  const int status = read_capture(
      path, network, false, active_profile().can.node_count,
      [&](const host::pcapng_record& record, const capture_position&, std::string&) {
        shown.update(static_cast<double>(out.size() + (genius_words != nullptr ? 2 * genius_words->size() : 0)));
        too_much =
            too_much || out.size() + record.bytes.size() > max_input ||
            (genius_words != nullptr && genius_words->size() + record.bytes.size() / 2 > max_input / 2);
        if (too_much) return;
        if (genius_words == nullptr) {
          out.insert(out.end(), record.bytes.begin(), record.bytes.end());
          return;
        }
        for (std::uint16_t w : host::genius_record_words(record.bytes)) genius_words->push_back(w);
      });
  if (status != exit_ok) return status;
  return too_much ? too_much_input() : exit_ok;
}

// Each word of `text` (separated by blanks) through `take(word)`; the first it refuses is a usage error
// that names its line and says `expected`.
template <class Take>
int each_word(const std::string& text, const char* expected, Take&& take) {
  std::size_t line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    if (host::is_blank(text[i])) {
      if (text[i++] == '\n') ++line;
      continue;
    }
    std::size_t end = i;
    while (end < text.size() && !host::is_blank(text[end])) ++end;
    const std::string_view word(text.data() + i, end - i);
    if (!take(word)) {
      return fail("line " + std::to_string(line) + ": '" + host::printable(std::string(word)) + "' is not " +
                  expected);
    }
    i = end;
  }
  return exit_ok;
}

// The ring bytes the arguments point at; `what` names the command on the progress line.
int ring_input(const arguments& args, std::vector<std::uint8_t>& bytes, const char* what) {
  if (args.has("--pcap")) {
    if (args.flag("--raw") || !args.positionals.empty()) {
      return fail("--pcap reads a capture file: no --raw and no FILE with it");
    }
    return read_capture_bytes(args.options.at("--pcap"), host::capture_network::ring, what, bytes);
  }
  std::string text;
  const int status = read_input(args.positionals, text, what);
  if (status != exit_ok) return status;
  if (args.flag("--raw")) {
    bytes.assign(text.begin(), text.end());
    return exit_ok;
  }
  return each_word(text, "hex bytes (pairs of hex digits)",
                   [&bytes](std::string_view word) { return host::parse_hex_bytes(word, bytes); });
}

std::string hex_number(std::uint32_t value, int digits) {
  char text[12];
  std::snprintf(text, sizeof text, "0x%0*" PRIx32, digits, value);
  return text;
}

std::string frame_hex(const learn::variable_frame& frame) {
  return hex_line(frame.data(), frame.size());
}

// One "crc" event per class of a CRC search (ring or Genius): its representative, hex with `digits` digits.
template <class Classes>
void crc_events(std::string& out, const Classes& classes, int digits) {
  std::size_t number = 0;
  for (const auto& c : classes) {
    const auto& m = c.members.front();
    event e(out, "crc");
    e.number("class", ++number).text("polynomial", hex_number(m.parameters.polynomial, digits));
    e.text("initial", hex_number(m.parameters.initial, digits))
        .boolean("reflect_in", m.parameters.reflect_in);
    e.boolean("reflect_out", m.parameters.reflect_out)
        .text("xor_out", hex_number(m.parameters.xor_out, digits));
    e.text("name", m.name).number("members", c.members.size());
  }
}

// Writes the profile with what was learned when asked to (-o) and it was learned; the exit status.
int finish(bool learned, const arguments& args, const learn::profile& p, output& out) {
  if (!out.flush()) return fail_output();
  if (!learned) return exit_check;
  if (!args.has("-o")) return exit_ok;
  return write_profile_file(p, args.options.at("-o"));
}

int ring_learn_crc(const arguments& args) {
  if (args.has("--sent")) return fail("--sent applies to ring learn layout");
  std::vector<std::uint8_t> bytes;
  const int status = ring_input(args, bytes, "ring learn crc");
  if (status != exit_ok) return status;
  const learn::frame_extraction found = learn::variable_transfers(byte_view(bytes.data(), bytes.size()));
  learn::crc_learn_options options;
  options.layout = active_profile().ring.layout;
  options.even_polynomials = args.flag("--even");
  host::progress shown("ring learn crc", "polynomials tried", 0x20000);
  options.progress = [&shown](double done, double) { shown.update(done); };
  const learn::crc_learn_result r = learn::learn_ring_crc(found.frames, options);
  shown.finish();
  output out;
  crc_events(out.text(), r.classes, 4);
  {
    event e(out.text(), "result");
    e.text("status", learn::to_string(r.status)).number("frames", found.frames.size());
    e.number("skipped_bytes", found.skipped_bytes).number("classes", r.classes.size());
    e.number("survivors", r.survivors);
  }
  learn::profile learned = active_profile();
  if (r) learned.ring.crc = r.classes.front().members.front().parameters;
  return finish(static_cast<bool>(r), args, learned, out);
}

int ring_learn_layout(const arguments& args) {
  if (!args.has("--sent"))
    return fail("ring learn layout needs --sent LIST (the VR numbers and values sent)");
  if (args.flag("--even")) return fail("--even applies to ring learn crc");
  std::string list;
  const int read = read_input({args.options.at("--sent")}, list, "ring learn layout");
  if (read != exit_ok) return read;
  const learn::sent_list_result sent = learn::parse_sent_list(list);
  if (!sent) {
    return fail("--sent " + host::printable(args.options.at("--sent")) + " line " + std::to_string(sent.line) +
                ": " + learn::to_string(sent.status) + " (expected \"VR VALUE\", VR 0..16383)");
  }
  std::vector<std::uint8_t> bytes;
  const int status = ring_input(args, bytes, "ring learn layout");
  if (status != exit_ok) return status;
  const learn::frame_extraction found = learn::variable_transfers(byte_view(bytes.data(), bytes.size()));
  learn::layout_learn_options options;
  if (profile_given()) options.crc = &active_profile().ring.crc;
  const learn::layout_learn_result r = learn::learn_layout(found.frames, sent.sent, options);
  output out;
  for (const learn::order_fit& fit : r.orders) {
    event e(out.text(), "order");
    e.text("vr_group_order", ring::to_string(fit.vr)).text("value_group_order", ring::to_string(fit.value));
    e.boolean("fits", fit.fits);
    const std::size_t i = fit.first_contradiction;
    if (fit.fits || i >= found.frames.size() || i >= sent.sent.size()) continue;
    // The first frame that reads otherwise: what it reads as in this order, and what was sent.
    std::uint16_t vr = 0;
    std::int64_t value = 0;
    ring::read_variable_fields(found.frames[i].data(), vr, value, fit.vr, fit.value);
    e.number("first_contradiction", i + 1).text("frame", frame_hex(found.frames[i]));
    e.number("reads_vr", vr).real("reads_value", trionet::q32_to_double(value));
    e.number("sent_vr", sent.sent[i].vr).real("sent_value", trionet::q32_to_double(sent.sent[i].value));
  }
  {
    event e(out.text(), "result");
    e.text("status", learn::to_string(r.status)).number("frames", found.frames.size());
    e.number("sent", sent.sent.size()).number("skipped_bytes", found.skipped_bytes);
    if (r) {
      e.text("vr_group_order", ring::to_string(r.layout.vr))
          .text("value_group_order", ring::to_string(r.layout.value));
      e.text("crc_input", ring::to_string(r.layout.crc));
    }
    e.text("crc_finding", learn::to_string(r.crc));
  }
  learn::profile learned = active_profile();
  if (r) learned.ring.layout = r.layout;
  return finish(static_cast<bool>(r), args, learned, out);
}

// The Genius characters the arguments point at; a word with a framing error breaks the sample it is in.
int genius_input(const arguments& args, std::vector<genius::character>& characters) {
  std::vector<std::uint16_t> words;
  if (args.has("--pcap")) {
    if (args.flag("--raw") || !args.positionals.empty()) {
      return fail("--pcap reads a capture file: no --raw and no FILE with it");
    }
    std::vector<std::uint8_t> unused;
    const int status =
        read_capture_bytes(args.options.at("--pcap"), host::capture_network::genius, "genius learn crc", unused, &words);
    if (status != exit_ok) return status;
  } else {
    std::string text;
    const int status = read_input(args.positionals, text, "genius learn crc");
    if (status != exit_ok) return status;
    if (args.flag("--raw")) {
      if (text.size() % 2 != 0) return fail("--raw input has an odd number of bytes (2 bytes per character)");
      words = host::genius_record_words(
          byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    } else {
      const int parsed = each_word(text, "a character (XX, c:XX or w:XXX)", [&words](std::string_view token) {
        std::uint16_t w = 0;
        if (!parse_genius_token(token, w)) return false;
        words.push_back(w);
        return true;
      });
      if (parsed != exit_ok) return parsed;
    }
  }
  characters.reserve(words.size());
  for (std::uint16_t w : words) {
    const genius::character_result c = genius::decode_character(w);
    // A damaged character ends the sample it is in: it stands in as a control character the profile's
    // control layout leaves unused (genius::control_kind::unknown abandons the open transmission).
    characters.push_back(c ? c.value : genius::unknown_control_character(active_profile().genius.control));
  }
  return exit_ok;
}

int genius_learn_crc(const arguments& args) {
  if (args.has("--sent")) return fail("--sent applies to ring learn layout");
  std::vector<genius::character> characters;
  const int status = genius_input(args, characters);
  if (status != exit_ok) return status;
  learn::sample_extraction found =
      learn::genius_crc_samples(span<const genius::character>(characters.data(), characters.size()),
                                active_profile().genius.control);
  std::vector<genius::character>().swap(characters);  // the samples hold what is needed from here on
  std::vector<learn::crc6_sample> samples = std::move(found.blocks);
  samples.reserve(samples.size() + found.stops.size());
  std::move(found.stops.begin(), found.stops.end(), std::back_inserter(samples));
  std::vector<learn::crc6_sample>().swap(found.stops);
  learn::crc6_learn_options options;
  options.even_polynomials = args.flag("--even");
  host::progress shown("genius learn crc", "polynomials tried", 64);
  options.progress = [&shown](double done, double) { shown.update(done); };
  const learn::crc6_learn_result r = learn::learn_genius_crc(samples, options);
  shown.finish();
  output out;
  crc_events(out.text(), r.classes, 2);
  {
    event e(out.text(), "result");
    e.text("status", learn::to_string(r.status)).number("samples", samples.size());
    e.number("skipped_characters", found.skipped_characters).number("classes", r.classes.size());
    e.number("survivors", r.survivors);
  }
  learn::profile learned = active_profile();
  if (r) learned.genius.crc = r.classes.front().members.front().parameters;
  return finish(static_cast<bool>(r), args, learned, out);
}

// `<part> learn KIND ...`: the kind, then the options every kind shares.
int learn_main(const words& all, const char* part_name, const char* kinds, const option_list& options,
               int (*run)(const std::string& kind, const arguments& args)) {
  if (all.empty()) return fail(std::string(part_name) + " learn needs what to learn: " + kinds);
  arguments args;
  std::string error;
  const words rest(all.begin() + 1, all.end());
  if (!parse_arguments(rest, options, args, error)) return fail(error);
  return run(all[0], args);
}

}  // namespace

int ring_learn_main(const words& all) {
  return learn_main(all, "ring", "crc or layout", ring_learn_options(), [](const std::string& kind, const arguments& args) {
    if (kind == "crc") return ring_learn_crc(args);
    if (kind == "layout") return ring_learn_layout(args);
    return fail("unknown ring learn kind '" + host::printable(kind) + "' (expected crc or layout)");
  });
}

int genius_learn_main(const words& all) {
  return learn_main(all, "genius", "crc", genius_learn_options(), [](const std::string& kind, const arguments& args) {
    if (kind == "crc") return genius_learn_crc(args);
    return fail("unknown genius learn kind '" + host::printable(kind) + "' (expected crc)");
  });
}

}  // namespace trionet::cli
