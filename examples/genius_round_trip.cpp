// Genius bus in one page: encode a transmission, send it bit by bit through a receiver, and check the
// seed's bus layout for collisions. Everything below runs without heap, exceptions or a clock.
#include <cstdio>

#include <trionet/genius.hpp>

namespace genius = trionet::genius;

int main() {
  // SBA 4 sends to SBA 7: data 11 22, then a block for SBA 9.
  const std::uint8_t data[] = {0x11, 0x22};
  const std::uint8_t block[] = {0xaa, 0xbb};
  const genius::segment segments[] = {{false, 0, data}, {true, 9, block}};
  const genius::transmission sent{4, false, 7, segments};

  std::uint16_t words[16];
  const genius::encode_result encoded =
      genius::encode_transmission(trionet::span<std::uint16_t>(words), sent);
  if (!encoded) return 1;

  // The line, one bit per bit period: idle 1s, then each word least significant bit first.
  genius::transmission_receiver<64, 4> receiver;
  for (int idle = 0; idle < 5; ++idle) (void)receiver.push(true);
  for (std::size_t i = 0; i < encoded.length; ++i) {
    for (unsigned bit = 0; bit < genius::character_bits; ++bit) {
      const genius::bit_result r = receiver.push(((static_cast<unsigned>(words[i]) >> bit) & 1u) != 0);
      if (r.status == genius::bit_status::ok && r.parse == genius::parse_status::ok) {
        const genius::transmission& got = receiver.parser().received();
        std::printf("received from SBA %u to SBA %u, %zu segments\n", unsigned{got.sender},
                    unsigned{got.destination}, got.segments.size());
      }
    }
  }

  // The seed's layout: SBA 4 and 6 at one end of a 2000 ft bus, SBA 5 at the other.
  const genius::device_position bad[] = {{4, 0, 1}, {5, 2000, 1}, {6, 0, 1}};
  const genius::device_position fixed[] = {{4, 0, 1}, {5, 0, 1}, {6, 2000, 1}};
  const genius::bus_timing timing = genius::default_timing(genius::rate::standard_153k6);
  std::printf("seed layout: %zu collision(s)\n", genius::simulate_scan(bad, timing, 4).collisions);
  std::printf("SBAs in order along the bus: %zu collision(s)\n",
              genius::simulate_scan(fixed, timing, 4).collisions);
  return 0;
}
