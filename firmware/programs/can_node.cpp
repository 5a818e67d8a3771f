// Firmware image (d): a TN20-17 CAN VR-exchange node (node 1 of 5).
//
// The CAN receive-FIFO interrupt hands every frame to a trionet::can node, which writes VR() for
// the frames addressed to this node (through a vr_table with the default write policy) and counts the rest.
// Every SysTick (10 ms) the main loop sends VR(0), the axis position it keeps up to date, to the next node
// round the ring (transmit channel 5) through a one-mailbox bxCAN port.
//
// Its baseline, firmware/measure/can_node_baseline.cpp, is the same ISRs and main loop moving frames without
// the library (and the same integer arithmetic on the position): scripts/firmware-size reports the
// difference, the CAN codec + node. VRs are Q32.32 and values go out through the parts-based interface, so
// the image has no floating point.
#include <cstdint>

#include "board.hpp"

#include "trionet/can/node.hpp"
#include "trionet/vr.hpp"

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t ticks_per_second = 100;

volatile bool tick = false;
volatile std::uint32_t frames_received = 0;

namespace can = trionet::can;

constexpr std::uint8_t node_count = 5;
constexpr std::uint8_t this_node = 1;
constexpr std::uint8_t next_node_channel = can::first_transmit_channel;
constexpr std::uint16_t position_vr = 0;

/// The bxCAN transmit mailbox 0 as a trionet port. Called from the main loop only.
class bxcan_port final : public can::port {
 public:
  can::transmit_status send(const can::frame& outgoing) noexcept override {
    if (!board::can0::tx_free()) return can::transmit_status::busy;
    board::can0::write(outgoing.id, outgoing.dlc, outgoing.data);
    return can::transmit_status::ok;
  }
};

trionet::vr_table<64, std::int64_t> vr;  // Q32.32 VRs: no floating point anywhere in the image
bxcan_port can_port;
// The network's byte order is known when the firmware is built (big-endian, the default of docs/protocol.md
// 2.2): fixed at compile time, the node holds none and has no choice to make.
can::basic_vr_exchange_node<can::fixed_byte_order<can::byte_order::big_endian>> node(
    can::make_node_address(node_count, this_node).address, can_port, vr);

}  // namespace

extern "C" void SysTick_Handler() {
  tick = true;
}

extern "C" void CAN0_RX0_IRQHandler() {
  while (board::can0::rx_pending()) {
    frames_received = frames_received + 1;
    can::frame received;
    board::can0::read(received.id, received.dlc, received.data);
    static_cast<void>(node.receive(received));  // counted by the node
  }
}

int main() {
  board::can0::start();
  board::systick::start(core_clock_hz / ticks_per_second - 1);
  for (;;) {
    if (!tick) {
      board::wait_for_interrupt();
      continue;
    }
    tick = false;
    vr[position_vr] += 4294967;                 // the axis moves 0.001 (Q32.32)
    can::vr_message message;
    message.vr = position_vr;
    message.value = trionet::q32_to_decimal(vr[position_vr]);
    static_cast<void>(node.send_on_channel(next_node_channel, message));
  }
}
