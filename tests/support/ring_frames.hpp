// Ring frames for tests: a message encoded into a vector, and a node fed and drained byte by byte, as a UART
// interrupt would (docs/protocol.md 1.2-1.5).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "trionet/ring.hpp"

namespace trionet::test {

inline std::vector<std::uint8_t> frame_of(const trionet::ring::message& m) {
  std::vector<std::uint8_t> out(trionet::ring::frame_length(m));
  EXPECT_TRUE(trionet::ring::encode(trionet::byte_buffer(out.data(), out.size()), m));
  return out;
}

// A character transfer of `text` to the node `hops` along.
inline std::vector<std::uint8_t> chars(std::uint8_t hops, const std::string& text) {
  return frame_of(trionet::ring::message::characters(
      hops, trionet::byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())));
}

// Every byte received, one at a time.
template <class Node>
void feed(Node& node, const std::vector<std::uint8_t>& bytes) {
  for (std::uint8_t b : bytes) node.receive(b);
}

// Every byte the node has to send, one at a time, until it has none.
template <class Node>
std::vector<std::uint8_t> drain(Node& node) {
  std::vector<std::uint8_t> out;
  std::uint8_t b = 0;
  while (node.transmit(b)) out.push_back(b);
  return out;
}

// GET#channel until the receive buffer is empty.
template <class Node>
std::string read_all(Node& node, int channel = 4) {
  std::string out;
  while (auto r = node.get(channel)) out += static_cast<char>(r.value);
  return out;
}

}  // namespace trionet::test
