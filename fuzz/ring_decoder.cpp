// Fuzz harness: the ring decoder (docs/protocol.md 1.2-1.4) on arbitrary bytes.
//
// The whole input is the byte stream from the fibre. It goes through the decoder three ways: one byte at a
// time, in bulk with split points derived from the input, and once more followed by the golden frame.
// Invariants:
//   - byte-at-a-time and bulk give the same results, in the same order, at the same byte (bulk results
//     after each chunk are exactly the byte-at-a-time results up to that byte): so results <= bytes fed;
//   - each result fits the byte that produced it (stray_data on a data byte, interrupted/zero_hops on a
//     header, the message checks on an end of message) and `in_message()` follows the byte classes;
//   - a decoded message is in range (hops 1..15, type 1..4, characters 1..Max and each < 128, vr <= 16383,
//     offset 1..15, mode 0 or 127) and decode -> encode -> decode is the identity: the encoder writes
//     exactly the input bytes the message came from, and a fresh decoder reads them back as the same message;
//     into a buffer one byte short the encoder fails and writes nothing;
//   - with the decoder's own character buffer there is never `no_room`;
//   - whatever came before, the golden frame that follows is decoded (sync recovery at the next header).
// Run for a small capacity (8) so that over-long character transfers are common, and for the default (256).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <trionet/ring/decoder.hpp>
#include <trionet/ring/encode.hpp>

#include "fuzz_check.hpp"

