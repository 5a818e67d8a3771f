// CAN bus model: worst-case frame length and times, arbitration and latency, a 5-node TN20-17 exchange with
// all 20 sender/receiver pairs, and the highest VR update rate per node that a 5-node exchange sustains.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include <trionet/can.hpp>

namespace {

using namespace trionet::can;
using trionet::vr_table;

// Stuff bits a transmitter inserts into `bits` (after 5 equal bits, a complement that starts the next run).
unsigned count_stuff_bits(const std::vector<int>& bits) {
  unsigned stuffed = 0;
  int last = -1;
  unsigned run = 0;
  for (int b : bits) {
    if (b == last) {
      ++run;
    } else {
      last = b;
      run = 1;
    }
    if (run == 5) {
      ++stuffed;
      last = 1 - b;  // the stuff bit
      run = 1;
    }
  }
  return stuffed;
}

TEST(CanBusTiming, WorstCaseStuffingFormulaMatchesExhaustiveSearchOnShortStreams) {
  for (unsigned length = 1; length <= 18; ++length) {
    unsigned worst = 0;
    for (unsigned pattern = 0; pattern < (1U << length); ++pattern) {
      std::vector<int> bits;
      for (unsigned i = 0; i < length; ++i) bits.push_back(static_cast<int>(pattern >> i & 1U));
      const unsigned s = count_stuff_bits(bits);
      if (s > worst) worst = s;
    }
    EXPECT_EQ(worst, (length - 1) / 4) << "length " << length;
  }
}

TEST(CanBusTiming, WorstCaseFrameWithElevenBitIdentifierAndEightBytesIs135Bits) {
  EXPECT_EQ(unstuffed_frame_bits(8), 111U);
  EXPECT_EQ(worst_case_stuff_bits(8), 24U);
  EXPECT_EQ(worst_case_frame_bits(8), 135U);
  EXPECT_EQ(worst_case_frame_bits(0), 47U + 8U);
  EXPECT_EQ(worst_case_frame_bits(8, true), 160U);
  // The worst pattern exists for the 98 stuffable bits: 5 equal bits, then alternating runs of 4.
  std::vector<int> bits;
  for (unsigned i = 0; i < 34 + 64; ++i) bits.push_back(i < 5 ? 0 : static_cast<int>((i - 5) / 4 % 2 == 0));
  EXPECT_EQ(count_stuff_bits(bits), worst_case_stuff_bits(8));
}

TEST(CanBusTiming, FrameTimeAtEachStandardBitRate) {
  const std::uint64_t expected_ns[] = {1080000, 540000, 270000, 135000};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(nanoseconds(worst_case_frame_bits(8), standard_bit_rates[i]), expected_ns[i]);
  }
}

/// Records deliveries in order.
class recorder final : public bus_listener {
 public:
  std::vector<bus_delivery> deliveries;
  void on_delivery(const bus_delivery& delivery) noexcept override { deliveries.push_back(delivery); }
};

frame vr_frame(std::uint32_t id) {
  frame f;
  f.id = id;
  f.dlc = 8;
  return f;
}

TEST(CanBusModel, LowestIdentifierWinsArbitration) {
  bus_model<3> bus;
  recorder heard;
  ASSERT_EQ(bus.station_port(0).send(vr_frame(40)), transmit_status::ok);
  ASSERT_EQ(bus.station_port(1).send(vr_frame(12)), transmit_status::ok);
  ASSERT_EQ(bus.station_port(2).send(vr_frame(31)), transmit_status::ok);
  bus.run_until_idle(heard);
  ASSERT_EQ(heard.deliveries.size(), 3U);
  EXPECT_EQ(heard.deliveries[0].sent.id, 12U);
  EXPECT_EQ(heard.deliveries[0].station, 1U);
  EXPECT_EQ(heard.deliveries[1].sent.id, 31U);
  EXPECT_EQ(heard.deliveries[2].sent.id, 40U);
  EXPECT_EQ(heard.deliveries[0].latency(), 135U);
  EXPECT_EQ(heard.deliveries[1].latency(), 270U);
  EXPECT_EQ(heard.deliveries[2].latency(), 405U);
  EXPECT_EQ(bus.now(), 405U);
  EXPECT_EQ(bus.busy_bits(), 405U);
}

