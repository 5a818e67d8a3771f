// The fibre-optic network chapter's own examples, end to end on the simulated ring. Examples 1 and 2 are the
// manual's programs, run by the BASIC interpreter from examples/manual/.
#include <gtest/gtest.h>

#include <string>

#include "support/networks.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
namespace host = trionet::host;
using trionet::test::mc_file;
using trionet::test::recorded_network;
using trionet::test::variable_of;
using trionet::test::vr_of;
using keypad_node = ring::keypad<>;
using mc_node = ring::motion_coordinator<>;

namespace {

std::string read_all(mc_node& mc) {
  std::string out;
  while (auto r = mc.get(4)) out += static_cast<char>(r.value);
  return out;
}

}  // namespace

// "If a message was sent with the address 13 then the message would come back to the sender. Likewise if
// address 14 was used the message would completely traverse the ring once and finish up at node #10. If
// address 18 was used then the message would go twice round the ring and finish up at node #10."
TEST(ManualNodeAddressingExample, RingOfFour) {
  trionet::vr_table<16> vr[4];
  mc_node sender(vr[0]), node10(vr[1]), node11(vr[2]), node12(vr[3]);
  ring::simulator<> sim;
  for (mc_node* n : {&sender, &node10, &node11, &node12}) ASSERT_TRUE(sim.add(*n));
  const struct {
    int address;
    mc_node* destination;
  } cases[] = {{10, &node10}, {12, &node12}, {13, &sender}, {14, &node10}, {18, &node10}};
  for (const auto& c : cases) {
    const std::string text = "TO " + std::to_string(c.address);
    ASSERT_EQ(sender.print(c.address, text.c_str()).status, ring::send_status::ok);
    sim.run(200);
    for (mc_node* n : {&sender, &node10, &node11, &node12}) {
      EXPECT_EQ(read_all(*n), n == c.destination ? text : "") << "address " << c.address;
    }
  }
  // Node 10 passed on #12, #13 and #14 once each (#14 came back to it after a lap), and #18 twice.
  EXPECT_EQ(node10.forwarding_counters().messages_forwarded, 1u + 1u + 1u + 2u);
}

// "SEND(10+2,2,10+2)": MCa -> MCb -> MCc -> keypad; the keypad, three nodes from MCa, sends its keys three
// nodes on: round through MCa and MCb to MCc.
TEST(ManualKeypadOffsetExample, KeyPressesReachMCc) {
  trionet::vr_table<16> vr[3];
  mc_node a(vr[0]), b(vr[1]), c(vr[2]);
  keypad_node keypad;
  ring::simulator<> sim;
  for (trionet::byte_port* n : std::initializer_list<trionet::byte_port*>{&a, &b, &c, &keypad})
    ASSERT_TRUE(sim.add(*n));
  ASSERT_EQ(a.send_keypad_offset(10 + 2, 10 + 2), ring::send_status::ok);
  sim.run(50);
  ASSERT_TRUE(keypad.network_mode());
  EXPECT_EQ(keypad.offset(), 3);
  ASSERT_EQ(keypad.press(ring::key::digit_4), ring::key_status::ok);
  ASSERT_EQ(keypad.press(ring::key::yes), ring::key_status::ok);
  sim.run(50);
  EXPECT_EQ(read_all(a), "");
  EXPECT_EQ(read_all(b), "");
  EXPECT_EQ(c.get(3).value, 4);
  EXPECT_EQ(c.get(3).value, 13);
}

