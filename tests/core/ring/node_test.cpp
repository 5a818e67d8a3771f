// Ring nodes (docs/protocol.md 1.5-1.6): forwarding, delivery, the receive buffer, NETSTAT, and the
// simulator's fault injection. The keypad's own tests are in keypad_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
using trionet::byte_view;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;
using trionet::test::frame_of;
using trionet::test::read_all;

namespace {

using mc_node = ring::motion_coordinator<>;

void expect_same(const ring::print_result& a, const ring::print_result& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.queued, b.queued);
}

// Counter snapshots (plain structs of 32-bit counters) compared whole.
template <class Counters>
bool same(const Counters& a, const Counters& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

// ---- forwarding ----

TEST(RingForwarding, DecrementsHopsInHeaderAndEndOfMessageAndKeepsData) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  feed(mc, chars(3, "HELLO"));
  EXPECT_EQ(drain(mc), chars(2, "HELLO"));
  EXPECT_FALSE(mc.key(4));  // re-transmission is invisible to the program
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 1u);
}

TEST(RingForwarding, IsCutThrough) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  std::uint8_t b = 0;
  mc.receive(ring::make_header(5, 1));
  ASSERT_TRUE(mc.transmit(b));  // the header goes out before the message has ended
  EXPECT_EQ(b, ring::make_header(4, 1));
  EXPECT_FALSE(mc.transmit(b));  // waiting for the next byte
  mc.receive('A');
  ASSERT_TRUE(mc.transmit(b));
  EXPECT_EQ(b, 'A');
  mc.receive(ring::make_end_of_message(5));
  ASSERT_TRUE(mc.transmit(b));
  EXPECT_EQ(b, ring::make_end_of_message(4));
}

TEST(RingForwarding, ForwardedTrafficGoesBeforeOwnAtMessageBoundaries) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  const auto forwarded = chars(2, "FW");
  feed(mc, forwarded);
  ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);
  std::vector<std::uint8_t> expected = chars(1, "FW");
  const auto own = chars(1, "OWN");
  expected.insert(expected.end(), own.begin(), own.end());
  EXPECT_EQ(drain(mc), expected);
}

TEST(RingForwarding, NeverInterleavesTwoMessages) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  ASSERT_EQ(mc.print(10, "OWN MESSAGE").status, ring::send_status::ok);
  std::vector<std::uint8_t> sent;
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));  // own message has begun
  sent.push_back(b);
  // A forwarded message arrives while the own message is going out: it is buffered, not interleaved.
  for (std::uint8_t x : chars(3, "FORWARD")) {
    mc.receive(x);
    if (mc.transmit(b)) sent.push_back(b);
  }
  const auto rest = drain(mc);
  sent.insert(sent.end(), rest.begin(), rest.end());
  std::vector<std::uint8_t> expected = chars(1, "OWN MESSAGE");
  const auto fw = chars(2, "FORWARD");
  expected.insert(expected.end(), fw.begin(), fw.end());
  EXPECT_EQ(sent, expected);
}

TEST(RingForwarding, ForwardBufferOverflowLosesTheMessageAndSetsNetstatBit1) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<256, 16, 48> mc(vr);  // forward buffer of 16
  ASSERT_EQ(mc.print(10, "OWN MESSAGE 14").status, ring::send_status::ok);
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));  // own message has begun: forwarding must wait
  // Faster than the line could bring it (a burst from a host, say): 22 bytes for 16 places.
  feed(mc, chars(3, "THIS DOES NOT FIT"));
  EXPECT_EQ(mc.netstat() & ring::netstat_tx_buffer_error, ring::netstat_tx_buffer_error);
  EXPECT_EQ(mc.forwarding_counters().forwards_lost, 1u);
  // A message after the lost one is forwarded normally.
  feed(mc, chars(3, "OK"));
  std::vector<std::uint8_t> expected = chars(1, "OWN MESSAGE 14");
  expected.erase(expected.begin());  // the header already went out
  const auto ok = chars(2, "OK");
  expected.insert(expected.end(), ok.begin(), ok.end());
  EXPECT_EQ(drain(mc), expected);
}

TEST(RingForwarding, AForwardedMessageCutShortUpstreamDoesNotBlockTheNode) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  mc.receive(ring::make_header(3, 1));
  mc.receive('X');
  // The end of message is lost; a message for this node arrives instead.
  feed(mc, chars(1, "ME"));
  ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);
  std::vector<std::uint8_t> expected = {ring::make_header(2, 1), 'X'};
  const auto own = chars(1, "OWN");
  expected.insert(expected.end(), own.begin(), own.end());
  EXPECT_EQ(drain(mc), expected);
  EXPECT_EQ(read_all(mc, 4), "ME");
}

// The ways bytes reach a node: one at a time (a UART interrupt), all in one bulk call (a DMA buffer), or in
// bulk pieces of 5.
enum class arrival { byte_by_byte, bulk, bulk_in_pieces };

template <class Node>
void arrive(Node& node, const std::vector<std::uint8_t>& bytes, arrival how) {
  if (how == arrival::byte_by_byte) return feed(node, bytes);
  const std::size_t piece = how == arrival::bulk ? bytes.size() : 5;
  for (std::size_t at = 0; at < bytes.size(); at += piece)
    node.receive(byte_view(bytes.data() + at, std::min(piece, bytes.size() - at)));
}

