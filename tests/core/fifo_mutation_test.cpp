// The byte queue under the nodes' transmit queues and receive buffers (detail/fifo.hpp): index_for is the
// smallest unsigned type that holds 0..Max, and a queue of Capacity bytes takes exactly Capacity bytes by
// push, refusing the next one, whether Capacity is a power of two or not.
#include <gtest/gtest.h>

#include <cstdint>
#include <type_traits>

#include "trionet/detail/fifo.hpp"

namespace {

using trionet::detail::index_for;
using trionet::detail::spsc_fifo;

static_assert(std::is_same_v<index_for<255>, std::uint8_t>, "0..255 fits a byte");
static_assert(std::is_same_v<index_for<256>, std::uint16_t>, "256 does not");
static_assert(std::is_same_v<index_for<65535>, std::uint16_t>);

// "two indices (one byte each up to a capacity of 128, else two bytes)" (fifo.hpp, Cost).
template <std::size_t Capacity>
constexpr std::size_t index_bytes = sizeof(typename spsc_fifo<Capacity>::index);
static_assert(index_bytes<3> == 1 && index_bytes<100> == 1 && index_bytes<127> == 1 && index_bytes<128> == 1,
              "one byte up to a capacity of 128");
static_assert(index_bytes<129> == 2 && index_bytes<200> == 2 && index_bytes<256> == 2, "two bytes above");

template <class Fifo>
void expect_takes_exactly_its_capacity() {
  Fifo fifo;
  for (std::size_t i = 0; i < Fifo::capacity(); ++i) {
    EXPECT_TRUE(fifo.push(static_cast<std::uint8_t>(i + 1))) << i;
  }
  EXPECT_EQ(fifo.free(), 0U);
  EXPECT_FALSE(fifo.push(0x55)) << "full";
  EXPECT_EQ(fifo.available(), Fifo::capacity());
  for (std::size_t i = 0; i < Fifo::capacity(); ++i) {
    std::uint8_t byte = 0;
    ASSERT_TRUE(fifo.pop(byte));
    EXPECT_EQ(byte, static_cast<std::uint8_t>(i + 1));
  }
  std::uint8_t byte = 0;
  EXPECT_FALSE(fifo.pop(byte)) << "the refused byte was not queued";
  EXPECT_TRUE(fifo.push(0x66)) << "room again";
}

TEST(SpscFifo, PushTakesExactlyTheCapacity) {
  expect_takes_exactly_its_capacity<spsc_fifo<4>>();
  expect_takes_exactly_its_capacity<spsc_fifo<5>>();
  expect_takes_exactly_its_capacity<spsc_fifo<1>>();
}

// Full, then one out and one in for many rounds: the bytes come out in order as the positions wrap round.
template <class Fifo>
void expect_order_kept_round_the_buffer() {
  Fifo fifo;
  std::uint8_t next_in = 0;
  std::uint8_t next_out = 0;
  while (fifo.push(next_in)) ++next_in;
  for (int round = 0; round < 600; ++round) {
    std::uint8_t byte = 0;
    ASSERT_TRUE(fifo.pop(byte));
    ASSERT_EQ(byte, next_out) << round;
    ++next_out;
    ASSERT_TRUE(fifo.push(next_in)) << round;
    ++next_in;
  }
}

TEST(SpscFifo, OrderIsKeptRoundTheBufferAtAnyCapacity) {
  expect_order_kept_round_the_buffer<spsc_fifo<3>>();
  expect_order_kept_round_the_buffer<spsc_fifo<4>>();
  expect_order_kept_round_the_buffer<spsc_fifo<7>>();
  expect_order_kept_round_the_buffer<spsc_fifo<200>>();
}

}  // namespace
