// The emulated Cortex-M3 test: runs trionet on a real Arm core (qemu-system-arm -M lm3s6965evb) and reports
// to the host through semihosting. scripts/firmware-qemu-test runs it.
//
// Output: one line per group, "FAIL ..." for each failed check, then "trionet-qemu-test: PASS" or
// "trionet-qemu-test: FAIL"; qemu exits with 0 on pass, 1 on a failed check, 2 on a fault.
// With TRIONET_QEMU_TEST_INJECT_FAILURE=1 one deliberately wrong check is added: that image must fail.
#include <cstddef>
#include <cstdint>

#include "semihosting.hpp"
#include "trionet/ring.hpp"

#ifndef TRIONET_QEMU_TEST_INJECT_FAILURE
#define TRIONET_QEMU_TEST_INJECT_FAILURE 0
#endif

namespace {

namespace ring = trionet::ring;

unsigned checks_run = 0;
unsigned checks_failed = 0;

void write_unsigned(unsigned value) {
  char text[12];
  char* p = text + sizeof text;
  *--p = '\0';
  do {
    *--p = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  semihosting::write(p);
}

void check(bool ok, const char* what, unsigned line) {
  ++checks_run;
  if (ok) return;
  ++checks_failed;
  semihosting::write("FAIL line ");
  write_unsigned(line);
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

// PROTOCOL.md 1.3: hop 1, vr 200, value 99.
constexpr std::uint8_t golden_frame[16] = {0x8a, 0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30,
                                           0x0c, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x3e, 0x88};
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
  const ring::encode_result table = ring::encode_variable(frame, 1, vr, ring::q32_from_integer(99));
  CHECK(table.error == ring::encode_error::none);
  CHECK(table.length == 16);
  CHECK(equal(frame, golden_frame, sizeof frame));

  std::uint8_t frame_bitwise[16] = {};
  const ring::encode_result bitwise = ring::encode_variable<ring::crc16_ccitt_false_bitwise>(
      frame_bitwise, 1, vr, ring::q32_from_integer(99));
  CHECK(bitwise.length == 16);
  CHECK(equal(frame_bitwise, golden_frame, sizeof frame_bitwise));

  std::uint8_t small[15] = {0x55};
  const ring::encode_result too_small = ring::encode_variable(small, 1, vr, ring::q32_from_integer(99));
  CHECK(too_small.error == ring::encode_error::buffer_too_small);
  CHECK(small[0] == 0x55);  // untouched on error
  const ring::encode_result no_hops = ring::encode_variable(frame, 0, vr, 0);
  CHECK(no_hops.error == ring::encode_error::hops_out_of_range);
}

void golden_decode() {
  group("golden example: decode, table and table-free CRC");
  const std::uint8_t* bytes = opaque(golden_frame);
  unsigned reports = 0;
  ring::decoder<> table;
  ring::decode_result result = feed(table, bytes, sizeof golden_frame, reports);
  CHECK(reports == 1);
  CHECK(result.status == ring::decode_status::message);
  CHECK(result.msg.type == ring::message_type::variable);
  CHECK(result.msg.hops == 1);
  CHECK(result.msg.vr == 200);
  CHECK(result.msg.value == ring::q32_from_integer(99));

  ring::decoder<ring::default_max_characters, ring::crc16_ccitt_false_bitwise> bitwise;
  result = feed(bitwise, bytes, sizeof golden_frame, reports);
  CHECK(reports == 1);
  CHECK(result.status == ring::decode_status::message);
  CHECK(result.msg.vr == 200);
  CHECK(result.msg.value == ring::q32_from_integer(99));
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
  CHECK(result.status == ring::decode_status::message);
  CHECK(result.msg.type == ring::message_type::character);
  CHECK(result.msg.hops == 3);
  CHECK(result.msg.text.size() == 5 &&
        equal(result.msg.text.data(), reinterpret_cast<const std::uint8_t*>("HELLO"), 5));
  std::uint8_t bad[4] = {};
  const std::uint8_t high[1] = {0x80};
  CHECK(ring::encode_characters(bad, 1, trionet::byte_view(high)).error ==
        ring::encode_error::character_out_of_range);
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
  CHECK(reports == 1 && result.status == ring::decode_status::message && result.msg.vr == 200);

  // A header inside an open message: the first message is lost, the second one decodes.
  ring::decoder<> interrupted;
  const std::uint8_t cut[3] = {0x8a, 0x48, 0x01};
  result = feed(interrupted, opaque(cut), sizeof cut, reports);
  CHECK(reports == 0);
  CHECK(interrupted.push(0x8a).error == ring::frame_error::interrupted);
  result = feed(interrupted, opaque(golden_frame) + 1, sizeof golden_frame - 1, reports);
  CHECK(reports == 1 && result.status == ring::decode_status::message);

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
  const ring::q32_result value = ring::q32_from_double(half);
  CHECK(value.error == ring::q32_error::none);
  CHECK(value.raw == 0x280000000LL);
  CHECK(ring::q32_to_double(value.raw) == 2.5);
  CHECK(ring::q32_from_double(half * 1e12).error == ring::q32_error::out_of_range);
  CHECK(ring::q32_from_raw(0xFFFFFFFFFFFFFFFFULL) == -1);
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

  write_unsigned(checks_run);
  semihosting::write(" checks, ");
  write_unsigned(checks_failed);
  semihosting::write(" failed\n");
  if (checks_failed != 0 || checks_run == 0) {
    semihosting::write("trionet-qemu-test: FAIL\n");
    semihosting::exit(1);
  }
  semihosting::write("trionet-qemu-test: PASS\n");
  semihosting::exit(0);
}
