// Firmware image (b): a UART interrupt feeding a ring Motion Coordinator node.
//
// The PL011 interrupt is the node's link (see include/trionet/transport.hpp): every received byte goes to
// `node.receive` (which forwards, or decodes, fills the receive buffer and writes VR()), and while the
// transmitter has room it takes bytes from `node.transmit`; the transmit interrupt is switched off when the
// node has nothing to send. The main loop is the user program: every SysTick (10 ms) it updates VR(0), the
// axis position, and sends it to the next node (SEND(10,1,0,VR(0))); it echoes any characters that arrived
// (IF KEY#4 THEN GET#4 ... PRINT#10). The ISR is the node's link side, the main loop its program side: they
// share the node with no lock and no interrupt masking (transport.hpp), and the main loop only switches the
// transmit interrupt on after queuing (the ISR switches it off when nothing is left). Table-free CRC: the
// smallest firmware configuration.
//
// The node and the UART interrupt are in mc_node_link.hpp (the measurement image shares them). Its baseline,
// firmware/measure/mc_node_baseline.cpp, is the same ISR and main loop moving bytes without the library (and
// the same integer arithmetic on the position): scripts/firmware-size reports the difference, the MC node:
// link, decoder, encoder, receive buffer, VR writes.
#include <cstddef>
#include <cstdint>

#include "board.hpp"
#include "mc_node_link.hpp"

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t ticks_per_second = 100;

volatile bool tick = false;

constexpr int next_node = 10;  // BASIC address of the next node round the ring
constexpr std::uint16_t position_vr = 0;

constexpr std::int64_t step = trionet::q32_from_double(0.001).raw;  // computed at compile time

}  // namespace

extern "C" void SysTick_Handler() {
  tick = true;
}
int main() {
  board::uart0::start();
  board::systick::start(core_clock_hz / ticks_per_second - 1);
  for (;;) {
    if (!tick) {
      board::wait_for_interrupt();
      continue;
    }
    tick = false;
    vr[position_vr] += step;  // the axis moves
    bool queued = node.send_variable_q32(next_node, position_vr, vr[position_vr]) == ring::send_status::ok;
    std::uint8_t echo[16];
    std::size_t length = 0;
    while (length < sizeof echo && node.key(4)) echo[length++] = node.get(4).value;
    if (length != 0 && node.print(next_node, trionet::byte_view(echo, length)).queued != 0) queued = true;
    if (queued) board::uart0::enable_tx_interrupt(true);
  }
}