// While a node sends its own message, forwarded bytes wait in the forward buffer. Bytes can come faster than
// the node sends (a host that reads a burst, a transmitter held up): a forwarded message that overruns the
// forward buffer then is lost whole (none of it has gone out), counted, NETSTAT bit 1; the rest of it,
// its end of message included, is dropped, and the next message is forwarded as usual.
TEST(RingForwarding, AMessageThatOverrunsTheForwardBufferDuringAnOwnMessageIsLostWhole) {
  for (const arrival how : {arrival::byte_by_byte, arrival::bulk, arrival::bulk_in_pieces}) {
    SCOPED_TRACE(static_cast<int>(how));
    trionet::vr_table<16> vr;
    mc_node mc(vr);  // forward buffer of 16 bytes
    ASSERT_EQ(mc.print(10, "OWN MESSAGE 14").status, ring::send_status::ok);
    std::uint8_t b = 0;
    ASSERT_TRUE(mc.transmit(b));  // the own message has begun
    std::vector<std::uint8_t> burst = chars(3, "SEVENTEEN LETTERS");  // header + 15 fit, the 16th does not
    const auto next = chars(3, "NEXT");
    burst.insert(burst.end(), next.begin(), next.end());
    arrive(mc, burst, how);
    EXPECT_EQ(mc.forwarding_counters().forwards_lost, 1u);
    EXPECT_EQ(mc.forwarding_counters().forwards_cut, 0u);
    EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 2u);
    EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
    EXPECT_EQ(mc.counters().frame_errors, 0u);  // its dropped end of message is no stray end of message
    std::vector<std::uint8_t> expected = chars(1, "OWN MESSAGE 14");
    expected.erase(expected.begin());  // the header already went out
    const auto next_on = chars(2, "NEXT");
    expected.insert(expected.end(), next_on.begin(), next_on.end());
    EXPECT_EQ(drain(mc), expected);
  }
}

// The same when the message's data just fit and its end of message is the byte that finds the forward buffer
// full: the message is lost whole, not sent on without its end. That end of message ends it: the node is
// between messages again (it used to stay inside the lost message up to the next control byte, reporting
// `in_message()` and dropping the stray data after it uncounted).
TEST(RingForwarding, AnEndOfMessageThatFindsTheForwardBufferFullLosesTheMessageWhole) {
  for (const arrival how : {arrival::byte_by_byte, arrival::bulk, arrival::bulk_in_pieces}) {
    SCOPED_TRACE(static_cast<int>(how));
    trionet::vr_table<16> vr;
    mc_node mc(vr);
    ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);
    std::uint8_t b = 0;
    ASSERT_TRUE(mc.transmit(b));
    arrive(mc, chars(4, "FIFTEEN LETTERS"), how);  // header + 15 data: exactly 16, then its end of message
    EXPECT_EQ(mc.forwarding_counters().forwards_lost, 1u);
    EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
    EXPECT_FALSE(mc.in_message());
    arrive(mc, {'X'}, how);  // a stray data byte after it: outside any message, a frame error
    EXPECT_EQ(mc.counters().frame_errors, 1u);
    arrive(mc, chars(2, "ON"), how);
    std::vector<std::uint8_t> expected = chars(1, "OWN");
    expected.erase(expected.begin());
    const auto next_on = chars(1, "ON");
    expected.insert(expected.end(), next_on.begin(), next_on.end());
    EXPECT_EQ(drain(mc), expected);
    EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 2u);
  }
}

// A header that finds the forward buffer full loses only its own message: the messages before it, which ended
// with room to spare for their bound, stay whole in the buffer (byte by byte and in bulk).
TEST(RingForwarding, AHeaderThatFindsTheForwardBufferFullLosesOnlyItsOwnMessage) {
  for (const arrival how : {arrival::byte_by_byte, arrival::bulk, arrival::bulk_in_pieces}) {
    SCOPED_TRACE(static_cast<int>(how));
    trionet::vr_table<16> vr;
    ring::motion_coordinator<256, 64, 32> mc(vr);  // a forward buffer of 64 bytes
    ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);
    std::uint8_t b = 0;
    ASSERT_TRUE(mc.transmit(b));  // the own message has begun: what arrives now waits
    const auto first = chars(3, std::string(40, 'a'));   // 42 bytes
    const auto second = chars(3, std::string(20, 'b'));  // 22 bytes: the buffer is full after it
    std::vector<std::uint8_t> burst = first;
    burst.insert(burst.end(), second.begin(), second.end());
    const auto third = chars(3, "LOST");
    burst.insert(burst.end(), third.begin(), third.end());
    arrive(mc, burst, how);
    EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 3u);
    EXPECT_EQ(mc.forwarding_counters().forwards_lost, 1u);
    EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
    std::vector<std::uint8_t> expected = chars(1, "OWN");
    expected.erase(expected.begin());  // the header already went out
    for (const auto& passed : {chars(2, std::string(40, 'a')), chars(2, std::string(20, 'b'))})
      expected.insert(expected.end(), passed.begin(), passed.end());
    EXPECT_EQ(drain(mc), expected);
  }
}

// A forwarded message that has partly gone out when the forward buffer overflows is cut short: what went out
// stays out, the rest is dropped (its destination sees a frame error).
TEST(RingForwarding, AMessagePartlySentWhenTheForwardBufferOverflowsIsCutShort) {
  for (const arrival how : {arrival::byte_by_byte, arrival::bulk, arrival::bulk_in_pieces}) {
    SCOPED_TRACE(static_cast<int>(how));
    trionet::vr_table<16> vr;
    mc_node mc(vr);
    arrive(mc, {ring::make_header(3, 1), 'A', 'B'}, how);
    std::vector<std::uint8_t> sent = drain(mc);  // cut-through: its header and data so far are out
    ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);  // waits for the forwarded message
    std::vector<std::uint8_t> rest(20, 'C');  // 20 more data bytes at once: 16 fit
    rest.push_back(ring::make_end_of_message(3));
    arrive(mc, rest, how);
    EXPECT_EQ(mc.forwarding_counters().forwards_lost, 1u);
    const auto more = drain(mc);
    sent.insert(sent.end(), more.begin(), more.end());
    std::vector<std::uint8_t> expected = {ring::make_header(2, 1), 'A', 'B'};
    expected.insert(expected.end(), 16, 'C');  // what fitted went on; no end of message
    const auto own = chars(1, "OWN");
    expected.insert(expected.end(), own.begin(), own.end());
    EXPECT_EQ(sent, expected);
  }
}

