// The concurrency stress of a node's two sides (docs/design.md, "Contexts"): one thread plays the UART
// interrupt (the link side: it feeds received bytes and pulls bytes to transmit, one of each per step as a
// UART at full rate does, and calls line_idle now and then), the other calls the program API at random (the
// program side: PRINT#, SEND, GET#, KEY#, VR(), NETSTAT, counters, key presses). No lock, no masking: the two
// threads share only the node (and, for the check, nothing else until both have ended).
//
// What is checked:
//   - nothing lost, duplicated or reordered: every forwarded message leaves the node whole, in order, with A
//     decremented; every own frame (PRINT#, SEND, key press) leaves whole and in the order it was queued;
//     the characters GET# returns are the local character messages, whole and in order (a message dropped
//     for lack of room is counted as a receive overflow, and only then missing); nothing else is sent;
//   - no value is ever seen half-written: VR() as the program reads it always holds a value some writer wrote
//     whole, a VR only the network writes never goes back, one only the program writes reads back exactly;
//   - counters only grow while read concurrently, and add up at the end: messages forwarded, delivered, VRs
//     written, frame and CRC errors, own messages sent, refused sends equal what both threads did;
//   - NETSTAT shows only the bits the traffic can raise, and a clear then an error gives exactly that bit.
// Built with ThreadSanitizer (scripts/concurrency-test) the same run also proves that no variable is
// accessed by both threads without the synchronisation the contract promises.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "trionet/can.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace trionet::stress {

/// How long to run: the link thread's steps (one byte in and one byte out at most each).
struct config {
  std::uint64_t link_steps = 200000;
  std::uint64_t seed = 1;
  bool dma = false;  ///< the ring nodes' link side in bulk (a DMA-fed UART) instead of a byte at a time
};

/// What a run did, and every failed check (empty: it passed).
struct report {
  std::uint64_t link_steps = 0;     ///< link-side steps (receive + transmit)
  std::uint64_t link_calls = 0;     ///< link-side calls into the node
  std::uint64_t program_calls = 0;  ///< program-side calls into the node
  std::uint64_t messages_in = 0;    ///< messages fed to the node
  std::uint64_t frames_out = 0;     ///< frames the node sent
  std::uint64_t own_frames = 0;     ///< of which the program's own
  std::uint64_t dropped_whole = 0;  ///< local messages dropped for lack of room (counted)
  std::vector<std::string> failures;
  bool ok() const { return failures.empty(); }
};

namespace detail {

/// A thread's own failure list (merged after both threads ended).
class checks {
 public:
  void expect(bool ok, const std::string& what) {
    if (ok) return;
    if (failures.size() < 20) failures.push_back(what);
    ++failed;
  }
  std::vector<std::string> failures;
  std::uint64_t failed = 0;
};

inline std::vector<std::uint8_t> frame_of(const ring::message& m) {
  std::vector<std::uint8_t> out(ring::frame_length(m));
  (void)ring::encode(byte_buffer(out.data(), out.size()), m);
  return out;
}

inline std::vector<std::uint8_t> text_frame(std::uint8_t hops, const std::string& text) {
  return frame_of(
      ring::message::characters(hops, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())));
}

inline std::string letters(std::mt19937_64& rng, std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += static_cast<char>('a' + rng() % 26);
  return s;
}

/// A forwarded frame as the next node must receive it: A decremented in its header and end of message.
inline std::vector<std::uint8_t> passed_on(std::vector<std::uint8_t> frame) {
  frame.front() = ring::decrement_hops(frame.front());
  frame.back() = ring::decrement_hops(frame.back());
  return frame;
}

/// A VR value whose two 32-bit halves belong together: a half-written one breaks the relation.
constexpr std::int64_t whole_value(std::uint32_t s) noexcept {
  return static_cast<std::int64_t>((std::uint64_t{s} << 32) | (s ^ 0x5A5A5A5Au));
}
constexpr bool is_whole(std::int64_t v) noexcept {
  const auto bits = static_cast<std::uint64_t>(v);
  return static_cast<std::uint32_t>(bits) == (static_cast<std::uint32_t>(bits >> 32) ^ 0x5A5A5A5Au);
}
constexpr std::uint32_t serial_of(std::int64_t v) noexcept {
  return static_cast<std::uint32_t>(static_cast<std::uint64_t>(v) >> 32);
}

/// Cuts a transmitted stream into frames; anything outside a whole frame is a failure.
inline std::vector<std::vector<std::uint8_t>> frames_in(const std::vector<std::uint8_t>& out, checks& c) {
  std::vector<std::vector<std::uint8_t>> frames;
  std::vector<std::uint8_t> current;
  for (std::uint8_t b : out) {
    switch (ring::classify(b)) {
      case ring::byte_class::header:
        c.expect(current.empty(), "a header inside a frame");
        current.assign(1, b);
        break;
      case ring::byte_class::data:
        c.expect(!current.empty(), "data outside a frame");
        if (!current.empty()) current.push_back(b);
        break;
      case ring::byte_class::end_of_message:
        c.expect(!current.empty(), "an end of message outside a frame");
        if (!current.empty()) {
          current.push_back(b);
          frames.push_back(current);
          current.clear();
        }
        break;
    }
  }
  c.expect(current.empty(), "the stream ends inside a frame");
  return frames;
}

