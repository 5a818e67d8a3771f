// The emulated Cortex-M3 test: runs trionet on a real Arm core (qemu-system-arm -M lm3s6965evb) and reports
// to the host through semihosting. scripts/firmware-qemu-test runs it.
//
// Ring codec golden vectors and errors, then two-node rings: two Motion Coordinators wired back to back
// through their byte ports (SEND and PRINT#, forwarding round the ring, a corrupted byte), and a Motion
// Coordinator with a keypad (keypad offset, a key press read with GET#3). Then the CAN VR exchange:
// the docs/protocol.md 2.2 example frame between two nodes, and the integer-only decimal <-> Q32.32
// conversions against 64-bit arithmetic.
//
// Output: one line per group, "FAIL ..." for each failed check, then "trionet-qemu-test: PASS" or
// "trionet-qemu-test: FAIL"; qemu exits with 0 on pass, 1 on a failed check, 2 on a fault.
// With TRIONET_QEMU_TEST_INJECT_FAILURE=1 one deliberately wrong check is added: that image must fail.
#include <cstddef>
#include <cstdint>

#include "semihosting.hpp"
#include "trionet/can.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

#ifndef TRIONET_QEMU_TEST_CUSTOM_CRC
#define TRIONET_QEMU_TEST_CUSTOM_CRC 1
#endif
#ifndef TRIONET_QEMU_TEST_INJECT_FAILURE
#define TRIONET_QEMU_TEST_INJECT_FAILURE 0
#endif

namespace {

namespace ring = trionet::ring;

unsigned checks_run = 0;
unsigned checks_failed = 0;

void check(bool ok, const char* what, unsigned line) {
  ++checks_run;
  if (ok) return;
  ++checks_failed;
  semihosting::write("FAIL line ");
  semihosting::write_unsigned(line);
  semihosting::write(": ");
  semihosting::write(what);
  semihosting::write("\n");
}

#define CHECK(condition) check((condition), #condition, __LINE__)

void group(const char* name) {
  semihosting::write("group: ");
  semihosting::write(name);
  semihosting::write("\n");
}

/// Hides a pointer's target from the optimiser, so that the checks run on the core instead of being folded
/// at compile time.
template <class T>
T* opaque(T* pointer) {
  __asm__ volatile("" : "+r"(pointer) : : "memory");
  return pointer;
}

bool equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t length) {
  for (std::size_t i = 0; i < length; ++i) {
    if (a[i] != b[i]) return false;
  }
  return true;
}

// docs/protocol.md 1.3: hop 1, vr 200, value 99.
constexpr std::uint8_t golden_frame[16] = {0x8a, 0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30,
                                           0x0c, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x3e, 0x88};
constexpr std::uint32_t can_scale = 10000;  // ten-thousandths per unit
constexpr std::uint8_t check_input[9] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

/// Pushes bytes one at a time; returns the last result that was not `incomplete` and how many there were.
template <class Decoder>
ring::decode_result feed(Decoder& decoder, const std::uint8_t* bytes, std::size_t length, unsigned& reports) {
  ring::decode_result last;
  reports = 0;
  for (std::size_t i = 0; i < length; ++i) {
    const ring::decode_result result = decoder.push(bytes[i]);
    if (result.status != ring::decode_status::incomplete) {
      last = result;
      ++reports;
    }
  }
  return last;
}

void crc_check_values() {
  group("CRC-16/CCITT-FALSE check value 0x29B1, table and table-free");
  const std::uint8_t* input = opaque(check_input);
  CHECK(ring::crc16_ccitt_false::compute(input, sizeof check_input) == 0x29B1);
  CHECK(ring::crc16_ccitt_false_bitwise::compute(input, sizeof check_input) == 0x29B1);
#if TRIONET_QEMU_TEST_INJECT_FAILURE
  CHECK(ring::crc16_ccitt_false_bitwise::compute(input, sizeof check_input) == 0x29B2);  // deliberately wrong
#endif
}

