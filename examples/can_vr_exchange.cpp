// Five Motion Coordinators exchanging VR() values over CANbus as Trio application note TN20-17 lays out, on
// the trionet bus model: every 2 ms each controller sends its axis position (VR(10 + node)) to the next node
// round the ring through transmit channel 5, 6, 7 and 8 in turn. Prints every update as it lands, then the
// bus load and what the bus could sustain.
//
//   usage: can_vr_exchange [bit rate, default 500000]
#include <cstdio>
#include <cstdlib>

#include <trionet/can.hpp>

namespace {

using namespace trionet::can;

constexpr std::uint8_t node_count = 5;

/// The bus and five controllers; station i is node i + 1. Every station hears every other station's frames.
class exchange final : public bus_listener {
 public:
  explicit exchange(std::uint32_t bit_rate) noexcept : bit_rate_(bit_rate) {}

  void on_delivery(const bus_delivery& delivery) noexcept override {
    for (std::size_t i = 0; i < node_count; ++i) {
      if (i == delivery.station) continue;
      const receive_result r = nodes_[i].receive(delivery.sent);
      if (r.status != receive_status::ok) continue;
      std::printf("%8.3f ms  node %u -> node %u  Rx #%u  id %3u  VR(%3u) = %-10.4f latency %6.1f us\n",
                  milliseconds(delivery.delivered_at), unsigned{r.sender}, static_cast<unsigned>(i + 1),
                  unsigned{r.receive_channel}, delivery.sent.identifier(), unsigned{r.message.vr},
                  trionet::to_double(r.message.value), milliseconds(delivery.latency()) * 1000.0);
      if (delivery.latency() > worst_latency_) worst_latency_ = delivery.latency();
    }
  }

  bus_model<node_count, 8>& bus() noexcept { return bus_; }
  vr_exchange_node& node(std::uint8_t k) noexcept { return nodes_[k - 1]; }
  trionet::vr_table<256>& vrs(std::uint8_t k) noexcept { return vrs_[k - 1]; }
  std::uint64_t worst_latency() const noexcept { return worst_latency_; }
  double milliseconds(std::uint64_t bits) const noexcept {
    return static_cast<double>(nanoseconds(bits, bit_rate_)) / 1e6;
  }
  std::uint64_t bits_in(double ms) const noexcept {
    return static_cast<std::uint64_t>(ms * bit_rate_ / 1000.0);
  }

 private:
  std::uint32_t bit_rate_;
  bus_model<node_count, 8> bus_;
  trionet::vr_table<256> vrs_[node_count];
  vr_exchange_node nodes_[node_count] = {
      {make_node_address(node_count, 1).address, bus_.station_port(0), vrs_[0]},
      {make_node_address(node_count, 2).address, bus_.station_port(1), vrs_[1]},
      {make_node_address(node_count, 3).address, bus_.station_port(2), vrs_[2]},
      {make_node_address(node_count, 4).address, bus_.station_port(3), vrs_[3]},
      {make_node_address(node_count, 5).address, bus_.station_port(4), vrs_[4]},
  };
  std::uint64_t worst_latency_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const long requested = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 500000;
  if (requested < 10000 || requested > 1000000) {
    std::fprintf(stderr, "can_vr_exchange: bit rate must be 10000..1000000 bit/s\n");
    return 2;
  }
  const auto bit_rate = static_cast<std::uint32_t>(requested);
  static exchange net(bit_rate);  // static: about 15 kB of VR tables and queues

  std::printf("TN20-17 VR exchange: %u nodes at %u bit/s, worst-case frame %u bits = %.1f us\n\n", node_count,
              bit_rate, worst_case_frame_bits(8), net.milliseconds(worst_case_frame_bits(8)) * 1000.0);
  constexpr int rounds = 8;
  constexpr double period_ms = 2.0;
  for (int round = 0; round < rounds; ++round) {
    net.bus().advance_to(net.bits_in(round * period_ms), net);
    for (std::uint8_t k = 1; k <= node_count; ++k) {
      const auto channel = static_cast<std::uint8_t>(first_transmit_channel + round % (node_count - 1));
      const double position = k * 100.0 + round * 0.125 + k / 10000.0;
      const send_status sent =
          net.node(k).send_on_channel(channel, static_cast<std::uint16_t>(10 + k), position);
      if (sent != send_status::ok) std::printf("node %u: send failed (%d)\n", k, static_cast<int>(sent));
    }
  }
  net.bus().run_until_idle(net);
  const std::uint64_t elapsed = net.bits_in(rounds * period_ms);

  std::printf("\nafter %.1f ms: %llu frames, bus busy %.1f us, load %.2f %%, worst latency %.1f us\n",
              net.milliseconds(elapsed), static_cast<unsigned long long>(net.bus().delivered()),
              net.milliseconds(net.bus().busy_bits()) * 1000.0,
              100.0 * static_cast<double>(net.bus().busy_bits()) / static_cast<double>(elapsed),
              net.milliseconds(net.worst_latency()) * 1000.0);
  for (std::uint8_t k = 1; k <= node_count; ++k) {
    const node_counters& c = net.node(k).counters();
    std::printf("node %u: sent %u, written %u, foreign %u, malformed %u\n", k, c.sent, c.written, c.foreign,
                c.malformed());
  }
  const double per_node = static_cast<double>(bit_rate) / (node_count * worst_case_frame_bits(8));
  std::printf(
      "\nthis bus sustains at most %.1f VR updates/s per node with %u nodes (%.1f per sender-receiver "
      "pair)\n",
      per_node, node_count, per_node / (node_count - 1));
  return 0;
}