/// Compares the frames seen with the frames expected, in order.
inline void same_frames(const std::vector<std::vector<std::uint8_t>>& seen,
                        const std::vector<std::vector<std::uint8_t>>& expected, const char* what, checks& c) {
  c.expect(seen.size() == expected.size(), std::string(what) + ": " + std::to_string(seen.size()) +
                                               " frames sent, " + std::to_string(expected.size()) + " expected");
  const std::size_t n = std::min(seen.size(), expected.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (seen[i] != expected[i]) {
      c.expect(false, std::string(what) + ": frame " + std::to_string(i) + " differs (lost, reordered or torn)");
      return;
    }
  }
}

/// Every counter grew or stayed (a traffic counter that wraps at 2^16 may have wrapped: from 0xFFFF to 0).
template <class Counters>
bool grew_or_same(const Counters& now, const Counters& before) {
  static_assert(sizeof(Counters) % sizeof(std::uint32_t) == 0, "counters are 32-bit fields");
  std::uint32_t a[sizeof(Counters) / 4], b[sizeof(Counters) / 4];
  std::memcpy(a, &now, sizeof a);
  std::memcpy(b, &before, sizeof b);
  for (std::size_t i = 0; i < sizeof a / 4; ++i) {
    const bool wrapped = b[i] <= 0xFFFFu && a[i] < 0x8000u && b[i] - a[i] >= 0x8000u;
    if (a[i] < b[i] && !wrapped) return false;
  }
  return true;
}

/// One step of a ring node's link side: a byte in (unless the line is quiet) and a byte out, as a UART
/// interrupt does; or, with `config::dma`, a run of 1..8 bytes in and room for as many out, as a DMA-fed UART
/// does (receive in bulk, then transmit in bulk or a byte at a time).
template <class Node>
void link_step(Node& node, const config& cfg, std::mt19937_64& rng, const std::vector<std::uint8_t>& current,
               std::size_t& at, bool quiet, std::vector<std::uint8_t>& out, std::uint64_t& calls) {
  if (!cfg.dma) {
    if (!quiet && at < current.size()) {
      node.receive(current[at++]);
      ++calls;
    }
    std::uint8_t b = 0;
    ++calls;
    if (node.transmit(b)) out.push_back(b);
    return;
  }
  const std::size_t room = 1 + rng() % 8;
  std::uint8_t buffer[8];
  const std::size_t in = quiet ? 0 : std::min(room, current.size() - at);
  std::size_t sent = 0;
  if (in != 0) {
    node.receive(byte_view(current.data() + at, in));
    ++calls;
  }
  if ((rng() & 1) != 0) {
    sent = node.transmit(byte_buffer(buffer, room));
    ++calls;
  } else {
    while (sent < room && node.transmit(buffer[sent])) ++sent;
    calls += sent + 1;
  }
  at += in;
  out.insert(out.end(), buffer, buffer + sent);
}

/// Program side: a ring node's counters and forwarding counters now; none went back since `before`.
template <class Node, class Counters>
void check_counters_grow(const Node& node, Counters& before, ring::link_counters& links_before, checks& c) {
  const Counters now = node.counters();
  const ring::link_counters links = node.forwarding_counters();
  c.expect(grew_or_same(now, before), "a counter went back");
  c.expect(grew_or_same(links, links_before), "a forwarding counter went back");
  before = now;
  links_before = links;
}

/// How the two threads start together and end (the test's own synchronisation, not the node's).
struct handshake {
  std::atomic<int> started{0};             // both threads wait for each other before their first call
  std::atomic<std::uint64_t> program_calls{0};  // so that the link side does not end before the program ran
  std::atomic<bool> fed{false};            // the link thread has fed every message
  std::atomic<bool> program_done{false};   // the program thread has queued its last frame and read everything

  void start() {
    started.fetch_add(1);
    while (started.load() < 2) std::this_thread::yield();
  }
  // The link thread, after its steps: keeps `transmit`ting until the program side made at least `calls`
  // calls, then says that everything is fed.
  template <class Transmit>
  void end_feeding(std::uint64_t calls, Transmit&& transmit) {
    while (program_calls.load(std::memory_order_relaxed) < calls) transmit();
    fed.store(true, std::memory_order_release);
  }
};

}  // namespace detail

// ---- the Motion Coordinator ----