// Example 1: number entry and the up/down keys from either keypad change VR(length); both displays show the
// same SPEED/LENGTH text.
TEST(ManualExample1, TwoKeypadsOneMotionCoordinator) {
  recorded_network n({mc_file("examples/manual/example1.bas"), trionet::test::keypad(), trionet::test::keypad()});
  ASSERT_TRUE(n.ok());
  n.net().run(200);  // the program's set-up
  for (std::size_t node : {2u, 3u}) {
    const host::node_report k = n.net().report(node);
    ASSERT_TRUE(k.network_mode);
    // PRINT #10,"SPEED:":PRINT #10,"LENGTH:": PRINT without ';' ends with CR LF; CR moves to the start of the
    // other line unless the cursor is at the start of a line (protocol 1.9), so SPEED: is on line 1 and
    // LENGTH: on line 2.
    EXPECT_EQ(k.display[0], "SPEED:              ");
    EXPECT_EQ(k.display[1], "LENGTH:             ");
    EXPECT_FALSE(k.cursor_visible);  // CHR(14)
  }
  EXPECT_EQ(n.net().report(2).offset, 2u);  // SEND(10,2,11): two nodes on, round to the MC
  EXPECT_EQ(n.net().report(3).offset, 1u);  // SEND(11,2,10)

  n.keys("1:1 2:2 1:5 2:up 1:up 2:up 1:down");
  EXPECT_EQ(n.net().run(100000), host::run_end::settled);
  const host::node_report mc = n.net().report(1);
  EXPECT_EQ(variable_of(mc, "a"), 125);  // a=a*10+k for 1, 2, 5 from either keypad
  EXPECT_NEAR(vr_of(mc, 2), 0.2, 1e-9);  // VR(length): +0.1 three times, -0.1 once
  for (std::size_t node : {2u, 3u}) {
    const host::node_report k = n.net().report(node);
    // PRINT #10,CHR(27);CHR(72);CHR(7);a[6,0]: a in 6 characters from position 7, after "SPEED: ".
    EXPECT_EQ(k.display[0], "SPEED:    125       ");
    // PRINT #10,CURSOR(28);VR(length)[8,1]: 8 characters from position 28, after "LENGTH: " on line 2.
    EXPECT_EQ(k.display[1], "LENGTH:      0.2    ");
    EXPECT_EQ(k.dropped, 0u);
  }
  EXPECT_EQ(mc.netstat, 0u);
  EXPECT_EQ(mc.state, "running");  // REPEAT ... UNTIL FALSE
  EXPECT_TRUE(mc.idle);            // polling KEY#3 with no key left to come
}

// Example 2: the "I" handshake sets VR(200)=99 on the three-axis node, the parameters entered on the keypad
// reach VR(0) and VR(1) on the two-axis node, "G" sets VR(200)=999.
TEST(ManualExample2, TwoMotionCoordinatorsOneKeypad) {
  recorded_network n({mc_file("examples/manual/example2_three_axis.bas"),
                      mc_file("examples/manual/example2_two_axis.bas"), trionet::test::keypad()});
  ASSERT_TRUE(n.ok());
  n.net().run(1000);
  // PRINT #10,"I"; from the three-axis node to the next node; SEND(11,1,200,99) back through the keypad.
  EXPECT_TRUE(n.saw(host::event_kind::message, "1 -> 2  hops 1  PRINT \"I\""));
  EXPECT_EQ(vr_of(n.net().report(1), 200), 99);
  EXPECT_EQ(n.net().report(1).state, "waiting");  // GET #3,VR(100) in setlen
  // PRINT #11,CHR(12);CHR(14);"MACHINE READY" ends with CR LF: "FEED LENGTH:" starts line 2.
  const host::node_report before = n.net().report(3);
  EXPECT_EQ(before.display[0], "MACHINE READY       ");
  EXPECT_EQ(before.display[1], "FEED LENGTH:   0.0  ");

  n.keys("1:up 1:up 1:up 1:y 1:up 1:up 1:y 1:start");
  EXPECT_EQ(n.net().run(100000), host::run_end::settled);
  // PRINT#11,CHR(27);CHR(72);CHR(32);VR(0)[6.1];: position 32 is right after "FEED LENGTH:" on line 2. (The
  // loop then prints "FEED LENGTH:" again where the cursor is, which wraps on a 2 x 20 display.)
  bool seen = false;
  for (const host::network_event& e : n.events()) {
    if (e.kind == host::event_kind::display && e.display[1] == "FEED LENGTH:   0.1  ") seen = true;
  }
  EXPECT_TRUE(seen) << "no display showed VR(0) = 0.1 at position 32";

  const host::node_report three = n.net().report(1);
  const host::node_report two = n.net().report(2);
  const host::node_report keypad = n.net().report(3);
  EXPECT_EQ(vr_of(three, 200), 999);
  EXPECT_NEAR(vr_of(three, 0), 0.3, 1e-9);
  EXPECT_NEAR(vr_of(three, 1), 0.02, 1e-9);
  EXPECT_NEAR(vr_of(two, 0), 0.3, 1e-9);   // SEND(10,1,0,VR(0))
  EXPECT_NEAR(vr_of(two, 1), 0.02, 1e-9);  // SEND(10,1,1,VR(1))
  EXPECT_NEAR(trionet::test::parameter_of(two, "SPEED"), 0.02, 1e-9);  // SPEED=VR(1)
  EXPECT_EQ(vr_of(two, 100), 71);                                        // "G"
  EXPECT_EQ(keypad.display[0], "PRESS START TO RUN  ");
  EXPECT_EQ(three.netstat, 0u);
  EXPECT_EQ(two.netstat, 0u);
  EXPECT_EQ(keypad.dropped, 0u);
  EXPECT_EQ(three.state, "ended");  // at the STOP of the "moves:" placeholder
  EXPECT_EQ(two.state, "ended");
}

