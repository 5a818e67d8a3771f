// Ring liveness (docs/protocol.md 1.5, 1.6, 1.10): whatever the links lose, once the faults stop the ring is
// back to normal within a bounded time, every loss a node can see is counted, and nothing needs a power
// cycle. The manual: "The sender places the message on the ring and assumes it arrives at its destination."
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "support/ring_frames.hpp"
#include "support/ring_soak.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
using trionet::byte_view;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;
using trionet::test::read_all;

namespace {

// Drops the first byte on `link` that `pick` chooses.
struct drop_first {
  std::size_t link;
  bool (*pick)(std::uint8_t);
  bool done = false;
  static ring::byte_fault hook(void* context, std::size_t link, std::uint64_t, std::uint8_t byte) {
    auto* self = static_cast<drop_first*>(context);
    ring::byte_fault f;
    if (!self->done && link == self->link && self->pick(byte)) {
      self->done = true;
      f.drop = true;
    }
    return f;
  }
};

bool is_end_of_message(std::uint8_t byte) {
  return ring::classify(byte) == ring::byte_class::end_of_message;
}

}  // namespace

// ---- the idle line ----

// "Each successive node decrements the address by 1 and if the result is greater than zero it re-transmits
// the message": a forwarded message whose end of message is lost used to leave the forwarding node inside it
// for ever, reporting nothing pending and never sending its own messages, with no counter and no NETSTAT bit.
TEST(RingLiveness, SilentStallAForwardedMessageThatLostItsEndIsEndedByTheIdleLine) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  feed(mc, {ring::make_header(3, 1), 'A', 'B', 'C'});  // ... and its end of message is lost
  ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);
  EXPECT_EQ(drain(mc), (std::vector<std::uint8_t>{ring::make_header(2, 1), 'A', 'B', 'C'}));
  EXPECT_TRUE(mc.in_message());
  EXPECT_FALSE(mc.transmit_pending());  // waiting for the rest of the forwarded message

  mc.line_idle();  // the UART's idle-line interrupt
  EXPECT_FALSE(mc.in_message());
  EXPECT_EQ(mc.forwarding_counters().forwards_ended_idle, 1u);
  EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
  EXPECT_TRUE(mc.transmit_pending());
  EXPECT_EQ(drain(mc), chars(1, "OWN"));
  // A late byte of the ended message is stray data, counted, and does not reopen anything.
  mc.receive('D');
  EXPECT_EQ(mc.counters().frame_errors, 1u);
  EXPECT_FALSE(mc.in_message());
}

TEST(RingLiveness, IdleLineEndsAMessageForThisNodeAsAFrameError) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  feed(mc, {ring::make_header(1, 1), 'H', 'I'});  // the end of message never comes
  EXPECT_TRUE(mc.in_message());
  mc.line_idle();
  EXPECT_FALSE(mc.in_message());
  EXPECT_EQ(mc.counters().frame_errors, 1u);
  EXPECT_EQ(mc.netstat(), ring::netstat_rx_frame_error);
  EXPECT_FALSE(mc.key(4));  // nothing of it was kept
  feed(mc, chars(1, "OK"));
  EXPECT_EQ(read_all(mc), "OK");
  mc.line_idle();  // harmless between messages
  EXPECT_EQ(mc.counters().frame_errors, 1u);
}

TEST(RingLiveness, KeypadHasTheIdleLineToo) {
  ring::keypad<> keypad;
  feed(keypad, {ring::make_header(1, 3), 2, ring::make_end_of_message(1)});  // offset: network mode
  ASSERT_TRUE(keypad.network_mode());
  feed(keypad, {ring::make_header(4, 1), 'X'});  // forwarded, then the line goes quiet
  EXPECT_TRUE(keypad.in_message());
  keypad.line_idle();
  EXPECT_FALSE(keypad.in_message());
  EXPECT_EQ(keypad.forwarding_counters().forwards_ended_idle, 1u);
  EXPECT_EQ(keypad.netstat(), ring::netstat_tx_buffer_error);
  ASSERT_EQ(keypad.press(ring::key::digit_5), ring::key_status::ok);
  EXPECT_EQ(drain(keypad), (std::vector<std::uint8_t>{ring::make_header(3, 1), 'X',  // cut short
                                                      ring::make_header(2, 1), '5', ring::make_end_of_message(2)}));
}