void golden_encode() {
  group("golden example: encode_variable(hops 1, vr 200, 99)");
  std::uint8_t frame[16] = {};
  const std::uint16_t vr = *opaque(&golden_frame[1]) == 0x48 ? 200 : 0;
  const ring::encode_result table = ring::encode_variable(frame, 1, vr, trionet::q32_from_integer(99));
  CHECK(table.status == ring::encode_status::ok);
  CHECK(table.length == 16);
  CHECK(equal(frame, golden_frame, sizeof frame));

  std::uint8_t frame_bitwise[16] = {};
  const ring::encode_result bitwise = ring::encode_variable<ring::crc16_ccitt_false_bitwise>(
      frame_bitwise, 1, vr, trionet::q32_from_integer(99));
  CHECK(bitwise.length == 16);
  CHECK(equal(frame_bitwise, golden_frame, sizeof frame_bitwise));

  std::uint8_t small[15] = {0x55};
  const ring::encode_result too_small = ring::encode_variable(small, 1, vr, trionet::q32_from_integer(99));
  CHECK(too_small.status == ring::encode_status::buffer_too_small);
  CHECK(small[0] == 0x55);  // untouched on error
  const ring::encode_result no_hops = ring::encode_variable(frame, 0, vr, 0);
  CHECK(no_hops.status == ring::encode_status::hops_out_of_range);
}

void golden_decode() {
  group("golden example: decode, table and table-free CRC");
  const std::uint8_t* bytes = opaque(golden_frame);
  unsigned reports = 0;
  ring::decoder<> table;
  ring::decode_result result = feed(table, bytes, sizeof golden_frame, reports);
  CHECK(reports == 1);
  CHECK(result.status == ring::decode_status::ok);
  CHECK(result.msg.type == ring::message_type::variable);
  CHECK(result.msg.hops == 1);
  CHECK(result.msg.vr == 200);
  CHECK(result.msg.value == trionet::q32_from_integer(99));

  ring::decoder<ring::default_max_characters, ring::crc16_ccitt_false_bitwise> bitwise;
  result = feed(bitwise, bytes, sizeof golden_frame, reports);
  CHECK(reports == 1);
  CHECK(result.status == ring::decode_status::ok);
  CHECK(result.msg.vr == 200);
  CHECK(result.msg.value == trionet::q32_from_integer(99));
}

void character_round_trip() {
  group("character transfer: encode then decode PRINT#12, \"HELLO\"");
  const char* text = opaque("HELLO");
  std::uint8_t frame[8] = {};
  const ring::encode_result encoded = ring::encode_characters(frame, 3, text, 5);
  CHECK(encoded.length == 7);
  CHECK(frame[0] == 0x99 && frame[6] == 0x98);
  ring::decoder<16> decoder;
  unsigned reports = 0;
  const ring::decode_result result = feed(decoder, frame, encoded.length, reports);
  CHECK(reports == 1);
  CHECK(result.status == ring::decode_status::ok);
  CHECK(result.msg.type == ring::message_type::character);
  CHECK(result.msg.hops == 3);
  CHECK(result.msg.text.size() == 5 &&
        equal(result.msg.text.data(), reinterpret_cast<const std::uint8_t*>("HELLO"), 5));
  std::uint8_t bad[4] = {};
  const std::uint8_t high[1] = {0x80};
  CHECK(ring::encode_characters(bad, 1, trionet::byte_view(high)).status ==
        ring::encode_status::character_out_of_range);
}