// ---- delivery at a Motion Coordinator ----

TEST(RingMotionCoordinator, KeyAndGetWithDefkey) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  EXPECT_FALSE(mc.key(3));
  EXPECT_EQ(mc.get(4).status, ring::get_status::nothing_yet);
  feed(mc, chars(1, "U5"));
  EXPECT_TRUE(mc.key(3));
  EXPECT_TRUE(mc.key(4));
  EXPECT_FALSE(mc.key(2));
  EXPECT_EQ(mc.characters_waiting(), 2u);  // KEY# consumes nothing
  EXPECT_EQ(mc.get(3).value, 10);          // 'U' through DEFKEY: up = 10
  EXPECT_EQ(mc.get(3).value, 5);           // '5' -> 5
  EXPECT_FALSE(mc.get(3));
  feed(mc, chars(1, "U"));
  EXPECT_EQ(mc.get(4).value, 'U');  // GET#4 is raw
  EXPECT_EQ(mc.get(7).status, ring::get_status::bad_channel);
}

TEST(RingMotionCoordinator, DefaultDefkeyTranslatesTheKeypadCodes) {
  const std::pair<char, int> table[] = {{'0', 0},  {'9', 9},  {'U', 10}, {'D', 11}, {'C', 12},  {'Y', 13},
                                        {'N', 14}, {'.', 15}, {'S', 20}, {'T', 21}, {'A', 'A'}, {'x', 'x'}};
  for (const auto& [raw, value] : table)
    EXPECT_EQ(ring::default_defkey[static_cast<std::uint8_t>(raw)], value) << raw;
}

TEST(RingMotionCoordinator, ConfigurableDefkey) {
  ring::defkey_table mine = ring::default_defkey;
  mine.value[static_cast<std::uint8_t>('A')] = 99;
  trionet::vr_table<16> vr;
  mc_node mc(vr, mine);
  feed(mc, chars(1, "A"));
  EXPECT_EQ(mc.get(3).value, 99);
}

TEST(RingMotionCoordinator, DirectVariableTransferWritesVr) {
  trionet::vr_table<256> vr;
  mc_node mc(vr);
  feed(mc, frame_of(ring::message::variable(1, 200, trionet::q32_from_integer(99))));
  EXPECT_EQ(vr[200], 99.0);
  EXPECT_EQ(mc.counters().variables_written, 1u);
  EXPECT_FALSE(mc.key(4));  // not a character
}

TEST(RingMotionCoordinator, WritePolicyRefusesAndOutOfRangeIsCounted) {
  auto read_only_below_10 = [](void*, std::uint16_t vr, double) noexcept { return vr >= 10; };
  trionet::vr_table<64> vr(read_only_below_10);
  mc_node mc(vr);
  feed(mc, frame_of(ring::message::variable(1, 5, trionet::q32_from_integer(1))));
  feed(mc, frame_of(ring::message::variable(1, 20, trionet::q32_from_integer(2))));
  feed(mc, frame_of(ring::message::variable(1, 64, trionet::q32_from_integer(3))));
  EXPECT_EQ(vr[5], 0.0);
  EXPECT_EQ(vr[20], 2.0);
  EXPECT_EQ(mc.counters().variables_refused, 1u);
  EXPECT_EQ(mc.counters().variables_written, 1u);
  EXPECT_EQ(mc.counters().variables_out_of_range, 1u);
}

// A store that cannot hold a value says so (`value_out_of_range`), and the MC counts that apart from a vr
// past the table.
TEST(RingMotionCoordinator, ValueOutOfRangeIsNotFoldedIntoOutOfRange) {
  class small_values final : public trionet::vr_store {  // holds VR(0..9), values below 1000 only
   public:
    trionet::vr_write_status write(std::uint16_t vr, const trionet::network_value& value) noexcept override {
      if (vr >= 10) return trionet::vr_write_status::out_of_range;
      if (value.to_double() >= 1000.0) return trionet::vr_write_status::value_out_of_range;
      return trionet::vr_write_status::ok;
    }
  } store;
  mc_node mc(store);
  feed(mc, frame_of(ring::message::variable(1, 5, trionet::q32_from_integer(1000))));
  EXPECT_EQ(mc.counters().variables_value_out_of_range, 1u);
  EXPECT_EQ(mc.counters().variables_out_of_range, 0u);
  feed(mc, frame_of(ring::message::variable(1, 10, trionet::q32_from_integer(1))));
  EXPECT_EQ(mc.counters().variables_out_of_range, 1u);
  EXPECT_EQ(mc.counters().variables_value_out_of_range, 1u);
  feed(mc, frame_of(ring::message::variable(1, 5, trionet::q32_from_integer(999))));
  EXPECT_EQ(mc.counters().variables_written, 1u);
}

TEST(RingMotionCoordinator, CrcErrorSetsNetstatBit2AndDoesNotWrite) {
  trionet::vr_table<256> vr;
  mc_node mc(vr);
  auto frame = frame_of(ring::message::variable(1, 200, trionet::q32_from_integer(99)));
  frame[8] ^= 0x01;
  feed(mc, frame);
  EXPECT_EQ(vr[200], 0.0);
  EXPECT_EQ(mc.netstat(), ring::netstat_rx_crc_error);
  EXPECT_EQ(mc.counters().crc_errors, 1u);
}

