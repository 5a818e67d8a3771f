// Fuzz harness: the TN20-17 VR codec and a VR-exchange node (docs/protocol.md 2.1-2.2) on arbitrary frames.
//
// Input: byte 0 picks the node (node count 2..11, node number) and its port's behaviour; then a sequence of
// operations, each an operation byte and its arguments:
//   op % 4 != 3  receive a frame: identifier (an exchange identifier near 10..119 or any 32-bit word, flags
//                included), DLC 0..15 and 8 data bytes, all from the input
//   op % 4 == 3  send VR(vr) = value to a destination node: vr 0..511, value an arbitrary double (NaN,
//                infinities and huge values included), a decimal tie x.xxxx5, or a parts-based message with
//                any fraction
// Invariants:
//   - decode_vr_frame classifies every frame exactly as the wire rules say (DLC exactly 8 and not remote,
//     sign 0/1, fraction <= 9999), in that order;
//   - a decoded message re-encodes to the same 8 bytes, except that a negative zero is sent with sign 0;
//     the re-encoded bytes decode to the same value; and the double the node writes rounds back (encode_vr)
//     to the same 8 bytes: decode -> double -> encode is the identity on the wire;
//   - the node's `receive` says foreign exactly for frames not on its own receive identifiers, counts every
//     frame exactly once (the receive counters add up to the frames fed), and a written VR holds the value;
//   - a send either fails for the stated reason with no frame handed to the port, or hands the port one
//     frame on the exchange identifier from this node to the destination that decodes to the rounded value;
//     the send counters add up to the frames handed to the port; a failed encode writes nothing; a decimal
//     tie rounds away from zero (docs/protocol.md 2.2: 2.34565 -> 2.3457), checked with integer arithmetic.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include <trionet/can/frame.hpp>
#include <trionet/can/identifiers.hpp>
#include <trionet/can/node.hpp>
#include <trionet/can/port.hpp>
#include <trionet/can/vr_codec.hpp>
#include <trionet/vr.hpp>

#include "fuzz_check.hpp"

namespace {

using namespace trionet::can;

constexpr std::size_t vr_count = 128;

bool refuse_some(void*, std::uint16_t vr, double) noexcept {
  return vr % 5 != 4;
}

/// A port that records the frame it is handed and answers as the input says.
class recording_port final : public port {
 public:
  transmit_status answer = transmit_status::ok;
  frame last{};
  std::uint32_t calls = 0;

  transmit_status send(const frame& outgoing) noexcept override {
    last = outgoing;
    ++calls;
    return answer;
  }
};

bool same(const vr_value& a, const vr_value& b) {
  return a.negative == b.negative && a.integer_part == b.integer_part && a.fraction == b.fraction;
}

/// The wire rules, written out independently of the codec.
decode_status classify(const frame& f) {
  if ((f.id & frame::remote_flag) != 0 || f.dlc != 8) return decode_status::bad_dlc;
  if (f.data[1] > 1) return decode_status::bad_sign;
  if ((f.data[6] << 8 | f.data[7]) > 9999) return decode_status::bad_fraction;
  return decode_status::ok;
}

void check_codec(const frame& f) {
  const decode_result decoded = decode_vr_frame(f);
  FUZZ_CHECK(decoded.status == classify(f));
  if (decoded.status != decode_status::ok) return;

  const vr_message& m = decoded.message;
  FUZZ_CHECK(m.vr == f.data[0]);
  FUZZ_CHECK(m.value.fraction <= vr_value::max_fraction);
  const bool zero = m.value.integer_part == 0 && m.value.fraction == 0;

  // decode -> encode: the same 8 bytes (negative zero goes out with sign 0).
  std::uint8_t again[vr_message_size] = {};
  FUZZ_CHECK(encode_vr_message(m, again) == encode_status::ok);
  std::uint8_t wire[vr_message_size];
  std::memcpy(wire, f.data, sizeof wire);
  if (zero) wire[1] = 0;
  FUZZ_CHECK(std::memcmp(again, wire, sizeof wire) == 0);

  // encode -> decode: the same message.
  const decode_result redecoded = decode_vr_message(trionet::byte_view(again, vr_message_size));
  FUZZ_CHECK(redecoded.status == decode_status::ok);
  FUZZ_CHECK(redecoded.message.vr == m.vr);
  vr_value normal = m.value;
  if (zero) normal.negative = false;
  FUZZ_CHECK(same(redecoded.message.value, normal));

  // decode -> double -> encode_vr: the double a node writes stands for exactly the wire value.
  const double value = to_double(m.value);
  FUZZ_CHECK(std::isfinite(value));
  FUZZ_CHECK(std::signbit(value) == m.value.negative);
  std::uint8_t rounded[vr_message_size] = {};
  FUZZ_CHECK(encode_vr(m.vr, value, rounded) == encode_status::ok);
  FUZZ_CHECK(std::memcmp(rounded, wire, sizeof wire) == 0);
}

class harness {
 public:
  harness(node_address address, trionet::vr_table<vr_count>& table)
      : table_(table), node_(address, port_, table), count_(address.node_count()), self_(address.node()) {}