void decoder_errors() {
  group("decoder errors: CRC, end-of-message mismatch, stray data, interrupted, bad field");
  std::uint8_t frame[16];
  unsigned reports = 0;
  ring::decode_result result;

  // A corrupted C0: a CRC error, the variable is reported but must not be written.
  for (std::size_t i = 0; i < sizeof frame; ++i) frame[i] = golden_frame[i];
  frame[13] = 0x7e;
  ring::decoder<> crc_case;
  result = feed(crc_case, opaque(frame), sizeof frame, reports);
  CHECK(reports == 1);
  CHECK(result.status == ring::decode_status::crc_error);
  CHECK(result.msg.vr == 200);

  // An end of message whose A differs from the header's.
  for (std::size_t i = 0; i < sizeof frame; ++i) frame[i] = golden_frame[i];
  frame[15] = ring::make_end_of_message(2);
  ring::decoder<> mismatch;
  result = feed(mismatch, opaque(frame), sizeof frame, reports);
  CHECK(result.status == ring::decode_status::frame_error);
  CHECK(result.error == ring::frame_error::eom_mismatch);

  // Stray data before a message: one report, then the decoder re-synchronises on the header.
  ring::decoder<> stray;
  const std::uint8_t noise[3] = {0x11, 0x22, 0x33};
  result = feed(stray, opaque(noise), sizeof noise, reports);
  CHECK(reports == 1);
  CHECK(result.error == ring::frame_error::stray_data);
  result = feed(stray, opaque(golden_frame), sizeof golden_frame, reports);
  CHECK(reports == 1 && result.status == ring::decode_status::ok && result.msg.vr == 200);

  // A header inside an open message: the first message is lost, the second one decodes.
  ring::decoder<> interrupted;
  const std::uint8_t cut[3] = {0x8a, 0x48, 0x01};
  result = feed(interrupted, opaque(cut), sizeof cut, reports);
  CHECK(reports == 0);
  CHECK(interrupted.push(0x8a).error == ring::frame_error::interrupted);
  result = feed(interrupted, opaque(golden_frame) + 1, sizeof golden_frame - 1, reports);
  CHECK(reports == 1 && result.status == ring::decode_status::ok);

  // X9 bits 6..1 set under a valid CRC: a bad field.
  for (std::size_t i = 0; i < sizeof frame; ++i) frame[i] = golden_frame[i];
  frame[12] = 0x02;
  const std::uint16_t crc = ring::crc16_ccitt_false::compute(frame + 1, ring::variable_crc_length);
  frame[13] = static_cast<std::uint8_t>(crc & 0x7F);
  frame[14] = static_cast<std::uint8_t>((crc >> 8) & 0x7F);
  ring::decoder<> field;
  result = feed(field, opaque(frame), sizeof frame, reports);
  CHECK(result.status == ring::decode_status::frame_error);
  CHECK(result.error == ring::frame_error::bad_field);
}

void q32_values() {
  group("Q32.32 conversions");
  const double half = *opaque(&golden_frame[0]) == 0x8a ? 2.5 : 0.0;
  const trionet::q32_result value = trionet::q32_from_double(half);
  CHECK(value.status == trionet::q32_status::ok);
  CHECK(value.raw == 0x280000000LL);
  CHECK(trionet::q32_to_double(value.raw) == 2.5);
  CHECK(trionet::q32_from_double(half * 1e12).status == trionet::q32_status::out_of_range);
  CHECK(trionet::q32_from_raw(0xFFFFFFFFFFFFFFFFULL) == -1);
}

/// The docs/protocol.md 2.2 example between two CAN nodes of five, with Q32.32 VR tables (no floating point):
/// node 1 sends VR(1) = 2.345 to node 4 as 028#0100000000020D7A.
class capture_port final : public trionet::can::port {
 public:
  trionet::can::transmit_status send(const trionet::can::frame& outgoing) noexcept override {
    last = outgoing;
    ++sent;
    return trionet::can::transmit_status::ok;
  }
  trionet::can::frame last{};
  unsigned sent = 0;
};

void can_example() {
  namespace can = trionet::can;
  group("CAN VR exchange: node 1 sends VR(1) = 2.345 to node 4 (028#0100000000020D7A), integers only");
  capture_port wire;
  trionet::vr_table<8, std::int64_t> vr1, vr4;
  can::vr_exchange_node node1(can::make_node_address(5, 1).address, wire, vr1);
  can::vr_exchange_node node4(can::make_node_address(5, 4).address, wire, vr4);
  const std::int64_t value = *opaque(&golden_frame[0]) == 0x8a ? 10071698309LL : 0;  // 2.345 in Q32.32
  can::vr_message message;
  message.vr = 1;
  message.value = trionet::q32_to_decimal(value);
  CHECK(node1.send_to_node(4, message) == can::send_status::ok);
  const std::uint8_t expected[8] = {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0D, 0x7A};
  CHECK(wire.sent == 1 && wire.last.id == 0x028 && wire.last.dlc == 8 && equal(wire.last.data, expected, 8));
  const can::receive_result received = node4.receive(wire.last);
  CHECK(received.status == can::receive_status::ok);
  CHECK(received.sender == 1 && received.receive_channel == 1);
  CHECK(vr4[1] == (std::int64_t{2} << 32) + 1481763717);  // 2.3450 rounded to the nearest 2^-32
  CHECK(node1.receive(wire.last).status == can::receive_status::foreign);
}

