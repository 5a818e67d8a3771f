// What a ring node's `receive` and `line_idle` answer for each byte (the fate of the message it ended, or
// `incomplete`), and `clear_counters`, which starts every count again from 0 (docs/design.md, "Results and
// counters"): the same shape as a CAN node's `receive` and `clear_counters`.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "support/ring_frames.hpp"
#include "support/rng.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
using ring::receive_status;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;
using trionet::test::frame_of;

namespace {

using mc_node = ring::motion_coordinator<>;

// The answer of each byte of `bytes`, fed one at a time.
template <class Node>
std::vector<receive_status> answers(Node& node, const std::vector<std::uint8_t>& bytes) {
  std::vector<receive_status> out;
  for (std::uint8_t b : bytes) out.push_back(node.receive(b));
  return out;
}

// `incomplete` for every byte but the last, which answers `last`.
std::vector<receive_status> ending_with(std::size_t n, receive_status last) {
  std::vector<receive_status> out(n, receive_status::incomplete);
  out.back() = last;
  return out;
}

std::vector<std::uint8_t> variable_frame(std::uint8_t hops, std::uint16_t vr, std::int64_t value) {
  return frame_of(ring::message::variable(hops, vr, value));
}

}  // namespace

// ---- the answer of each byte ----

TEST(RingReceiveOutcome, AMessageForTheNodeAnswersOkAtItsEndOfMessageOnly) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  const auto text = chars(1, "HI");
  EXPECT_EQ(answers(mc, text), ending_with(text.size(), receive_status::ok));
  const auto variable = variable_frame(1, 3, std::int64_t{5} << 32);
  EXPECT_EQ(answers(mc, variable), ending_with(variable.size(), receive_status::ok));
  EXPECT_EQ(vr[3], 5.0);
}

TEST(RingReceiveOutcome, ADiscardedMessageAnswersItsErrorAtTheByteThatEndsIt) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  auto corrupt = variable_frame(1, 3, 1);
  corrupt[5] ^= 0x01;  // a value bit: the CRC no longer matches
  EXPECT_EQ(answers(mc, corrupt), ending_with(corrupt.size(), receive_status::crc_error));
  // An end of message whose A differs from the header's.
  EXPECT_EQ(answers(mc, {ring::make_header(1, 1), 'X', ring::make_end_of_message(2)}),
            ending_with(3, receive_status::frame_error));
  // A header for the node that cuts a message for it short: the header answers for the message it ended.
  EXPECT_EQ(answers(mc, {ring::make_header(1, 1), 'X', ring::make_header(1, 1)}),
            ending_with(3, receive_status::frame_error));
  (void)mc.line_idle();
  // Stray data answers at its first byte (one report per run).
  EXPECT_EQ(answers(mc, {'a', 'b'}), (std::vector<receive_status>{receive_status::frame_error,
                                                                   receive_status::incomplete}));
  EXPECT_EQ(mc.counters().crc_errors, 1u);
  EXPECT_EQ(mc.counters().frame_errors, 4u);  // and the idle line's
}

TEST(RingReceiveOutcome, ACharacterTransferWithNoRoomAnswersNoRoom) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<16> mc(vr);  // a receive buffer of 16 characters
  const auto fits = chars(1, "0123456789");
  EXPECT_EQ(answers(mc, fits), ending_with(fits.size(), receive_status::ok));
  const auto too_many = chars(1, "ABCDEFGHIJ");  // 10 more do not fit while the first 10 wait
  EXPECT_EQ(answers(mc, too_many), ending_with(too_many.size(), receive_status::no_room));
  EXPECT_EQ(mc.counters().receive_overflows, 1u);
}

TEST(RingReceiveOutcome, AForwardedMessageAnswersForwardedAtItsEndOfMessage) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  const auto text = chars(3, "PASSING");
  EXPECT_EQ(answers(mc, text), ending_with(text.size(), receive_status::forwarded));
  EXPECT_EQ(drain(mc).size(), text.size());
  const auto variable = variable_frame(4, 7, -1);
  EXPECT_EQ(answers(mc, variable), ending_with(variable.size(), receive_status::forwarded));
  EXPECT_EQ(drain(mc).size(), variable.size());
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 2u);
}

