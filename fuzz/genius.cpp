// Fuzz harness: the Genius character codec, bit receiver and transmission parser (docs/protocol.md 3.1-3.2).
//
// Every input is read three ways:
//   - as 16-bit words for `decode_character`;
//   - as characters for a `transmission_parser`, two bytes each: flags (bit 0: control character, bit 1: a
//     framing error from the character layer instead of a character) and the data byte;
//   - as a bit stream (each byte least significant bit first) for a `transmission_receiver`.
// Small capacities (32 data bytes, 4 segments) so that overflow is common.
// Invariants:
//   - decode_character classifies every word by the 11-bit format and a good word re-encodes to itself;
//   - the parser counts every push under exactly one status (the counts add up to the pushes, `errors()` to
//     the error counts) and `in_transmission()` follows the statuses;
//   - a complete transmission is within the rules and capacities (SBAs 0..31, blocks non-empty, segments and
//     data within capacity) and re-encodes to exactly the characters received since its Start; those
//     characters parse again to the same transmission, and as bits they are received again as the same
//     transmission (parse -> encode -> parse, at both layers);
//   - the bit receiver: its counters add up to the characters and framing errors it reported; a character
//     is exactly the last 11 bits on the line; a stop-bit error was a 0 and a start-bit error a 1; the
//     transmission receiver's parse statuses are exactly what a separate parser makes of the same characters.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <trionet/genius/character.hpp>
#include <trionet/genius/crc6.hpp>
#include <trionet/genius/transmission.hpp>

#include "fuzz_check.hpp"

namespace {

using namespace trionet::genius;

constexpr std::size_t data_capacity = 32;
constexpr std::size_t segment_capacity = 4;
using parser_type = transmission_parser<data_capacity, segment_capacity>;
using receiver_type = transmission_receiver<data_capacity, segment_capacity>;

bool same(const transmission& a, const transmission& b) {
  if (a.sender != b.sender || a.broadcast != b.broadcast) return false;
  if (!a.broadcast && a.destination != b.destination) return false;
  if (a.segments.size() != b.segments.size()) return false;
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    const segment& x = a.segments[i];
    const segment& y = b.segments[i];
    if (x.block != y.block || (x.block && x.destination != y.destination)) return false;
    if (x.data.size() != y.data.size()) return false;
    for (std::size_t k = 0; k < x.data.size(); ++k) {
      if (x.data[k] != y.data[k]) return false;
    }
  }
  return true;
}

void check_word(std::uint16_t word) {
  const character_result r = decode_character(word);
  if ((word & ~word_mask) != 0) {
    FUZZ_CHECK(r.status == character_status::not_11_bits);
  } else if ((word & 1u) != 0) {
    FUZZ_CHECK(r.status == character_status::start_bit_not_0);
  } else if ((word & 0x400u) == 0) {
    FUZZ_CHECK(r.status == character_status::stop_bit_not_1);
  } else {
    FUZZ_CHECK(r.status == character_status::ok);
    FUZZ_CHECK(encode_character(r.value) == word);
    FUZZ_CHECK(r.value.byte == ((word >> 2) & 0xFFu) && r.value.control == ((word & 2u) != 0));
  }
}

std::uint32_t total_count(const parser_type& p) {
  std::uint32_t total = 0;
  for (std::size_t i = 0; i < parse_status_count; ++i) total += p.count(static_cast<parse_status>(i));
  return total;
}

std::uint32_t error_count(const parser_type& p) {
  std::uint32_t total = 0;
  for (std::size_t i = 0; i < parse_status_count; ++i) {
    if (is_error(static_cast<parse_status>(i))) total += p.count(static_cast<parse_status>(i));
  }
  return total;
}

/// Checks a complete transmission against the rules and the characters it came from, then parses its
/// encoding again, as characters and as bits.
void check_complete(const transmission& t, const std::vector<character>& since_start) {
  FUZZ_CHECK(t.sender <= max_sba);
  if (!t.broadcast) FUZZ_CHECK(t.destination <= max_sba);
  FUZZ_CHECK(t.segments.size() <= segment_capacity);
  std::size_t data = 0;
  for (std::size_t i = 0; i < t.segments.size(); ++i) {
    const segment& s = t.segments[i];
    if (s.block) {
      FUZZ_CHECK(s.destination <= max_sba);
      FUZZ_CHECK(!s.data.empty());
    } else {
      FUZZ_CHECK(!s.data.empty());
      FUZZ_CHECK(i == 0 || t.segments[i - 1].block);  // consecutive plain data is one segment
    }
    data += s.data.size();
  }
  FUZZ_CHECK(data <= data_capacity);
  if (t.broadcast) FUZZ_CHECK(data >= 1u);

  // parse -> encode: exactly the characters since the Start.
  const encode_result length = encoded_length(t);
  FUZZ_CHECK(length);
  FUZZ_CHECK(length.length == since_start.size());
  std::vector<character> characters(length.length);
  const encode_result encoded =
      encode_transmission(trionet::span<character>(characters.data(), characters.size()), t);
  FUZZ_CHECK(encoded && encoded.length == length.length);
  FUZZ_CHECK(characters == since_start);
  // A buffer one short: nothing written.
  if (!characters.empty()) {
    std::vector<character> short_buffer(characters.size() - 1, character{0xEE, true});
    const encode_result refused =
        encode_transmission(trionet::span<character>(short_buffer.data(), short_buffer.size()), t);
    FUZZ_CHECK(refused.status == encode_status::buffer_too_small);
    for (const character& c : short_buffer) FUZZ_CHECK(c == (character{0xEE, true}));
  }

  // encode -> parse, characters: the same transmission, on the Stop only.
  parser_type again;
  for (std::size_t i = 0; i < characters.size(); ++i) {
    const parse_status s = again.push(characters[i]);
    FUZZ_CHECK(s == (i + 1 == characters.size() ? parse_status::ok : parse_status::in_progress));
  }
  FUZZ_CHECK(same(again.received(), t));

  // encode -> parse, bits: idle line, the words back to back, idle line.
  std::vector<std::uint16_t> words(length.length);
  FUZZ_CHECK(encode_transmission(trionet::span<std::uint16_t>(words.data(), words.size()), t));
  receiver_type receiver;
  for (int i = 0; i < 3; ++i) FUZZ_CHECK(receiver.push(true).status == bit_status::nothing_yet);
  std::size_t completed = 0;
  for (std::size_t w = 0; w < words.size(); ++w) {
    FUZZ_CHECK(words[w] == encode_character(characters[w]));
    for (unsigned b = 0; b < character_bits; ++b) {
      const bit_result r = receiver.push(((static_cast<unsigned>(words[w]) >> b) & 1u) != 0);
      if (b + 1 < character_bits) {
        FUZZ_CHECK(r.status == bit_status::nothing_yet);
      } else {
        FUZZ_CHECK(r.status == bit_status::ok);
        if (r.parse == parse_status::ok) ++completed;
      }
    }
  }
  FUZZ_CHECK(completed == 1);
  FUZZ_CHECK(same(receiver.parser().received(), t));
  FUZZ_CHECK(receiver.parser().errors() == 0);
}

