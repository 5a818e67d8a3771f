// Decoder results as comparable values, and the decoder fed byte by byte or in bulk, for the ring codec's
// tests (docs/protocol.md 1.2-1.4).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "trionet/ring.hpp"

namespace trionet::test {

// A decode result with its text copied out of the decoder, comparable with ==.
struct event {
  trionet::ring::decode_status status;
  trionet::ring::frame_error error;
  trionet::ring::message_type type;
  int hops;
  std::string text;
  int vr;
  std::int64_t value;
  int offset;
  int mode;
  bool operator==(const event& o) const {
    return status == o.status && error == o.error && type == o.type && hops == o.hops && text == o.text &&
           vr == o.vr && value == o.value && offset == o.offset && mode == o.mode;
  }
};

inline event to_event(const trionet::ring::decode_result& r) {
  return {r.status,
          r.error,
          r.msg.type,
          r.msg.hops,
          std::string(reinterpret_cast<const char*>(r.msg.text.data()), r.msg.text.size()),
          r.msg.vr,
          r.msg.value,
          r.msg.offset,
          r.msg.mode};
}

template <class Decoder>
std::vector<event> decode_bytewise(Decoder& d, const std::vector<std::uint8_t>& bytes) {
  std::vector<event> out;
  for (std::uint8_t b : bytes) {
    const trionet::ring::decode_result r = d.push(b);
    if (r.status != trionet::ring::decode_status::incomplete) out.push_back(to_event(r));
  }
  return out;
}

template <class Decoder>
std::vector<event> decode_bulk(Decoder& d, const std::vector<std::uint8_t>& bytes) {
  std::vector<event> out;
  d.push(trionet::byte_view(bytes.data(), bytes.size()),
         [&](const trionet::ring::decode_result& r) { out.push_back(to_event(r)); });
  return out;
}

// docs/protocol.md 1.3's example: hop 1, vr 200, value 99.
inline const std::vector<std::uint8_t> golden_variable_transfer = {
    0x8a, 0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30, 0x0c, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x3e, 0x88};

}  // namespace trionet::test