TEST(CanBusModel, ATransmissionIsNotPreemptedByAHigherPriorityFrame) {
  bus_model<2> bus;
  recorder heard;
  ASSERT_EQ(bus.send(0, vr_frame(50)), transmit_status::ok);
  bus.advance_to(10, heard);
  EXPECT_TRUE(heard.deliveries.empty());
  ASSERT_EQ(bus.send(1, vr_frame(10)), transmit_status::ok);
  bus.advance_to(1000, heard);
  ASSERT_EQ(heard.deliveries.size(), 2U);
  EXPECT_EQ(heard.deliveries[0].sent.id, 50U);
  EXPECT_EQ(heard.deliveries[0].delivered_at, 135U);
  EXPECT_EQ(heard.deliveries[1].sent.id, 10U);
  EXPECT_EQ(heard.deliveries[1].queued_at, 10U);
  EXPECT_EQ(heard.deliveries[1].started_at, 135U);
  EXPECT_EQ(heard.deliveries[1].latency(), 260U);
  EXPECT_EQ(bus.now(), 1000U);
  EXPECT_TRUE(bus.idle());
}

TEST(CanBusModel, StationQueueOrdersByIdentifierThenFifoAndReportsFull) {
  bus_model<1, 3> bus;
  recorder heard;
  frame a = vr_frame(20);
  a.data[0] = 1;
  frame b = vr_frame(20);
  b.data[0] = 2;
  ASSERT_EQ(bus.send(0, a), transmit_status::ok);
  ASSERT_EQ(bus.send(0, b), transmit_status::ok);
  ASSERT_EQ(bus.send(0, vr_frame(11)), transmit_status::ok);
  EXPECT_EQ(bus.send(0, vr_frame(5)), transmit_status::busy);
  EXPECT_EQ(bus.send(7, vr_frame(5)), transmit_status::failed);
  bus.run_until_idle(heard);
  ASSERT_EQ(heard.deliveries.size(), 3U);
  EXPECT_EQ(heard.deliveries[0].sent.id, 11U);
  EXPECT_EQ(heard.deliveries[1].sent.data[0], 1);
  EXPECT_EQ(heard.deliveries[2].sent.data[0], 2);
}

TEST(CanBusModel, StandardFrameBeatsExtendedFrameWithTheSameBaseIdentifier) {
  frame standard = vr_frame(0x123);
  frame extended = vr_frame((0x123U << 18U) | frame::extended_flag);
  frame remote = vr_frame(0x123 | frame::remote_flag);
  EXPECT_LT(bus_model<1>::arbitration_key(standard), bus_model<1>::arbitration_key(remote));
  EXPECT_LT(bus_model<1>::arbitration_key(remote), bus_model<1>::arbitration_key(extended));
  EXPECT_LT(bus_model<1>::arbitration_key(extended), bus_model<1>::arbitration_key(vr_frame(0x124)));
  bus_model<1> unstuffed(stuffing::none);
  EXPECT_EQ(unstuffed.frame_bits(standard), 111U);
  EXPECT_EQ(unstuffed.frame_bits(remote), 47U);
}

/// Five controllers on one bus: station i is node i + 1; every station hears every other station's frames.
template <std::size_t QueueDepth>
struct five_node_exchange final : bus_listener {
  bus_model<5, QueueDepth> bus;
  vr_table<256> vrs[5];
  vr_exchange_node nodes[5] = {
      {make_node_address(5, 1).address, bus.station_port(0), vrs[0]},
      {make_node_address(5, 2).address, bus.station_port(1), vrs[1]},
      {make_node_address(5, 3).address, bus.station_port(2), vrs[2]},
      {make_node_address(5, 4).address, bus.station_port(3), vrs[3]},
      {make_node_address(5, 5).address, bus.station_port(4), vrs[4]},
  };
  std::uint64_t worst_latency = 0;
  std::uint64_t delivered = 0;

  void on_delivery(const bus_delivery& delivery) noexcept override {
    ++delivered;
    if (delivery.latency() > worst_latency) worst_latency = delivery.latency();
    for (std::size_t i = 0; i < 5; ++i) {
      if (i != delivery.station) (void)nodes[i].receive(delivery.sent);
    }
  }
};

