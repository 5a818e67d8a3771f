// TN20-17 VR-exchange node: sending by destination and by transmit channel, receiving into VR() through the
// vr_store hook, and the counters for foreign, malformed, refused and out-of-range frames.
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>
#include <limits>
#include <utility>
#include <vector>

#include <trionet/can.hpp>

namespace {

using namespace trionet::can;
using trionet::vr_table;
using trionet::vr_write_status;

/// A port that records frames and answers with a chosen status.
class recording_port final : public port {
 public:
  transmit_status answer = transmit_status::ok;
  std::vector<frame> frames;

  transmit_status send(const frame& outgoing) noexcept override {
    if (answer == transmit_status::ok) frames.push_back(outgoing);
    return answer;
  }
};

frame make_frame(std::uint32_t id, std::vector<std::uint8_t> bytes) {
  frame f;
  f.id = id;
  f.dlc = static_cast<std::uint8_t>(bytes.size());
  for (std::size_t i = 0; i < bytes.size() && i < 8; ++i) f.data[i] = bytes[i];
  return f;
}

node_address address(std::uint8_t nodes, std::uint8_t node) {
  const address_result made = make_node_address(nodes, node);
  EXPECT_EQ(made.status, scheme_status::ok);
  return made.address;
}

TEST(CanNode, ProtocolExampleNodeOneSendsVrOneToNodeFour) {
  recording_port wire;
  vr_table<256> vrs;
  vr_exchange_node node1(address(5, 1), wire, vrs);
  ASSERT_EQ(node1.send_to_node(4, 1, 2.345), send_status::ok);
  ASSERT_EQ(node1.send_on_channel(7, 1, 2.345), send_status::ok) << "buffer 7 of node 1 is node 4";
  ASSERT_EQ(wire.frames.size(), 2U);
  EXPECT_EQ(wire.frames[0], make_frame(40, {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0D, 0x7A}));
  EXPECT_EQ(wire.frames[1], wire.frames[0]);
  EXPECT_EQ(node1.counters().sent, 2U);
}

TEST(CanNode, NoteSendVrRoutineChannelFiveIsTheNextNode) {
  recording_port wire;
  vr_table<256> vrs;
  for (std::uint8_t k = 1; k <= 5; ++k) {
    vr_exchange_node node(address(5, k), wire, vrs);
    ASSERT_EQ(node.send_on_channel(5, 1, 2.345), send_status::ok);
    const route_result route = route_of(5, wire.frames.back().id);
    EXPECT_EQ(route.value.sender, k);
    EXPECT_EQ(route.value.receiver, k % 5 + 1);
  }
}

TEST(CanNode, PartsBasedSendNeedsNoDouble) {
  recording_port wire;
  vr_table<8> vrs;
  vr_exchange_node node5(address(5, 5), wire, vrs);
  ASSERT_EQ(node5.send_on_channel(6, vr_message{7, {true, 3, 1416}}), send_status::ok);
  EXPECT_EQ(wire.frames.back(), make_frame(23, {7, 1, 0, 0, 0, 3, 0x05, 0x88}));
  EXPECT_EQ(node5.send_to_node(2, vr_message{7, {false, 3, 10000}}), send_status::fraction_out_of_range);
}

TEST(CanNode, SendMisuseIsReportedAndNothingIsQueued) {
  recording_port wire;
  vr_table<8> vrs;
  vr_exchange_node node2(address(5, 2), wire, vrs);
  EXPECT_EQ(node2.send_to_node(2, 1, 1.0), send_status::own_node);
  EXPECT_EQ(node2.send_to_node(0, 1, 1.0), send_status::no_such_node);
  EXPECT_EQ(node2.send_to_node(6, 1, 1.0), send_status::no_such_node);
  EXPECT_EQ(node2.send_on_channel(4, 1, 1.0), send_status::no_such_channel);
  EXPECT_EQ(node2.send_on_channel(9, 1, 1.0), send_status::no_such_channel);
  EXPECT_EQ(node2.send_to_node(1, 256, 1.0), send_status::vr_out_of_range);
  EXPECT_EQ(node2.send_to_node(1, 1, std::numeric_limits<double>::quiet_NaN()), send_status::not_a_number);
  EXPECT_EQ(node2.send_to_node(1, 1, 4294967296.0), send_status::too_large);
  EXPECT_TRUE(wire.frames.empty());
  EXPECT_EQ(node2.counters().sent, 0U);
}

TEST(CanNode, PortRefusalsAreCountedBySort) {
  recording_port wire;
  vr_table<8> vrs;
  vr_exchange_node node3(address(5, 3), wire, vrs);
  wire.answer = transmit_status::busy;
  EXPECT_EQ(node3.send_to_node(1, 1, 1.0), send_status::port_busy);
  EXPECT_EQ(node3.send_to_node(1, 1, 1.0), send_status::port_busy);
  wire.answer = transmit_status::failed;
  EXPECT_EQ(node3.send_on_channel(5, 1, 1.0), send_status::port_failed);
  EXPECT_EQ(node3.counters().send_busy, 2U);
  EXPECT_EQ(node3.counters().send_failed, 1U);
  EXPECT_EQ(node3.counters().sent, 0U);
}

TEST(CanNode, ReceivedFrameOnOwnIdentifierWritesTheVr) {
  recording_port wire;
  vr_table<256> vrs;
  vr_exchange_node node4(address(5, 4), wire, vrs);
  const receive_result r = node4.receive(make_frame(40, {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0D, 0x7A}));
  EXPECT_EQ(r.status, receive_status::ok);
  EXPECT_EQ(r.sender, 1);
  EXPECT_EQ(r.receive_channel, 1);
  EXPECT_EQ(r.message.vr, 1);
  EXPECT_EQ(to_double(r.message.value), 2.345);
  EXPECT_EQ(vrs[1], 2.345);
  const receive_result negative = node4.receive(make_frame(43, {200, 1, 0, 0, 0x01, 0x00, 0x00, 0x05}));
  EXPECT_EQ(negative.status, receive_status::ok);
  EXPECT_EQ(negative.sender, 5);
  EXPECT_EQ(vrs[200], -256.0005);
  EXPECT_EQ(node4.counters().written, 2U);
}

// The byte order is configurable (docs/protocol.md 2.2): a little-endian node sends and reads little-endian
// numbers, and a big-endian node reads the same bytes as another value.
TEST(CanNode, LittleEndianNodesSendAndReceiveLittleEndianNumbers) {
  recording_port wire;
  vr_table<256> vrs1;
  vr_table<256> vrs4;
  vr_table<256> big_endian_vrs;
  vr_exchange_node node1(address(5, 1), wire, vrs1, byte_order::little_endian);
  vr_exchange_node node4(address(5, 4), wire, vrs4, byte_order::little_endian);
  vr_exchange_node big4(address(5, 4), wire, big_endian_vrs);
  EXPECT_EQ(node1.order(), byte_order::little_endian);
  EXPECT_EQ(big4.order(), byte_order::big_endian);
  ASSERT_EQ(node1.send_to_node(4, 1, 2.345), send_status::ok);
  ASSERT_EQ(wire.frames.size(), 1U);
  EXPECT_EQ(wire.frames[0], make_frame(40, {0x01, 0x00, 0x02, 0x00, 0x00, 0x00, 0x7A, 0x0D}));
  EXPECT_EQ(node4.receive(wire.frames[0]).status, receive_status::ok);
  EXPECT_EQ(vrs4[1], 2.345);
  // Read big-endian, 7A 0D is 31245 ten-thousandths: not a fraction, so nothing is written.
  EXPECT_EQ(big4.receive(wire.frames[0]).status, receive_status::bad_fraction);
  EXPECT_EQ(big_endian_vrs[1], 0.0);
}

// A byte order fixed at compile time (firmware that knows its network) sends and reads exactly what a node
// given the same order at run time does, and the node holds no byte order.
TEST(CanNode, AByteOrderFixedAtCompileTimeBehavesAsTheSameOrderChosenAtRunTime) {
  using little_node = basic_vr_exchange_node<fixed_byte_order<byte_order::little_endian>>;
  using big_node = basic_vr_exchange_node<fixed_byte_order<byte_order::big_endian>>;
  static_assert(sizeof(little_node) <= sizeof(vr_exchange_node));
  static_assert(!std::is_constructible_v<big_node, node_address, port&, trionet::vr_store&, byte_order>,
                "a fixed order cannot be given another at run time");
  for (const byte_order order : {byte_order::big_endian, byte_order::little_endian}) {
    recording_port fixed_wire;
    recording_port run_time_wire;
    vr_table<256> fixed_vrs;
    vr_table<256> run_time_vrs;
    little_node little(address(5, 1), fixed_wire, fixed_vrs);
    big_node big(address(5, 1), fixed_wire, fixed_vrs);
    vr_exchange_node run_time(address(5, 1), run_time_wire, run_time_vrs, order);
    EXPECT_EQ(little.order(), byte_order::little_endian);
    EXPECT_EQ(big.order(), byte_order::big_endian);
    for (const double value : {2.345, -256.0005, 65536.25, 0.0001}) {
      ASSERT_EQ(order == byte_order::little_endian ? little.send_to_node(4, 7, value)
                                                   : big.send_to_node(4, 7, value),
                send_status::ok);
      ASSERT_EQ(run_time.send_to_node(4, 7, value), send_status::ok);
    }
    EXPECT_EQ(fixed_wire.frames, run_time_wire.frames);
    // Frames on node 1's first receive identifier: each node reads them as its order says.
    for (const std::vector<std::uint8_t>& data :
         {std::vector<std::uint8_t>{3, 0, 0, 0, 0x01, 0x02, 0x00, 0x05},
          std::vector<std::uint8_t>{4, 1, 0x02, 0x00, 0x00, 0x00, 0x0D, 0x7A}}) {
      const frame f = make_frame(10, data);
      const receive_result fixed_result =
          order == byte_order::little_endian ? little.receive(f) : big.receive(f);
      const receive_result run_time_result = run_time.receive(f);
      EXPECT_EQ(fixed_result.status, run_time_result.status);
      EXPECT_EQ(fixed_result.message.vr, run_time_result.message.vr);
      EXPECT_EQ(fixed_result.message.value.integer_part, run_time_result.message.value.integer_part);
      EXPECT_EQ(fixed_result.message.value.fraction, run_time_result.message.value.fraction);
    }
    for (std::uint16_t vr = 0; vr < 8; ++vr) EXPECT_EQ(fixed_vrs[vr], run_time_vrs[vr]) << "VR " << vr;
  }
}

TEST(CanNode, ForeignAndMalformedFramesAreDroppedAndCountedByReason) {
  recording_port wire;
  vr_table<256> vrs;
  vr_exchange_node node4(address(5, 4), wire, vrs);
  const std::vector<std::uint8_t> good = {9, 0, 0, 0, 0, 1, 0, 0};
  EXPECT_EQ(node4.receive(make_frame(50, good)).status, receive_status::foreign);  // node 5's
  EXPECT_EQ(node4.receive(make_frame(44, good)).status, receive_status::foreign);  // no Rx #5
  EXPECT_EQ(node4.receive(make_frame(0x7FF, good)).status, receive_status::foreign);
  EXPECT_EQ(node4.receive(make_frame(40 | frame::extended_flag, good)).status, receive_status::foreign);
  EXPECT_EQ(node4.receive(make_frame(40 | frame::remote_flag, {})).status, receive_status::foreign);
  EXPECT_EQ(node4.receive(make_frame(41, {9, 0, 0, 0, 0, 1, 0})).status, receive_status::bad_dlc);
  frame long_dlc = make_frame(41, good);
  long_dlc.dlc = 15;
  EXPECT_EQ(node4.receive(long_dlc).status, receive_status::bad_dlc);
  EXPECT_EQ(node4.receive(make_frame(42, {9, 2, 0, 0, 0, 1, 0, 0})).status, receive_status::bad_sign);
  EXPECT_EQ(node4.receive(make_frame(42, {9, 0, 0, 0, 0, 1, 0x27, 0x10})).status,
            receive_status::bad_fraction);
  const node_counters& c = node4.counters();
  EXPECT_EQ(c.foreign, 5U);
  EXPECT_EQ(c.bad_dlc, 2U);
  EXPECT_EQ(c.bad_sign, 1U);
  EXPECT_EQ(c.bad_fraction, 1U);
  EXPECT_EQ(c.malformed(), 4U);
  EXPECT_EQ(c.written, 0U);
  EXPECT_EQ(vrs[9], 0.0) << "nothing was written";
  node4.clear_counters();
  EXPECT_EQ(node4.counters().foreign, 0U);
}

bool refuse_vr_seven(void* context, std::uint16_t vr, double) noexcept {
  ++*static_cast<int*>(context);
  return vr != 7;
}

TEST(CanNode, WritesGoThroughTheVrStorePolicyLikeTheRing) {
  recording_port wire;
  int asked = 0;
  vr_table<100> vrs(refuse_vr_seven, &asked);
  vr_exchange_node node1(address(5, 1), wire, vrs);
  EXPECT_EQ(node1.receive(make_frame(10, {7, 0, 0, 0, 0, 5, 0, 0})).status, receive_status::refused);
  EXPECT_EQ(node1.receive(make_frame(11, {8, 0, 0, 0, 0, 5, 0, 0})).status, receive_status::ok);
  EXPECT_EQ(node1.receive(make_frame(12, {150, 0, 0, 0, 0, 5, 0, 0})).status, receive_status::out_of_range);
  EXPECT_EQ(vrs[7], 0.0);
  EXPECT_EQ(vrs[8], 5.0);
  EXPECT_EQ(asked, 2) << "the policy is asked for in-range VRs only";
  EXPECT_EQ(node1.counters().refused, 1U);
  EXPECT_EQ(node1.counters().written, 1U);
  EXPECT_EQ(node1.counters().out_of_range, 1U);
}

// A value the VR table cannot hold is its own outcome, not a vr past the table: a Q32.32 table holds
// [-2^31, 2^31), and the wire carries integer parts up to 2^32 - 1.
TEST(CanNode, ValueOutOfRangeIsNotFoldedIntoOutOfRange) {
  recording_port wire;
  vr_table<100, std::int64_t> vrs;
  vr_exchange_node node1(address(5, 1), wire, vrs);
  const receive_result r = node1.receive(make_frame(10, {7, 0, 0x80, 0, 0, 0, 0, 0}));  // VR(7) = 2^31
  EXPECT_EQ(r.status, receive_status::value_out_of_range);
  EXPECT_EQ(r.message.vr, 7U);
  EXPECT_EQ(vrs[7], 0);
  EXPECT_EQ(node1.counters().value_out_of_range, 1U);
  EXPECT_EQ(node1.counters().out_of_range, 0U);
  EXPECT_EQ(node1.receive(make_frame(11, {100, 0, 0, 0, 0, 1, 0, 0})).status, receive_status::out_of_range);
  EXPECT_EQ(node1.counters().out_of_range, 1U);
  EXPECT_EQ(node1.counters().value_out_of_range, 1U);
}

TEST(CanNode, AddressesAreChecked) {
  EXPECT_EQ(make_node_address(5, 0).status, scheme_status::bad_node);
  EXPECT_EQ(make_node_address(5, 6).status, scheme_status::bad_node);
  EXPECT_EQ(make_node_address(1, 1).status, scheme_status::bad_node_count);
  EXPECT_EQ(make_node_address(12, 1).status, scheme_status::bad_node_count);
  constexpr address_result eleven = make_node_address(11, 11);
  static_assert(eleven.status == scheme_status::ok && eleven.address.node() == 11, "constexpr address");
  EXPECT_EQ(node_address{}.node_count(), default_node_count);
}

TEST(CanNode, ElevenNodeExchangeEveryPairDelivers) {
  recording_port wire;
  vr_table<256> vrs[11];
  for (std::uint8_t s = 1; s <= 11; ++s) {
    vr_exchange_node sender(address(11, s), wire, vrs[s - 1]);
    for (std::uint8_t d = 1; d <= 11; ++d) {
      if (d == s) continue;
      ASSERT_EQ(sender.send_to_node(d, static_cast<std::uint16_t>(s * 11 + d), s + d / 100.0),
                send_status::ok);
    }
  }
  for (std::uint8_t r = 1; r <= 11; ++r) {
    vr_exchange_node receiver(address(11, r), wire, vrs[r - 1]);
    for (const frame& f : wire.frames) (void)receiver.receive(f);
    EXPECT_EQ(receiver.counters().written, 10U);
    EXPECT_EQ(receiver.counters().foreign, 100U);
    for (std::uint8_t s = 1; s <= 11; ++s) {
      if (s != r) {
        EXPECT_EQ(vrs[r - 1][s * 11U + r], s + r / 100.0);
      }
    }
  }
}

// The node's own identifier arithmetic agrees with the scheme's functions (identifiers.hpp) for every node of
// every exchange size: which frames it takes, from whom and on which receive channel, for every 11-bit
// identifier and with the extended and remote flags; and the identifier it sends to every destination.
TEST(CanNode, IdentifiersAgreeWithTheSchemeForEveryNodeAndIdentifier) {
  recording_port wire;
  vr_table<256> vr;
  for (std::uint8_t n = min_node_count; n <= max_node_count; ++n) {
    for (std::uint8_t k = 1; k <= n; ++k) {
      vr_exchange_node node(address(n, k), wire, vr);
      const frame value = make_frame(0, {1, 0, 0, 0, 0, 2, 0, 0});
      for (std::uint32_t id = 0; id <= 0x7FF; ++id) {
        for (std::uint32_t flags : {0U, frame::extended_flag, frame::remote_flag}) {
          frame f = value;
          f.id = id | flags;
          const receive_result got = node.receive(f);
          const channel_result channel = receive_channel_of(n, k, f.id);
          if (channel.status != scheme_status::ok) {  // flagged identifiers included: never exchange frames
            ASSERT_EQ(got.status, receive_status::foreign) << int(n) << " " << int(k) << " " << f.id;
            continue;
          }
          ASSERT_EQ(flags, 0U);
          ASSERT_EQ(got.status, receive_status::ok) << int(n) << " " << int(k) << " " << f.id;
          ASSERT_EQ(got.receive_channel, channel.channel);
          const route_result route = route_of(n, f.id);
          ASSERT_EQ(got.sender, route.value.sender);
          ASSERT_EQ(exchange_identifier(n, got.sender, k).identifier, f.id);
        }
      }
      for (std::uint8_t d = 0; d <= n + 1; ++d) {
        wire.frames.clear();
        const send_status sent = node.send_to_node(d, vr_message{});
        const identifier_result expected = exchange_identifier(n, k, d);
        if (expected.status != scheme_status::ok) {
          ASSERT_EQ(sent, d == k ? send_status::own_node : send_status::no_such_node);
          ASSERT_TRUE(wire.frames.empty());
          continue;
        }
        ASSERT_EQ(sent, send_status::ok);
        ASSERT_EQ(wire.frames.at(0).id, expected.identifier) << int(n) << " " << int(k) << " " << int(d);
      }
    }
  }
}

// Every send_status, receive_status and transmit_status has its enumerator's spelling (the CLI prints them);
// a value outside the enum is "unknown".
TEST(CanNode, StatusNamesAreTheEnumeratorsSpelling) {
  const std::pair<send_status, const char*> sends[] = {
      {send_status::ok, "ok"},
      {send_status::no_such_node, "no_such_node"},
      {send_status::own_node, "own_node"},
      {send_status::no_such_channel, "no_such_channel"},
      {send_status::vr_out_of_range, "vr_out_of_range"},
      {send_status::not_a_number, "not_a_number"},
      {send_status::too_large, "too_large"},
      {send_status::fraction_out_of_range, "fraction_out_of_range"},
      {send_status::port_busy, "port_busy"},
      {send_status::port_failed, "port_failed"}};
  for (const auto& [status, name] : sends) EXPECT_STREQ(to_string(status), name);
  EXPECT_STREQ(to_string(static_cast<send_status>(99)), "unknown");
  const std::pair<receive_status, const char*> receives[] = {
      {receive_status::ok, "ok"},
      {receive_status::refused, "refused"},
      {receive_status::out_of_range, "out_of_range"},
      {receive_status::value_out_of_range, "value_out_of_range"},
      {receive_status::foreign, "foreign"},
      {receive_status::bad_dlc, "bad_dlc"},
      {receive_status::bad_sign, "bad_sign"},
      {receive_status::bad_fraction, "bad_fraction"}};
  for (const auto& [status, name] : receives) EXPECT_STREQ(to_string(status), name);
  EXPECT_STREQ(to_string(static_cast<receive_status>(99)), "unknown");
  EXPECT_STREQ(to_string(transmit_status::ok), "ok");
  EXPECT_STREQ(to_string(transmit_status::busy), "busy");
  EXPECT_STREQ(to_string(transmit_status::failed), "failed");
  EXPECT_STREQ(to_string(static_cast<transmit_status>(99)), "unknown");
}

}  // namespace
