// Direct variable transfers a ring sent, drawn at random (any VR 0..16383, any raw Q32.32 value), for the
// learning tests: what a capture of an unknown ring would hold.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "learn/ring_capture.hpp"

namespace trionet::test {

inline std::vector<trionet::learn::sent_variable> random_sent(std::mt19937_64& rng, std::size_t count) {
  std::vector<trionet::learn::sent_variable> sent;
  for (std::size_t i = 0; i < count; ++i) {
    sent.push_back({static_cast<std::uint16_t>(rng() % 16384), static_cast<std::int64_t>(rng())});
  }
  return sent;
}

}  // namespace trionet::test
