// Fuzz harness: a Motion Coordinator node and a keypad node on the ring (docs/protocol.md 1.5-1.9), driven by
// received bytes interleaved with program calls, every choice read from the input.
//
// Input: a sequence of operations; the top 3 bits of an operation byte say which:
//   0, 1  receive the next (op & 63) + 1 input bytes (raw bytes from the fibre)
//   2     receive one well-formed message built from the input (type op & 3, hops ((op >> 2) & 7) + 1)
//   3     PRINT #n (n = 10 + (op & 15), 25 is invalid): text from the input, 7-bit unless op & 16
//   4     SEND: variable, keypad offset, keypad mode, or an out-of-range value / a raw Q32.32 (op & 3)
//   5     GET #3 / GET #4 (op & 16), (op & 15) + 1 times; the 16th is GET on a bad channel
//   6     pull (op & 31) + 1 bytes from the MC's transmitter
//   7     clear NETSTAT, KEY#, keypad press/release, pull from the keypad, idle line (op & 7)
// Every received byte goes to both nodes. At the end both transmitters are drained.
// A twin of the MC gets the same bytes and calls through the bulk forms (receive(byte_view),
// transmit(byte_buffer)) and must send the same bytes, answer every call the same and end with the same
// counters, NETSTAT and VRs.
//
// Invariants (MC):
//   - a model of the link (docs/protocol.md 1.5) says where each received byte goes (local, forwarded,
//     dropped, lost: the forward buffer full, or past the longest legal message of its type) and the node's
//     forwarding counters (messages forwarded, lost, cut) must follow it byte by byte;
//   - every result of the node's local decoding is classified and counted exactly once: a reference decoder
//     fed the same local bytes says what the node must count (frame error, CRC error, message by type; VR
//     written with the decoded value, refused by the policy, or out of range) and nothing else may change;
//   - a character message is delivered whole or not at all, in order: when the reference decodes one, the
//   node
//     either takes it (all its characters join the expected queue) or drops it whole (receive overflow, only
//     if it could not fit); GET returns exactly the expected queue, `characters_waiting()` equals its size
//     and never exceeds the receive capacity; KEY# is true exactly when it is non-empty;
//   - SEND queues the whole frame or nothing; PRINT# queues whole character messages, each as long as fits
//     (docs/protocol.md 1.6), and reports how many characters; a valid call is refused only for lack of room
//     (NETSTAT bit 0); NETSTAT bits are set when the matching counters grow;
//   - the transmitted stream is exactly what the link rules give (docs/protocol.md 1.5): forwarded bytes with A-1,
//     data unchanged, forwarded traffic first between messages, own frames whole, a lost forwarded message
//     removed whole if none of it went out, a forwarded message cut at the first data byte past the longest
//     legal message of its type, an idle line ending the forwarded message; and a second decoder reading it
//     sees no stray data, stray end of message or zero hop count.
// Invariants (keypad): it forwards nothing and never transmits in local mode; its stream is well formed; key
// results match its mode; the display cursor stays on the display.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <deque>
#include <type_traits>
#include <vector>

#include <trionet/q32.hpp>
#include <trionet/ring/decoder.hpp>
#include <trionet/ring/encode.hpp>
#include <trionet/ring/keypad.hpp>
#include <trionet/ring/motion_coordinator.hpp>
#include <trionet/vr.hpp>

#include "fuzz_check.hpp"