// ---- the forwarding bound ----

TEST(RingLiveness, AForwardedMessageLongerThanLegalIsCutAndCounted) {
  struct longest {
    std::uint8_t type;
    std::size_t data;
  };
  for (const longest l : {longest{1, 256}, longest{2, 14}, longest{3, 1}, longest{4, 1}, longest{5, 256},
                          longest{7, 256}}) {
    trionet::vr_table<16> vr;
    ring::motion_coordinator<> mc(vr);
    std::vector<std::uint8_t> sent;
    std::uint8_t b = 0;
    mc.receive(ring::make_header(3, l.type));
    for (std::size_t i = 0; i < l.data + 5; ++i) {
      mc.receive(static_cast<std::uint8_t>('a' + i % 26));
      while (mc.transmit(b)) sent.push_back(b);
    }
    mc.receive(ring::make_end_of_message(3));
    while (mc.transmit(b)) sent.push_back(b);
    SCOPED_TRACE("type " + std::to_string(l.type));
    // The header and exactly the longest legal data went on; the rest, and the end of message, did not.
    EXPECT_EQ(sent.size(), 1 + l.data);
    EXPECT_EQ(mc.forwarding_counters().forwards_cut, 1u);
    EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
    EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 1u);
    // A legal message just after is forwarded whole.
    feed(mc, chars(3, "NEXT"));
    EXPECT_EQ(drain(mc), chars(2, "NEXT"));
  }
}

TEST(RingLiveness, TheBoundHoldsInTheBulkPaths) {
  std::vector<std::uint8_t> stream = {ring::make_header(2, 2)};
  for (int i = 0; i < 20; ++i) stream.push_back(static_cast<std::uint8_t>(i));  // 20 > 14
  stream.push_back(ring::make_end_of_message(2));
  const auto next = chars(2, "NEXT");
  stream.insert(stream.end(), next.begin(), next.end());
  trionet::vr_table<4> v1, v2, v3;
  ring::motion_coordinator<> one(v1), bulk(v2), pieces(v3);
  feed(one, stream);
  bulk.receive(byte_view(stream.data(), stream.size()));
  for (std::size_t at = 0; at < stream.size(); at += 5)  // pieces that end inside the grant and past the bound
    pieces.receive(byte_view(stream.data() + at, std::min<std::size_t>(5, stream.size() - at)));
  std::uint8_t out[64];
  const std::size_t n = pieces.transmit(trionet::byte_buffer(out, 64));
  const auto expected = drain(one);
  EXPECT_EQ(drain(bulk), expected);
  EXPECT_EQ(std::vector<std::uint8_t>(out, out + n), expected);
  EXPECT_EQ(one.forwarding_counters().forwards_cut, 1u);
  EXPECT_EQ(bulk.forwarding_counters().forwards_cut, 1u);
  EXPECT_EQ(pieces.forwarding_counters().forwards_cut, 1u);
}

// ---- the rings of the field reports ----