TEST(RingReceiveOutcome, AForwardedMessageLostAnswersAtTheByteThatLosesIt) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<256, 16, 48> mc(vr);  // a forward buffer of 16
  ASSERT_EQ(mc.print(10, "OWN MESSAGE 14").status, ring::send_status::ok);
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));  // the own message holds the link: forwarded bytes wait
  const auto burst = chars(3, "THIS DOES NOT FIT");  // 19 bytes for 16 places
  std::vector<receive_status> expected(burst.size(), receive_status::incomplete);
  expected[16] = receive_status::forward_lost;  // the 17th byte finds no room; the rest is dropped
  EXPECT_EQ(answers(mc, burst), expected);
  EXPECT_EQ(mc.forwarding_counters().forwards_lost, 1u);
}

TEST(RingReceiveOutcome, AForwardedMessageLongerThanLegalAnswersForwardCut) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  // A keypad mode message carries one data byte: the second is past its bound.
  const std::vector<std::uint8_t> bytes = {ring::make_header(3, 4), 0, 0, ring::make_end_of_message(3)};
  EXPECT_EQ(answers(mc, bytes), (std::vector<receive_status>{receive_status::incomplete,
                                                               receive_status::incomplete,
                                                               receive_status::forward_cut,
                                                               receive_status::incomplete}));
  EXPECT_EQ(mc.forwarding_counters().forwards_cut, 1u);
}

TEST(RingReceiveOutcome, TheIdleLineAnswersForTheMessageItEnds) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  EXPECT_EQ(mc.line_idle(), receive_status::incomplete);  // nothing open
  feed(mc, {ring::make_header(3, 1), 'A'});
  EXPECT_EQ(mc.line_idle(), receive_status::forward_ended_idle);
  feed(mc, {ring::make_header(1, 1), 'A'});
  EXPECT_EQ(mc.line_idle(), receive_status::frame_error);
  EXPECT_EQ(mc.forwarding_counters().forwards_ended_idle, 1u);
  EXPECT_EQ(mc.counters().frame_errors, 1u);
}

TEST(RingReceiveOutcome, AKeypadInLocalModeAnswersDroppedAtTheHeaderOfAMessagePassingThrough) {
  ring::keypad<> keypad;
  const auto passing = chars(3, "NOT FOR ME");
  std::vector<receive_status> expected(passing.size(), receive_status::incomplete);
  expected[0] = receive_status::dropped;
  EXPECT_EQ(answers(keypad, passing), expected);
  EXPECT_EQ(keypad.forwarding_counters().messages_dropped, 1u);
  const auto offset = frame_of(ring::message::keypad_offset(1, 2));
  EXPECT_EQ(answers(keypad, offset), ending_with(offset.size(), receive_status::ok));
  EXPECT_TRUE(keypad.network_mode());
}

TEST(RingReceiveOutcome, TheNamesAreTheEnumeratorsSpelling) {
  EXPECT_STREQ(ring::to_string(receive_status::incomplete), "incomplete");
  EXPECT_STREQ(ring::to_string(receive_status::no_room), "no_room");
  EXPECT_STREQ(ring::to_string(receive_status::forwarded), "forwarded");
  EXPECT_STREQ(ring::to_string(receive_status::forward_ended_idle), "forward_ended_idle");
  EXPECT_STREQ(ring::to_string(static_cast<receive_status>(200)), "unknown");
  // The decoder's outcomes keep their values: a node's answer for a message for it is the decoder's status.
  EXPECT_EQ(trionet::detail::decode_outcome::of(ring::decode_status::crc_error), receive_status::crc_error);
}