TEST(RingMotionCoordinator, FrameErrorSetsNetstatBit3AndNetstatClearsOnlyWhenAsked) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  feed(mc, {ring::make_header(1, 1), 'A', ring::make_end_of_message(2)});  // EOM mismatch
  EXPECT_EQ(mc.netstat(), ring::netstat_rx_frame_error);
  feed(mc, chars(1, "OK"));
  EXPECT_EQ(mc.netstat(), ring::netstat_rx_frame_error);  // stays set
  EXPECT_EQ(read_all(mc, 4), "OK");
  mc.clear_netstat();
  EXPECT_EQ(mc.netstat(), 0);
  EXPECT_EQ(mc.counters().frame_errors, 1u);
}

TEST(RingMotionCoordinator, InterruptedLocalMessageIsAFrameError) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  feed(mc, {ring::make_header(1, 1), 'A', 'B'});
  feed(mc, chars(4, "PASSING"));  // a header for another node interrupts the message for us
  EXPECT_EQ(mc.counters().frame_errors, 1u);
  EXPECT_FALSE(mc.key(4));  // nothing of the broken message was kept
}

TEST(RingMotionCoordinator, ReceiveBufferIsAllOrNothingPerMessage) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<8> mc(vr);  // 8-character receive buffer
  feed(mc, chars(1, "ABCDE"));
  feed(mc, chars(1, "FGHI"));  // does not fit in the 3 free: dropped whole
  EXPECT_EQ(mc.netstat(), ring::netstat_rx_overflow);
  EXPECT_EQ(mc.counters().receive_overflows, 1u);
  EXPECT_EQ(mc.characters_waiting(), 5u);
  feed(mc, chars(1, "XYZ"));  // fits exactly
  EXPECT_EQ(read_all(mc, 4), "ABCDEXYZ");
  feed(mc, chars(1, "12345678"));  // a whole buffer, after GET freed it (and wraps round)
  EXPECT_EQ(read_all(mc, 4), "12345678");
  feed(mc, chars(1, "123456789"));  // longer than the buffer can ever hold: dropped whole, counted
  EXPECT_EQ(mc.counters().receive_overflows, 2u);
  EXPECT_EQ(mc.counters().frame_errors, 0u);
  EXPECT_EQ(mc.characters_waiting(), 0u);
}

// The character maximum (docs/protocol.md 1.4, default 256) is not the receive buffer's size: a longer message is a
// frame error (bad length), whatever the buffer.
TEST(RingMotionCoordinator, LongerThanTheCharacterMaximumIsABadLength) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  feed(mc, chars(1, std::string(256, 'a')));
  EXPECT_EQ(mc.characters_waiting(), 256u);
  EXPECT_EQ(read_all(mc, 4), std::string(256, 'a'));
  feed(mc, chars(1, std::string(257, 'b')));
  EXPECT_EQ(mc.counters().frame_errors, 1u);
  EXPECT_EQ(mc.characters_waiting(), 0u);
  ring::motion_coordinator<256, 32, 32, 40> forty(vr);  // a maximum of 40
  feed(forty, chars(1, std::string(41, 'c')));
  EXPECT_EQ(forty.counters().frame_errors, 1u);
  EXPECT_EQ(forty.counters().receive_overflows, 0u);
}

TEST(RingMotionCoordinator, KeypadMessagesAreIgnoredAndCounted) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  feed(mc, frame_of(ring::message::keypad_offset(1, 3)));
  feed(mc, frame_of(ring::message::keypad_mode(1, 127)));
  EXPECT_EQ(mc.counters().keypad_messages_ignored, 2u);
  EXPECT_EQ(mc.netstat(), 0);
}

TEST(RingMotionCoordinator, SendCallsRejectOutOfRangeBeforeQueuingAByte) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  EXPECT_EQ(mc.print(9, "X").status, ring::send_status::bad_address);
  EXPECT_EQ(mc.print(25, "X").status, ring::send_status::bad_address);
  EXPECT_EQ(mc.print(10, "").status, ring::send_status::empty_text);
  EXPECT_EQ(mc.print(10, "caf\xc3\xa9").status, ring::send_status::character_out_of_range);
  EXPECT_EQ(mc.send_variable(10, 16384, 1.0), ring::send_status::vr_out_of_range);
  EXPECT_EQ(mc.send_variable(10, 1, 3e9), ring::send_status::value_out_of_range);
  EXPECT_EQ(mc.send_variable(10, 16384, 3e9), ring::send_status::vr_out_of_range);  // address, vr, value
  EXPECT_EQ(mc.send_variable(9, 16384, 3e9), ring::send_status::bad_address);
  EXPECT_EQ(mc.send_variable(8, 1, 1.0), ring::send_status::bad_address);
  EXPECT_EQ(mc.send_keypad_offset(10, 9), ring::send_status::offset_out_of_range);
  EXPECT_EQ(mc.send_keypad_offset(10, 25), ring::send_status::offset_out_of_range);
  EXPECT_EQ(mc.send_keypad_mode(10, 1), ring::send_status::mode_out_of_range);
  EXPECT_FALSE(mc.transmit_pending());
  EXPECT_EQ(mc.netstat(), 0);
  EXPECT_EQ(mc.transmit_free(), 32u);
}

TEST(RingMotionCoordinator, SendMapsBasicAddressesAndTypes) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  ASSERT_EQ(mc.send_keypad_offset(12, 12), ring::send_status::ok);  // SEND(10+2,2,10+2)
  EXPECT_EQ(drain(mc), frame_of(ring::message::keypad_offset(3, 3)));
  ASSERT_EQ(mc.send_variable(10, 200, 99), ring::send_status::ok);
  EXPECT_EQ(drain(mc), frame_of(ring::message::variable(1, 200, trionet::q32_from_integer(99))));
  ASSERT_EQ(mc.send_keypad_mode(24, 127), ring::send_status::ok);
  EXPECT_EQ(drain(mc), frame_of(ring::message::keypad_mode(15, 127)));
}