void can_conversions() {
  group("CAN decimal <-> Q32.32 in 32-bit arithmetic, checked against 64-bit arithmetic");
  unsigned wrong = 0;
  const std::uint32_t scale = *opaque(&can_scale);
  for (std::uint32_t t = 0; t < scale; ++t) {  // every ten-thousandth to Q32.32
    const trionet::q32_result q = trionet::q32_from_decimal({false, 3, static_cast<std::uint16_t>(t)});
    const std::uint64_t fraction = ((std::uint64_t{t} << 32) + scale / 2) / scale;
    if (!q || static_cast<std::uint64_t>(q.raw) != ((std::uint64_t{3} << 32) | fraction)) ++wrong;
  }
  CHECK(wrong == 0);
  wrong = 0;
  for (std::uint64_t k = 0; k < scale;
       ++k) {  // Q32.32 to the nearest ten-thousandth, either side of each tie
    const std::uint64_t tie = ((2 * k + 1) << 32) / (2 * scale);
    for (std::uint64_t f = tie - 1; f <= tie + 1; ++f) {
      const trionet::can::vr_value v = trionet::q32_to_decimal(static_cast<std::int64_t>(f));
      const std::uint64_t nearest = (f * scale + (1ULL << 31)) >> 32;
      const std::uint64_t got = v.integer_part == 1 ? scale : v.fraction;
      if (got != nearest) ++wrong;
    }
  }
  CHECK(wrong == 0);
}

/// Wires two ring nodes back to back (a's transmitter to b's receiver and b's to a's) and moves bytes until
/// neither has anything to send, at most `limit` bytes. `corrupt_at` (if not 0) flips bit 0 of the byte with
/// that number on the way from a to b. Returns the number of bytes moved.
unsigned exchange(trionet::byte_port& a, trionet::byte_port& b, unsigned corrupt_at = 0,
                  unsigned limit = 2000) {
  unsigned moved = 0;
  unsigned from_a = 0;
  std::uint8_t byte = 0;
  while (moved < limit) {
    bool any = false;
    if (a.transmit(byte)) {
      if (++from_a == corrupt_at) byte ^= 0x01;
      b.receive(byte);
      any = true;
      ++moved;
    }
    if (b.transmit(byte)) {
      a.receive(byte);
      any = true;
      ++moved;
    }
    if (!any) break;
  }
  return moved;
}

/// Reads every waiting character with GET#4 into `text` (at most `size`); returns how many.
template <class Node>
std::size_t read_all(Node& node, std::uint8_t* text, std::size_t size) {
  std::size_t length = 0;
  while (length < size && node.key(4)) text[length++] = node.get(4).value;
  return length;
}

const std::uint8_t hello[5] = {'H', 'E', 'L', 'L', 'O'};

template <class CrcA, class CrcB, class Layout = ring::default_variable_layout>
void two_motion_coordinators(const char* name) {
  group(name);
  trionet::vr_table<256> vr_a;
  trionet::vr_table<256> vr_b;
  ring::motion_coordinator<256, 48, 48, ring::default_max_characters, CrcA, Layout> a(vr_a);
  ring::motion_coordinator<256, 48, 48, ring::default_max_characters, CrcB, Layout> b(vr_b);

  // SEND(10,1,200,99) and PRINT #10,"HELLO": a ring of two, so address 10 (one hop) is the other node.
  const double value = *opaque(&golden_frame[1]) == 0x48 ? 99.0 : 0.0;
  CHECK(a.send_variable(10, 200, value) == ring::send_status::ok);
  CHECK(a.print(10, trionet::byte_view(opaque(hello), sizeof hello)).status == ring::send_status::ok);
  CHECK(exchange(a, b) == 16 + 7);
  CHECK(vr_b[200] == 99.0);
  CHECK(b.counters().variables_written == 1);
  CHECK(b.key(4));
  std::uint8_t text[16] = {};
  CHECK(read_all(b, text, sizeof text) == 5 && equal(text, hello, 5));
  CHECK(!b.key(4));
  CHECK(a.netstat() == 0 && b.netstat() == 0);

  // PRINT #11 from b: two hops round a ring of two comes back to b; a forwards it with A decremented.
  CHECK(b.print(11, "OK").status == ring::send_status::ok);
  CHECK(exchange(b, a) == 4 + 4);
  CHECK(a.forwarding_counters().messages_forwarded == 1);
  CHECK(!a.key(4));
  CHECK(read_all(b, text, sizeof text) == 2 && text[0] == 'O' && text[1] == 'K');

  // A byte corrupted on the fibre: a CRC error at the destination, NETSTAT bit 2, VR(201) not written.
  CHECK(a.send_variable(10, 201, 5.25) == ring::send_status::ok);
  exchange(a, b, 8);
  CHECK(vr_b[201] == 0.0);
  CHECK((b.netstat() & ring::netstat_rx_crc_error) != 0);
  CHECK(b.counters().crc_errors == 1);
  b.clear_netstat();
  CHECK(b.netstat() == 0);
}