/// Characters (and framing errors) into a parser.
void run_parser(const std::uint8_t* data, std::size_t size) {
  parser_type parser;
  std::vector<character> since_start;
  bool have_start = false;
  std::uint32_t pushes = 0;
  for (std::size_t i = 0; i + 1 < size; i += 2) {
    const std::uint8_t flags = data[i];
    const character c{data[i + 1], (flags & 1u) != 0};
    parse_status s;
    if ((flags & 2u) != 0) {
      s = parser.push_framing_error();
      have_start = false;
      FUZZ_CHECK(s == parse_status::framing_error || s == parse_status::skipped);
      FUZZ_CHECK(!parser.in_transmission());
    } else {
      if (c.control && read_control(c.byte).kind == control_kind::start) {
        since_start.clear();
        have_start = true;
      }
      since_start.push_back(c);
      s = parser.push(c);
    }
    ++pushes;
    FUZZ_CHECK(total_count(parser) == pushes);
    FUZZ_CHECK(parser.errors() == error_count(parser));
    switch (s) {
      case parse_status::in_progress:
      case parse_status::start_inside_transmission:
        FUZZ_CHECK(parser.in_transmission());
        break;
      case parse_status::ok:
        FUZZ_CHECK(!parser.in_transmission());
        FUZZ_CHECK(have_start);
        check_complete(parser.received(), since_start);
        have_start = false;
        break;
      default:
        FUZZ_CHECK(!parser.in_transmission());
        break;
    }
  }
}

/// Bits into a transmission receiver, checked against a separate parser fed the same characters.
void run_bits(const std::uint8_t* data, std::size_t size) {
  receiver_type receiver;
  parser_type shadow;
  std::uint32_t line = 0xFFFFFFFFu;  // the last 32 bits on the line, newest in bit 0; idle is 1
  std::uint32_t reported = 0;
  std::vector<character> since_start;
  bool have_start = false;
  for (std::size_t i = 0; i < size; ++i) {
    for (unsigned b = 0; b < 8; ++b) {
      const bool bit = ((data[i] >> b) & 1u) != 0;
      line = line << 1 | (bit ? 1u : 0u);
      const bit_result r = receiver.push(bit);
      parse_status expected = parse_status::in_progress;
      switch (r.status) {
        case bit_status::nothing_yet:
          continue;
        case bit_status::ok: {
          const character c = receiver.bits().last();
          // The last 11 bits, oldest first, are the character's word.
          std::uint16_t word = 0;
          for (unsigned k = 0; k < character_bits; ++k) {
            word = static_cast<std::uint16_t>(word | (((line >> (character_bits - 1 - k)) & 1u) << k));
          }
          FUZZ_CHECK(word == encode_character(c));
          if (c.control && read_control(c.byte).kind == control_kind::start) {
            since_start.clear();
            have_start = true;
          }
          since_start.push_back(c);
          expected = shadow.push(c);
          break;
        }
        case bit_status::stop_bit_not_1:
          FUZZ_CHECK(!bit);
          expected = shadow.push_framing_error();
          have_start = false;
          break;
        case bit_status::start_bit_not_0:
          FUZZ_CHECK(bit);
          expected = shadow.push_framing_error();
          have_start = false;
          break;
      }
      ++reported;
      FUZZ_CHECK(r.parse == expected);
      const bit_receiver& bits = receiver.bits();
      FUZZ_CHECK(bits.characters() + bits.start_bit_errors() + bits.stop_bit_errors() == reported);
      FUZZ_CHECK(receiver.parser().in_transmission() == shadow.in_transmission());
      if (r.parse == parse_status::ok) {
        FUZZ_CHECK(have_start);
        FUZZ_CHECK(same(receiver.parser().received(), shadow.received()));
        check_complete(receiver.parser().received(), since_start);
        have_start = false;
      }
    }
  }
  for (std::size_t i = 0; i < parse_status_count; ++i) {
    const auto s = static_cast<parse_status>(i);
    FUZZ_CHECK(receiver.parser().count(s) == shadow.count(s));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (data == nullptr) return 0;
  for (std::size_t i = 0; i + 1 < size; i += 2)
    check_word(static_cast<std::uint16_t>(data[i] << 8 | data[i + 1]));
  run_parser(data, size);
  run_bits(data, size);
  return 0;
}
