// An outside program that links the installed trionet package and uses its codec.
#include <trionet/trionet.hpp>

#include <cstdio>

int main() {
  std::uint8_t frame[32];
  const auto result = trionet::ring::encode_variable(frame, 1, 200, trionet::q32_from_integer(99));
  if (!result || result.length != 16 || frame[14] != 0x3e) {
    std::puts("consumer: unexpected frame");
    return 1;
  }
  std::puts("consumer: ok");
  return 0;
}