// Regression: the node's own direct variable transfers used the default CRC whatever the node's policy.
TEST(RingMotionCoordinator, SendsWithItsOwnCrcPolicy) {
  using xmodem = ring::crc16<0x1021, 0x0000>;
  trionet::vr_table<256> vr_a, vr_b;
  ring::motion_coordinator<256, 48, 48, ring::default_max_characters, xmodem> a(vr_a), b(vr_b);
  ASSERT_EQ(a.send_variable(10, 200, 99), ring::send_status::ok);
  const auto sent = drain(a);
  std::uint8_t expected[16];
  ASSERT_TRUE(ring::encode_variable<xmodem>(expected, 1, 200, trionet::q32_from_integer(99)));
  EXPECT_EQ(sent, std::vector<std::uint8_t>(expected, expected + 16));
  feed(b, sent);
  EXPECT_EQ(vr_b[200], 99.0);
  EXPECT_EQ(b.netstat(), 0);
  // The table-free variant sends the same bytes as the table one.
  ring::motion_coordinator<256, 48, 48, ring::default_max_characters, ring::crc16_ccitt_false_bitwise> c(vr_a);
  ASSERT_EQ(c.send_variable(10, 200, 99), ring::send_status::ok);
  EXPECT_EQ(drain(c), frame_of(ring::message::variable(1, 200, trionet::q32_from_integer(99))));
}

// Every send_status and get_status has its enumerator's spelling (the CLI and the traces print them).
TEST(RingMotionCoordinator, StatusNamesAreTheEnumeratorsSpelling) {
  using ring::send_status;
  const std::pair<send_status, const char*> sends[] = {
      {send_status::ok, "ok"},
      {send_status::bad_address, "bad_address"},
      {send_status::empty_text, "empty_text"},
      {send_status::character_out_of_range, "character_out_of_range"},
      {send_status::vr_out_of_range, "vr_out_of_range"},
      {send_status::value_out_of_range, "value_out_of_range"},
      {send_status::offset_out_of_range, "offset_out_of_range"},
      {send_status::mode_out_of_range, "mode_out_of_range"},
      {send_status::queue_full, "queue_full"}};
  for (const auto& [status, name] : sends) EXPECT_STREQ(ring::to_string(status), name);
  EXPECT_STREQ(ring::to_string(static_cast<send_status>(99)), "unknown");
  EXPECT_STREQ(ring::to_string(ring::get_status::ok), "ok");
  EXPECT_STREQ(ring::to_string(ring::get_status::nothing_yet), "nothing_yet");
  EXPECT_STREQ(ring::to_string(ring::get_status::bad_channel), "bad_channel");
  EXPECT_STREQ(ring::to_string(static_cast<ring::get_status>(99)), "unknown");
}

TEST(RingMotionCoordinator, FullTransmitQueueRefusesWholeAndSetsNetstatBit0) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<256, 48, 10> mc(vr);                  // 10-byte transmit queue
  ASSERT_EQ(mc.print(10, "123456").status, ring::send_status::ok);  // 8 bytes
  EXPECT_EQ(mc.print(10, "AB").status, ring::send_status::queue_full);  // needs 4, 2 free
  EXPECT_EQ(mc.netstat(), ring::netstat_tx_timeout);
  EXPECT_EQ(mc.counters().sends_refused, 1u);
  EXPECT_EQ(drain(mc), chars(1, "123456"));  // nothing partial was queued
  EXPECT_EQ(mc.print(10, "12345678").status, ring::send_status::ok);
}

// ---- keypad ----

// ---- simulator ----

TEST(RingSimulator, IsDeterministicAndCountsByteTimes) {
  auto run = [] {
    trionet::vr_table<16> vr0, vr1, vr2;
    mc_node a(vr0), b(vr1), c(vr2);
    ring::simulator<> sim;
    EXPECT_TRUE(sim.add(a));
    EXPECT_TRUE(sim.add(b));
    EXPECT_TRUE(sim.add(c));
    (void)a.print(11, "HELLO");
    std::string trace;
    sim.run(20, [&](const ring::link_byte& x) {
      trace += std::to_string(x.time) + ":" + std::to_string(x.link) + "=" + std::to_string(x.sent) + " ";
    });
    EXPECT_EQ(read_all(c, 4), "HELLO");
    return trace;
  };
  const std::string first = run();
  EXPECT_EQ(first, run());
  // 7 bytes on link 0 at t = 0..6, forwarded on link 1 one byte-time later.
  EXPECT_NE(first.find("0:0=145 "), std::string::npos);
  EXPECT_NE(first.find("1:1=137 "), std::string::npos);
  EXPECT_NE(first.find("7:1=136 "), std::string::npos);
}

TEST(RingSimulator, FlippedBitIsACrcErrorAtTheDestination) {
  trionet::vr_table<256> vr0, vr1;
  mc_node a(vr0), b(vr1);
  ring::simulator<> sim;
  (void)sim.add(a);
  (void)sim.add(b);
  ASSERT_EQ(a.send_variable(10, 200, 99), ring::send_status::ok);
  sim.run(5);
  sim.flip_next(0, 0x01);
  sim.run(20);
  EXPECT_EQ(vr1[200], 0.0);
  EXPECT_EQ(b.netstat(), ring::netstat_rx_crc_error);
}

TEST(RingSimulator, DroppedByteAndCutLink) {
  trionet::vr_table<16> vr0, vr1;
  mc_node a(vr0), b(vr1);
  ring::simulator<> sim;
  (void)sim.add(a);
  (void)sim.add(b);
  ASSERT_EQ(a.print(10, "ABC").status, ring::send_status::ok);
  sim.run(2);
  sim.drop_next(0);
  sim.run(10);
  EXPECT_EQ(read_all(b, 4), "AC");  // a lost data byte is not detectable for a character message
  sim.cut(0);
  ASSERT_EQ(a.print(10, "XYZ").status, ring::send_status::ok);
  int lost = 0;
  sim.run(10, [&](const ring::link_byte& x) { lost += x.delivered ? 0 : 1; });
  EXPECT_EQ(lost, 5);
  EXPECT_FALSE(b.key(4));
  sim.cut(0, false);
  ASSERT_EQ(a.print(10, "OK").status, ring::send_status::ok);
  sim.run(10);
  EXPECT_EQ(read_all(b, 4), "OK");
}