// Ring [A, B, keypad]: a PRINT# that laps the ring once loses its end of message. Without the idle line no
// byte crossed any link again, while A and B held queued messages.
TEST(RingLiveness, DeadRingALappingPrintLosesItsEndOfMessage) {
  for (const std::uint32_t idle : {0u, ring::default_idle_byte_times}) {
    trionet::vr_table<16> va, vb;
    ring::motion_coordinator<> a(va), b(vb);
    ring::keypad<> keypad;
    ring::simulator<> sim(idle);
    ASSERT_TRUE(sim.add(a) && sim.add(b) && sim.add(keypad));
    ASSERT_EQ(a.send_keypad_offset(11, 11), ring::send_status::ok);  // keys to A, two hops on
    sim.run(20);
    ASSERT_TRUE(keypad.network_mode());

    drop_first fault{0, is_end_of_message};
    sim.set_fault_hook(&drop_first::hook, &fault);
    ASSERT_EQ(a.print(14, "ONCE ROUND THE RING").status, ring::send_status::ok);  // 5 hops: ends at B
    ASSERT_EQ(a.print(10, "A TO B").status, ring::send_status::ok);
    ASSERT_EQ(b.print(11, "B TO A").status, ring::send_status::ok);
    std::uint64_t crossed_late = 0, idles = 0;
    sim.run(1000, [&](const auto& event) {
      if constexpr (std::is_same_v<std::decay_t<decltype(event)>, ring::link_byte>) {
        if (event.time >= 100) ++crossed_late;
      } else {
        ++idles;
      }
    });
    ASSERT_TRUE(fault.done);
    if (idle == 0) {  // the failure as it was: nothing moves, messages wait for ever
      EXPECT_EQ(crossed_late, 0u);
      EXPECT_TRUE(a.in_message() && b.in_message() && keypad.in_message());
      EXPECT_LT(a.transmit_free(), 32u);  // "A TO B" is still waiting
      EXPECT_EQ(read_all(b).find("A TO B"), std::string::npos);
      continue;
    }
    EXPECT_GT(idles, 0u);  // the trace shows the idle lines
    EXPECT_EQ(read_all(b).find("A TO B") != std::string::npos, true);
    EXPECT_EQ(read_all(a), "B TO A");
    EXPECT_TRUE(sim.quiet());
    EXPECT_NE(a.netstat() | b.netstat(), 0);  // the loss was seen
  }
}

// Ring of 3 MCs: PRINT# with BASIC address 24 laps the ring five times. Its end of message and its last
// header are lost: the characters used to circulate for ever, every link busy, no counter moving.
TEST(RingLiveness, LivelockCirculatingCharactersAreCutByTheBound) {
  trionet::vr_table<16> va, vb, vc;
  ring::motion_coordinator<> a(va), b(vb), c(vc);
  ring::simulator<> sim;
  ASSERT_TRUE(sim.add(a) && sim.add(b) && sim.add(c));
  struct fault {
    int dropped = 0;
    static ring::byte_fault hook(void* context, std::size_t, std::uint64_t, std::uint8_t byte) {
      auto* self = static_cast<fault*>(context);
      ring::byte_fault f;
      const bool eom = ring::classify(byte) == ring::byte_class::end_of_message;
      const bool last_header = ring::classify(byte) == ring::byte_class::header && ring::hops_of(byte) == 1;
      if ((self->dropped & 1) == 0 && eom) {
        f.drop = true;
        self->dropped |= 1;
      } else if ((self->dropped & 2) == 0 && last_header) {
        f.drop = true;
        self->dropped |= 2;
      }
      return f;
    }
  } f;
  sim.set_fault_hook(&fault::hook, &f);
  ASSERT_EQ(a.print(24, "FIVE LAPS").status, ring::send_status::ok);  // one message
  std::uint64_t last_byte = 0, last_fault = 0;
  sim.run(2000, [&](const auto& event) {
    if constexpr (std::is_same_v<std::decay_t<decltype(event)>, ring::link_byte>) {
      last_byte = event.time;
      if (!event.delivered) last_fault = event.time;
    }
  });
  ASSERT_EQ(f.dropped, 3);
  // The circulation stopped within idle time + one longest message + one lap of the last fault (1.10).
  EXPECT_LE(last_byte - last_fault, trionet::soak::recovery_bound(3));
  EXPECT_TRUE(sim.quiet());
  const std::uint32_t cut = a.forwarding_counters().forwards_cut + b.forwarding_counters().forwards_cut +
                            c.forwarding_counters().forwards_cut;
  EXPECT_GE(cut, 1u);
  // And the ring works: every node's probe arrives.
  ASSERT_EQ(a.print(10, "PROBE A").status, ring::send_status::ok);
  ASSERT_EQ(b.print(10, "PROBE B").status, ring::send_status::ok);
  ASSERT_EQ(c.print(10, "PROBE C").status, ring::send_status::ok);
  sim.run(100);
  EXPECT_NE(read_all(b).find("PROBE A"), std::string::npos);
  EXPECT_NE(read_all(c).find("PROBE B"), std::string::npos);
  EXPECT_NE(read_all(a).find("PROBE C"), std::string::npos);
}

