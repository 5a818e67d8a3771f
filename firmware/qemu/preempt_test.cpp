// The two sides of a Motion Coordinator on one Arm core, the link side preempting the program side at
// varying points (qemu-system-arm -M lm3s6965evb; scripts/firmware-qemu-test runs it).
//
// The link side is the SysTick interrupt, standing in for a UART interrupt at line rate: each tick it hands
// the node one byte of the incoming stream (`receive`) and takes one byte to send (`transmit`). Its reload
// value changes every tick (a pseudo-random 150..1173 cycles), so it lands at ever different instructions of
// the main loop. The incoming stream, made in the interrupt as it goes, is character messages for the node
// (hops 1, 1..24 characters), messages passing through (hops 3: characters and direct variable transfers),
// and direct variable transfers for the node (VR(0..7), each value a 64-bit pattern whose two halves
// are equal). The interrupt checks what the node sends: every message passing through comes out whole and
// unchanged but for A, and the node's own messages come out whole, in the order the program queued them.
//
// The program side is the main loop, calling the node's program API the whole time: PRINT #11 of numbered
// texts (retrying while the transmit queue is full), GET#4 of every character (they must arrive in order,
// whole messages only), VR() of the eight variables (never torn, never going back), NETSTAT (bits 1..4
// never set: nothing on the wire is wrong), and the counters (none ever decreases).
//
// With TRIONET_PREEMPT_TEST_BROKEN=1 the main loop breaks the contract (it also calls `transmit`, the link
// side's, now and then): that image must fail, which shows that the checks see a broken contract.
//
// Output through semihosting: the counts, "FAIL ..." for each broken invariant, then "trionet-preempt-test:
// PASS" or "trionet-preempt-test: FAIL"; qemu exits with 0 on pass, 1 on a failure, 2 on a fault.
#include <cstddef>
#include <cstdint>

#include "board.hpp"
#include "semihosting.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/vr.hpp"

#ifndef TRIONET_PREEMPT_TEST_BROKEN
#define TRIONET_PREEMPT_TEST_BROKEN 0
#endif