  void receive(const frame& f) {
    check_codec(f);
    const node_counters before = node_.counters();
    const receive_result r = node_.receive(f);
    ++fed_;

    const bool ours = f.id <= 0x7FF && f.id / 10 == self_ && f.id % 10 + 1 < count_;
    FUZZ_CHECK((r.status == receive_status::foreign) == !ours);
    if (ours) {
      const std::uint32_t channel = f.id % 10 + 1;
      FUZZ_CHECK(r.receive_channel == channel);
      FUZZ_CHECK(r.sender == (channel < self_ ? channel : channel + 1));
      const identifier_result back = exchange_identifier(count_, r.sender, self_);
      FUZZ_CHECK(back.status == scheme_status::ok && back.identifier == f.id);
    }
    const decode_status verdict = classify(f);
    node_counters want = before;
    switch (r.status) {
      case receive_status::foreign:
        ++want.foreign;
        break;
      case receive_status::bad_dlc:
        FUZZ_CHECK(verdict == decode_status::bad_dlc);
        ++want.bad_dlc;
        break;
      case receive_status::bad_sign:
        FUZZ_CHECK(verdict == decode_status::bad_sign);
        ++want.bad_sign;
        break;
      case receive_status::bad_fraction:
        FUZZ_CHECK(verdict == decode_status::bad_fraction);
        ++want.bad_fraction;
        break;
      case receive_status::value_out_of_range:  // a double table holds every decimal the wire carries
        FUZZ_CHECK(false);
        break;
      case receive_status::ok:
      case receive_status::refused:
      case receive_status::out_of_range: {
        FUZZ_CHECK(verdict == decode_status::ok);
        const std::uint8_t vr = f.data[0];
        FUZZ_CHECK(r.message.vr == vr);
        const double value = to_double(r.message.value);
        if (vr >= vr_count) {
          FUZZ_CHECK(r.status == receive_status::out_of_range);
          ++want.out_of_range;
        } else if (!refuse_some(nullptr, vr, value)) {
          FUZZ_CHECK(r.status == receive_status::refused);
          ++want.refused;
        } else {
          FUZZ_CHECK(r.status == receive_status::ok);
          // The double written stands for exactly the wire value: rounded to 4 decimals it gives the same
          // bytes (negative zero as sign 0).
          std::uint8_t back[vr_message_size] = {};
          FUZZ_CHECK(encode_vr(vr, table_[vr], back) == encode_status::ok);
          std::uint8_t wire[vr_message_size];
          std::memcpy(wire, f.data, sizeof wire);
          if (r.message.value.integer_part == 0 && r.message.value.fraction == 0) wire[1] = 0;
          FUZZ_CHECK(std::memcmp(back, wire, sizeof wire) == 0);
          ++want.written;
        }
        break;
      }
    }
    const node_counters& now = node_.counters();
    FUZZ_CHECK(std::memcmp(&now, &want, sizeof want) == 0);
    FUZZ_CHECK(std::uint64_t{now.foreign} + now.malformed() + now.written + now.refused + now.out_of_range +
                   now.value_out_of_range ==
               fed_);
  }