// 300 episodes of a link cut for 100 byte-times on a 5-node ring with a keypad: 19 of them used to leave the
// ring wedged after the faults had stopped.
TEST(RingLiveness, WedgedCutFiveNodesWithAKeypadSurviveThreeHundredCuts) {
  trionet::soak::config cfg;
  cfg.nodes = 5;
  cfg.keypads = 1;
  cfg.kind = trionet::soak::fault_kind::cut;
  cfg.cut_length = 100;
  cfg.episodes = 300;
  cfg.fault_byte_times = 400;
  cfg.seed = 19;
  const trionet::soak::report r = trionet::soak::run(cfg);
  EXPECT_EQ(r.wedged, 0u) << r.first_problem;
  EXPECT_EQ(r.livelocked, 0u) << r.first_problem;
  EXPECT_EQ(r.wrong_vr_writes, 0u) << r.first_problem;
  EXPECT_EQ(r.lost_unexplained, 0u) << r.first_problem;
  EXPECT_EQ(r.probes_delivered, r.probes);
  EXPECT_GT(r.faults, 0u);
  EXPECT_GT(r.lost(), 0u);  // the cuts did cost messages...
  EXPECT_LE(trionet::soak::maximum(r.damage_cleared), trionet::soak::recovery_bound(cfg.nodes));
}

// ---- a header changed together with its end of message ----

// The soak's wrong VR writes (flips at 1e-2 per byte): a direct variable transfer's header A and, on another
// link, its end of message's A changed alike, so the message was whole and valid at another node, whose VR
// was written. The CRC covers V0..X9 only (docs/protocol.md 1.3), so no node can see it; a write policy that
// accepts only the node's own VRs refuses it and counts it instead.
TEST(RingLiveness, AMisaddressedVariableTransferIsRefusedByAnOwnershipPolicy) {
  struct owner {
    std::uint16_t first;
    static bool policy(void* context, std::uint16_t vr, double) noexcept {
      const auto first = static_cast<owner*>(context)->first;
      return vr >= first && vr < first + 16;
    }
  };
  // SEND(11,1,32,5) from A to C, two hops: on link A -> B its header's A goes 2 -> 3 (bit 3 flips), so it
  // is forwarded past C; on link C -> D its end of message, forwarded down to A = 0 by C, goes 0 -> 1. D
  // takes a header with A = 1, 14 intact data bytes and an end of message with A = 1.
  struct double_flip {
    bool header = false, end = false;
    static ring::byte_fault hook(void* context, std::size_t link, std::uint64_t, std::uint8_t byte) {
      auto* self = static_cast<double_flip*>(context);
      ring::byte_fault f;
      if (!self->header && link == 0 && byte == ring::make_header(2, 2)) {
        self->header = true;
        f.flip_mask = 0x08;
      } else if (!self->end && link == 2 && ring::classify(byte) == ring::byte_class::end_of_message) {
        EXPECT_EQ(byte, ring::make_end_of_message(0));
        self->end = true;
        f.flip_mask = 0x08;
      }
      return f;
    }
  };
  for (const bool owned_only : {false, true}) {
    SCOPED_TRACE(owned_only ? "each MC accepts its own VRs" : "the default policy");
    owner owners[4] = {{0}, {16}, {32}, {48}};
    trionet::vr_table<64> owned[4] = {trionet::vr_table<64>(&owner::policy, &owners[0]),
                                      trionet::vr_table<64>(&owner::policy, &owners[1]),
                                      trionet::vr_table<64>(&owner::policy, &owners[2]),
                                      trionet::vr_table<64>(&owner::policy, &owners[3])};
    trionet::vr_table<64> every[4];
    trionet::vr_table<64>* tables = owned_only ? owned : every;
    ring::motion_coordinator<> a(tables[0]), b(tables[1]), c(tables[2]), d(tables[3]);
    ring::simulator<> sim;
    ASSERT_TRUE(sim.add(a) && sim.add(b) && sim.add(c) && sim.add(d));
    double_flip fault;
    sim.set_fault_hook(&double_flip::hook, &fault);
    ASSERT_EQ(a.send_variable(11, 32, 5.0), ring::send_status::ok);  // VR 32: one of C's
    sim.run(100);
    ASSERT_TRUE(fault.header && fault.end);
    // No node saw anything wrong: no frame or CRC error, no lost forward, NETSTAT clear.
    for (const auto* mc : {&a, &b, &c, &d}) {
      EXPECT_EQ(mc->counters().frame_errors, 0u);
      EXPECT_EQ(mc->counters().crc_errors, 0u);
      EXPECT_EQ(mc->forwarding_counters().forwards_failed(), 0u);
      EXPECT_EQ(mc->netstat(), 0);
    }
    EXPECT_EQ(c.counters().variables_written + c.counters().variables_refused, 0u);  // C never had it
    EXPECT_EQ(tables[2].get(32), 0.0);
    if (owned_only) {  // refused and counted at D, nothing written
      EXPECT_EQ(d.counters().variables_refused, 1u);
      EXPECT_EQ(d.counters().variables_written, 0u);
      EXPECT_EQ(tables[3].get(32), 0.0);
    } else {  // the default policy writes C's VR at D: the loss the protocol cannot see
      EXPECT_EQ(d.counters().variables_written, 1u);
      EXPECT_EQ(tables[3].get(32), 5.0);
    }
  }
}