namespace {

namespace ring = trionet::ring;

constexpr std::uint32_t incoming_messages = 1500;  // messages the link side receives
constexpr std::uint32_t own_messages = 300;        // PRINT #11 messages the program side sends

trionet::vr_table<8, std::int64_t> vr;
ring::motion_coordinator<> node(vr);

// ---- shared by both sides, one writer each ----
volatile std::uint32_t link_failures = 0;      // link side
const char* volatile link_failure = nullptr;   // link side: the first broken invariant it saw
volatile bool incoming_done = false;           // link side: the whole incoming stream has been received
volatile std::uint32_t own_received = 0;       // link side: own messages seen whole on the way out
volatile std::uint32_t passing_received = 0;   // link side: forwarded messages seen whole on the way out
volatile std::uint32_t ticks = 0;              // link side

std::uint32_t lcg = 12345;  // link side only
std::uint32_t next_random() {
  lcg = lcg * 1664525u + 1013904223u;
  return lcg >> 8;
}

void link_fail(const char* what) {
  if (link_failures == 0) link_failure = what;
  link_failures = link_failures + 1;
}

// The character a message carries at `k`: the program side knows it from the message's number.
std::uint8_t text_at(std::uint32_t message, std::size_t k) {
  return static_cast<std::uint8_t>('A' + (message * 7u + k) % 26u);
}
std::size_t text_length(std::uint32_t message) { return 1u + message % 24u; }

// ---- the link side: the incoming stream, made as it goes ----
std::uint8_t frame[ring::framing_length + 256];
std::size_t frame_size = 0;
std::size_t frame_at = 0;
volatile std::uint32_t made = 0;          // messages made so far
volatile std::uint32_t for_node = 0;      // character messages for the node made so far
volatile std::uint32_t passing_made = 0;  // messages passing through made so far
// What the node must send on for the messages passing through: their frames with A decremented, in order.
std::uint8_t expected_passing[8][ring::framing_length + 256];
std::size_t expected_passing_size[8] = {};
std::uint32_t variables_made[8] = {};

bool next_frame() {
  if (made == incoming_messages) return false;
  const std::uint32_t kind = made % 5;
  if (kind == 0 || kind == 3) {  // characters for the node
    const std::size_t n = text_length(for_node);
    std::uint8_t text[24];
    for (std::size_t k = 0; k < n; ++k) text[k] = text_at(for_node, k);
    frame_size = ring::encode_characters(trionet::byte_buffer(frame, sizeof frame), 1,
                                         trionet::byte_view(text, n)).length;
    ++for_node;
  } else if (kind == 1) {  // a variable transfer for the node: VR(made % 8) = a pattern with equal halves
    const std::uint16_t v = static_cast<std::uint16_t>((made / 5) % 8);
    const std::uint32_t half = ++variables_made[v];
    const std::int64_t value = static_cast<std::int64_t>((std::uint64_t{half} << 32) | half);
    frame_size = ring::encode_variable(trionet::byte_buffer(frame, sizeof frame), 1, v, value).length;
  } else {  // passing through (hops 3): characters or a variable transfer
    if (kind == 2) {
      std::uint8_t text[24];
      const std::size_t n = 1u + made % 20u;
      for (std::size_t k = 0; k < n; ++k) text[k] = static_cast<std::uint8_t>('a' + (made + k) % 26u);
      frame_size = ring::encode_characters(trionet::byte_buffer(frame, sizeof frame), 3,
                                           trionet::byte_view(text, n)).length;
    } else {
      frame_size = ring::encode_variable(trionet::byte_buffer(frame, sizeof frame), 3,
                                         static_cast<std::uint16_t>(made % 1000u),
                                         static_cast<std::int64_t>(made) << 20).length;
    }
    std::uint8_t* expected = expected_passing[passing_made % 8];
    for (std::size_t k = 0; k < frame_size; ++k) expected[k] = frame[k];
    expected[0] = static_cast<std::uint8_t>(expected[0] - 0x08);
    expected[frame_size - 1] = static_cast<std::uint8_t>(expected[frame_size - 1] - 0x08);
    expected_passing_size[passing_made % 8] = frame_size;
    ++passing_made;
  }
  if (frame_size == 0) link_fail("a test frame did not encode");
  frame_at = 0;
  ++made;
  return true;
}

// What the node sends, parsed message by message.
std::uint8_t out[ring::framing_length + 256];
std::size_t out_size = 0;
std::uint32_t own_checked = 0;
std::uint32_t passing_checked = 0;

void sent(std::uint8_t byte) {
  if (out_size == sizeof out) {
    link_fail("a message out longer than any legal one");
    out_size = 0;
  }
  out[out_size++] = byte;
  if ((byte & 0x80u) == 0 || (byte & 0x07u) != 0 || out_size == 1) return;  // not yet an end of message
  // A whole message: [header ... end of message].
  const std::uint8_t hops = static_cast<std::uint8_t>((out[0] >> 3) & 0x0F);
  if ((out[0] & 0x80u) == 0 || (out[0] & 0x07u) == 0) {
    link_fail("a message out without its header");
  } else if (hops == 2 && (out[0] & 0x07u) == 1 && out_size >= 3 && out[1] == '#') {
    // An own PRINT #11 message: "#<number>:" then text of the number.
    std::uint32_t number = 0;
    std::size_t k = 2;
    while (k < out_size - 1 && out[k] >= '0' && out[k] <= '9') number = number * 10u + (out[k++] - '0');
    if (number != own_checked) link_fail("own messages out of order or lost");
    own_checked = number + 1;
    own_received = own_checked;
  } else {
    const std::uint8_t* expected = expected_passing[passing_checked % 8];
    const std::size_t size = expected_passing_size[passing_checked % 8];
    bool same = size == out_size;
    for (std::size_t k = 0; same && k < size; ++k) same = expected[k] == out[k];
    if (!same) link_fail("a message passing through came out changed");
    ++passing_checked;
    passing_received = passing_checked;
  }
  out_size = 0;
}

}  // namespace

extern "C" void SysTick_Handler() {
  ticks = ticks + 1;
  board::systick::start(150u + (next_random() & 0x3FFu));  // the next preemption somewhere else
  if (frame_at == frame_size && !next_frame()) {
    incoming_done = true;
  } else {
    node.receive(frame[frame_at++]);
  }
  std::uint8_t byte = 0;
  if (node.transmit(byte)) sent(byte);
}

extern "C" void HardFault_Handler() {
  semihosting::write("trionet-preempt-test: FAIL (hard fault)\n");
  semihosting::exit(2);
}

