// The simulator workload shared by the benchmark and the instruction counter: four Motion Coordinators on a
// ring, each SENDing direct variable transfers whenever its transmit queue has room, alternately to the next
// node (BASIC address 10, hops 1) and to the one after (11, hops 2, forwarded by the next node).
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/ring/simulator.hpp"
#include "trionet/vr.hpp"

namespace trionet::bench {

class simulated_ring {
 public:
  static constexpr std::size_t nodes = 4;

  simulated_ring() noexcept {
    for (auto& node : nodes_) (void)ring_.add(node);
  }
  simulated_ring(const simulated_ring&) = delete;
  simulated_ring& operator=(const simulated_ring&) = delete;

  /// `byte_times` steps of the ring, topping up every node's transmit queue before each step.
  void run(std::uint64_t byte_times) noexcept {
    for (std::uint64_t t = 0; t < byte_times; ++t) {
      for (std::size_t i = 0; i < nodes; ++i) top_up(i);
      ring_.step();
    }
  }

  std::uint64_t delivered() const noexcept { return ring_.bytes_delivered(); }
  std::uint64_t now() const noexcept { return ring_.now(); }

  /// True if no node flagged an error and messages went round.
  bool healthy() const noexcept {
    std::uint32_t written = 0;
    for (const auto& node : nodes_) {
      if (node.netstat() != 0) return false;
      written += node.counters().variables_written;
    }
    return written != 0 || ring_.now() == 0;
  }

 private:
  static constexpr std::size_t variable_frame = 16;

  void top_up(std::size_t i) noexcept {
    auto& node = nodes_[i];
    if (node.transmit_free() < variable_frame) return;
    const int address = (sent_[i] & 1U) == 0 ? 10 : 11;
    const auto vr = static_cast<std::uint16_t>(sent_[i] % 200U);
    if (node.send_variable(address, vr, static_cast<double>(sent_[i]) * 0.25) == ring::send_status::ok) {
      ++sent_[i];
    }
  }

  vr_table<256> vr_[nodes];
  ring::motion_coordinator<> nodes_[nodes] = {
      ring::motion_coordinator<>(vr_[0]), ring::motion_coordinator<>(vr_[1]),
      ring::motion_coordinator<>(vr_[2]), ring::motion_coordinator<>(vr_[3])};
  ring::simulator<nodes> ring_;
  std::uint32_t sent_[nodes] = {};
};

}  // namespace trionet::bench