TEST(RingSimulator, ByteTimesToSeconds) {
  EXPECT_DOUBLE_EQ(ring::byte_times_to_seconds(1000, 10000.0), 1.0);
  EXPECT_DOUBLE_EQ(ring::byte_times_to_seconds(1, 125000.0, 10), 80e-6);
  ring::simulator<2> full;
  trionet::vr_table<1> vr;
  mc_node a(vr), b(vr), c(vr);
  EXPECT_FALSE(full.ready());
  EXPECT_TRUE(full.add(a));
  EXPECT_TRUE(full.add(b));
  EXPECT_FALSE(full.add(c));
  EXPECT_TRUE(full.ready());
}

// ---- RAM ----

TEST(RingNodeRam, DefaultCapacities) {
  const std::size_t mc = sizeof(mc_node);
  const std::size_t keypad = sizeof(ring::keypad<>);
  std::printf(
      "RAM with default capacities: motion_coordinator<> %zu bytes, keypad<> %zu bytes (host, %zu-bit)\n", mc,
      keypad, sizeof(void*) * 8);
  RecordProperty("motion_coordinator_bytes", static_cast<int>(mc));
  RecordProperty("keypad_bytes", static_cast<int>(keypad));
  // The buffers dominate: receive 256 + forward 32 + transmit 32 for an MC.
  EXPECT_GE(mc, 256u + 32u + 32u);
  EXPECT_LE(mc, 256u + 32u + 32u + 192u);
  EXPECT_LE(keypad, 256u + 16u + 16u + 45u + 160u);
}

TEST(RingForwarding, EveryReceivedMessageIsAccountedFor) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<256, 16, 48> mc(vr);
  std::vector<std::uint8_t> stream = chars(1, "LOCAL");
  for (auto part : {chars(3, "FORWARDED MESSAGE"), chars(2, "A MESSAGE TOO LONG FOR SIXTEEN"),
                    std::vector<std::uint8_t>{1, 2, 0x88}}) {
    stream.insert(stream.end(), part.begin(), part.end());
  }
  ASSERT_EQ(mc.print(10, "HOLD THE LINK").status, ring::send_status::ok);
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));
  feed(mc, stream);
  // Both forwarded messages overflow the forward buffer while the own frame holds the link; the local
  // message is taken; the stray data and the stray end of message are one frame error each.
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 2u);
  EXPECT_EQ(mc.forwarding_counters().forwards_lost, 2u);
  EXPECT_EQ(mc.counters().character_messages, 1u);
  EXPECT_EQ(mc.counters().frame_errors, 2u);
  EXPECT_EQ(read_all(mc, 4), "LOCAL");
}

TEST(RingMotionCoordinator, Q32TableAndSendWithoutFloatingPoint) {
  trionet::vr_table<256, std::int64_t> vr_a, vr_b;
  ring::motion_coordinator<> a(vr_a), b(vr_b);
  ASSERT_EQ(a.send_variable_q32(10, 200, trionet::q32_from_integer(99) + 1), ring::send_status::ok);
  EXPECT_EQ(a.send_variable_q32(10, 16384, 0), ring::send_status::vr_out_of_range);
  EXPECT_EQ(a.send_variable_q32(25, 1, 0), ring::send_status::bad_address);
  feed(b, drain(a));
  EXPECT_EQ(vr_b[200], trionet::q32_from_integer(99) + 1);  // exact: no double on the way
}

// Now and then, bytes outside any message between frames: stray data, or a header with A = 0 and its data.
void insert_junk(std::vector<std::uint8_t>& stream, std::mt19937_64& rng) {
  switch (rng() % 8) {
    case 0:
      for (std::uint64_t k = 1 + rng() % 3; k > 0; --k)
        stream.push_back(static_cast<std::uint8_t>(rng() % 128));
      break;
    case 1:
      stream.push_back(ring::make_header(0, static_cast<std::uint8_t>(1 + rng() % 4)));
      stream.push_back(0x20);
      break;
    default:
      break;
  }
}

// Regression: a message passing through the node ends the decoder's run of stray data (or its skipping of an
// A = 0 message), so stray data after it is a new frame error, in the bulk forms (whole, and in pieces of 3) as
// byte by byte.
TEST(RingMotionCoordinator, PassingMessageEndsStrayRunInEveryForm) {
  const std::vector<std::uint8_t> passing = chars(2, "THROUGH");
  std::vector<std::uint8_t> stray_then_passing = {0x41, 0x42};  // stray data
  stray_then_passing.insert(stray_then_passing.end(), passing.begin(), passing.end());
  stray_then_passing.push_back(0x43);  // stray data again: a second frame error
  std::vector<std::uint8_t> skipped_then_passing = {ring::make_header(0, 1), 0x41};  // A = 0: skipped
  skipped_then_passing.insert(skipped_then_passing.end(), passing.begin(), passing.end());
  skipped_then_passing.push_back(0x43);  // stray data: a frame error
  for (const auto& stream : {stray_then_passing, skipped_then_passing}) {
    trionet::vr_table<4> vr_one, vr_bulk, vr_pieces;
    ring::motion_coordinator<> one(vr_one), bulk(vr_bulk), pieces(vr_pieces);
    for (std::uint8_t b : stream) one.receive(b);
    bulk.receive(byte_view(stream.data(), stream.size()));
    for (std::size_t at = 0; at < stream.size(); at += 3)
      pieces.receive(byte_view(stream.data() + at, std::min<std::size_t>(3, stream.size() - at)));
    std::uint8_t out[64];
    const std::size_t sent = pieces.transmit(trionet::byte_buffer(out, 64));
    EXPECT_EQ(std::vector<std::uint8_t>(out, out + sent), drain(bulk));
    EXPECT_EQ(one.counters().frame_errors, 2u);  // stray data or A = 0 before, stray data after
    EXPECT_EQ(bulk.counters().frame_errors, one.counters().frame_errors);
    EXPECT_EQ(pieces.counters().frame_errors, one.counters().frame_errors);
  }
}