void motion_coordinator_and_keypad() {
  group("two-node ring: Motion Coordinator and keypad (keypad offset, key press, GET#3, display)");
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  ring::keypad<> keypad;

  // In local mode the keypad sends nothing. SEND(10,2,10) puts it in network mode with its keys going one hop
  // along, which in a ring of two is the MC.
  CHECK(keypad.press(ring::key::yes) == ring::key_status::local_mode);
  CHECK(mc.send_keypad_offset(10, 10) == ring::send_status::ok);
  exchange(mc, keypad);
  CHECK(keypad.network_mode());
  CHECK(keypad.offset() == 1);
  CHECK(keypad.press(ring::key::yes) == ring::key_status::ok);
  exchange(keypad, mc);
  CHECK(mc.key(3));
  const ring::get_result key = mc.get(3);
  CHECK(key && key.value == 13);  // 'Y' through DEFKEY
  CHECK(!mc.key(3));

  // PRINT #10 from the MC reaches the keypad's display.
  CHECK(mc.print(10, "RUN").status == ring::send_status::ok);
  exchange(mc, keypad);
  const char* line = keypad.display().line(0);
  CHECK(line[0] == 'R' && line[1] == 'U' && line[2] == 'N');
}

}  // namespace

extern "C" void HardFault_Handler() {
  semihosting::write("trionet-qemu-test: FAIL (hard fault)\n");
  semihosting::exit(2);
}

int main() {
  semihosting::write("trionet-qemu-test: start (Cortex-M3, lm3s6965evb)\n");
  crc_check_values();
  golden_encode();
  golden_decode();
  character_round_trip();
  decoder_errors();
  q32_values();
  two_motion_coordinators<ring::crc16_ccitt_false, ring::crc16_ccitt_false>(
      "two-node ring: two Motion Coordinators (SEND, PRINT#, forwarding, corrupted byte)");
  two_motion_coordinators<ring::crc16_ccitt_false_bitwise, ring::crc16_ccitt_false>(
      "two-node ring: table-free CRC node to table CRC node");
  motion_coordinator_and_keypad();
#if TRIONET_QEMU_TEST_CUSTOM_CRC
  // The CRC is configurable (docs/protocol.md 1.3), so two nodes that both use another polynomial must still
  // exchange variables (the regression test, on the core, for nodes that sent with the default CRC).
  using crc16_arc_polynomial = ring::crc16<0x8005, 0x0000, 0, ring::crc_table::none>;
  two_motion_coordinators<crc16_arc_polynomial, crc16_arc_polynomial>(
      "two-node ring: both nodes with a non-default CRC (poly 0x8005, init 0)");
  // A profile's other choices: a reflected CRC and each field's most significant group first.
  using crc16_modbus = ring::crc16<0x8005, 0xFFFF, 0, ring::crc_table::lookup, true, true>;
  using most_significant_first = ring::variable_layout<ring::group_order::most_significant_first,
                                                       ring::group_order::most_significant_first>;
  two_motion_coordinators<crc16_modbus, crc16_modbus, most_significant_first>(
      "two-node ring: reflected CRC (CRC-16/MODBUS), most significant group first");
#endif
  can_example();
  can_conversions();

  semihosting::write_unsigned(checks_run);
  semihosting::write(" checks, ");
  semihosting::write_unsigned(checks_failed);
  semihosting::write(" failed\n");
  if (checks_failed != 0 || checks_run == 0) {
    semihosting::write("trionet-qemu-test: FAIL\n");
    semihosting::exit(1);
  }
  semihosting::write("trionet-qemu-test: PASS\n");
  semihosting::exit(0);
}