// ---- capacities ----

// A transmit queue larger than the forward buffer (128 and 32) used to lose forwarded traffic under load: the
// node never queues an own frame longer than the forward buffer, so nothing forwarded is lost.
TEST(RingLiveness, ABigTransmitQueueNeverCostsForwardedTraffic) {
  trionet::vr_table<16> va, vb, vc;
  ring::motion_coordinator<256, 32, 128> a(va), b(vb), c(vc);
  ring::simulator<> sim;
  ASSERT_TRUE(sim.add(a) && sim.add(b) && sim.add(c));
  std::string got_c;
  int sent = 0;
  for (int t = 0; t < 20000; ++t) {
    if (a.transmit_free() >= 64) {  // A keeps B busy forwarding 60-character PRINT#s to C (2 messages)
      ASSERT_EQ(a.print(11, std::string(60, static_cast<char>('a' + sent % 26)).c_str()).status,
                ring::send_status::ok);
      ++sent;
    }
    if (b.transmit_free() >= 64) (void)b.print(10, std::string(60, 'B').c_str());  // and has its own
    sim.step();
    got_c += read_all(c);
  }
  EXPECT_EQ(b.forwarding_counters().forwards_lost, 0u);
  EXPECT_EQ(b.netstat() & ring::netstat_tx_buffer_error, 0);
  EXPECT_GT(sent, 50);
  EXPECT_EQ(a.max_own_frame, 32u);
}

// ---- PRINT# of any length ----

TEST(RingLiveness, AFortyCharacterDisplayUpdateAtDefaultCapacities) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  ring::keypad<> keypad;
  ring::simulator<> sim;
  ASSERT_TRUE(sim.add(mc) && sim.add(keypad));
  ASSERT_EQ(mc.send_keypad_offset(10, 10), ring::send_status::ok);
  sim.run(10);
  const std::string line = "LINE ONE IS TWENTY..LINE TWO TOO, TWENTY";  // the whole 2 x 20 display
  ASSERT_EQ(line.size(), 40u);
  // BASIC's PRINT# (the blocking form): the ring runs while it waits for room.
  const ring::print_result r = mc.print_all(10, (std::string(1, '\x0c') + line).c_str(), [&] {
    sim.step();
    return true;
  });
  EXPECT_EQ(r.status, ring::send_status::ok);
  EXPECT_EQ(r.queued, 41u);
  sim.run(100);
  EXPECT_EQ(std::string(keypad.display().line(0)), line.substr(0, 20));
  EXPECT_EQ(std::string(keypad.display().line(1)), line.substr(20));
  EXPECT_EQ(keypad.counters().display_messages, 3u);  // three messages: 14 + 14 + 13 characters
  EXPECT_EQ(keypad.counters().frame_errors, 0u);
}