// "The Motion Coordinator that is not controlling the membrane keypad must not transmit anything to or via
// the keypad until the keypad has been set into network mode": such a message is lost, visibly.
TEST(ManualWarning, MessageThroughAKeypadInLocalModeIsLost) {
  trionet::vr_table<16> vr[2];
  mc_node a(vr[0]), b(vr[1]);
  keypad_node keypad;
  ring::simulator<> sim;  // a -> keypad -> b -> a
  ASSERT_TRUE(sim.add(a));
  ASSERT_TRUE(sim.add(keypad));
  ASSERT_TRUE(sim.add(b));
  ASSERT_EQ(a.print(11, "TOO EARLY").status, ring::send_status::ok);
  sim.run(50);
  EXPECT_EQ(read_all(b), "");
  EXPECT_EQ(keypad.forwarding_counters().messages_dropped, 1u);
  ASSERT_EQ(a.send_keypad_offset(10, 11), ring::send_status::ok);
  ASSERT_EQ(a.print(11, "IN TIME").status, ring::send_status::ok);
  sim.run(50);
  EXPECT_EQ(read_all(b), "IN TIME");
  EXPECT_EQ(keypad.forwarding_counters().messages_dropped, 1u);
}

// "If these two nodes are not adjacent in the ring any nodes between them will be tied up re-transmitting
// messages and will not be able to transmit as priority is given to re-transmission of messages. This can be
// a particular problem if one of the nodes re-transmitting is a membrane keypad."
namespace {

// Byte-times from a key press on the keypad to its message leaving the keypad, while MC `source` sends a
// burst of `burst` variable transfers `hops` nodes along.
std::uint64_t key_wait(bool keypad_between, int burst) {
  trionet::vr_table<256> vr[3];
  mc_node source(vr[0]), sink(vr[1]), other(vr[2]);
  keypad_node keypad;
  ring::simulator<> sim;
  // Between: source -> keypad -> sink -> other.   Adjacent: source -> sink -> keypad -> other.
  if (keypad_between) {
    for (trionet::byte_port* n : std::initializer_list<trionet::byte_port*>{&source, &keypad, &sink, &other})
      (void)sim.add(*n);
  } else {
    for (trionet::byte_port* n : std::initializer_list<trionet::byte_port*>{&source, &sink, &keypad, &other})
      (void)sim.add(*n);
  }
  const int keypad_hops = keypad_between ? 1 : 2;
  const int sink_address = keypad_between ? 11 : 10;
  (void)source.send_keypad_offset(9 + keypad_hops, 10);
  sim.run(20);
  EXPECT_TRUE(keypad.network_mode());
  int queued = 0;
  auto refill = [&] {
    while (queued < burst && source.transmit_free() >= 16) {
      EXPECT_EQ(source.send_variable(sink_address, 1, queued), ring::send_status::ok);
      ++queued;
    }
  };
  refill();
  sim.run(20);  // the flow is running
  EXPECT_EQ(keypad.press(ring::key::digit_1), ring::key_status::ok);
  const std::uint64_t pressed = sim.now();
  std::uint64_t left = 0;
  const std::size_t keypad_link = keypad_between ? 1 : 2;
  for (int t = 0; t < 100000; ++t) {
    refill();
    sim.step([&](const ring::link_byte& b) {
      if (b.link == keypad_link && left == 0 && b.sent == ring::make_header(1, 1)) left = b.time;
    });
    if (left != 0 && queued == burst && sim.quiet()) break;
  }
  EXPECT_NE(left, 0u) << "the key press never left the keypad";
  EXPECT_EQ(vr[1][1], burst - 1);  // the whole flow arrived
  return left - pressed;
}

}  // namespace

TEST(ManualPerformanceNote, NodesBetweenAHeavyFlowWaitToSendTheirOwn) {
  const std::uint64_t between = key_wait(true, 200);
  const std::uint64_t adjacent = key_wait(false, 200);
  std::printf(
      "key press to transmission: %llu byte-times with a 200-message flow through the keypad, "
      "%llu when the flow's ends are adjacent\n",
      static_cast<unsigned long long>(between), static_cast<unsigned long long>(adjacent));
  RecordProperty("wait_between", static_cast<int>(between));
  RecordProperty("wait_adjacent", static_cast<int>(adjacent));
  EXPECT_LE(adjacent, 2u);
  EXPECT_GT(between, 16u * 150u);  // it waited for (most of) the flow of 16-byte messages to pass
  // A longer flow makes it wait longer: the wait is the flow, not a constant.
  EXPECT_GT(key_wait(true, 400), between + 16u * 150u);
}
