// The README's library example: encode SEND(10,1,200,99) and decode it byte by byte.
#include <trionet/ring.hpp>

#include <cstdio>

int main() {
  namespace ring = trionet::ring;

  // SEND(10,1,200,99): a direct variable transfer to the next node (BASIC address 10 = 1 hop).
  std::uint8_t frame[16];
  auto encoded = ring::encode_variable(frame, *ring::hops_from_basic_address(10), 200,
                                       trionet::q32_from_double(99.0).raw);
  if (!encoded) return 1;  // encoded.status says why; nothing was written

  // The receiver: a decoder whose state you own, fed one byte at a time (e.g. from a UART ISR).
  ring::decoder<> decoder;
  for (std::size_t i = 0; i < encoded.length; ++i) {
    ring::decode_result r = decoder.push(frame[i]);
    if (r.status == ring::decode_status::ok && r.msg.type == ring::message_type::variable)
      std::printf("VR(%u) = %g\n", r.msg.vr, trionet::q32_to_double(r.msg.value));
  }
}