// The bulk transmit fills at most the buffer it is given (buffers of exactly `pull` bytes on the heap, so that
// the sanitizer build catches a write past them), and the bulk forms in random pieces give exactly what one
// byte at a time gives, over damaged streams with the node's own traffic now and then.
TEST(RingMotionCoordinator, BulkTransmitStaysInItsBufferAndMatchesByteAtATime) {
  std::mt19937_64 rng(2024);
  std::uint64_t forwarded = 0, lost = 0;
  for (int round = 0; round < 300; ++round) {
    std::vector<std::uint8_t> stream;
    for (int i = 0; i < 30; ++i) {
      const auto hops = static_cast<std::uint8_t>(1 + rng() % 3);
      std::vector<std::uint8_t> frame =
          rng() % 2 == 0 ? chars(hops, std::string(1 + rng() % 30, static_cast<char>('a' + rng() % 26)))
                         : frame_of(ring::message::variable(hops, static_cast<std::uint16_t>(rng() % 20),
                                                            static_cast<std::int64_t>(rng())));
      insert_junk(stream, rng);
      stream.insert(stream.end(), frame.begin(), frame.end());
    }
    for (int i = 0; i < 8; ++i) stream[rng() % stream.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
    trionet::vr_table<16> vr_one, vr_bulk;
    ring::motion_coordinator<64, 16, 24> one(vr_one), bulk(vr_bulk);
    std::vector<std::uint8_t> out_one, out_bulk;
    for (std::size_t at = 0; at < stream.size();) {
      const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 24);
      if (rng() % 4 == 0) {  // own traffic now and then
        const int address = 10 + static_cast<int>(rng() % 3);
        expect_same(one.print(address, "OWN"), bulk.print(address, "OWN"));
      }
      const std::size_t pull = rng() % 40;
      for (std::size_t i = 0; i < n; ++i) one.receive(stream[at + i]);
      std::uint8_t b = 0;
      for (std::size_t i = 0; i < pull && one.transmit(b); ++i) out_one.push_back(b);
      std::vector<std::uint8_t> buffer(pull);
      bulk.receive(byte_view(stream.data() + at, n));
      const std::size_t got = bulk.transmit(trionet::byte_buffer(buffer.data(), pull));
      ASSERT_LE(got, pull);
      out_bulk.insert(out_bulk.end(), buffer.begin(), buffer.begin() + static_cast<long>(got));
      ASSERT_EQ(out_one, out_bulk) << "round " << round << " at " << at;
      at += n;
    }
    EXPECT_EQ(drain(one), drain(bulk));
    EXPECT_EQ(one.netstat(), bulk.netstat());
    EXPECT_EQ(read_all(one, 4), read_all(bulk, 4));
    EXPECT_TRUE(same(one.forwarding_counters(), bulk.forwarding_counters()));
    EXPECT_TRUE(same(one.counters(), bulk.counters()));
    for (std::size_t v = 0; v < 16; ++v) EXPECT_EQ(vr_one[v], vr_bulk[v]);
    forwarded += one.forwarding_counters().messages_forwarded;
    lost += one.forwarding_counters().forwards_lost;
  }
  EXPECT_GT(forwarded, 1000u);  // forwarding was exercised...
  EXPECT_GT(lost, 10u);         // ... and so was the forward buffer overflowing
}

// The bulk forms (a DMA buffer in, a transmit buffer out) behave exactly as the byte-at-a-time forms.
TEST(RingMotionCoordinator, BulkReceiveAndTransmitMatchByteAtATime) {
  std::mt19937_64 rng(99);
  std::uint64_t lost = 0, forwarded_whole = 0;
  for (int round = 0; round < 200; ++round) {
    std::vector<std::uint8_t> stream;
    for (int i = 0; i < 30; ++i) {
      const auto hops = static_cast<std::uint8_t>(1 + rng() % 3);
      std::vector<std::uint8_t> frame;
      switch (rng() % 3) {
        case 0:
          frame = chars(hops, std::string(1 + rng() % 40, static_cast<char>('a' + rng() % 26)));
          break;
        case 1:
          frame = frame_of(ring::message::variable(hops, static_cast<std::uint16_t>(rng() % 20),
                                                   static_cast<std::int64_t>(rng())));
          break;
        default:
          frame = frame_of(ring::message::keypad_mode(hops, 127));
          break;
      }
      insert_junk(stream, rng);
      stream.insert(stream.end(), frame.begin(), frame.end());
    }
    for (int i = 0; i < 10; ++i)
      stream[rng() % stream.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
    trionet::vr_table<16> vr_one, vr_bulk;
    ring::motion_coordinator<64, 16, 24> one(vr_one), bulk(vr_bulk);
    std::vector<std::uint8_t> out_one, out_bulk;
    std::size_t at = 0;
    int step = 0;
    while (at < stream.size()) {
      const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 50);
      for (std::size_t i = 0; i < n; ++i) one.receive(stream[at + i]);
      bulk.receive(byte_view(stream.data() + at, n));
      at += n;
      if (++step % 3 == 0) {  // own traffic now and then
        const int address = 10 + static_cast<int>(rng() % 2);
        expect_same(one.print(address, "OWN"), bulk.print(address, "OWN"));
      }
      const std::size_t pull = rng() % 64;
      std::uint8_t b = 0;
      for (std::size_t i = 0; i < pull && one.transmit(b); ++i) out_one.push_back(b);
      std::uint8_t buffer[64];
      const std::size_t got = bulk.transmit(trionet::byte_buffer(buffer, pull));
      out_bulk.insert(out_bulk.end(), buffer, buffer + got);
      ASSERT_EQ(out_one, out_bulk) << "round " << round;
    }
    EXPECT_EQ(drain(one), drain(bulk));
    EXPECT_EQ(one.netstat(), bulk.netstat());
    EXPECT_EQ(read_all(one, 4), read_all(bulk, 4));
    // Every counter, the link's and the node's (plain structs of 32-bit counters: compared whole).
    EXPECT_TRUE(same(one.forwarding_counters(), bulk.forwarding_counters()));
    EXPECT_TRUE(same(one.counters(), bulk.counters()));
    lost += one.forwarding_counters().forwards_lost;
    forwarded_whole += one.forwarding_counters().messages_forwarded;
    for (std::size_t v = 0; v < 16; ++v) EXPECT_EQ(vr_one[v], vr_bulk[v]);
  }
  // The streams exercised forwarding and the loss of forwarded messages to a full forward buffer.
  EXPECT_GT(forwarded_whole, 1000u);
  EXPECT_GT(lost, 10u);
}