namespace {

using namespace trionet::ring;

/// A result with its characters copied out of the decoder (a decoded `text` view dies at the next push).
struct owned_result {
  decode_status status;
  frame_error error;
  message msg;
  std::vector<std::uint8_t> text;
  std::size_t at;  ///< index of the byte that produced it
};

bool same(const owned_result& a, const owned_result& b) {
  return a.status == b.status && a.error == b.error && a.msg.type == b.msg.type && a.msg.hops == b.msg.hops &&
         a.msg.vr == b.msg.vr && a.msg.value == b.msg.value && a.msg.offset == b.msg.offset &&
         a.msg.mode == b.msg.mode && a.text == b.text;
}

owned_result own(const decode_result& r, std::size_t at) {
  owned_result o{r.status, r.error, r.msg, {}, at};
  if (r.status == decode_status::ok && r.msg.type == message_type::character) {
    o.text.assign(r.msg.text.begin(), r.msg.text.end());
  }
  o.msg.text = {};
  return o;
}

template <std::size_t Max>
void check_result(const owned_result& r, const std::uint8_t* data) {
  const std::uint8_t byte = data[r.at];
  switch (r.status) {
    case decode_status::incomplete:
      FUZZ_CHECK(false);  // never recorded
      break;
    case decode_status::no_room:
      FUZZ_CHECK(false);  // the decoder's own buffer holds Max characters
      break;
    case decode_status::crc_error:
      FUZZ_CHECK(classify(byte) == byte_class::end_of_message);
      FUZZ_CHECK(r.error == frame_error::none);
      FUZZ_CHECK(r.msg.type == message_type::variable);
      FUZZ_CHECK(valid_hops(r.msg.hops) && r.msg.hops == hops_of(byte));
      FUZZ_CHECK(r.msg.vr <= max_vr);
      break;
    case decode_status::frame_error:
      switch (r.error) {
        case frame_error::none:
        case frame_error::idle_line:  // only from line_idle(), which this harness does not call
          FUZZ_CHECK(false);
          break;
        case frame_error::stray_data:
          FUZZ_CHECK(is_data(byte));
          break;
        case frame_error::interrupted:
        case frame_error::zero_hops:
          FUZZ_CHECK(classify(byte) == byte_class::header);
          break;
        case frame_error::stray_eom:
        case frame_error::eom_mismatch:
        case frame_error::bad_length:
        case frame_error::bad_field:
        case frame_error::unknown_type:
          FUZZ_CHECK(classify(byte) == byte_class::end_of_message);
          break;
      }
      break;
    case decode_status::ok: {
      FUZZ_CHECK(r.error == frame_error::none);
      FUZZ_CHECK(classify(byte) == byte_class::end_of_message);
      FUZZ_CHECK(valid_hops(r.msg.hops) && r.msg.hops == hops_of(byte));
      const auto type = static_cast<unsigned>(r.msg.type);
      FUZZ_CHECK(type >= 1 && type <= 4);
      switch (r.msg.type) {
        case message_type::character:
          FUZZ_CHECK(!r.text.empty() && r.text.size() <= Max);
          for (std::uint8_t c : r.text) FUZZ_CHECK(c < 128);
          break;
        case message_type::variable:
          FUZZ_CHECK(r.msg.vr <= max_vr);
          break;
        case message_type::keypad_offset:
          FUZZ_CHECK(valid_hops(r.msg.offset));
          break;
        case message_type::keypad_mode:
          FUZZ_CHECK(r.msg.mode == keypad_mode_key_on || r.msg.mode == keypad_mode_key_on_off);
          break;
      }

      // decode -> encode: exactly the bytes the message came from.
      message m = r.msg;
      m.text = trionet::byte_view(r.text.data(), r.text.size());
      std::uint8_t frame[Max + framing_length + variable_data_length] = {};
      const encode_result encoded = encode(frame, m);
      FUZZ_CHECK(encoded);
      FUZZ_CHECK(encoded.length == frame_length(m));
      FUZZ_CHECK(encoded.length <= r.at + 1);
      FUZZ_CHECK(std::memcmp(frame, data + r.at + 1 - encoded.length, encoded.length) == 0);

      // A buffer one byte short: an error, and nothing written.
      std::uint8_t short_frame[sizeof frame];
      std::memset(short_frame, 0xEE, sizeof short_frame);
      const encode_result refused = encode(trionet::byte_buffer(short_frame, encoded.length - 1), m);
      FUZZ_CHECK(!refused && refused.status == encode_status::buffer_too_small && refused.length == 0);
      for (std::uint8_t b : short_frame) FUZZ_CHECK(b == 0xEE);

      // encode -> decode: a fresh decoder reads the same message, on the last byte only.
      decoder<Max> again;
      for (std::size_t i = 0; i < encoded.length; ++i) {
        const decode_result d = again.push(frame[i]);
        if (i + 1 < encoded.length) {
          FUZZ_CHECK(d.status == decode_status::incomplete);
        } else {
          FUZZ_CHECK(same(own(d, r.at), r));
        }
      }
      break;
    }
  }
}

template <std::size_t Max>
void run(const std::uint8_t* data, std::size_t size) {
  // One byte at a time, with a state model: a header with A > 0 opens a message, a data byte keeps it open,
  // anything else closes it.
  std::vector<owned_result> bytewise;
  std::vector<std::size_t> results_after(size + 1, 0);  // results_after[i]: results from the first i bytes
  {
    decoder<Max> d;
    bool open = false;
    for (std::size_t i = 0; i < size; ++i) {
      const std::uint8_t byte = data[i];
      const decode_result r = d.push(byte);
      if (r.status != decode_status::incomplete) {
        bytewise.push_back(own(r, i));
        check_result<Max>(bytewise.back(), data);
      }
      if (is_data(byte)) {
        // unchanged
      } else {
        open = classify(byte) == byte_class::header && hops_of(byte) != 0;
      }
      FUZZ_CHECK(d.in_message() == open);
      results_after[i + 1] = bytewise.size();
    }
  }

  // In bulk, cut at points derived from the input; chunks of 0..40 bytes.
  {
    trionet_fuzz::split_source split(trionet_fuzz::hash(data, size) ^ static_cast<std::uint32_t>(Max));
    decoder<Max> d;
    std::vector<owned_result> bulk;
    std::size_t at = 0;
    std::size_t chunk_start = 0;
    while (at < size) {
      std::size_t chunk = split.next() % 41;
      if (chunk > size - at) chunk = size - at;
      chunk_start = at;
      d.push(trionet::byte_view(data + at, chunk), [&](const decode_result& r) {
        // The bulk decoder does not say which byte produced a result: take it from the byte-at-a-time run.
        const std::size_t index = bulk.size();
        FUZZ_CHECK(index < bytewise.size());
        FUZZ_CHECK(bytewise[index].at >= chunk_start && bytewise[index].at < chunk_start + chunk);
        bulk.push_back(own(r, bytewise[index].at));
        FUZZ_CHECK(same(bulk.back(), bytewise[index]));
      });
      at += chunk;
      FUZZ_CHECK(bulk.size() == results_after[at]);
    }
    FUZZ_CHECK(bulk.size() == bytewise.size());
    FUZZ_CHECK(bulk.size() <= size);
  }

  // Sync recovery: after anything at all, the next header starts afresh and the golden frame is decoded.
  {
    static constexpr std::uint8_t golden[] = {0x8a, 0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30,
                                              0x0c, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x3e, 0x88};
    decoder<Max> d;
    d.push(trionet::byte_view(data, size), [](const decode_result&) {});
    decode_result last{};
    for (std::size_t i = 0; i < sizeof golden; ++i) {
      const decode_result r = d.push(golden[i]);
      if (i == 0) {
        FUZZ_CHECK(r.status == decode_status::incomplete ||
                   (r.status == decode_status::frame_error && r.error == frame_error::interrupted));
      } else if (i + 1 < sizeof golden) {
        FUZZ_CHECK(r.status == decode_status::incomplete);
      }
      last = r;
    }
    FUZZ_CHECK(last.status == decode_status::ok);
    FUZZ_CHECK(last.msg.type == message_type::variable && last.msg.hops == 1 && last.msg.vr == 200);
    FUZZ_CHECK(last.msg.value == std::int64_t{99} * 4294967296LL);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static constexpr std::uint8_t empty[1] = {0};
  if (data == nullptr) data = empty;
  run<8>(data, size);
  run<default_max_characters>(data, size);
  return 0;
}
