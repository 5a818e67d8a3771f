// The counters of a TN20-17 VR-exchange node (docs/protocol.md 2.1, 2.2): each counts its own event, from
// construction and again from each `clear_counters`, and `malformed` is the sum of the three malformed kinds.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <trionet/can.hpp>

namespace {

using namespace trionet::can;
using trionet::vr_table;

/// A port that answers each send with the next status of a script (then `ok`).
class scripted_port final : public port {
 public:
  std::vector<transmit_status> answers;
  std::size_t sends = 0;

  transmit_status send(const frame&) noexcept override {
    return sends < answers.size() ? answers[sends++] : (++sends, transmit_status::ok);
  }
};

frame frame_on(std::uint32_t id, std::vector<std::uint8_t> bytes) {
  frame f;
  f.id = id;
  f.dlc = static_cast<std::uint8_t>(bytes.size());
  for (std::size_t i = 0; i < bytes.size() && i < 8; ++i) f.data[i] = bytes[i];
  return f;
}

bool refuse_vr_seven(void*, std::uint16_t vr, std::int64_t) noexcept {
  return vr != 7;
}

/// Node 1 of 5 (receive identifiers 10..13) with a Q32.32 table of 100 VRs that refuses VR(7).
struct node_one {
  scripted_port wire;
  vr_table<100, std::int64_t> vrs{refuse_vr_seven, nullptr};
  vr_exchange_node node{make_node_address(5, 1).address, wire, vrs};

  /// One event of every kind each counter counts, `times` times over, on the send and the receive side.
  void one_of_each(unsigned times) {
    for (unsigned i = 0; i < times; ++i) {
      wire.answers = {transmit_status::ok, transmit_status::busy, transmit_status::failed};
      wire.sends = 0;
      EXPECT_EQ(node.send_to_node(2, 1, 1.0), send_status::ok);
      EXPECT_EQ(node.send_to_node(2, 1, 1.0), send_status::port_busy);
      EXPECT_EQ(node.send_to_node(2, 1, 1.0), send_status::port_failed);
      EXPECT_EQ(node.receive(frame_on(10, {8, 0, 0, 0, 0, 5, 0, 0})).status, receive_status::ok);
      EXPECT_EQ(node.receive(frame_on(11, {7, 0, 0, 0, 0, 5, 0, 0})).status, receive_status::refused);
      EXPECT_EQ(node.receive(frame_on(12, {100, 0, 0, 0, 0, 5, 0, 0})).status, receive_status::out_of_range);
      EXPECT_EQ(node.receive(frame_on(13, {9, 0, 0x80, 0, 0, 0, 0, 0})).status,
                receive_status::value_out_of_range);  // 2^31: more than a Q32.32 table holds
      EXPECT_EQ(node.receive(frame_on(20, {9, 0, 0, 0, 0, 5, 0, 0})).status, receive_status::foreign);
      EXPECT_EQ(node.receive(frame_on(10, {9, 0, 0, 0, 0, 5, 0})).status, receive_status::bad_dlc);
      EXPECT_EQ(node.receive(frame_on(11, {9, 2, 0, 0, 0, 5, 0, 0})).status, receive_status::bad_sign);
      EXPECT_EQ(node.receive(frame_on(12, {9, 0, 0, 0, 0, 5, 0x27, 0x10})).status,
                receive_status::bad_fraction);
    }
  }
};

void expect_each_counter_is(const node_counters& c, std::uint32_t n) {
  EXPECT_EQ(c.sent, n);
  EXPECT_EQ(c.send_busy, n);
  EXPECT_EQ(c.send_failed, n);
  EXPECT_EQ(c.written, n);
  EXPECT_EQ(c.refused, n);
  EXPECT_EQ(c.out_of_range, n);
  EXPECT_EQ(c.value_out_of_range, n);
  EXPECT_EQ(c.foreign, n);
  EXPECT_EQ(c.bad_dlc, n);
  EXPECT_EQ(c.bad_sign, n);
  EXPECT_EQ(c.bad_fraction, n);
  EXPECT_EQ(c.malformed(), 3 * n);
}

TEST(CanNodeCounters, EachCounterCountsItsOwnEventOnly) {
  node_one n;
  expect_each_counter_is(n.node.counters(), 0);
  n.one_of_each(1);
  expect_each_counter_is(n.node.counters(), 1);
  n.one_of_each(2);
  expect_each_counter_is(n.node.counters(), 3);
}

TEST(CanNodeCounters, ClearCountersStartsEveryCountAgainFromZero) {
  node_one n;
  n.one_of_each(3);
  n.node.clear_counters();
  expect_each_counter_is(n.node.counters(), 0);
  n.one_of_each(2);
  {
    SCOPED_TRACE("counted again from the clear");
    expect_each_counter_is(n.node.counters(), 2);
  }
  n.node.clear_counters();
  n.one_of_each(1);
  SCOPED_TRACE("a second clear starts from there");
  expect_each_counter_is(n.node.counters(), 1);
}

TEST(CanNodeCounters, MalformedIsTheSumOfItsThreeKinds) {
  node_counters c;
  c.bad_dlc = 1;
  c.bad_sign = 20;
  c.bad_fraction = 300;
  EXPECT_EQ(c.malformed(), 321U);
}

}  // namespace
