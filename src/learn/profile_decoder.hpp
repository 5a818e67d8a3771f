// A ring decoder with a profile's CRC and variable layout, chosen at run time (docs/profile.md): what the
// tool's decoders and the Python package's `trionet.ring.Decoder` decode with. Host side.
#pragma once

#include <cstdint>
#include <variant>

#include "learn/profile.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/variable_layout.hpp"
#include "trionet/span.hpp"

namespace trionet::learn {

/// A ring decoder for `profile.crc` and `profile.layout`, with the same calls as `ring::decoder<>` (whose
/// 256-character capacity it has: check `max_characters` before using it for another).
class profile_decoder {
 public:
  /// The library's default decoder for the default CRC and layout (its CRC sliced at compile time: the
  /// common case keeps its speed), else one with the profile's CRC and layout.
  explicit profile_decoder(const ring_profile& profile) {
    if (profile.crc == ring::crc16_parameters{} && profile.layout == ring::variable_layout_parameters{}) return;
    const ring::crc16_runtime crc(profile.crc);
    ring::with_variable_layout(profile.layout, [&](auto layout) {
      using layout_type = decltype(layout);
      decoder_.emplace<ring::decoder<ring::default_max_characters, ring::crc16_runtime, layout_type>>(crc);
    });
  }

  // The default decoder is called directly (inlined), the others through the variant.
  ring::decode_result push(std::uint8_t byte) {
    if (auto* const fixed = std::get_if<0>(&decoder_)) return fixed->push(byte);
    return std::visit([byte](auto& dec) { return dec.push(byte); }, decoder_);
  }
  template <class Sink>
  void push(byte_view bytes, Sink&& sink) {
    if (auto* const fixed = std::get_if<0>(&decoder_)) return fixed->push(bytes, sink);
    std::visit([&](auto& dec) { dec.push(bytes, sink); }, decoder_);
  }
  ring::decode_result line_idle() {
    return std::visit([](auto& dec) { return dec.line_idle(); }, decoder_);
  }
  void reset() {
    std::visit([](auto& dec) { dec.reset(); }, decoder_);
  }
  [[nodiscard]] bool in_message() const {
    return std::visit([](const auto& dec) { return dec.in_message(); }, decoder_);
  }
  [[nodiscard]] bool open() const {
    return std::visit([](const auto& dec) { return dec.open(); }, decoder_);
  }

 private:
  template <ring::group_order V, ring::group_order X, ring::crc_input C>
  using with =
      ring::decoder<ring::default_max_characters, ring::crc16_runtime, ring::variable_layout<V, X, C>>;
  static constexpr ring::group_order l = ring::group_order::least_significant_first;
  static constexpr ring::group_order m = ring::group_order::most_significant_first;
  static constexpr ring::crc_input s = ring::crc_input::as_sent;
  static constexpr ring::crc_input d = ring::crc_input::least_significant_first;
  std::variant<ring::decoder<>, with<l, l, s>, with<l, m, s>, with<m, l, s>, with<m, m, s>, with<l, l, d>,
               with<l, m, d>, with<m, l, d>, with<m, m, d>>
      decoder_;
};

}  // namespace trionet::learn