// Any byte stream: every answer other than `incomplete` is counted by its counter, and the bulk `receive`
// says how many bytes answered.
TEST(RingReceiveOutcome, EveryAnswerIsCountedByItsCounterWhateverTheBytes) {
  trionet::test::rng random(20);
  for (int round = 0; round < 40; ++round) {
    trionet::vr_table<8> vr;
    ring::motion_coordinator<64, 16, 32, 32> mc(vr);
    ring::motion_coordinator<64, 16, 32, 32> twin(vr);
    std::vector<std::uint8_t> bytes;
    for (int i = 0; i < 600; ++i) {
      const unsigned r = random();
      // Mostly well-formed pieces: headers and ends of small A, data, now and then anything.
      switch (r % 6) {
        case 0:
          bytes.push_back(ring::make_header(static_cast<std::uint8_t>(r >> 3) % 4, 1 + (r >> 6) % 4));
          break;
        case 1:
          bytes.push_back(ring::make_end_of_message(static_cast<std::uint8_t>(r >> 3) % 4));
          break;
        case 2:
          bytes.push_back(static_cast<std::uint8_t>(r >> 8));
          break;
        default:
          bytes.push_back(static_cast<std::uint8_t>((r >> 8) & 0x7F));
      }
    }
    std::size_t answered = 0;
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      const auto before = mc.counters();
      const auto links_before = mc.forwarding_counters();
      const receive_status s = (i % 97 == 96) ? mc.line_idle() : mc.receive(bytes[i]);
      if (i % 97 == 96) {
        (void)twin.line_idle();
      } else {
        answered += s != receive_status::incomplete;
      }
      const auto after = mc.counters();
      const auto links = mc.forwarding_counters();
      const std::uint32_t delivered = after.character_messages + after.variables_written + after.variables_refused +
                                      after.variables_out_of_range + after.variables_value_out_of_range +
                                      after.keypad_messages_ignored -
                                      (before.character_messages + before.variables_written +
                                       before.variables_refused + before.variables_out_of_range +
                                       before.variables_value_out_of_range + before.keypad_messages_ignored);
      const std::uint32_t counted[] = {
          0,
          delivered,
          after.frame_errors - before.frame_errors,
          after.crc_errors - before.crc_errors,
          after.receive_overflows - before.receive_overflows,
          0,  // forwarded: counted at the header
          0,  // dropped: only a keypad drops
          links.forwards_lost - links_before.forwards_lost,
          links.forwards_cut - links_before.forwards_cut,
          links.forwards_ended_idle - links_before.forwards_ended_idle,
      };
      const auto k = static_cast<std::size_t>(s);
      ASSERT_LT(k, sizeof counted / sizeof counted[0]);
      if (s == receive_status::incomplete) {
        for (std::uint32_t c : counted) ASSERT_EQ(c, 0u) << "byte " << i << " of round " << round;
      } else if (k != 5) {
        ASSERT_EQ(counted[k], 1u) << ring::to_string(s) << " at byte " << i << " of round " << round;
      }
      if (i % 97 == 96) {  // the transmitter and GET# catch up at each idle line
        std::uint8_t out = 0;
        while (mc.transmit(out)) {
        }
        while (mc.get(4)) {
        }
      }
    }
    // The same bytes in bulk, between the same idle lines: the same number answered.
    std::size_t bulk = 0;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= bytes.size(); ++i) {
      if (i == bytes.size() || i % 97 == 96) {
        bulk += twin.receive(trionet::byte_view(bytes.data() + start, i - start));
        if (i == bytes.size()) break;
        (void)twin.line_idle();
        start = i + 1;
        std::uint8_t out = 0;
        while (twin.transmit(out)) {
        }
        while (twin.get(4)) {
        }
      }
    }
    EXPECT_EQ(bulk, answered) << "round " << round;
  }
}

// ---- clear_counters ----

