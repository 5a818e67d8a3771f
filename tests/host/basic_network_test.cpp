// BASIC programs on the simulated ring (src/sim/ring_network.hpp): the clock, the key script, what ends a run,
// the manual's ordering warning (examples/keypad_order/), and determinism.
#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "support/networks.hpp"

namespace host = trionet::host;
using host::event_kind;
using trionet::test::keypad;
using trionet::test::mc_file;
using trionet::test::mc_text;
using trionet::test::plain_mc;
using trionet::test::recorded_network;
using trionet::test::variable_of;
using trionet::test::vr_of;

namespace {

// The byte-time of the first event of `kind` whose text has `part`, or -1.
long long time_of(const recorded_network& n, event_kind kind, const std::string& part) {
  for (const auto& e : n.events()) {
    if (e.kind == kind && e.text.find(part) != std::string::npos) return static_cast<long long>(e.time);
  }
  return -1;
}

}  // namespace

// The manual: "The Motion Coordinator that is not controlling the membrane keypad must not transmit anything to
// or via the keypad until the keypad has been set into network mode". The feeder does both at once; the keypad
// drops both messages and the master waits for ever for the feeder's "R".
TEST(BasicNetworkOrdering, PrintingThroughAKeypadTooEarlyIsDroppedAndReported) {
  recorded_network n({mc_file("examples/keypad_order/master.bas"), mc_file("examples/keypad_order/feeder.bas"),
                      keypad()});
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n.net().run(100000), host::run_end::settled);
  const std::vector<std::string> dropped = n.texts(event_kind::dropped);
  ASSERT_EQ(dropped.size(), 2u);
  EXPECT_EQ(dropped[0].rfind("dropped PRINT \"\\x1bH\\x14FEEDER READY\" from node 2, sent to this keypad: the keypad "
                             "is in local mode",
                             0),
            0u)
      << dropped[0];
  EXPECT_EQ(dropped[1].rfind("dropped PRINT \"R\" from node 2, passing through to node 1: the keypad is in local mode",
                             0),
            0u)
      << dropped[1];
  for (const auto& e : n.events()) {
    if (e.kind == event_kind::dropped) {
      EXPECT_EQ(e.node, 3u);  // where: the keypad
    }
  }
  const host::node_report master = n.net().report(1);
  EXPECT_EQ(master.state, "waiting");
  EXPECT_EQ(master.waiting, "GET #");
  EXPECT_EQ(master.line, 7u);
  const host::node_report k = n.net().report(3);
  EXPECT_TRUE(k.network_mode);
  EXPECT_EQ(k.dropped, 2u);
  EXPECT_EQ(k.display[0], "MASTER READY        ");
  EXPECT_EQ(k.display[1], "                    ");
}

TEST(BasicNetworkOrdering, WaitingForTheMastersHandshakeFixesIt) {
  recorded_network n({mc_file("examples/keypad_order/master_fixed.bas"),
                      mc_file("examples/keypad_order/feeder_fixed.bas"), keypad()});
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n.net().run(100000), host::run_end::settled);
  EXPECT_TRUE(n.texts(event_kind::dropped).empty());
  EXPECT_EQ(n.net().report(1).state, "ended");
  EXPECT_EQ(variable_of(n.net().report(1), "reply"), 'R');
  EXPECT_EQ(n.net().report(2).state, "ended");
  const host::node_report k = n.net().report(3);
  EXPECT_EQ(k.dropped, 0u);
  EXPECT_EQ(k.display[0], "MASTER READY  RUN   ");
  EXPECT_EQ(k.display[1], "FEEDER READY        ");
  // The feeder sent nothing before VR(10) arrived.
  EXPECT_LT(time_of(n, event_kind::vr_from_ring, "VR(10) is now 1"),
            time_of(n, event_kind::message, "2 -> 3  hops 1  PRINT \"\\x1bH\\x14FEEDER READY\""));
}

TEST(BasicNetworkDeterminism, TwoRunsPutTheSameBytesOnEveryLink) {
  using byte_on_link = std::tuple<std::uint64_t, std::size_t, std::uint8_t>;
  const auto run = [] {
    std::vector<byte_on_link> bytes;
    recorded_network n({mc_file("examples/manual/example2_three_axis.bas"),
                        mc_file("examples/manual/example2_two_axis.bas"), keypad()});
    n.net().on_link_byte([&](std::uint64_t t, std::size_t link, std::uint8_t b) { bytes.emplace_back(t, link, b); });
    n.keys("wait=1000 1:up 1:up 1:y 1:up 1:y 1:start");
    n.net().run(100000);
    return std::make_pair(bytes, n.events().size());
  };
  const auto first = run();
  const auto second = run();
  EXPECT_GT(first.first.size(), 400u);
  EXPECT_EQ(first.first, second.first);
  EXPECT_EQ(first.second, second.second);
  std::size_t links_used[3] = {};
  for (const auto& b : first.first) ++links_used[std::get<1>(b)];
  for (std::size_t used : links_used) EXPECT_GT(used, 0u);
}

