// genius::bus_controller's defaults and edges (genius/bus_controller.hpp): 16 bytes of outputs and of inputs
// per device, inputs from SBA 31 counted like any other, an overflow counted only for a broadcast longer than
// it keeps, and its RAM: the device core with a turn of 31 blocks, plus tables of 32 x (outputs + inputs + 6)
// bytes.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "support/genius_words.hpp"
#include "trionet/genius/bus_controller.hpp"
#include "trionet/genius/transmission.hpp"

namespace {

using namespace trionet::genius;
using trionet::byte_view;
using trionet::span;
using trionet::test::broadcast_from;
using trionet::test::hear;

std::vector<std::uint8_t> bytes(byte_view v) {
  return {v.begin(), v.end()};
}

TEST(GeniusBusControllerDefaults, SixteenBytesOfOutputsAndOfInputsPerDevice) {
  static_assert(bus_controller<>::output_capacity == 16 && bus_controller<>::input_capacity == 16);
  bus_controller<> controller(0);
  const std::vector<std::uint8_t> seventeen(17, 0x5A);
  EXPECT_EQ(controller.set_outputs(3, byte_view(seventeen.data(), 16)), outputs_status::ok);
  EXPECT_EQ(controller.set_outputs(3, byte_view(seventeen.data(), 17)), outputs_status::too_long);
  std::vector<std::uint8_t> inputs(17);
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs[i] = static_cast<std::uint8_t>(i);
  (void)hear(controller, broadcast_from(5, inputs));
  EXPECT_EQ(controller.collect(), 1U);
  EXPECT_EQ(bytes(controller.inputs(5)), std::vector<std::uint8_t>(inputs.begin(), inputs.begin() + 16));
  EXPECT_EQ(controller.input_overflows(), 1U);
}

TEST(GeniusBusControllerDefaults, InputsOfAnyLengthUpToItsCapacityAreNoOverflowAndSba31Counts) {
  bus_controller<4, 4> controller(0);
  (void)hear(controller, broadcast_from(31, {1, 2, 3, 4}));  // exactly what it keeps
  (void)hear(controller, broadcast_from(2, {9}));
  EXPECT_EQ(controller.collect(), 2U);
  EXPECT_EQ(controller.input_overflows(), 0U);
  EXPECT_EQ(controller.input_updates(31), 1U);
  EXPECT_EQ(bytes(controller.inputs(31)), (std::vector<std::uint8_t>{1, 2, 3, 4}));
  EXPECT_EQ(controller.input_updates(2), 1U);
  EXPECT_EQ(controller.input_updates(32), 0U);
}

// The default device core holds a turn of 31 blocks of 16 bytes (31 x 18 bytes of turn data), and the tables
// add no more than 32 x (16 + 16 + 6) bytes and the overflow counter, up to the alignment's padding.
TEST(GeniusBusControllerDefaults, RamIsTheDeviceCoreForThirtyOneBlocksAndTheTables) {
  using core = device<31 * (16 + 2), 256>;
  static_assert(bus_controller<>::turn_capacity == 31 * (16 + 2), "a turn of 31 blocks of 16 bytes");
  static_assert(sizeof(bus_controller<>) - sizeof(core) <
                    32 * (16 + 16 + 6) + sizeof(std::uint32_t) + alignof(bus_controller<>),
                "the tables of 32 x (outputs + inputs + 6) bytes, and the overflow counter");
}

}  // namespace