TEST(CanTn2017Exchange, AllTwentySenderReceiverPairsOfFiveNodesOnTheBus) {
  five_node_exchange<8> exchange;
  for (std::uint8_t s = 1; s <= 5; ++s) {
    for (std::uint8_t d = 1; d <= 5; ++d) {
      if (s == d) continue;
      const auto vr = static_cast<std::uint16_t>(10 * s + d);
      ASSERT_EQ(exchange.nodes[s - 1].send_to_node(d, vr, -(s * 1000.0 + d + 0.1234)), send_status::ok);
    }
  }
  exchange.bus.run_until_idle(exchange);
  EXPECT_EQ(exchange.delivered, 20U);
  EXPECT_EQ(exchange.bus.now(), 20U * 135U);
  for (std::uint8_t r = 1; r <= 5; ++r) {
    const vr_exchange_node& node = exchange.nodes[r - 1];
    EXPECT_EQ(node.counters().sent, 4U);
    EXPECT_EQ(node.counters().written, 4U) << "node " << int{r};
    EXPECT_EQ(node.counters().foreign, 12U) << "node " << int{r} << " hears 16 frames, 4 of them its own";
    EXPECT_EQ(node.counters().malformed(), 0U);
    for (std::uint16_t vr = 0; vr < 256; ++vr) {
      const std::uint8_t s = static_cast<std::uint8_t>(vr / 10);
      const bool expected = vr % 10 == r && s >= 1 && s <= 5 && s != r;
      if (expected) {
        EXPECT_EQ(exchange.vrs[r - 1][vr], -(s * 1000.0 + r + 0.1234)) << "node " << int{r} << " VR " << vr;
      } else {
        EXPECT_EQ(exchange.vrs[r - 1][vr], 0.0) << "node " << int{r} << " VR " << vr;
      }
    }
  }
}

struct periodic_outcome {
  std::uint64_t worst_latency = 0;
  std::size_t backlog = 0;
  std::uint64_t delivered = 0;
  std::uint64_t refused = 0;
};

// Every node sends one VR update every `period` bit times (all in phase: the critical instant), cycling
// through its four transmit channels, for `periods` periods; then reports the worst latency and the frames
// left queued.
periodic_outcome run_periodic(std::uint64_t period, unsigned periods) {
  five_node_exchange<64> exchange;
  periodic_outcome out;
  for (unsigned p = 0; p < periods; ++p) {
    exchange.bus.advance_to(p * period, exchange);
    for (std::uint8_t k = 1; k <= 5; ++k) {
      const auto channel = static_cast<std::uint8_t>(5 + (p + k) % 4);
      if (exchange.nodes[k - 1].send_on_channel(channel, static_cast<std::uint16_t>(p % 256), p) !=
          send_status::ok) {
        ++out.refused;
      }
    }
  }
  exchange.bus.advance_to(std::uint64_t{periods} * period, exchange);
  out.worst_latency = exchange.worst_latency;
  out.backlog = exchange.bus.queued();
  out.delivered = exchange.delivered;
  return out;
}

TEST(CanTn2017Exchange, HighestSustainedUpdateRatePerNodeForFiveNodes) {
  // Search (bisection; keeping up is monotonic in the period) the shortest period, in bit times, at which 5
  // nodes sending one update each per period keep up for 2000 periods: nothing refused, and at the end at
  // most one period's frames still undelivered.
  const auto keeps_up = [](std::uint64_t period) {
    const periodic_outcome r = run_periodic(period, 2000);
    return r.refused == 0 && 5 * 2000 - r.delivered <= 5;
  };
  std::uint64_t too_short = 100;  // 5 frames cannot fit in 100 bit times
  std::uint64_t shortest = 2000;
  ASSERT_FALSE(keeps_up(too_short));
  ASSERT_TRUE(keeps_up(shortest));
  while (shortest - too_short > 1) {
    const std::uint64_t middle = (too_short + shortest) / 2;
    (keeps_up(middle) ? shortest : too_short) = middle;
  }
  ASSERT_EQ(shortest, 5U * worst_case_frame_bits(8)) << "5 frames of 135 bits per period";
  const periodic_outcome at_limit = run_periodic(shortest, 2000);
  EXPECT_EQ(at_limit.worst_latency, shortest) << "the lowest-priority frame waits for the other four";
  const periodic_outcome beyond = run_periodic(shortest - 1, 2000);
  EXPECT_GT(beyond.refused + beyond.backlog, 0U) << "one bit time less and the queues grow";

  for (std::uint32_t rate : standard_bit_rates) {
    const double frame_us = static_cast<double>(nanoseconds(worst_case_frame_bits(8), rate)) / 1000.0;
    const double per_node = static_cast<double>(rate) / static_cast<double>(shortest);
    const double worst_ms = static_cast<double>(nanoseconds(at_limit.worst_latency, rate)) / 1e6;
    std::printf(
        "[ figures  ] %7u bit/s: frame %7.1f us, bus %7.1f frames/s, %7.1f VR updates/s per node "
        "(%6.1f per sender-receiver pair), worst latency %.3f ms\n",
        rate, frame_us, static_cast<double>(rate) / 135.0, per_node, per_node / 4.0, worst_ms);
    EXPECT_NEAR(per_node * 5.0 * frame_us / 1e6, 1.0, 1e-9) << "the bus is exactly full";
  }
}

}  // namespace
