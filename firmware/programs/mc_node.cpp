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
// Built twice (see CMakeLists.txt): normally, and with TRIONET_FIRMWARE_BASELINE=1, where the same ISR and
// main loop move bytes without the library (and do the same integer arithmetic on the position). The
// difference between the two images is the MC node: link, decoder, encoder, receive buffer, VR writes.
//
// Built once more for the emulated Cortex-M3 with TRIONET_FIRMWARE_MEASURE=1 (scripts/firmware-instructions):
// the same UART interrupt, and a quiet main loop that only reads the characters that arrive (GET#4) until a
// keypad mode message to this node ends the run, then reports the node's counters through semihosting. The
// script counts the Thumb instructions that the interrupt executes per byte.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

#ifndef TRIONET_FIRMWARE_MEASURE
#define TRIONET_FIRMWARE_MEASURE 0
#endif
#if TRIONET_FIRMWARE_MEASURE
#include "semihosting.hpp"
#endif

#if !TRIONET_FIRMWARE_BASELINE
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/vr.hpp"
#endif

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t ticks_per_second = 100;

volatile bool tick = false;

#if TRIONET_FIRMWARE_BASELINE
volatile std::uint8_t last_byte = 0;
volatile std::size_t bytes_waiting = 0;
volatile std::int64_t position = 0;  // Q32.32
constexpr std::uint8_t fixed_frame[16] = {0x8a, 0x00, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x88};
std::size_t transmitted = sizeof fixed_frame;  // index of the next byte to send

bool next_byte(std::uint8_t& byte) {
  if (transmitted == sizeof fixed_frame) return false;
  byte = fixed_frame[transmitted++];
  return true;
}

#else
namespace ring = trionet::ring;

constexpr int next_node = 10;  // BASIC address of the next node round the ring
constexpr std::uint16_t position_vr = 0;

constexpr std::int64_t step = trionet::q32_from_double(0.001).raw;  // computed at compile time

trionet::vr_table<64, std::int64_t> vr;  // Q32.32 VRs: no floating point anywhere in the image
ring::motion_coordinator<256, 16, 32, 256, ring::crc16_ccitt_false_bitwise> node(vr);  // default capacities
#endif

}  // namespace

extern "C" void SysTick_Handler() {
  tick = true;
}

// One received byte and one transmitted byte per interrupt, as a UART at line rate gives them (FIFOs off:
// one byte in the receive register, one place in the transmitter). A byte that is still waiting re-raises
// the interrupt at once.
extern "C" void UART0_IRQHandler() {
  if (board::uart0::rx_ready()) {
#if TRIONET_FIRMWARE_BASELINE
    last_byte = board::uart0::read();
    bytes_waiting = bytes_waiting + 1;
#else
    node.receive(board::uart0::read());
#endif
  }
  if (board::uart0::tx_ready()) {
    std::uint8_t byte = 0;
#if TRIONET_FIRMWARE_BASELINE
    const bool have = next_byte(byte);
#else
    const bool have = node.transmit(byte);
#endif
    if (have) {
      board::uart0::write(byte);
    } else {
      board::uart0::enable_tx_interrupt(false);  // nothing to send: the main loop switches it on again
    }
  }
}

#if TRIONET_FIRMWARE_MEASURE
void report(const char* name, std::uint32_t value) {
  char text[12];
  char* p = text + sizeof text;
  *--p = '\0';
  do {
    *--p = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  semihosting::write(name);
  semihosting::write(p);
  semihosting::write("\n");
}

int main() {
  board::uart0::start();
  std::uint32_t characters = 0;
  for (;;) {  // (no wfi: under qemu's instruction trace a core asleep may miss the serial input)
    while (node.key(4)) {
      static_cast<void>(node.get(4));
      ++characters;
    }
    if (node.counters().keypad_messages_ignored == 0) continue;  // the end of the run
    // Nothing arrives after the end: what is read now is final (counters() reads one counter at a time).
    while (node.key(4)) {
      static_cast<void>(node.get(4));
      ++characters;
    }
    const ring::motion_coordinator_counters c = node.counters();
    const ring::link_counters links = node.forwarding_counters();
    report("forwarded ", links.messages_forwarded);
    report("character_messages ", c.character_messages);
    report("characters_read ", characters);
    report("variables_written ", c.variables_written);
    report("frame_errors ", c.frame_errors);
    report("crc_errors ", c.crc_errors);
    report("receive_overflows ", c.receive_overflows);
    report("forwards_failed ", links.forwards_failed());
    semihosting::exit(0);
  }
}
#else
int main() {
  board::uart0::start();
  board::systick::start(core_clock_hz / ticks_per_second - 1);
  for (;;) {
    if (!tick) {
      board::wait_for_interrupt();
      continue;
    }
    tick = false;
#if TRIONET_FIRMWARE_BASELINE
    position = position + 4294967;  // the same application arithmetic as below (0.001 in Q32.32)
    if (bytes_waiting != 0) bytes_waiting = 0;
    transmitted = 0;
    board::uart0::enable_tx_interrupt(true);
#else
    vr[position_vr] += step;  // the axis moves
    bool queued = node.send_variable_q32(next_node, position_vr, vr[position_vr]) == ring::send_status::ok;
    std::uint8_t echo[16];
    std::size_t length = 0;
    while (length < sizeof echo && node.key(4)) echo[length++] = node.get(4).value;
    if (length != 0 && node.print(next_node, trionet::byte_view(echo, length)).queued != 0) queued = true;
    if (queued) board::uart0::enable_tx_interrupt(true);
#endif
  }
}
#endif
