// What the CAN bus model reports while it runs (can/bus_model.hpp): frames queued per station, the bus time,
// the busy bits and the deliveries with who sent them and when.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <trionet/can/bus_model.hpp>

namespace {

using namespace trionet::can;

struct recorder final : bus_listener {
  std::vector<bus_delivery> deliveries;
  void on_delivery(const bus_delivery& delivery) noexcept override { deliveries.push_back(delivery); }
};

frame data_frame(std::uint32_t id, std::uint8_t bytes) {
  frame f;
  f.id = id;
  f.dlc = bytes;
  return f;
}

TEST(CanBusModelReports, ANewDeliveryRecordIsAllZero) {
  const bus_delivery none;
  EXPECT_EQ(none.station, 0U);
  EXPECT_EQ(none.sent, frame{});
  EXPECT_EQ(none.queued_at, 0U);
  EXPECT_EQ(none.started_at, 0U);
  EXPECT_EQ(none.delivered_at, 0U);
  EXPECT_EQ(none.latency(), 0U);
}

// An 8-byte standard frame takes 135 bit times at worst; one with no data 55 (34 + 13 bits and 8 stuff bits).
TEST(CanBusModelReports, QueuedTimeAndBusyBitsFollowEachFrame) {
  bus_model<2> bus;
  recorder heard;
  EXPECT_TRUE(bus.idle());
  ASSERT_EQ(bus.station_port(1).send(data_frame(20, 8)), transmit_status::ok);
  EXPECT_EQ(bus.queued(0), 0U);
  EXPECT_EQ(bus.queued(1), 1U);
  EXPECT_EQ(bus.queued(2), 0U) << "a station the bus does not have queues nothing";
  EXPECT_EQ(bus.queued(), 1U);
  EXPECT_FALSE(bus.idle());
  EXPECT_EQ(bus.busy_bits(), 0U);

  bus.advance_to(134, heard);  // the frame has started and is not over
  EXPECT_TRUE(heard.deliveries.empty());
  EXPECT_EQ(bus.queued(), 0U);
  EXPECT_FALSE(bus.idle()) << "a frame on the bus";
  EXPECT_EQ(bus.busy_bits(), 135U);
  EXPECT_EQ(bus.delivered(), 0U);
  EXPECT_EQ(bus.now(), 134U);

  bus.advance_to(135, heard);
  ASSERT_EQ(heard.deliveries.size(), 1U);
  EXPECT_EQ(heard.deliveries[0].station, 1U);
  EXPECT_EQ(heard.deliveries[0].sent, data_frame(20, 8));
  EXPECT_EQ(heard.deliveries[0].queued_at, 0U);
  EXPECT_EQ(heard.deliveries[0].started_at, 0U);
  EXPECT_EQ(heard.deliveries[0].delivered_at, 135U);
  EXPECT_EQ(bus.delivered(), 1U);
  EXPECT_TRUE(bus.idle());

  bus.advance_to(100, heard);
  EXPECT_EQ(bus.now(), 135U) << "a time before now is now";
  bus.advance_to(200, heard);
  ASSERT_EQ(bus.send(0, data_frame(30, 0)), transmit_status::ok);
  EXPECT_EQ(bus.run_until_idle(heard), 255U);
  ASSERT_EQ(heard.deliveries.size(), 2U);
  EXPECT_EQ(heard.deliveries[1].station, 0U);
  EXPECT_EQ(heard.deliveries[1].queued_at, 200U);
  EXPECT_EQ(heard.deliveries[1].started_at, 200U);
  EXPECT_EQ(heard.deliveries[1].latency(), 55U);
  EXPECT_EQ(bus.busy_bits(), 190U);
  EXPECT_EQ(bus.delivered(), 2U);
}

TEST(CanBusModelReports, AFrameWaitingForTheBusHasTheLatencyOfItsWait) {
  bus_model<2> bus;
  recorder heard;
  ASSERT_EQ(bus.send(0, data_frame(40, 8)), transmit_status::ok);
  bus.advance_to(10, heard);  // station 0's frame is on the bus
  ASSERT_EQ(bus.send(1, data_frame(10, 8)), transmit_status::ok);
  EXPECT_EQ(bus.run_until_idle(heard), 270U);
  ASSERT_EQ(heard.deliveries.size(), 2U);
  EXPECT_EQ(heard.deliveries[1].station, 1U);
  EXPECT_EQ(heard.deliveries[1].queued_at, 10U);
  EXPECT_EQ(heard.deliveries[1].started_at, 135U);
  EXPECT_EQ(heard.deliveries[1].latency(), 260U);
}

TEST(CanBusModelReports, RunUntilIdleStopsAtItsLimit) {
  bus_model<1> bus(stuffing::none);
  recorder heard;
  for (int i = 0; i < 3; ++i) ASSERT_EQ(bus.send(0, data_frame(10, 8)), transmit_status::ok);
  EXPECT_EQ(bus.frame_bits(data_frame(10, 8)), 111U);
  EXPECT_EQ(bus.run_until_idle(heard, 250), 250U);
  EXPECT_EQ(heard.deliveries.size(), 2U);
  EXPECT_FALSE(bus.idle());
  EXPECT_EQ(bus.run_until_idle(heard), 333U);
  EXPECT_EQ(heard.deliveries.size(), 3U);
}

}  // namespace