namespace {

// One of each thing a Motion Coordinator counts, `n` times: a character message and a direct variable
// transfer for it, a keypad message for it, a frame error, a CRC error, a forwarded message, and an own
// message sent.
void traffic(mc_node& mc, unsigned n) {
  for (unsigned i = 0; i < n; ++i) {
    feed(mc, chars(1, "C"));
    feed(mc, variable_frame(1, 2, std::int64_t{1} << 32));
    feed(mc, frame_of(ring::message::keypad_mode(1, 0)));
    feed(mc, {ring::make_header(1, 1), ring::make_end_of_message(1)});  // no data: a frame error
    auto corrupt = variable_frame(1, 2, 1);
    corrupt[3] ^= 0x01;
    feed(mc, corrupt);
    feed(mc, chars(2, "F"));
    ASSERT_EQ(mc.print(11, "S").status, ring::send_status::ok);
    (void)drain(mc);
    while (mc.get(4)) {
    }
  }
}

void expect_counts(const mc_node& mc, std::uint32_t n) {
  const auto c = mc.counters();
  EXPECT_EQ(c.character_messages, n);
  EXPECT_EQ(c.variables_written, n);
  EXPECT_EQ(c.keypad_messages_ignored, n);
  EXPECT_EQ(c.frame_errors, n);
  EXPECT_EQ(c.crc_errors, n);
  const auto links = mc.forwarding_counters();
  EXPECT_EQ(links.messages_forwarded, n);
  EXPECT_EQ(links.messages_sent, n);
}

}  // namespace

TEST(RingClearCounters, StartsEveryCountAgainFromZero) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  traffic(mc, 3);
  expect_counts(mc, 3);
  mc.clear_counters();
  {
    SCOPED_TRACE("at once, before the link side has carried it out");
    expect_counts(mc, 0);
  }
  traffic(mc, 2);
  {
    SCOPED_TRACE("counted again from the clear");
    expect_counts(mc, 2);
  }
  mc.clear_counters();
  traffic(mc, 1);
  SCOPED_TRACE("a second clear starts from there");
  expect_counts(mc, 1);
}

TEST(RingClearCounters, EveryCounterReadsZeroAfterAClear) {
  trionet::vr_table<4> vr;
  ring::motion_coordinator<16, 16, 48> mc(vr);  // small buffers: every kind of loss can happen
  // Losses of each kind, overflows, out-of-range writes, refused sends.
  ASSERT_EQ(mc.print(10, "HOLD").status, ring::send_status::ok);
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));
  feed(mc, chars(3, "THIS DOES NOT FIT AT ALL"));
  (void)drain(mc);
  feed(mc, {ring::make_header(3, 4), 0, 0, ring::make_end_of_message(3)});
  feed(mc, {ring::make_header(3, 1), 'A'});
  (void)mc.line_idle();
  feed(mc, chars(1, "0123456789ABC"));
  feed(mc, chars(1, "0123456789ABC"));
  feed(mc, variable_frame(1, 9, 1));
  while (mc.print(10, "FILL THE TRANSMIT QUEUE").status == ring::send_status::ok) {
  }
  const auto c = mc.counters();
  const auto links = mc.forwarding_counters();
  ASSERT_NE(c.receive_overflows, 0u);
  ASSERT_NE(c.variables_out_of_range, 0u);
  ASSERT_NE(c.sends_refused, 0u);
  ASSERT_NE(links.forwards_lost, 0u);
  ASSERT_NE(links.forwards_cut, 0u);
  ASSERT_NE(links.forwards_ended_idle, 0u);
  const std::uint8_t netstat = mc.netstat();
  mc.clear_counters();
  const ring::motion_coordinator_counters zero{};
  const ring::link_counters zero_links{};
  const auto check = [&](const char* when) {
    SCOPED_TRACE(when);
    const auto now = mc.counters();
    const auto now_links = mc.forwarding_counters();
    EXPECT_EQ(std::memcmp(&now, &zero, sizeof now), 0);
    EXPECT_EQ(std::memcmp(&now_links, &zero_links, sizeof now_links), 0);
  };
  check("asked");
  EXPECT_EQ(mc.netstat(), netstat);  // NETSTAT is cleared by clear_netstat only
  (void)drain(mc);
  feed(mc, chars(2, "X"));  // counted at its header: the link side clears first
  const auto after = mc.counters();
  const auto after_links = mc.forwarding_counters();
  EXPECT_EQ(after_links.messages_forwarded, 1u);
  EXPECT_EQ(after_links.forwards_lost + after_links.forwards_cut + after_links.forwards_ended_idle, 0u);
  EXPECT_EQ(after.receive_overflows + after.variables_out_of_range + after.frame_errors, 0u);
  mc.clear_counters();
  mc.clear_counters();  // asked twice before the link side counts again: one clear
  check("asked twice");
  (void)mc.line_idle();  // counts nothing: nothing is open
  check("after an idle line that counted nothing");
}