// A UART interrupt per byte (one byte in, then one out) at the library's default capacities, against the bulk
// forms a byte at a time and a bulk receive with a per-byte transmit: the forward buffer's grant running out
// at its end, forwarded ends of message and headers, over long character messages, headers that cut into an
// open grant, losses while the node's own messages go out, and damaged bytes.
TEST(RingMotionCoordinator, OneByteEachWayMatchesTheBulkForms) {
  std::mt19937_64 rng(7);
  std::uint64_t forwarded = 0, lost = 0, cut = 0;
  for (int round = 0; round < 100; ++round) {
    std::vector<std::uint8_t> stream;
    for (int i = 0; i < 24; ++i) {
      const auto hops = static_cast<std::uint8_t>(1 + rng() % 3);
      std::vector<std::uint8_t> frame;
      if (rng() % 2 == 0) {
        frame = chars(hops, std::string(1 + rng() % 120, static_cast<char>('a' + rng() % 26)));
      } else {
        frame = frame_of(ring::message::variable(hops, static_cast<std::uint16_t>(rng() % 16),
                                                 static_cast<std::int64_t>(rng())));
      }
      if (rng() % 6 == 0) frame.resize(frame.size() / 2);  // cut short: the next header ends it
      if (rng() % 8 == 0) frame.insert(frame.end() - 1, 20, 'x');  // longer than a variable transfer may be
      insert_junk(stream, rng);
      stream.insert(stream.end(), frame.begin(), frame.end());
    }
    for (int i = 0; i < 6; ++i) stream[rng() % stream.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
    trionet::vr_table<16> vr_one, vr_bulk, vr_mixed;
    ring::motion_coordinator<> one(vr_one), bulk(vr_bulk), mixed(vr_mixed);
    std::vector<std::uint8_t> out_one, out_bulk, out_mixed;
    for (std::size_t i = 0; i < stream.size(); ++i) {
      if (i % 97 == 0) {  // an own message now and then: forwarded bytes wait while it goes out
        const int address = 10 + static_cast<int>(rng() % 2);
        const ring::print_result printed = one.print(address, "OWN MESSAGE");
        expect_same(printed, bulk.print(address, "OWN MESSAGE"));
        expect_same(printed, mixed.print(address, "OWN MESSAGE"));
      }
      const bool pull = rng() % 8 != 0;  // now and then the transmitter is busy: a backlog builds up
      one.receive(stream[i]);
      std::uint8_t b = 0;
      if (pull && one.transmit(b)) out_one.push_back(b);
      bulk.receive(byte_view(&stream[i], 1));
      std::uint8_t buffer[1];
      if (pull && bulk.transmit(trionet::byte_buffer(buffer, 1)) == 1) out_bulk.push_back(buffer[0]);
      mixed.receive(byte_view(&stream[i], 1));
      if (pull && mixed.transmit(b)) out_mixed.push_back(b);
      ASSERT_EQ(out_one, out_bulk) << "round " << round << ", byte " << i;
      ASSERT_EQ(out_one, out_mixed) << "round " << round << ", byte " << i;
    }
    const auto rest = drain(one);
    EXPECT_EQ(rest, drain(bulk));
    EXPECT_EQ(rest, drain(mixed));
    EXPECT_EQ(one.netstat(), bulk.netstat());
    EXPECT_EQ(one.netstat(), mixed.netstat());
    const std::string text = read_all(one, 4);
    EXPECT_EQ(text, read_all(bulk, 4));
    EXPECT_EQ(text, read_all(mixed, 4));
    EXPECT_TRUE(same(one.forwarding_counters(), bulk.forwarding_counters()));
    EXPECT_TRUE(same(one.counters(), bulk.counters()));
    EXPECT_TRUE(same(one.forwarding_counters(), mixed.forwarding_counters()));
    EXPECT_TRUE(same(one.counters(), mixed.counters()));
    for (std::size_t v = 0; v < 16; ++v) {
      EXPECT_EQ(vr_one[v], vr_bulk[v]);
      EXPECT_EQ(vr_one[v], vr_mixed[v]);
    }
    forwarded += one.forwarding_counters().messages_forwarded;
    lost += one.forwarding_counters().forwards_lost;
    cut += one.forwarding_counters().forwards_cut;
  }
  // Forwarding, the loss of forwarded messages to a full forward buffer and the bound were all exercised.
  EXPECT_GT(forwarded, 1000u);
  EXPECT_GT(lost, 10u);
  EXPECT_GT(cut, 10u);
}