  void send(trionet_fuzz::input_reader& in) {
    const std::uint8_t how = in.byte();
    port_.answer = how % 8 == 6   ? transmit_status::busy
                   : how % 8 == 7 ? transmit_status::failed
                                  : transmit_status::ok;
    const auto destination = static_cast<std::uint8_t>(in.byte() % 13);  // 0 and 12 are never nodes
    const std::uint16_t vr = in.u16() % 512;
    const std::uint32_t calls_before = port_.calls;
    const node_counters before = node_.counters();

    send_status status;
    value_result expected_value;
    if ((how & 8u) == 0) {
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits = bits << 8 | in.byte();
      double value;
      std::memcpy(&value, &bits, sizeof value);
      bool tie = false;
      std::uint64_t ten_thousandths = 0;
      if ((how & 16u) != 0) {  // a decimal tie k.kkkk5: rounds away from zero to k.kkkk + 0.0001
        ten_thousandths = bits >> 24;
        value = static_cast<double>(ten_thousandths * 10u + 5u) / 100000.0;
        if ((how & 32u) != 0) value = -value;
        tie = true;
      }
      status = node_.send_to_node(destination, vr, value);
      expected_value = to_vr_value(value);
      // The encoder itself: on any error nothing is written.
      std::uint8_t out[vr_message_size];
      std::memset(out, 0xEE, sizeof out);
      if (encode_vr(vr, value, out) != encode_status::ok) {
        for (std::uint8_t b : out) FUZZ_CHECK(b == 0xEE);
      }
      if (tie) {  // independent of the codec's arithmetic: exact decimal rounding
        FUZZ_CHECK(expected_value.status == encode_status::ok);
        FUZZ_CHECK(expected_value.value.negative == ((how & 32u) != 0));
        FUZZ_CHECK(expected_value.value.integer_part == (ten_thousandths + 1u) / 10000u);
        FUZZ_CHECK(expected_value.value.fraction == (ten_thousandths + 1u) % 10000u);
      }
    } else {
      vr_message m;
      m.vr = static_cast<std::uint8_t>(vr);
      m.value.negative = (how & 16u) != 0;
      m.value.integer_part = in.u32();
      m.value.fraction = static_cast<std::uint16_t>(in.u16() % 10016);  // a few past 9999
      status = node_.send_to_node(destination, m);
      expected_value.status = m.value.fraction > vr_value::max_fraction ? encode_status::fraction_out_of_range
                                                                        : encode_status::ok;
      expected_value.value = m.value;
      if (m.value.integer_part == 0 && m.value.fraction == 0) expected_value.value.negative = false;
    }

    // Why it must fail, in the node's order: destination, vr (double form only), value.
    send_status want = send_status::ok;
    if (destination < 1 || destination > count_) {
      want = send_status::no_such_node;
    } else if (destination == self_) {
      want = send_status::own_node;
    } else if ((how & 8u) == 0 && vr > max_message_vr) {
      want = send_status::vr_out_of_range;
    } else if (expected_value.status == encode_status::not_a_number) {
      want = send_status::not_a_number;
    } else if (expected_value.status == encode_status::too_large) {
      want = send_status::too_large;
    } else if (expected_value.status == encode_status::fraction_out_of_range) {
      want = send_status::fraction_out_of_range;
    } else if (port_.answer == transmit_status::busy) {
      want = send_status::port_busy;
    } else if (port_.answer == transmit_status::failed) {
      want = send_status::port_failed;
    }
    FUZZ_CHECK(status == want);

    const bool handed =
        want == send_status::ok || want == send_status::port_busy || want == send_status::port_failed;
    FUZZ_CHECK(port_.calls == calls_before + (handed ? 1u : 0u));
    const node_counters& now = node_.counters();
    FUZZ_CHECK(now.sent + now.send_busy + now.send_failed == port_.calls);
    FUZZ_CHECK(now.sent == before.sent + (want == send_status::ok ? 1u : 0u));
    if (!handed) return;

    const frame& out = port_.last;
    FUZZ_CHECK(out.dlc == vr_message_size && !out.extended() && !out.remote());
    const route_result routed = route_of(count_, out.id);
    FUZZ_CHECK(routed.status == scheme_status::ok);
    FUZZ_CHECK(routed.value.sender == self_ && routed.value.receiver == destination);
    const decode_result decoded = decode_vr_frame(out);
    FUZZ_CHECK(decoded.status == decode_status::ok);
    FUZZ_CHECK(decoded.message.vr == static_cast<std::uint8_t>(vr));
    FUZZ_CHECK(same(decoded.message.value, expected_value.value));
    check_codec(out);
  }

 private:
  trionet::vr_table<vr_count>& table_;
  recording_port port_;
  vr_exchange_node node_;
  std::uint8_t count_;
  std::uint8_t self_;
  std::uint64_t fed_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static constexpr std::uint8_t empty[1] = {0};
  trionet_fuzz::input_reader in(data == nullptr ? empty : data, size);

  const std::uint8_t setup = in.byte();
  const auto count = static_cast<std::uint8_t>(2 + setup % 10);
  const auto node = static_cast<std::uint8_t>(1 + (setup >> 4) % count);
  const address_result address = make_node_address(count, node);
  FUZZ_CHECK(address.status == scheme_status::ok);
  FUZZ_CHECK(make_node_address(1, 1).status != scheme_status::ok);
  FUZZ_CHECK(make_node_address(count, static_cast<std::uint8_t>(count + 1)).status != scheme_status::ok);

  trionet::vr_table<vr_count> table(refuse_some);
  harness h(address.address, table);
  while (!in.done()) {
    const std::uint8_t op = in.byte();
    if (op % 4 == 3) {
      h.send(in);
      continue;
    }
    frame f;
    if ((op & 4u) == 0) {
      f.id = 10u + in.byte() % 110u;  // near the exchange identifiers of 2..11 nodes
      if ((op & 8u) != 0) f.id |= frame::remote_flag;
    } else {
      f.id = in.u32();
    }
    f.dlc = (op & 16u) == 0 ? std::uint8_t{8} : static_cast<std::uint8_t>(in.byte() & 15u);
    for (auto& byte : f.data) byte = in.byte();
    h.receive(f);
  }
  return 0;
}
