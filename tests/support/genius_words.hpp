// A Genius device (or bus controller) driven word by word in tests, as its UART and timer interrupts would drive
// it: transmissions as the 9-bit UART words of their characters, words heard with their start bits, and the
// words it sends in its turn.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "trionet/genius/device.hpp"
#include "trionet/genius/transmission.hpp"

namespace trionet::test {

/// The UART words of transmission `t` (default CRC-6 and control layout unless `layout` says otherwise).
inline std::vector<std::uint16_t> words_of(const genius::transmission& t,
                                           const genius::control_layout& layout = genius::control_layout{}) {
  std::vector<genius::character> chars(genius::encoded_length(t).length);
  EXPECT_TRUE(genius::encode_transmission(span<genius::character>(chars.data(), chars.size()), t,
                                          genius::crc6_g704{}, layout));
  std::vector<std::uint16_t> words;
  for (const genius::character c : chars) words.push_back(genius::to_uart_word(c));
  return words;
}

/// The UART words of a broadcast from `sender` carrying `data` as one plain segment.
inline std::vector<std::uint16_t> broadcast_from(std::uint8_t sender, const std::vector<std::uint8_t>& data) {
  const genius::segment plain{false, 0, byte_view(data.data(), data.size())};
  return words_of(genius::transmission{sender, true, 0, span<const genius::segment>(&plain, 1)});
}

/// Every word with its start bit before it, as the UART reports them; the request of the last word.
template <class Device>
genius::link_request hear(Device& d, const std::vector<std::uint16_t>& words) {
  genius::link_request last{};
  for (const std::uint16_t w : words) {
    (void)d.start_bit();
    last = d.receive(w);
  }
  return last;
}

/// What the device sends when its turn timer expires, each word read back unchanged, until it has nothing
/// more. With `must_send` (the default) the turn is expected to send something.
template <class Device>
std::vector<std::uint16_t> take_turn(Device& d, bool must_send = true) {
  std::vector<std::uint16_t> sent;
  genius::link_request r = d.timer_expired();
  if (must_send) {
    EXPECT_TRUE(r.transmit) << "the turn sends nothing";
  }
  std::uint16_t w = 0;
  while (r.transmit && d.transmit(w)) {
    sent.push_back(w);
    (void)d.start_bit();
    r = d.receive(w);
  }
  return sent;
}

}  // namespace trionet::test