TEST(RingClearCounters, TheLinkSideClearsBeforeItsNextCountWhereverItCounts) {
  trionet::vr_table<16> vr;
  mc_node mc(vr);
  // Counted by the transmitter: an own message going out.
  traffic(mc, 2);
  mc.clear_counters();
  ASSERT_EQ(mc.print(11, "S").status, ring::send_status::ok);
  (void)drain(mc);
  EXPECT_EQ(mc.forwarding_counters().messages_sent, 1u);
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 0u);
  EXPECT_EQ(mc.counters().character_messages, 0u);
  // Counted by the idle line.
  traffic(mc, 2);
  mc.clear_counters();
  feed(mc, {ring::make_header(3, 1), 'A'});  // (its header is counted: the clear happens there)
  EXPECT_EQ(mc.line_idle(), receive_status::forward_ended_idle);
  EXPECT_EQ(mc.forwarding_counters().forwards_ended_idle, 1u);
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 1u);
  EXPECT_EQ(mc.counters().frame_errors, 0u);
  // Counted at the end of a message for the node that began before the clear.
  feed(mc, {ring::make_header(1, 1), 'A'});
  mc.clear_counters();
  EXPECT_EQ(mc.receive(ring::make_end_of_message(1)), receive_status::ok);
  EXPECT_EQ(mc.counters().character_messages, 1u);
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 0u);
  // Counted by a loss in the middle of a forwarded message that began before the clear.
  feed(mc, {ring::make_header(3, 4), 0});
  mc.clear_counters();
  EXPECT_EQ(mc.receive(0), receive_status::forward_cut);
  EXPECT_EQ(mc.forwarding_counters().forwards_cut, 1u);
  EXPECT_EQ(mc.counters().character_messages, 0u);
}

TEST(RingClearCounters, AKeypadStartsEveryCountAgainFromZero) {
  ring::keypad<> keypad;
  feed(keypad, chars(3, "DROPPED"));                           // dropped in local mode (link)
  feed(keypad, chars(1, "TOO EARLY"));                         // dropped in local mode (keypad)
  EXPECT_EQ(keypad.press(ring::key::digit_1), ring::key_status::local_mode);  // a key lost
  feed(keypad, frame_of(ring::message::keypad_offset(1, 2)));
  feed(keypad, chars(1, "HELLO"));
  feed(keypad, frame_of(ring::message::variable(1, 1, 1)));
  EXPECT_EQ(keypad.press(ring::key::digit_2), ring::key_status::ok);
  feed(keypad, {ring::make_header(1, 1), ring::make_end_of_message(1)});
  auto c = keypad.counters();
  ASSERT_EQ(c.dropped_in_local_mode, 1u);
  ASSERT_EQ(c.display_messages, 1u);
  ASSERT_EQ(c.variables_ignored, 1u);
  ASSERT_EQ(c.keys_sent, 1u);
  ASSERT_EQ(c.keys_lost, 1u);
  ASSERT_EQ(c.frame_errors, 1u);
  ASSERT_EQ(keypad.forwarding_counters().messages_dropped, 1u);
  keypad.clear_counters();
  const ring::keypad_counters zero{};
  c = keypad.counters();
  EXPECT_EQ(std::memcmp(&c, &zero, sizeof c), 0);
  EXPECT_EQ(keypad.forwarding_counters().messages_dropped, 0u);
  feed(keypad, chars(1, "AGAIN"));
  EXPECT_EQ(keypad.press(ring::key::digit_3), ring::key_status::ok);
  c = keypad.counters();
  EXPECT_EQ(c.display_messages, 1u);
  EXPECT_EQ(c.keys_sent, 1u);
  EXPECT_EQ(c.variables_ignored + c.dropped_in_local_mode + c.frame_errors + c.keys_lost, 0u);
}