TEST(BasicNetworkRuntimeErrors, StopOneProgramAndTheRingGoesOn) {
  recorded_network n({mc_text("bad.bas", "x=1\nRETURN\n"),
                      mc_text("good.bas", "WA(1)\nSEND(10,1,5,42)\n"), plain_mc()});
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n.net().run(10000), host::run_end::settled);
  EXPECT_TRUE(n.saw(event_kind::failed, "program stopped at line 2: RETURN without GOSUB"));
  const host::node_report bad = n.net().report(1);
  EXPECT_EQ(bad.state, "failed");
  EXPECT_EQ(bad.line, 2u);
  EXPECT_EQ(bad.error, "RETURN without GOSUB");
  EXPECT_EQ(n.net().report(2).state, "ended");
  EXPECT_EQ(vr_of(n.net().report(3), 5), 42);  // the plain node got the VR
}

TEST(BasicNetworkClock, WaFollowsTheBitRate) {
  for (const double bit_rate : {125000.0, 62500.0}) {
    host::network_config config;
    config.bit_rate = bit_rate;
    recorded_network n({mc_text("wait.bas", "WA(10)\nPRINT #10,\"X\";\n"), plain_mc()}, config);
    n.net().run(10000);
    // 10 ms = 125 byte-times at 125 kbit/s (80 us each), 62.5 -> 63 at 62.5 kbit/s; the message's three bytes
    // take three more byte-times.
    const long long expected = bit_rate == 125000.0 ? 125 + 3 : 63 + 3;
    EXPECT_EQ(time_of(n, event_kind::message, "PRINT \"X\""), expected) << bit_rate;
  }
}

TEST(BasicNetworkClock, StatementsPerByteTimeSetTheProgramsPace) {
  for (const std::uint32_t statements : {1u, 10u}) {
    host::network_config config;
    config.statements_per_byte_time = statements;
    recorded_network n({mc_text("count.bas", "FOR i=1 TO 100\nNEXT i\n"), plain_mc()}, config);
    n.net().run(10000);
    // FOR and 100 NEXTs: 101 statements; the program ends at the turn after the last one.
    const long long expected = statements == 1 ? 101 : 10;
    EXPECT_EQ(time_of(n, event_kind::ended, "program ended"), expected) << statements;
  }
}

TEST(BasicNetworkPrint, ALongPrintGoesInSeveralMessagesAndNothingIsRefused) {
  const std::string text(100, 'x');
  recorded_network n({mc_text("talker.bas", "PRINT #10,\"" + text + "\"\nPRINT #10,\"END\";\n"),
                      mc_text("listener.bas",
                              "REPEAT\n  GET #4,c\n  n=n+1\nUNTIL c=68\n")});  // 'D', the last character
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n.net().run(100000), host::run_end::settled);
  EXPECT_EQ(variable_of(n.net().report(2), "n"), 100 + 2 + 3);
  EXPECT_EQ(n.net().report(2).state, "ended");
  EXPECT_EQ(n.net().report(1).netstat, 0u);  // PRINT # waited for room; no refused call set bit 0
  std::size_t messages = 0;
  for (const std::string& m : n.texts(event_kind::message)) {
    EXPECT_LE(m.size(), std::string("1 -> 2  hops 1  PRINT \"\"").size() + 30 + 8) << m;  // 30 characters at most
    ++messages;
  }
  EXPECT_EQ(messages, 5u);  // 30 + 30 + 30 + 12 ("x" x 10, CR LF) and "END"
}

TEST(BasicNetworkRunEnd, SettlesOrStopsAtTheLimit) {
  recorded_network idle({mc_text("poll.bas", "loop: IF KEY#4 THEN GET #4,c\nGOTO loop\n"), plain_mc()});
  EXPECT_EQ(idle.net().run(100000), host::run_end::settled);
  EXPECT_LT(idle.net().now(), 100u);
  EXPECT_TRUE(idle.net().report(1).idle);

  recorded_network busy({mc_text("count.bas", "loop: i=i+1\nGOTO loop\n"), plain_mc()});
  EXPECT_EQ(busy.net().run(5000), host::run_end::limit);
  EXPECT_EQ(busy.net().now(), 5000u);
  EXPECT_EQ(busy.net().report(1).statements, 5000u);

  // WA is not waiting for ever: the run goes on until it is over.
  recorded_network timer({mc_text("timer.bas", "WA(100)\nVR(1)=1\n"), plain_mc()});
  EXPECT_EQ(timer.net().run(100000), host::run_end::settled);
  EXPECT_EQ(vr_of(timer.net().report(1), 1), 1);
  EXPECT_GE(timer.net().now(), 1250u);
}