TEST(RingLiveness, PrintQueuesWholeMessagesAndSaysHowMuch) {
  trionet::vr_table<16> va, vb;
  ring::motion_coordinator<> a(va), b(vb);
  std::string text;
  for (int i = 0; i < 256; ++i) text += static_cast<char>('!' + i % 90);
  ring::print_result r = a.print(10, text.c_str());
  EXPECT_EQ(r.status, ring::send_status::queue_full);
  EXPECT_EQ(r.queued, 28u);  // two messages of 14 (the 16-byte forward buffer) fill the 32-byte queue
  EXPECT_EQ(a.netstat(), ring::netstat_tx_timeout);
  EXPECT_EQ(a.counters().sends_refused, 1u);
  a.clear_netstat();
  // BASIC's PRINT#: waits for room until all of it is queued; NETSTAT stays clear.
  std::vector<std::uint8_t> wire;
  std::size_t waits = 0;
  r = a.print_all(10, text.c_str(), [&] {
    ++waits;
    std::uint8_t byte = 0;
    for (int i = 0; i < 5 && a.transmit(byte); ++i) wire.push_back(byte);
    return true;
  });
  EXPECT_EQ(r.status, ring::send_status::ok);
  EXPECT_EQ(r.queued, 256u);
  EXPECT_GT(waits, 0u);
  EXPECT_EQ(a.netstat(), 0);
  const auto rest = drain(a);
  wire.insert(wire.end(), rest.begin(), rest.end());
  std::string got;
  for (std::uint8_t byte : wire) {
    b.receive(byte);
    got += read_all(b);
  }
  EXPECT_EQ(got, text.substr(0, 28) + text);  // GET# sees the characters in order
  EXPECT_EQ(b.counters().frame_errors, 0u);
  // Giving up sets NETSTAT bit 0 and says how far it got.
  r = a.print_all(10, text.c_str(), [] { return false; });
  EXPECT_EQ(r.status, ring::send_status::queue_full);
  EXPECT_EQ(r.queued, 28u);
  EXPECT_EQ(a.netstat(), ring::netstat_tx_timeout);
  // Nothing is queued unless every character is valid.
  a.clear_netstat();
  const std::size_t free_before = a.transmit_free();
  EXPECT_EQ(a.print(10, (text + "\xff").c_str()).status, ring::send_status::character_out_of_range);
  EXPECT_EQ(a.transmit_free(), free_before);
}

// ---- the soak, seeded: every configuration kind, small ----

TEST(RingSoak, SeededRunsHaveNoWedgeNoLivelockNoWrongVrWrite) {
  using trionet::soak::fault_kind;
  struct setup {
    std::size_t nodes, keypads;
    fault_kind kind;
    double rate;
    std::uint32_t cut;
  };
  const setup setups[] = {
      {2, 0, fault_kind::flip, 1e-2, 0},    {3, 1, fault_kind::drop, 1e-2, 0},
      {5, 1, fault_kind::flip, 1e-3, 0},    {8, 2, fault_kind::drop, 1e-3, 0},
      {15, 3, fault_kind::flip, 1e-4, 0},   {4, 1, fault_kind::cut, 0, 10},
      {7, 2, fault_kind::cut, 0, 1000},     {15, 4, fault_kind::cut, 0, 100},
  };
  std::uint64_t seed = 1000;
  for (const setup& s : setups) {
    trionet::soak::config cfg;
    cfg.nodes = s.nodes;
    cfg.keypads = s.keypads;
    cfg.kind = s.kind;
    cfg.rate = s.rate;
    cfg.cut_length = s.cut;
    cfg.episodes = 12;
    cfg.fault_byte_times = 1500;
    cfg.seed = ++seed;
    const trionet::soak::report r = trionet::soak::run(cfg);
    SCOPED_TRACE(std::to_string(s.nodes) + " nodes, " + to_string(s.kind));
    EXPECT_EQ(r.wedged, 0u) << r.first_problem;
    EXPECT_EQ(r.livelocked, 0u) << r.first_problem;
    EXPECT_EQ(r.wrong_vr_writes, 0u) << r.first_problem;
    EXPECT_EQ(r.owned_refused, 0u) << r.first_problem;
    EXPECT_EQ(r.lost_unexplained, 0u) << r.first_problem;
    EXPECT_EQ(r.untracked_headers, 0u) << r.first_problem;
    EXPECT_EQ(r.probes_delivered, r.probes) << r.first_problem;
    EXPECT_GT(r.sent, 0u);
    EXPECT_EQ(r.sent, r.fates());
  }
}