int main() {
  semihosting::write("trionet-preempt-test: start (Cortex-M3, lm3s6965evb)\n");
  std::uint32_t failures = 0;
  auto fail = [&failures](const char* what) {
    if (failures < 8) {
      semihosting::write("FAIL ");
      semihosting::write(what);
      semihosting::write("\n");
    }
    ++failures;
  };

  std::uint32_t printed = 0;        // own messages queued
  std::uint32_t message = 0;        // the character message being read
  std::size_t at = 0;               // its next character
  std::uint32_t characters = 0;
  std::uint32_t refused = 0;        // PRINT# refused: queue full (NETSTAT bit 0)
  std::int64_t last_vr[8] = {};
  ring::motion_coordinator_counters last{};
  board::systick::start(1000);

  for (std::uint32_t round = 0;; ++round) {
    if (printed < own_messages) {  // PRINT #11,"#<n>:..."
      char text[24] = {'#'};
      std::size_t n = 1;
      char digits[10];
      std::size_t d = 0;
      std::uint32_t v = printed;
      do {
        digits[d++] = static_cast<char>('0' + v % 10);
        v /= 10;
      } while (v != 0);
      while (d != 0) text[n++] = digits[--d];
      text[n++] = ':';
      while (n < 4 + printed % 10) text[n++] = 'x';
      const ring::print_result r = node.print(11, trionet::byte_view(reinterpret_cast<std::uint8_t*>(text), n));
      if (r.status == ring::send_status::ok) {
        ++printed;
      } else if (r.status == ring::send_status::queue_full && r.queued == 0) {
        ++refused;  // the link side has not sent the last ones yet: again next round
      } else {
        fail("PRINT #11 did not queue a whole message");
      }
    }
#if TRIONET_PREEMPT_TEST_BROKEN
    std::uint8_t stolen = 0;
    if ((round & 1023u) == 0) static_cast<void>(node.transmit(stolen));  // the link side's call, here
#endif
    while (node.key(4)) {  // GET#4: whole messages, in order
      const ring::get_result c = node.get(4);
      if (!c || c.value != text_at(message, at)) fail("GET#4 gave a character out of order");
      ++characters;
      if (++at == text_length(message)) {
        at = 0;
        ++message;
      }
    }
    for (std::size_t v = 0; v < 8; ++v) {  // VR(): never torn, never going back
      const std::int64_t value = vr.get(v);
      const auto bits = static_cast<std::uint64_t>(value);
      if ((bits >> 32) != (bits & 0xFFFFFFFFu)) fail("a torn VR() value");
      if (value < last_vr[v]) fail("a VR() value went back");
      last_vr[v] = value;
    }
    if ((node.netstat() & 0x1Eu) != 0) fail("NETSTAT bits 1..4 raised with nothing wrong on the wire");
    if ((round & 63u) == 0) node.clear_netstat();
    const ring::motion_coordinator_counters c = node.counters();
    if (c.frame_errors != 0 || c.crc_errors != 0 || c.receive_overflows != 0) fail("wire errors counted");
    if (c.character_messages < last.character_messages || c.variables_written < last.variables_written)
      fail("a counter went back");
    last = c;
    if (incoming_done && printed == own_messages && own_received == own_messages &&
        passing_received == passing_made && !node.key(4)) {
      break;
    }
    if (failures > 100 || link_failures > 100) break;
  }
  board::systick::start(0);  // (reload 0: the timer stops)
  const ring::link_counters links = node.forwarding_counters();
  semihosting::report("link interrupts ", ticks);
  semihosting::report("messages received ", made);
  semihosting::report("characters read with GET#4 ", characters);
  semihosting::report("own messages sent ", own_received);
  semihosting::report("PRINT# refused for a full queue ", refused);
  semihosting::report("messages passed through ", passing_received);
  if (message != for_node) fail("not every character message was read");
  if (links.messages_forwarded != passing_made || links.forwards_failed() != 0) fail("forwarding counters");
  for (std::size_t v = 0; v < 8; ++v) {
    if (last_vr[v] != static_cast<std::int64_t>((std::uint64_t{variables_made[v]} << 32) | variables_made[v]))
      fail("a VR() value is not the last one sent");
  }
  if (link_failures != 0) {
    semihosting::write("FAIL (link side) ");
    semihosting::write(link_failure);
    semihosting::write("\n");
  }
  if (failures != 0 || link_failures != 0) {
    semihosting::write("trionet-preempt-test: FAIL\n");
    semihosting::exit(1);
  }
  semihosting::write("trionet-preempt-test: PASS\n");
  semihosting::exit(0);
}