namespace {

using namespace trionet::ring;
using trionet::q32_from_double;
using trionet::q32_result;
using trionet::q32_to_double;

constexpr std::size_t receive_capacity = 64;
constexpr std::size_t forward_capacity = 16;
constexpr std::size_t transmit_capacity = 40;
constexpr std::size_t vr_count = 32;

using node_type = motion_coordinator<receive_capacity, forward_capacity, transmit_capacity>;
using keypad_type = keypad<16, 8>;
constexpr std::size_t max_own_characters = forward_capacity - framing_length;  // forward 16 < transmit 40

bool refuse_some(void*, std::uint16_t vr, double) noexcept {
  return vr % 7 != 3;
}

bool same(const motion_coordinator_counters& a, const motion_coordinator_counters& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_answer(int a, int b) { return a == b; }
bool same_answer(receive_status a, receive_status b) { return a == b; }
bool same_answer(send_status a, send_status b) { return a == b; }
bool same_answer(const print_result& a, const print_result& b) { return a.status == b.status && a.queued == b.queued; }
bool same_answer(const get_result& a, const get_result& b) { return a.status == b.status && a.value == b.value; }

/// Checks a transmitted stream with a decoder of its own: a node never sends data outside a message, an end
/// of message without a header, or a header with A = 0.
struct stream_checker {
  decoder<256> reader;
  void take(std::uint8_t byte) {
    const decode_result r = reader.push(byte);
    if (r.status == decode_status::frame_error) {
      FUZZ_CHECK(r.error != frame_error::stray_data);
      FUZZ_CHECK(r.error != frame_error::stray_eom);
      FUZZ_CHECK(r.error != frame_error::zero_hops);
    }
  }
};

/// Where a received byte goes (docs/protocol.md 1.5).
enum class byte_route {
  local,      // to the node's own decoder
  forwarded,  // into the forward buffer
  dropped,    // the rest of a lost message
  lost,       // the byte on which a forwarded message was lost (no room, or past the longest legal message)
};

/// What the MC's link must do (docs/protocol.md 1.5): where each received byte goes, and what it transmits.
struct link_model {
  std::deque<std::uint8_t> forward;  // forwarded bytes not yet transmitted (A already decremented)
  std::deque<std::uint8_t> own;      // own frames not yet transmitted
  std::size_t pushed = 0;            // forwarded bytes ever buffered
  std::size_t popped = 0;            // ... and transmitted
  std::size_t message_start = 0;     // `pushed` when the message being forwarded began
  std::size_t budget = 0;            // data bytes the message being forwarded may still carry
  bool open = false;                 // a forwarded message has begun and not ended on the receive side
  bool discarding = false;           // the rest of a lost forwarded message is being dropped
  std::uint32_t messages_forwarded = 0, forwards_lost = 0, forwards_cut = 0;
  enum class sending { idle, forward, own } state = sending::idle;

  /// Where `byte` goes, and its effect on the model.
  byte_route received(std::uint8_t byte) {
    if (is_data(byte)) {
      if (discarding) return byte_route::dropped;
      if (!open) return byte_route::local;
      if (budget == 0) return lose(forwards_cut);  // the first byte past the longest legal message
      if (forward.size() == forward_capacity) return lose(forwards_lost);
      --budget;
      push(byte);
      return byte_route::forwarded;
    }
    const bool was_open = open, was_discarding = discarding;
    open = discarding = false;  // any header or end of message ends the message being forwarded
    if (classify(byte) == byte_class::end_of_message) {
      if (was_discarding) return byte_route::dropped;
      if (!was_open) return byte_route::local;
      if (forward.size() == forward_capacity) {  // lost on its end of message, which still ends it
        const byte_route r = lose(forwards_lost);
        discarding = false;
        return r;
      }
      push(with_hops(byte, static_cast<std::uint8_t>(hops_of(byte) == 0 ? 0 : hops_of(byte) - 1)));
      return byte_route::forwarded;
    }
    if (hops_of(byte) <= 1) return byte_route::local;
    ++messages_forwarded;
    if (forward.size() == forward_capacity) {  // nothing of it is buffered
      ++forwards_lost;
      discarding = true;
      return byte_route::lost;
    }
    message_start = pushed;
    open = true;
    const std::uint8_t type = type_of(byte);
    budget = type == 2 ? variable_data_length : type == 3 || type == 4 ? 1 : default_max_characters;
    push(with_hops(byte, static_cast<std::uint8_t>(hops_of(byte) - 1)));
    return byte_route::forwarded;
  }

  void push(std::uint8_t byte) {
    forward.push_back(byte);
    ++pushed;
  }

  // The forwarded message being received is lost: removed whole if none of it went out, the rest dropped.
  byte_route lose(std::uint32_t& counter) {
    ++counter;
    open = false;
    discarding = true;
    if (popped <= message_start) {
      const std::size_t drop = pushed - message_start;
      FUZZ_CHECK(drop <= forward.size());
      forward.erase(forward.end() - static_cast<std::ptrdiff_t>(drop), forward.end());
      pushed = message_start;
    }
    return byte_route::lost;
  }

  /// The byte the link must transmit next, if any.
  bool transmit(std::uint8_t& byte) {
    if (state == sending::forward) {
      if (!forward.empty()) return pop_forward(byte);
      if (open) return false;
      state = sending::idle;
    } else if (state == sending::own) {
      FUZZ_CHECK(!own.empty());  // own frames are queued whole
      byte = own.front();
      own.pop_front();
      if (classify(byte) == byte_class::end_of_message) state = sending::idle;
      return true;
    }
    if (!forward.empty()) return pop_forward(byte);
    if (!own.empty()) {
      state = sending::own;
      return transmit(byte);
    }
    return false;
  }

  bool pop_forward(std::uint8_t& byte) {
    byte = forward.front();
    forward.pop_front();
    ++popped;
    state = classify(byte) == byte_class::end_of_message ? sending::idle : sending::forward;
    return true;
  }
};

class harness {
 public:
  harness() : vr_(refuse_some), mc_(vr_) {}

  void run(trionet_fuzz::input_reader& in) {
    while (!in.done()) {
      const std::uint8_t op = in.byte();
      switch (op >> 5) {
        case 0:
        case 1: {
          const std::size_t n = (op & 63u) + 1u;
          for (std::size_t i = 0; i < n && !in.done(); ++i) receive(in.byte());
          break;
        }
        case 2:
          receive_message(op, in);
          break;
        case 3:
          print(op, in);
          break;
        case 4:
          send(op, in);
          break;
        case 5:
          get(op);
          break;
        case 6: {
          const unsigned pulls = (op & 31u) + 1u;
          for (unsigned i = 0; i < pulls; ++i) pull();
          relay_to_twin(pulls, op);
          break;
        }
        default:
          misc(op, in);
          break;
      }
      check_state();
    }
    // Drain: the model and the node agree to the end, and so does the twin.
    for (std::size_t i = 0; i < 4096; ++i) {
      if (!pull()) break;
    }
    relay_to_twin(4096, 0);
    check_twin();
    FUZZ_CHECK(!mc_.transmit_pending());
    FUZZ_CHECK(link_.forward.empty());
    FUZZ_CHECK(link_.own.empty() || (link_.state == link_model::sending::forward && link_.open));
    for (std::size_t i = 0; i < 4096; ++i) {
      if (!pull_keypad()) break;
    }
  }

 private:
  void receive(std::uint8_t byte) {
    const motion_coordinator_counters before = mc_.counters();
    const std::size_t waiting_before = mc_.characters_waiting();
    const link_counters links_before = mc_.forwarding_counters();

    const receive_status answered = mc_.receive(byte);
    twin_pending_.push_back(byte);

    // The link model says where the byte went; the node's forwarding counters follow it.
    const byte_route r = link_.received(byte);
    const link_counters links = mc_.forwarding_counters();
    FUZZ_CHECK(links.messages_forwarded == (link_.messages_forwarded & 0xFFFFu));
    FUZZ_CHECK(links.forwards_lost == link_.forwards_lost);
    FUZZ_CHECK(links.forwards_cut == link_.forwards_cut);
    FUZZ_CHECK(mc_.forward_backlog() == link_.forward.size());
    if (r == byte_route::lost) FUZZ_CHECK((mc_.netstat() & netstat_tx_buffer_error) != 0);

    // What the node must have counted, from the reference decoder.
    decode_result expected{};
    if (r == byte_route::local) {
      if (classify(byte) == byte_class::header && hops_of(byte) != 0) waiting_at_header_ = waiting_before;
      expected = reference_.push(byte);
    } else if (classify(byte) == byte_class::header) {
      expected = reference_.interrupt();
    }
    motion_coordinator_counters want = before;
    switch (expected.status) {
      case decode_status::incomplete:
        break;
      case decode_status::no_room:
        FUZZ_CHECK(false);  // the reference has its own full-size buffer
        break;
      case decode_status::frame_error:
        ++want.frame_errors;
        FUZZ_CHECK((mc_.netstat() & netstat_rx_frame_error) != 0);
        break;
      case decode_status::crc_error:
        ++want.crc_errors;
        FUZZ_CHECK((mc_.netstat() & netstat_rx_crc_error) != 0);
        break;
      case decode_status::ok:
        switch (expected.msg.type) {
          case message_type::character: {
            const std::size_t length = expected.msg.text.size();
            if (mc_.counters().character_messages != before.character_messages) {
              ++want.character_messages;  // taken whole
              for (std::uint8_t c : expected.msg.text) waiting_.push_back(c);
            } else {
              ++want.receive_overflows;  // dropped whole, and only when it could not fit
              FUZZ_CHECK(length + waiting_at_header_ > receive_capacity);
              FUZZ_CHECK((mc_.netstat() & netstat_rx_overflow) != 0);
            }
            break;
          }
          case message_type::variable: {
            const std::uint16_t vr = expected.msg.vr;
            if (vr >= vr_count) {
              ++want.variables_out_of_range;
            } else if (!refuse_some(nullptr, vr, 0.0)) {
              ++want.variables_refused;
            } else {
              ++want.variables_written;
              const double value = q32_to_double(expected.msg.value);
              const double written = vr_[vr];
              FUZZ_CHECK(std::memcmp(&written, &value, sizeof value) == 0);
            }
            break;
          }
          case message_type::keypad_offset:
          case message_type::keypad_mode:
            ++want.keypad_messages_ignored;
            break;
        }
        break;
    }
    FUZZ_CHECK(same(mc_.counters(), want));
    FUZZ_CHECK(mc_.characters_waiting() == waiting_.size());

    // What `receive` answered: the fate of the message the byte ended (a loss before a message for the node
    // that the same header cut short), else nothing.
    receive_status answer = receive_status::incomplete;
    if (r == byte_route::lost) {
      answer = links.forwards_cut != links_before.forwards_cut ? receive_status::forward_cut
                                                                 : receive_status::forward_lost;
    } else if (want.receive_overflows != before.receive_overflows) {
      answer = receive_status::no_room;
    } else if (expected.status != decode_status::incomplete) {
      answer = trionet::detail::decode_outcome::of(expected.status);
    } else if (r == byte_route::forwarded && classify(byte) == byte_class::end_of_message) {
      answer = receive_status::forwarded;
    }
    FUZZ_CHECK(answered == answer);

    receive_keypad(byte);
  }

  void receive_keypad(std::uint8_t byte) {
    keypad_.receive(byte);
    FUZZ_CHECK(keypad_.display().cursor() < keypad_display::positions);
    if (!keypad_.network_mode()) {  // nothing is forwarded in local mode
      const link_counters links = keypad_.forwarding_counters();
      FUZZ_CHECK(links.messages_forwarded == 0 && links.forwards_failed() == 0);
      FUZZ_CHECK(keypad_.forward_backlog() == 0);
    }
  }

  void receive_message(std::uint8_t op, trionet_fuzz::input_reader& in) {
    const auto hops = static_cast<std::uint8_t>(((op >> 2) & 7u) + 1u);
    std::uint8_t text[24] = {};
    message m;
    switch (op & 3u) {
      case 0: {
        const std::size_t length = in.byte() % 24u + 1u;
        for (std::size_t i = 0; i < length; ++i) text[i] = static_cast<std::uint8_t>(in.byte() & 0x7Fu);
        m = message::characters(hops, trionet::byte_view(text, length));
        break;
      }
      case 1: {
        const std::uint16_t vr = in.byte();
        const auto wide = static_cast<std::int64_t>(static_cast<std::int32_t>(in.u32()));
        const auto value = static_cast<std::int64_t>(static_cast<std::uint64_t>(wide) << (in.byte() & 31u));
        m = message::variable(hops, vr, value);
        break;
      }
      case 2:
        m = message::keypad_offset(hops, static_cast<std::uint8_t>(in.byte() % 15u + 1u));
        break;
      default:
        m = message::keypad_mode(hops, (in.byte() & 1u) != 0 ? keypad_mode_key_on_off : keypad_mode_key_on);
        break;
    }
    std::uint8_t frame[framing_length + 24] = {};
    const encode_result encoded = encode(frame, m);
    FUZZ_CHECK(encoded);
    for (std::size_t i = 0; i < encoded.length; ++i) receive(frame[i]);
  }

  // Checks a PRINT#/SEND outcome: the whole frame is queued, or nothing and the right reason.
  // `errors` lists every field error that applies (empty: the call is valid); which of several the node
  // reports first is its own business, but it must be one of them.
  void sent(send_status result, const std::vector<send_status>& errors, const message& m) {
    const bool fits = frame_length(m) <= free_before_;
    if (!errors.empty()) {
      FUZZ_CHECK(std::find(errors.begin(), errors.end(), result) != errors.end());
      FUZZ_CHECK(mc_.transmit_free() == free_before_);
      return;
    }
    if (!fits) {
      FUZZ_CHECK(result == send_status::queue_full);
      FUZZ_CHECK(mc_.transmit_free() == free_before_);
      FUZZ_CHECK((mc_.netstat() & netstat_tx_timeout) != 0);
      return;
    }
    FUZZ_CHECK(result == send_status::ok);
    FUZZ_CHECK(mc_.transmit_free() + frame_length(m) == free_before_);
    std::uint8_t frame[framing_length + 64] = {};
    const encode_result encoded = encode(frame, m);
    FUZZ_CHECK(encoded && encoded.length == frame_length(m));
    for (std::size_t i = 0; i < encoded.length; ++i) link_.own.push_back(frame[i]);
  }

  void print(std::uint8_t op, trionet_fuzz::input_reader& in) {
    const int n = 10 + (op & 15);
    const std::size_t length = in.byte() % 80u;
    std::uint8_t text[80] = {};
    bool seven_bit = true;
    for (std::size_t i = 0; i < length; ++i) {
      text[i] = (op & 16u) != 0 ? in.byte() : static_cast<std::uint8_t>(in.byte() & 0x7Fu);
      if (text[i] > 127) seven_bit = false;
    }
    free_before_ = mc_.transmit_free();
    const std::uint8_t netstat_before = mc_.netstat();
    const print_result result =
        both([&](node_type& node) { return node.print(n, trionet::byte_view(text, length)); });
    std::vector<send_status> errors;
    if (n > last_basic_address) errors.push_back(send_status::bad_address);
    if (length == 0) errors.push_back(send_status::empty_text);
    if (!seven_bit) errors.push_back(send_status::character_out_of_range);
    if (!errors.empty()) {
      FUZZ_CHECK(std::find(errors.begin(), errors.end(), result.status) != errors.end());
      FUZZ_CHECK(result.queued == 0);
      FUZZ_CHECK(mc_.transmit_free() == free_before_);
      FUZZ_CHECK(mc_.netstat() == netstat_before);
      return;
    }
    // Consecutive character messages of the longest own size, the last one shorter (docs/protocol.md 1.6).
    const auto hops = static_cast<std::uint8_t>(n - 9);
    std::size_t room = free_before_;
    std::size_t done = 0;
    while (done < length) {
      const std::size_t k = std::min(length - done, max_own_characters);
      if (k + framing_length > room) break;
      link_.own.push_back(make_header(hops, 1));
      link_.own.insert(link_.own.end(), text + done, text + done + k);
      link_.own.push_back(make_end_of_message(hops));
      room -= k + framing_length;
      done += k;
    }
    FUZZ_CHECK(result.queued == done);
    FUZZ_CHECK(mc_.transmit_free() == room);
    if (done == length) {
      FUZZ_CHECK(result.status == send_status::ok);
    } else {
      FUZZ_CHECK(result.status == send_status::queue_full);
      FUZZ_CHECK((mc_.netstat() & netstat_tx_timeout) != 0);
    }
  }

  void send(std::uint8_t op, trionet_fuzz::input_reader& in) {
    const int n = 9 + in.byte() % 17;  // 9 and 25 are not BASIC addresses
    const bool good_address = n >= first_basic_address && n <= last_basic_address;
    const auto hops = static_cast<std::uint8_t>(good_address ? n - 9 : 1);
    std::vector<send_status> errors;
    if (!good_address) errors.push_back(send_status::bad_address);
    free_before_ = mc_.transmit_free();
    switch (op & 3u) {
      case 0:
      case 3: {
        const std::uint16_t vr = in.u16() % 16400u;  // a few past 16383
        double value = static_cast<double>(static_cast<std::int32_t>(in.u32())) / 65536.0;
        if ((op & 3u) == 3) {
          const std::uint8_t pick = in.byte();
          if ((pick & 4u) != 0) {  // the integer-only form: any Q32.32 value is in range
            const auto raw = static_cast<std::int64_t>(static_cast<std::uint64_t>(in.u32()) << 32 | in.u32());
            const send_status result =
                both([&](node_type& node) { return node.send_variable_q32(n, vr, raw); });
            if (vr > max_vr) errors.push_back(send_status::vr_out_of_range);
            sent(result, errors, message::variable(hops, vr, raw));
            break;
          }
          value = pick % 3 == 0 ? 1e300 : pick % 3 == 1 ? -2147483648.5 : 2147483647.99999999;
        }
        const q32_result q = q32_from_double(value);
        const send_status result = both([&](node_type& node) { return node.send_variable(n, vr, value); });
        if (vr > max_vr) errors.push_back(send_status::vr_out_of_range);
        if (!q) errors.push_back(send_status::value_out_of_range);
        sent(result, errors, message::variable(hops, vr, q.raw));
        break;
      }
      case 1: {
        const int offset = 9 + in.byte() % 17;
        const send_status result = both([&](node_type& node) { return node.send_keypad_offset(n, offset); });
        const bool good_offset = offset >= first_basic_address && offset <= last_basic_address;
        if (!good_offset) errors.push_back(send_status::offset_out_of_range);
        sent(result, errors,
             message::keypad_offset(hops, static_cast<std::uint8_t>(good_offset ? offset - 9 : 1)));
        break;
      }
      default: {
        const std::uint8_t pick = in.byte();
        const int mode = pick % 3 == 0 ? 0 : pick % 3 == 1 ? 127 : pick;
        const send_status result = both([&](node_type& node) { return node.send_keypad_mode(n, mode); });
        const bool good_mode = mode == 0 || mode == 127;
        if (!good_mode) errors.push_back(send_status::mode_out_of_range);
        sent(result, errors, message::keypad_mode(hops, static_cast<std::uint8_t>(good_mode ? mode : 0)));
        break;
      }
    }
  }

  void get(std::uint8_t op) {
    const int channel = (op & 16u) != 0 ? 3 : 4;
    const unsigned count = (op & 15u) + 1u;
    for (unsigned i = 0; i < count; ++i) {
      FUZZ_CHECK(mc_.key(channel) == !waiting_.empty());
      const int used = i == 15 ? 2 : channel;
      const get_result got = both([&](node_type& node) { return node.get(used); });
      if (used == 2) {
        FUZZ_CHECK(got.status == get_status::bad_channel);
        FUZZ_CHECK(!mc_.key(used));
        continue;
      }
      if (waiting_.empty()) {
        FUZZ_CHECK(got.status == get_status::nothing_yet);
        continue;
      }
      FUZZ_CHECK(got.status == get_status::ok);
      const std::uint8_t raw = waiting_.front();
      waiting_.pop_front();
      FUZZ_CHECK(got.value == (channel == 4 ? raw : default_defkey[raw]));
    }
    FUZZ_CHECK(mc_.characters_waiting() == waiting_.size());
  }

  bool pull() {
    std::uint8_t want = 0;
    const bool pending = mc_.transmit_pending();
    const bool expected = link_.transmit(want);
    std::uint8_t byte = 0;
    const bool got = mc_.transmit(byte);
    FUZZ_CHECK(got == expected);
    FUZZ_CHECK(pending == expected);
    if (!got) return false;
    FUZZ_CHECK(byte == want);
    mc_stream_.take(byte);
    mc_sent_.push_back(byte);
    return true;
  }

  bool pull_keypad() {
    std::uint8_t byte = 0;
    const bool pending = keypad_.transmit_pending();
    const bool got = keypad_.transmit(byte);
    FUZZ_CHECK(pending == got);
    if (!keypad_.network_mode()) FUZZ_CHECK(!got);
    if (got) keypad_stream_.take(byte);
    return got;
  }

  void misc(std::uint8_t op, trionet_fuzz::input_reader& in) {
    switch (op & 7u) {
      case 0:
        both([](node_type& node) {
          node.clear_netstat();
          return 0;
        });
        FUZZ_CHECK(mc_.netstat() == 0);
        break;
      case 1:
        FUZZ_CHECK(mc_.key(3) == !waiting_.empty());
        FUZZ_CHECK(mc_.key(4) == !waiting_.empty());
        FUZZ_CHECK(!mc_.key(5));
        break;
      case 2:
      case 3: {
        const auto k = static_cast<key>(in.byte() % key_count);
        const key_status result = (op & 1u) == 0 ? keypad_.press(k) : keypad_.release(k);
        if (!keypad_.network_mode()) {
          FUZZ_CHECK(result == key_status::local_mode);
        } else if ((op & 1u) != 0 && keypad_.mode() != keypad_mode_key_on_off) {
          FUZZ_CHECK(result == key_status::nothing_to_send);
        } else {
          FUZZ_CHECK(result == key_status::ok || result == key_status::queue_full);
        }
        break;
      }
      case 4:
        for (int i = 0; i < 8; ++i) (void)pull_keypad();
        break;
      case 5:
        line_idle();
        break;
      default:
        break;
    }
  }

  // The idle line (docs/protocol.md 1.10): ends the message being forwarded (counted, NETSTAT bit 1) and the
  // message open at the node's decoder (a frame error).
  void line_idle() {
    const motion_coordinator_counters before = mc_.counters();
    const std::uint32_t ended = mc_.forwarding_counters().forwards_ended_idle;
    const receive_status answered = both([](node_type& node) { return node.line_idle(); });
    FUZZ_CHECK(!mc_.in_message());
    FUZZ_CHECK(mc_.forwarding_counters().forwards_ended_idle == ended + (link_.open ? 1u : 0u));
    if (link_.open) FUZZ_CHECK((mc_.netstat() & netstat_tx_buffer_error) != 0);
    const bool open = link_.open;
    link_.open = false;
    link_.discarding = false;
    motion_coordinator_counters want = before;
    receive_status answer = open ? receive_status::forward_ended_idle : receive_status::incomplete;
    if (reference_.line_idle().status == decode_status::frame_error) {
      ++want.frame_errors;
      FUZZ_CHECK((mc_.netstat() & netstat_rx_frame_error) != 0);
      answer = receive_status::frame_error;
    }
    FUZZ_CHECK(answered == answer);  // what the idle line ended
    FUZZ_CHECK(same(mc_.counters(), want));
    keypad_.line_idle();
    FUZZ_CHECK(!keypad_.in_message());
  }

  // The twin: the same node fed the same bytes through the bulk calls a DMA-fed node uses. The bytes received
  // since its last call go in at once with receive(byte_view), in two pieces (the last up to 15 of them
  // apart), and when `mc_` is pulled `pulls` times the twin's transmit(byte_buffer) gets room for `pulls`
  // bytes: the same as receiving them one by one and pulling that often, so it must send the same bytes and
  // end in the same state.
  void receive_in_twin() {
    twin_.receive(trionet::byte_view(twin_pending_.data(), twin_pending_.size()));
    twin_pending_.clear();
  }
  void relay_to_twin(std::size_t pulls, std::uint8_t op) {
    const std::size_t tail = std::min<std::size_t>(twin_pending_.size(), op & 15u);
    twin_.receive(trionet::byte_view(twin_pending_.data(), twin_pending_.size() - tail));
    twin_.receive(trionet::byte_view(twin_pending_.data() + twin_pending_.size() - tail, tail));
    std::vector<std::uint8_t> out(pulls);
    const std::size_t got = twin_.transmit(trionet::byte_buffer(out.data(), out.size()));
    FUZZ_CHECK(got <= pulls);
    twin_sent_.insert(twin_sent_.end(), out.begin(), out.begin() + static_cast<std::ptrdiff_t>(got));
    twin_pending_.clear();
    FUZZ_CHECK(twin_sent_ == mc_sent_);
  }
  // A program call on both nodes, after the twin has caught up on received bytes: the same answer.
  template <class Call>
  std::invoke_result_t<Call, node_type&> both(Call call) {
    receive_in_twin();
    const auto mine = call(mc_);
    const auto twins = call(twin_);
    FUZZ_CHECK(same_answer(mine, twins));
    return mine;
  }
  void check_twin() {
    receive_in_twin();
    FUZZ_CHECK(same(mc_.counters(), twin_.counters()));
    const link_counters mine = mc_.forwarding_counters(), twins = twin_.forwarding_counters();
    FUZZ_CHECK(std::memcmp(&mine, &twins, sizeof mine) == 0);
    FUZZ_CHECK(mc_.netstat() == twin_.netstat());
    FUZZ_CHECK(mc_.characters_waiting() == twin_.characters_waiting());
    for (std::size_t v = 0; v < vr_count; ++v) FUZZ_CHECK(vr_[v] == twin_vr_[v]);
  }

  void check_state() {
    FUZZ_CHECK(mc_.characters_waiting() == waiting_.size());
    FUZZ_CHECK(mc_.characters_waiting() <= receive_capacity);
    FUZZ_CHECK(mc_.transmit_free() <= transmit_capacity);
    FUZZ_CHECK(mc_.forward_backlog() == link_.forward.size());
    FUZZ_CHECK(mc_.forward_backlog() <= forward_capacity);
    FUZZ_CHECK(transmit_capacity - mc_.transmit_free() == link_.own.size());
  }

  trionet::vr_table<vr_count> vr_;
  node_type mc_;
  trionet::vr_table<vr_count> twin_vr_{refuse_some};
  node_type twin_{twin_vr_};
  std::vector<std::uint8_t> twin_pending_;         // received by mc_, not yet by the twin
  std::vector<std::uint8_t> mc_sent_, twin_sent_;  // what each has transmitted
  decoder<default_max_characters> reference_;  // the node's character maximum; its buffer is smaller
  link_model link_;
  std::deque<std::uint8_t> waiting_;  // characters GET must return, in order
  std::size_t waiting_at_header_ = 0;
  std::size_t free_before_ = 0;
  stream_checker mc_stream_;
  keypad_type keypad_;
  stream_checker keypad_stream_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static constexpr std::uint8_t empty[1] = {0};
  trionet_fuzz::input_reader in(data == nullptr ? empty : data, size);
  harness h;
  h.run(in);
  return 0;
}
