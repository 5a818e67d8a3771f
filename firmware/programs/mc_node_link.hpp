// The firmware MC program's node and its link side, the UART interrupt: firmware/programs/mc_node.cpp and the
// measurement image firmware/measure/mc_node_instructions.cpp both build on it, so that the interrupt whose
// instructions scripts/firmware-instructions counts is the program's own.
#pragma once

#include <cstddef>
#include <cstdint>

#include "board.hpp"
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/vr.hpp"

namespace {

namespace ring = trionet::ring;

trionet::vr_table<64, std::int64_t> vr;  // Q32.32 VRs: no floating point anywhere in the image
ring::motion_coordinator<256, 16, 32, 256, ring::crc16_ccitt_false_bitwise> node(vr);  // default capacities

}  // namespace

// One received byte and one transmitted byte per interrupt, as a UART at line rate gives them (FIFOs off:
// one byte in the receive register, one place in the transmitter). A byte that is still waiting re-raises
// the interrupt at once.
extern "C" void UART0_IRQHandler() {
  if (board::uart0::rx_ready()) {
    node.receive(board::uart0::read());
  }
  if (board::uart0::tx_ready()) {
    std::uint8_t byte = 0;
    const bool have = node.transmit(byte);
    if (have) {
      board::uart0::write(byte);
    } else {
      board::uart0::enable_tx_interrupt(false);  // nothing to send: the main loop switches it on again
    }
  }
}