TEST(BasicNetworkKeys, TheScriptPressesKeysInTime) {
  recorded_network n({mc_text("keys.bas", "SEND(10,2,10)\nREPEAT\n  GET #3,k\n  VR(k)=VR(k)+1\nUNTIL k=20\n"),
                      keypad()});
  n.keys("1:7 wait=100 1:7 1:up 1:start");
  EXPECT_EQ(n.net().run(100000), host::run_end::settled);
  // The first 7 came at t=0, before the keypad had its offset: lost.
  EXPECT_TRUE(n.saw(event_kind::key, "keypad 1: key 7 lost: the keypad is in local mode"));
  EXPECT_EQ(time_of(n, event_kind::key, "key 7 sent"), 1000 + 100);  // after the key gap and the wait
  EXPECT_EQ(time_of(n, event_kind::key, "key up sent"), 2100);
  const host::node_report mc = n.net().report(1);
  EXPECT_EQ(vr_of(mc, 7), 1);
  EXPECT_EQ(vr_of(mc, 10), 1);
  EXPECT_EQ(vr_of(mc, 20), 1);
  EXPECT_EQ(n.net().report(2).keys_lost, 1u);
}

TEST(BasicNetworkKeys, ScriptErrorsNameTheWord) {
  recorded_network n({plain_mc(), keypad()});
  std::string error;
  EXPECT_FALSE(n.net().set_keys("1:7 2:7", error));
  EXPECT_EQ(error, "key script, word 2 '2:7': there is no keypad 2 (the ring has 1 keypad)");
  EXPECT_FALSE(n.net().set_keys("1:x", error));
  EXPECT_EQ(error, "key script, word 1 '1:x': no key 'x' (keys: 0..9 up + down - clr y enter n . start stop)");
  EXPECT_FALSE(n.net().set_keys("wait=z", error));
  EXPECT_EQ(error, "key script, word 1 'wait=z': wait=N takes a whole number of byte-times 0..10^12");
  EXPECT_FALSE(n.net().set_keys("up", error));
  EXPECT_EQ(error, "key script, word 1 'up': expected KEYPAD:KEY (e.g. 1:up), nodeN:inM=on|off or wait=N");
  EXPECT_TRUE(n.net().set_keys(" 1:UP\t1:Y  1:+ 1:- 1:clr 1:enter 1:n 1:. 1:stop 1:0 wait=0 ", error)) << error;
}

TEST(BasicNetworkBuild, RingsAndProgramsThatCannotRun) {
  std::string error;
  EXPECT_EQ(host::ring_network::build({plain_mc()}, {}, error), nullptr);
  EXPECT_EQ(error, "a ring has 2 to 15 nodes, not 1");
  EXPECT_EQ(host::ring_network::build(std::vector<host::node_spec>(16, plain_mc()), {}, error), nullptr);
  EXPECT_EQ(error, "a ring has 2 to 15 nodes, not 16");
  EXPECT_EQ(host::ring_network::build({keypad(), keypad()}, {}, error), nullptr);
  EXPECT_EQ(error, "a ring needs at least one Motion Coordinator");
  EXPECT_EQ(host::ring_network::build({mc_text("oops.bas", "x=1\nIF x THEN\n"), keypad()}, {}, error), nullptr);
  EXPECT_EQ(error, "oops.bas:2:1: IF has no ENDIF");
}

// The README's two controllers: ping.bas hands 1..5 to pong.bas, which sends each back.
TEST(BasicNetworkExamples, TwoControllersFromTheReadme) {
  recorded_network n({mc_file("examples/two_controllers/ping.bas"), mc_file("examples/two_controllers/pong.bas")});
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(n.net().run(100000), host::run_end::settled);
  EXPECT_EQ(n.texts(event_kind::output), std::vector<std::string>{"prints: all 5 came back"});
  EXPECT_EQ(n.texts(event_kind::vr_from_ring).size(), 10u);
  EXPECT_EQ(vr_of(n.net().report(1), 21), 5);
  EXPECT_EQ(vr_of(n.net().report(2), 20), 5);
  EXPECT_EQ(n.net().report(1).state, "ended");
  EXPECT_EQ(n.net().report(2).state, "ended");
}