namespace detail {
/// A Motion Coordinator with a Q32.32 VR table: forwarded messages (A = 3 and 4), messages for it
/// (characters, variables, a CRC error, a frame error) and idle gaps come in; the program PRINTs, SENDs
/// (address 10: A = 1 on the wire), reads characters, VRs, NETSTAT and counters.
template <class mc_type>
report run_motion_coordinator(const config& cfg) {
  constexpr std::size_t vr_count = 16;
  vr_table<vr_count, std::int64_t> vr;
  mc_type mc(vr);
  handshake h;
  report rep;

  // What the link thread fed, and saw.
  std::vector<std::vector<std::uint8_t>> forwarded_expected;
  std::vector<std::string> local_texts;
  std::vector<std::uint8_t> out;
  std::uint64_t variables_fed = 0, crc_errors_fed = 0, frame_errors_fed = 0, link_calls = 0;
  std::int64_t last_network[vr_count] = {};
  checks link_checks;

  std::thread link([&] {
    std::mt19937_64 rng(cfg.seed);
    std::uint32_t serial[vr_count] = {};
    std::vector<std::uint8_t> current;
    std::size_t at = 0;
    std::uint64_t gap = 0;
    const auto transmit = [&] {
      std::uint8_t b = 0;
      ++link_calls;
      if (mc.transmit(b)) out.push_back(b);
    };
    h.start();
    for (std::uint64_t step = 0; step < cfg.link_steps; ++step) {
      if (at == current.size() && gap == 0) {  // between messages: the next one, or a quiet line
        at = 0;
        const unsigned pick = static_cast<unsigned>(rng() % 100);
        ++rep.messages_in;
        if (pick < 25) {
          current = text_frame(3, letters(rng, 1 + rng() % 40));
          forwarded_expected.push_back(passed_on(current));
        } else if (pick < 35) {
          current = frame_of(ring::message::variable(4, static_cast<std::uint16_t>(rng() % 16384),
                                                     static_cast<std::int64_t>(rng())));
          forwarded_expected.push_back(passed_on(current));
        } else if (pick < 55) {
          const std::string text = "#" + std::to_string(local_texts.size()) + letters(rng, rng() % 30) + ";";
          local_texts.push_back(text);
          current = text_frame(1, text);
        } else if (pick < 70) {
          const auto k = static_cast<std::uint16_t>(rng() % 4 + (rng() % 2) * 4);  // 0..3 network only, 4..7 both
          const std::int64_t value = whole_value(++serial[k]);
          current = frame_of(ring::message::variable(1, k, value));
          last_network[k] = value;
          ++variables_fed;
        } else if (pick < 74) {
          current = frame_of(ring::message::variable(1, 0, whole_value(0)));
          current[13] ^= 0x01;  // C0: a CRC error
          ++crc_errors_fed;
        } else if (pick < 78) {
          current = text_frame(1, "MISMATCH");
          current.back() = ring::make_end_of_message(2);  // a frame error
          ++frame_errors_fed;
        } else {
          current.clear();
          --rep.messages_in;
          gap = 1 + rng() % 60;  // a quiet line: the transmitter catches up
          mc.line_idle();
          ++link_calls;
        }
      }
      const bool quiet = gap != 0;
      if (quiet) --gap;
      link_step(mc, cfg, rng, current, at, quiet, out, link_calls);
      ++rep.link_steps;
      if ((step & 255) == 255) std::this_thread::yield();  // lets the program thread run on a busy machine
    }
    while (at < current.size()) {  // the last message whole
      mc.receive(current[at++]);
      transmit();
      link_calls += 2;
    }
    h.end_feeding(cfg.link_steps / 10, transmit);
    while (!h.program_done.load(std::memory_order_acquire)) transmit();
    for (int i = 0; i < 64; ++i) transmit();  // what the program queued last
  });

  // The program side.
  checks program_checks;
  std::vector<std::vector<std::uint8_t>> own_expected;
  std::string received;
  std::uint64_t refused = 0, program_calls = 0, printed = 0;
  std::int64_t program_value[vr_count] = {};
  std::thread program([&] {
    std::mt19937_64 rng(cfg.seed * 7919 + 1);
    std::uint32_t serial = 0x40000000u;
    std::uint32_t last_seen[vr_count] = {};
    ring::motion_coordinator_counters counters_before{};
    ring::link_counters links_before{};
    h.start();
    const auto read_characters = [&] {
      for (int i = 0; i < 64 && mc.key(4); ++i) {
        const ring::get_result got = mc.get(4);
        program_checks.expect(got.status == ring::get_status::ok, "KEY#4 said a character waits, GET#4 found none");
        received += static_cast<char>(got.value);
        program_calls += 2;
      }
      ++program_calls;
    };
    while (!h.fed.load(std::memory_order_acquire)) {
      const unsigned pick = static_cast<unsigned>(rng() % 100);
      ++program_calls;
      h.program_calls.store(program_calls, std::memory_order_relaxed);
      if (pick < 10) {
        const std::string text = "P" + std::to_string(printed++) + letters(rng, rng() % 40) + ";";
        const ring::print_result r =
            mc.print(10, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
        if (r.status == ring::send_status::queue_full) ++refused;
        program_checks.expect(r.status == ring::send_status::ok || r.status == ring::send_status::queue_full,
                              "PRINT# failed for another reason than a full queue");
        for (std::size_t done = 0; done < r.queued;) {  // the messages it was split into
          const std::size_t n = std::min(r.queued - done, mc_type::max_own_frame - ring::framing_length);
          own_expected.push_back(text_frame(1, text.substr(done, n)));
          done += n;
        }
      } else if (pick < 20) {
        const auto k = static_cast<std::uint16_t>(rng() % 16);
        const std::int64_t value = whole_value(++serial);
        const ring::send_status s = mc.send_variable_q32(10, k, value);
        if (s == ring::send_status::ok) {
          own_expected.push_back(frame_of(ring::message::variable(1, k, value)));
        } else {
          program_checks.expect(s == ring::send_status::queue_full, "SEND failed for another reason than a full queue");
          ++refused;
        }
      } else if (pick < 60) {
        read_characters();
      } else if (pick < 75) {  // VR(): 0..3 network only, 4..7 both, 8..11 the program only
        const std::size_t k = rng() % 12;
        const std::int64_t v = vr[k];
        program_checks.expect(v == 0 || is_whole(v), "VR(" + std::to_string(k) + ") read half-written");
        if (k < 4) {
          program_checks.expect(v == 0 || serial_of(v) >= last_seen[k], "VR written by the network went back");
          last_seen[k] = v == 0 ? 0 : serial_of(v);
        } else if (k >= 8) {
          program_checks.expect(v == program_value[k], "VR written by the program reads back wrong");
        }
        if (k >= 4) {
          const std::int64_t mine = whole_value(++serial);
          vr[k] = mine;
          if (k >= 8) program_value[k] = mine;
        }
      } else if (pick < 85) {
        const std::uint8_t n = mc.netstat();
        program_checks.expect((n & ~(ring::netstat_tx_timeout | ring::netstat_rx_crc_error |
                                     ring::netstat_rx_frame_error | ring::netstat_rx_overflow)) == 0,
                              "NETSTAT shows a bit the traffic cannot raise (no forwarded message is lost)");
        if ((rng() & 1) != 0) mc.clear_netstat();
      } else {
        check_counters_grow(mc, counters_before, links_before, program_checks);
      }
    }
    // Everything is fed: read the rest, and wait until the own frames have gone to the link side.
    read_characters();
    while (mc.key(4)) read_characters();
    while (mc.transmit_free() != mc_type::transmit_capacity) std::this_thread::yield();
    h.program_done.store(true, std::memory_order_release);
  });
  link.join();
  program.join();

  // Both sides have ended: check what was sent, delivered and counted.
  checks c;
  const auto frames = frames_in(out, c);
  std::vector<std::vector<std::uint8_t>> forwarded_seen, own_seen;
  for (const auto& f : frames) (ring::hops_of(f.front()) == 1 ? own_seen : forwarded_seen).push_back(f);
  same_frames(forwarded_seen, forwarded_expected, "forwarded messages", c);
  same_frames(own_seen, own_expected, "own messages", c);
  // The characters: whole local messages in order, the missing ones counted as receive overflows.
  std::size_t next = 0, missing = 0;
  for (std::size_t start = 0; start < received.size();) {
    const std::size_t end = received.find(';', start);
    if (end == std::string::npos) {
      c.expect(false, "a character message arrived in part");
      break;
    }
    const std::string text = received.substr(start, end + 1 - start);
    while (next < local_texts.size() && local_texts[next] != text) {
      ++next;
      ++missing;
    }
    c.expect(next < local_texts.size(), "GET# returned characters no message carried, or out of order");
    ++next;
    start = end + 1;
  }
  missing += local_texts.size() - std::min(next, local_texts.size());
  const ring::motion_coordinator_counters counters = mc.counters();
  const ring::link_counters links = mc.forwarding_counters();
  c.expect(counters.receive_overflows == missing, "receive overflows " + std::to_string(counters.receive_overflows) +
                                                      ", messages missing " + std::to_string(missing));
  c.expect(counters.character_messages == ((local_texts.size() - missing) & 0xFFFFu), "character messages miscounted");
  c.expect(counters.variables_written == (variables_fed & 0xFFFFu), "variables written miscounted");
  c.expect(counters.crc_errors == crc_errors_fed, "CRC errors miscounted");
  c.expect(counters.frame_errors == frame_errors_fed, "frame errors miscounted");
  c.expect(counters.sends_refused == (refused & 0xFFFFu), "refused sends miscounted");
  c.expect(links.messages_forwarded == (forwarded_expected.size() & 0xFFFFu), "forwarded messages miscounted");
  c.expect(links.messages_sent == (own_expected.size() & 0xFFFFu), "own messages sent miscounted");
  c.expect(links.forwards_failed() == 0, "a forwarded message was lost");
  // Every message fed is counted once: forwarded, taken as characters, dropped whole, written to VR(), or an
  // error (the 2^16 traffic counters taken modulo 2^16).
  const std::uint64_t accounted = std::uint64_t{links.messages_forwarded} + counters.character_messages +
                                  counters.receive_overflows + counters.variables_written + counters.crc_errors +
                                  counters.frame_errors;
  c.expect((accounted & 0xFFFFu) == (rep.messages_in & 0xFFFFu),
           "messages fed " + std::to_string(rep.messages_in) + " are not forwarded + characters + overflows + "
           "variables + errors (modulo 2^16: " + std::to_string(accounted & 0xFFFFu) + ")");
  for (std::size_t k = 0; k < 4; ++k) c.expect(vr[k] == last_network[k], "VR(0..3) is not the last network write");
  for (std::size_t k = 4; k < 8; ++k) c.expect(vr[k] == 0 || is_whole(vr[k]), "VR(4..7) is half-written");
  for (std::size_t k = 8; k < 12; ++k) c.expect(vr[k] == program_value[k], "VR(8..11) lost the program's write");
  // NETSTAT, now that both sides are quiet: cleared it is 0, and one CRC error raises exactly its bit.
  mc.clear_netstat();
  c.expect(mc.netstat() == 0, "NETSTAT not clear after clear_netstat");
  std::vector<std::uint8_t> bad = frame_of(ring::message::variable(1, 0, whole_value(1)));
  bad[13] ^= 0x01;
  for (std::uint8_t b : bad) mc.receive(b);
  c.expect(mc.netstat() == ring::netstat_rx_crc_error, "a CRC error did not raise exactly NETSTAT bit 2");

  rep.link_calls = link_calls;
  rep.program_calls = program_calls;
  rep.frames_out = frames.size();
  rep.own_frames = own_seen.size();
  rep.dropped_whole = missing;
  for (checks* each : {&link_checks, &program_checks, &c}) {
    for (auto& f : each->failures) rep.failures.push_back("motion coordinator: " + f);
  }
  return rep;
}

}  // namespace detail

/// The Motion Coordinator's run (see detail::run_motion_coordinator): default capacities with a UART link
/// side. A DMA-fed link side receives a run of bytes before it transmits, so by the capacity rule of
/// ring/node.hpp its forward buffer holds a longest own frame plus a run: 16 + 8 bytes, own frames of 16.
inline report run_motion_coordinator(const config& cfg) {
  if (cfg.dma) return detail::run_motion_coordinator<ring::motion_coordinator<256, 24, 16>>(cfg);
  return detail::run_motion_coordinator<ring::motion_coordinator<>>(cfg);
}

// ---- the keypad ----

/// A keypad put in network mode (key presses go 5 hops along: A = 5 on the wire) while messages pass
/// through it (A = 3), text comes for its display and its keypad mode changes; the program presses and
/// releases keys at random.
inline report run_keypad(const config& cfg) {
  using namespace detail;
  using keypad_type = ring::keypad<>;
  keypad_type keypad;
  handshake h;
  report rep;
  std::vector<std::vector<std::uint8_t>> forwarded_expected;
  std::vector<std::uint8_t> out;
  std::uint64_t display_fed = 0, link_calls = 0;

  std::thread link([&] {
    std::mt19937_64 rng(cfg.seed);
    std::vector<std::uint8_t> current = frame_of(ring::message::keypad_offset(1, 5));
    std::size_t at = 0;
    std::uint64_t gap = 0;
    const auto transmit = [&] {
      std::uint8_t b = 0;
      ++link_calls;
      if (keypad.transmit(b)) out.push_back(b);
    };
    h.start();
    for (std::uint64_t step = 0; step < cfg.link_steps; ++step) {
      if (at == current.size() && gap == 0) {
        at = 0;
        const unsigned pick = static_cast<unsigned>(rng() % 100);
        ++rep.messages_in;
        if (pick < 30) {
          current = text_frame(4, letters(rng, 1 + rng() % 40));
          forwarded_expected.push_back(passed_on(current));
        } else if (pick < 45) {
          current = frame_of(ring::message::variable(4, static_cast<std::uint16_t>(rng() % 100),
                                                     static_cast<std::int64_t>(rng())));
          forwarded_expected.push_back(passed_on(current));
        } else if (pick < 60) {
          current = text_frame(1, letters(rng, 1 + rng() % 20));
          ++display_fed;
        } else if (pick < 70) {
          current = frame_of(ring::message::keypad_mode(1, (rng() & 1) != 0 ? 127 : 0));
        } else {
          current.clear();
          --rep.messages_in;
          gap = 1 + rng() % 60;
          keypad.line_idle();
          ++link_calls;
        }
      }
      const bool quiet = gap != 0;
      if (quiet) --gap;
      link_step(keypad, cfg, rng, current, at, quiet, out, link_calls);
      ++rep.link_steps;
      if ((step & 255) == 255) std::this_thread::yield();
    }
    while (at < current.size()) {
      keypad.receive(current[at++]);
      transmit();
      link_calls += 2;
    }
    h.end_feeding(cfg.link_steps / 10, transmit);
    while (!h.program_done.load(std::memory_order_acquire)) transmit();
    for (int i = 0; i < 64; ++i) transmit();
  });

  checks program_checks;
  std::vector<std::vector<std::uint8_t>> keys_expected;
  std::uint64_t sent = 0, lost = 0, program_calls = 0;
  std::thread program([&] {
    std::mt19937_64 rng(cfg.seed * 104729 + 3);
    ring::keypad_counters counters_before{};
    ring::link_counters links_before{};
    h.start();
    while (!h.fed.load(std::memory_order_acquire)) {
      ++program_calls;
      h.program_calls.store(program_calls, std::memory_order_relaxed);
      const auto k = static_cast<ring::key>(rng() % ring::key_count);
      // Releases only once in network mode (it never ends): in local mode a release in keypad mode 0 is not
      // a lost key, in mode 127 it is, and the mode may change between the test's look and the call.
      const bool press = (rng() & 1) != 0 || !keypad.network_mode();
      const std::uint8_t mode = keypad.mode();
      program_checks.expect(mode == ring::keypad_mode_key_on || mode == ring::keypad_mode_key_on_off,
                            "keypad mode read as neither 0 nor 127");
      if (rng() % 8 == 0) {  // counters and NETSTAT while the link side runs
        check_counters_grow(keypad, counters_before, links_before, program_checks);
        program_checks.expect((keypad.netstat() & ~ring::netstat_tx_timeout) == 0,
                              "NETSTAT shows a bit the traffic cannot raise");
        if ((rng() & 1) != 0) keypad.clear_netstat();
      }
      const ring::key_status s = press ? keypad.press(k) : keypad.release(k);
      switch (s) {
        case ring::key_status::ok: {
          const std::uint8_t code = ring::default_keypad_codes[k];
          const std::uint8_t c = press ? code : ring::default_key_off_code(code);
          keys_expected.push_back(frame_of(ring::message::characters(5, byte_view(&c, 1))));
          ++sent;
          break;
        }
        case ring::key_status::local_mode:
        case ring::key_status::queue_full:
          ++lost;
          break;
        case ring::key_status::nothing_to_send:
          program_checks.expect(!press, "a key press had nothing to send");
          break;
      }
      if (keypad.network_mode()) program_checks.expect(keypad.offset() == 5, "keypad offset read wrong");
    }
    while (keypad.transmit_free() != keypad_type::transmit_capacity) std::this_thread::yield();
    h.program_done.store(true, std::memory_order_release);
  });
  link.join();
  program.join();

  checks c;
  const auto frames = frames_in(out, c);
  std::vector<std::vector<std::uint8_t>> forwarded_seen, keys_seen;
  for (const auto& f : frames) (ring::hops_of(f.front()) == 5 ? keys_seen : forwarded_seen).push_back(f);
  same_frames(forwarded_seen, forwarded_expected, "forwarded messages", c);
  same_frames(keys_seen, keys_expected, "key presses", c);
  const ring::keypad_counters counters = keypad.counters();
  // The keypad's traffic and key counters wrap at 2^16 (docs/design.md, "Results and counters").
  c.expect(counters.keys_sent == (sent & 0xFFFFu), "keys sent miscounted");
  c.expect(counters.keys_lost == (lost & 0xFFFFu), "keys lost miscounted");
  c.expect(counters.display_messages == (display_fed & 0xFFFFu), "display messages miscounted");
  c.expect(counters.frame_errors == 0 && counters.crc_errors == 0, "a frame or CRC error out of nothing");
  c.expect(counters.variables_ignored == 0 && counters.dropped_in_local_mode == 0,
           "a message for another node counted as the keypad's");
  const ring::link_counters links = keypad.forwarding_counters();
  c.expect(links.forwards_failed() == 0, "a forwarded message was lost");
  c.expect(links.messages_forwarded == (forwarded_expected.size() & 0xFFFFu), "forwarded messages miscounted");
  c.expect(links.messages_sent == (sent & 0xFFFFu), "key messages sent miscounted");
  rep.link_calls = link_calls;
  rep.program_calls = program_calls;
  rep.frames_out = frames.size();
  rep.own_frames = keys_seen.size();
  for (checks* each : {&program_checks, &c}) {
    for (auto& f : each->failures) rep.failures.push_back("keypad: " + f);
  }
  return rep;
}

// ---- the CAN VR exchange node ----

/// Node 1 of 5 with a Q32.32 VR table of 16: the receive thread (the CAN receive ISR) takes frames from nodes
/// 2..5 (VR writes in each VR's order, writes past the table, values the table cannot hold), foreign frames and
/// every kind of malformed frame; the program sends VRs to node 2, reads VRs, writes its own VRs, reads
/// counters and clears them now and then (then stops clearing, so that the last counts can be bounded).
inline report run_can(const config& cfg) {
  using namespace detail;
  constexpr std::size_t vr_count = 16;
  vr_table<vr_count, std::int64_t> vr;
  // The port checks each frame as the program's send hands it over (node 1 to node 2: identifier 20,
  // docs/protocol.md 2.1): one frame per send, the message asked for.
  struct checking_port final : can::port {
    can::transmit_status send(const can::frame& f) noexcept override {
      can::frame want;
      want.id = 20;
      want.dlc = 8;
      if (expected != nullptr) (void)can::encode_vr_message(*expected, want.data);
      if (expected == nullptr || f.id != want.id || f.dlc != 8 || std::memcmp(f.data, want.data, 8) != 0) {
        ++wrong;
      }
      expected = nullptr;
      ++sent;
      return can::transmit_status::ok;
    }
    const can::vr_message* expected = nullptr;
    std::uint64_t sent = 0;
    std::uint64_t wrong = 0;
  } port;
  can::vr_exchange_node node(can::make_node_address(5, 1).address, port, vr);
  handshake h;
  report rep;
  // What the receive side fed, by the count it must land in: in all, and after it saw that the program's last
  // clear was over (those are certainly in the last counts; one fed while the clear ran may be too). The
  // program clears the counts at random until the receive side is half way.
  enum kind { written, out_of_range, value_out_of_range, foreign, bad_dlc, bad_sign, bad_fraction, kinds };
  std::uint64_t fed[kinds] = {}, fed_after[kinds] = {};
  std::atomic<bool> half_way{false};
  std::atomic<bool> clearing_over{false};

  // A CAN value whose parts belong together: integer part n, fraction n mod 10000 (Q32.32 in the table).
  const auto can_value = [](std::uint8_t k, std::uint32_t n) {
    can::vr_message m;
    m.vr = k;
    m.value.integer_part = n;
    m.value.fraction = static_cast<std::uint16_t>(n % 10000u);
    return m;
  };
  const auto consistent = [](std::int64_t v) {
    const decimal d = q32_to_decimal(v);
    return d.fraction == d.integer_part % 10000u;
  };
  // A frame of each kind from node 2..5 to node 1 (receive identifiers 10..13, docs/protocol.md 2.1).
  const auto make = [&](kind what, std::mt19937_64& rng, std::uint32_t serial) {
    can::frame f;
    f.id = 10u + static_cast<std::uint32_t>(rng() % 4);
    f.dlc = 8;
    const auto k = static_cast<std::uint8_t>(serial % 8);
    switch (what) {
      case written:
        (void)can::encode_vr_message(can_value(k, serial / 8 + 1), f.data);
        break;
      case out_of_range:
        (void)can::encode_vr_message(can_value(static_cast<std::uint8_t>(vr_count + rng() % 200), 1), f.data);
        break;
      case value_out_of_range:  // 2^31 and more: not Q32.32
        (void)can::encode_vr_message(can_value(k, 0x80000000u + static_cast<std::uint32_t>(rng() % 1000)), f.data);
        break;
      case foreign:
        f.id = (rng() & 1) != 0 ? 14u + static_cast<std::uint32_t>(rng() % 2000)
                                : (10u | can::frame::extended_flag);
        break;
      case bad_dlc:
        f.dlc = static_cast<std::uint8_t>(rng() % 8);
        break;
      case bad_sign:
        (void)can::encode_vr_message(can_value(k, 1), f.data);
        f.data[1] = static_cast<std::uint8_t>(2 + rng() % 254);
        break;
      case bad_fraction:
        (void)can::encode_vr_message(can_value(k, 1), f.data);
        f.data[6] = static_cast<std::uint8_t>(0x27 + rng() % (0x100 - 0x27));  // 0x2710 = 10000 and above
        f.data[7] = 0x10;
        break;
      case kinds:
        break;
    }
    return f;
  };

  std::uint64_t network_serial = 0;
  std::thread receiver([&] {
    std::mt19937_64 rng(cfg.seed);
    h.start();
    for (std::uint64_t step = 0; step < cfg.link_steps; ++step) {
      const unsigned pick = static_cast<unsigned>(rng() % 100);
      const kind what = pick < 60   ? written
                        : pick < 65 ? out_of_range
                        : pick < 68 ? value_out_of_range
                        : pick < 80 ? foreign
                        : pick < 88 ? bad_dlc
                        : pick < 94 ? bad_sign
                                    : bad_fraction;
      const bool after = clearing_over.load(std::memory_order_acquire);
      const can::frame f = make(what, rng, what == written ? static_cast<std::uint32_t>(network_serial++) : 0u);
      ++fed[what];
      if (after) ++fed_after[what];
      (void)node.receive(f);
      ++rep.link_steps;
      if (step == cfg.link_steps / 2) half_way.store(true, std::memory_order_relaxed);
      if ((step & 255) == 255) std::this_thread::yield();
      if (step + 1 == cfg.link_steps && !clearing_over.load(std::memory_order_acquire)) --step;  // until then
    }
    h.fed.store(true, std::memory_order_release);
  });

  checks program_checks;
  std::uint64_t program_calls = 0, sends = 0, sends_counted = 0;
  std::int64_t program_value[vr_count] = {};
  std::thread program([&] {
    std::mt19937_64 rng(cfg.seed * 31 + 7);
    can::node_counters before{};
    std::uint32_t last_seen[8] = {};
    std::uint32_t serial = 0;
    h.start();
    while (!h.fed.load(std::memory_order_acquire)) {
      ++program_calls;
      const unsigned pick = static_cast<unsigned>(rng() % 10);
      if (pick < 3) {
        const can::vr_message m =
            can_value(static_cast<std::uint8_t>(rng() % vr_count), static_cast<std::uint32_t>(rng() % 100000));
        port.expected = &m;
        program_checks.expect(node.send_to_node(2, m) == can::send_status::ok, "send_to_node failed");
        program_checks.expect(port.expected == nullptr, "send_to_node sent no frame");
        ++sends;
        if (clearing_over.load(std::memory_order_relaxed)) ++sends_counted;
      } else if (pick < 5) {  // VR(0..7): only the network writes them, each in increasing order
        const std::size_t k = rng() % 8;
        const std::int64_t v = vr[k];
        program_checks.expect(consistent(v), "a VR written from CAN read half-written");
        const std::uint32_t n = q32_to_decimal(v).integer_part;
        program_checks.expect(n >= last_seen[k], "a VR written from CAN went back");
        last_seen[k] = n;
      } else if (pick < 7) {  // VR(8..15): only the program writes them, while the network writes the others
        const std::size_t k = 8 + rng() % 8;
        program_checks.expect(vr[k] == program_value[k], "a VR written by the program reads back wrong");
        program_value[k] = whole_value(++serial);
        vr[k] = program_value[k];
      } else {
        const can::node_counters now = node.counters();
        program_checks.expect(grew_or_same(now, before), "a CAN counter went back between clears");
        before = now;
        if (!clearing_over.load(std::memory_order_relaxed) && pick == 9) {
          node.clear_counters();
          before = can::node_counters{};
        }
      }
      if (!clearing_over.load(std::memory_order_relaxed) && half_way.load(std::memory_order_relaxed)) {
        // The last clear: from here on the counts only grow.
        node.clear_counters();
        before = can::node_counters{};
        clearing_over.store(true, std::memory_order_release);
      }
    }
    h.program_done.store(true, std::memory_order_release);
  });
  receiver.join();
  program.join();

  checks c;
  c.expect(port.sent == sends && port.wrong == 0, "frames sent " + std::to_string(port.sent) + " for " +
                                                       std::to_string(sends) + " sends, " +
                                                       std::to_string(port.wrong) + " not the message asked for");
  // The counts since the last clear: at least what was fed after it, at most what was fed in all.
  const can::node_counters counters = node.counters();
  c.expect(clearing_over.load(), "the run ended before the last clear");
  c.expect(counters.sent == sends_counted, "frames sent since the last clear miscounted");
  const std::uint32_t counted[kinds] = {counters.written,  counters.out_of_range, counters.value_out_of_range,
                                        counters.foreign,  counters.bad_dlc,      counters.bad_sign,
                                        counters.bad_fraction};
  static const char* const names[kinds] = {"written", "out_of_range", "value_out_of_range", "foreign",
                                           "bad_dlc", "bad_sign",     "bad_fraction"};
  for (int i = 0; i < kinds; ++i) {
    c.expect(counted[i] >= fed_after[i] && counted[i] <= fed[i],
             std::string("counter ") + names[i] + " " + std::to_string(counted[i]) + " outside " +
                 std::to_string(fed_after[i]) + ".." + std::to_string(fed[i]));
  }
  c.expect(counters.refused == 0 && counters.send_busy == 0 && counters.send_failed == 0, "a count out of nothing");
  // The VRs: each network one holds its last write, each program one the program's last.
  std::uint32_t last_written[8] = {};
  for (std::uint64_t s = 0; s < network_serial; ++s) last_written[s % 8] = static_cast<std::uint32_t>(s / 8 + 1);
  for (std::size_t k = 0; k < 8; ++k) {
    c.expect(q32_to_decimal(vr[k]).integer_part == last_written[k] && consistent(vr[k]), "a VR lost its last write");
  }
  for (std::size_t k = 8; k < vr_count; ++k) c.expect(vr[k] == program_value[k], "a VR lost the program's write");
  // Both sides quiet: cleared, then a known number of each kind gives exactly those counts.
  node.clear_counters();
  const can::node_counters zero = node.counters();
  c.expect(zero.written == 0 && zero.sent == 0 && zero.foreign == 0 && zero.malformed() == 0,
           "clear_counters left a count");
  std::mt19937_64 rng(cfg.seed + 1);
  for (int i = 0; i < kinds; ++i) {
    for (int n = 0; n <= i; ++n) (void)node.receive(make(static_cast<kind>(i), rng, static_cast<std::uint32_t>(n)));
  }
  const can::node_counters known = node.counters();
  const std::uint32_t got[kinds] = {known.written, known.out_of_range, known.value_out_of_range, known.foreign,
                                    known.bad_dlc, known.bad_sign,     known.bad_fraction};
  for (int i = 0; i < kinds; ++i) {
    c.expect(got[i] == static_cast<std::uint32_t>(i + 1), std::string("counter ") + names[i] + " after a clear");
  }
  rep.link_calls = rep.link_steps;
  rep.program_calls = program_calls;
  std::uint64_t in = 0;
  for (std::uint64_t n : fed) in += n;
  rep.messages_in = in;
  rep.frames_out = port.sent;
  rep.own_frames = port.sent;
  for (checks* each : {&program_checks, &c}) {
    for (auto& f : each->failures) rep.failures.push_back("CAN node: " + f);
  }
  return rep;
}

}  // namespace trionet::stress
