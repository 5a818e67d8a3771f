// The concurrency stress of a Genius device's two sides (docs/design.md, "Contexts"; docs/protocol.md 3.4),
// in the pattern of concurrency_stress.hpp. One thread plays the link side: the UART and timer interrupts of
// SBA 5 on a busy bus (start_bit, receive, framing_error, timer_expired, transmit, the device's own words read
// back); the other plays the program: turn data, directed transmissions, deliveries, counters and NETSTAT.
// No lock, no masking: the two threads share only the device until both have ended.
//
// The bus the link thread plays: other devices' transmissions (broadcast or directed, plain data and blocks,
// to SBA 5 or to others), some cut short (a sender that stops: the gap timer expires), some with a framing
// error, some with a bit flipped (a CRC-6 error); the device's turn when its timer is armed (it sends, or
// the turn passes), some turns lost to a collision (another device's start bit before its first word, or
// another device's Start read back instead of its own word) or cut (its read-back stops); now and then the
// quiet bus (an idle restart).
//
// What is checked:
//   - every transmission the device sends whole is a whole one of the program's: the turn data as the
//     program set it (never torn, never older than the one sent before it), the directed transmissions each
//     exactly once, in the order queued (one cut by a collision or silence goes again);
//   - the deliveries the program reads are exactly the records of the transmissions for SBA 5 that were
//     heard whole, in order, each transmission delivered whole or dropped whole, and the ones dropped are
//     the delivery overflows counted;
//   - counters only grow while read concurrently and add up at the end: turns taken and passed, transmissions
//     sent, collisions, characters, framing errors, transmissions heard, CRC errors, lost transmissions, idle
//     restarts, deliveries; no wire error out of nothing;
//   - NETSTAT shows only the bits the traffic can raise, and a clear then a CRC error gives exactly that bit.
// Built with ThreadSanitizer (scripts/concurrency-test) the same run also proves that no variable is accessed
// by both threads without the synchronisation the contract promises.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "support/concurrency_stress.hpp"
#include "trionet/genius/device.hpp"
#include "trionet/genius/transmission.hpp"

namespace trionet::stress {

namespace detail::genius_stress {

using namespace trionet::genius;

constexpr std::uint8_t own_sba = 5;
// Broadcasts delivered from every sender but 24..31 (set before the threads start).
constexpr std::uint32_t broadcast_mask = 0x00FFFFFFu;

/// A transmission described by value: its segments' bytes kept beside it.
struct described {
  std::uint8_t sender = 0;
  bool broadcast = true;
  std::uint8_t destination = 0;
  struct part {
    bool block;
    std::uint8_t destination;
    std::vector<std::uint8_t> data;
  };
  std::vector<part> parts;
};

inline std::vector<std::uint16_t> words_of(const described& d) {
  std::vector<segment> segments;
  for (const auto& p : d.parts) segments.push_back(segment{p.block, p.destination, byte_view(p.data.data(), p.data.size())});
  const transmission t{d.sender, d.broadcast, d.destination, span<const segment>(segments.data(), segments.size())};
  std::vector<character> chars(encoded_length(t).length);
  std::vector<std::uint16_t> words;
  if (!encode_transmission(span<character>(chars.data(), chars.size()), t)) return words;
  for (const character c : chars) words.push_back(to_uart_word(c));
  return words;
}

inline std::vector<std::uint8_t> serial_bytes(std::uint32_t serial, std::size_t length, std::uint8_t salt) {
  std::vector<std::uint8_t> data(length);
  for (std::size_t i = 0; i < length; ++i) {
    data[i] = i == 0   ? static_cast<std::uint8_t>(serial)
              : i == 1 ? static_cast<std::uint8_t>(serial >> 8)
              : i == 2 ? static_cast<std::uint8_t>(serial >> 16)
              : i == 3 ? salt
                       : static_cast<std::uint8_t>(serial * 7 + i * 13 + salt);
  }
  return data;
}

/// The program's turn data number `serial` (fits the default 32-byte turn data): plain data carrying the
/// serial, and every third one a block and a plain tail (a bus controller's outputs).
inline described turn_data(std::uint32_t serial) {
  described d;
  d.sender = own_sba;
  d.parts.push_back({false, 0, serial_bytes(serial, 4 + serial % 11, 0xA0)});
  if (serial % 3 == 0) {
    d.parts.push_back({true, static_cast<std::uint8_t>(serial % 32), serial_bytes(serial, 4 + serial % 2, 0xB0)});
    d.parts.push_back({false, 0, {static_cast<std::uint8_t>(serial)}});
  }
  return d;
}

/// The program's directed transmission number `serial` (at most the default 16 data bytes).
inline described directed(std::uint32_t serial) {
  described d;
  d.sender = own_sba;
  d.broadcast = false;
  d.destination = static_cast<std::uint8_t>((serial * 11) % 32);
  d.parts.push_back({false, 0, serial_bytes(serial, 3 + serial % 14, 0xC0)});
  return d;
}

/// The program side's view of a delivery.
struct record {
  delivery_kind kind;
  std::uint8_t sender;
  std::vector<std::uint8_t> data;
  bool operator==(const record& o) const { return kind == o.kind && sender == o.sender && data == o.data; }
};

/// What SBA 5 delivers of a transmission heard whole (docs/protocol.md 3.4): the plain data of a broadcast
/// (from a sender in the mask) or of a transmission directed to it, as one record up to a block to it; each
/// block to it as a record of its own.
inline std::vector<record> records_of(const described& d) {
  std::vector<record> out;
  const bool for_me = d.broadcast ? ((broadcast_mask >> d.sender) & 1u) != 0 : d.destination == own_sba;
  bool plain_open = false;
  for (const auto& p : d.parts) {
    if (p.block) {
      if (p.destination == own_sba) {
        out.push_back({delivery_kind::block, d.sender, p.data});
        plain_open = false;
      }
    } else if (for_me) {
      if (!plain_open) out.push_back({d.broadcast ? delivery_kind::broadcast : delivery_kind::directed, d.sender, {}});
      plain_open = true;
      out.back().data.insert(out.back().data.end(), p.data.begin(), p.data.end());
    }
  }
  return out;
}

/// Another device's transmission number `serial`: broadcast or directed (to SBA 5 a third of the time),
/// one to three segments of which some are blocks (to SBA 5 or others); its last segment plain data.
inline described other(std::mt19937_64& rng, std::uint32_t serial, bool for_nobody = false) {
  described d;
  do d.sender = static_cast<std::uint8_t>(rng() % 32);
  while (d.sender == own_sba || (for_nobody && ((broadcast_mask >> d.sender) & 1u) != 0));
  d.broadcast = for_nobody || rng() % 2 == 0;
  if (!d.broadcast) d.destination = rng() % 3 == 0 ? own_sba : static_cast<std::uint8_t>(rng() % 32);
  if (for_nobody) d.broadcast = true;
  const unsigned n = for_nobody ? 1 : 1 + static_cast<unsigned>(rng() % 3);
  for (unsigned i = 0; i < n; ++i) {
    const bool block = !for_nobody && i + 1 < n && rng() % 2 == 0;
    const auto to = static_cast<std::uint8_t>(rng() % 2 == 0 ? own_sba : rng() % 32);
    d.parts.push_back({block, block ? (for_nobody ? std::uint8_t{0} : to) : std::uint8_t{0},
                       serial_bytes(serial, 4 + rng() % 9, static_cast<std::uint8_t>(i))});
  }
  return d;
}

}  // namespace detail::genius_stress

/// SBA 5 of a Genius bus at 153.6 kbit/s, default capacities (32 bytes of turn data, a 96-byte delivery
/// queue, two directed slots of 16 bytes). `config::link_steps` counts the characters on the bus.
inline report run_genius_device(const config& cfg) {
  using namespace detail;
  using namespace detail::genius_stress;
  using device_type = genius::device<>;
  device_type dev(own_sba);
  dev.deliver_broadcasts_from(broadcast_mask);
  handshake h;
  report rep;

  // What the link thread fed and saw.
  std::vector<std::vector<record>> fed_for_me;  // per transmission heard whole, its records (when it has any)
  std::vector<std::vector<std::uint16_t>> own_whole;
  std::uint64_t heard = 0, crc_fed = 0, framing_fed = 0, lost_fed = 0, own_lost = 0, collisions_made = 0,
                turn_expiries = 0, idle_expiries = 0, words_received = 0, link_calls = 0;
  checks link_checks;

  std::thread link([&] {
    std::mt19937_64 rng(cfg.seed * 6151 + 5);
    std::uint32_t serial = 0;
    bool timer_on = false;
    std::uint64_t characters = 0, events = 0;
    const auto apply = [&](genius::link_request r) {
      ++link_calls;
      if (r.timer == genius::timer_action::arm) timer_on = true;
      if (r.timer == genius::timer_action::cancel) timer_on = false;
      return r;
    };
    const auto expire = [&] {
      timer_on = false;
      return apply(dev.timer_expired());
    };
    const auto word_in = [&](std::uint16_t w) {
      (void)apply(dev.start_bit());
      (void)apply(dev.receive(w));
      ++characters;
      ++words_received;
    };
    // Another device's transmission, from its word `from` on (0: from its Start), maybe with a fault.
    const auto feed = [&](const described& d, std::size_t from, bool faults) {
      const std::vector<std::uint16_t> words = words_of(d);
      const unsigned pick = faults ? static_cast<unsigned>(rng() % 100) : 99u;
      if (pick < 4 && words.size() > 2) {  // the sender stops: the gap timer ends it
        const std::size_t cut = std::max<std::size_t>(from, 1 + rng() % (words.size() - 2));
        for (std::size_t i = from; i < cut; ++i) word_in(words[i]);
        link_checks.expect(timer_on && !dev.turn_armed(), "no gap timer inside a transmission");
        (void)expire();
        ++lost_fed;
        return;
      }
      if (pick < 8 && words.size() > 2) {  // a framing error inside it
        const std::size_t bad = std::max<std::size_t>(from, 1 + rng() % (words.size() - 2));
        for (std::size_t i = from; i < words.size(); ++i) {
          if (i == bad) {
            (void)apply(dev.start_bit());
            (void)apply(dev.framing_error());
            ++characters;
          } else {
            word_in(words[i]);
          }
        }
        ++framing_fed;
        return;
      }
      if (pick < 12) {  // a bit flipped in its last data character: a CRC-6 error
        std::vector<std::uint16_t> bad = words;
        std::size_t at = bad.size() - 2;
        while ((bad[at] & 1u) != 0) --at;
        bad[at] = static_cast<std::uint16_t>(bad[at] ^ (2u << (rng() % 8)));
        for (std::size_t i = from; i < bad.size(); ++i) word_in(bad[i]);
        ++crc_fed;
        return;
      }
      for (std::size_t i = from; i < words.size(); ++i) word_in(words[i]);
      ++heard;
      std::vector<record> records = records_of(d);
      if (!records.empty()) fed_for_me.push_back(std::move(records));
    };
    // Its turn: what it sends, read back (or a collision, or its read-back stops).
    const auto turn = [&](bool faults) {
      ++turn_expiries;
      const genius::link_request r = expire();
      if (!r.transmit) return;  // nothing to send: the turn passes
      const unsigned pick = faults ? static_cast<unsigned>(rng() % 100) : 99u;
      if (pick < 3) {  // another device's start bit before its first word
        (void)apply(dev.start_bit());
        ++collisions_made;
        std::uint16_t w = 0;
        link_checks.expect(!dev.transmit(w), "a word to send after a collision");
        feed(other(rng, ++serial), 0, false);
        return;
      }
      std::vector<std::uint16_t> sent;
      const std::size_t collide_at = pick < 6 ? 1 + rng() % 8 : ~std::size_t{0};
      const std::size_t cut_at = pick >= 6 && pick < 8 ? 1 + rng() % 8 : ~std::size_t{0};
      std::uint16_t w = 0;
      while (dev.transmit(w)) {
        ++link_calls;
        sent.push_back(w);
        (void)apply(dev.start_bit());
        if (sent.size() == collide_at) {  // another device's Start read back instead of its word
          const described d = other(rng, ++serial);
          const std::vector<std::uint16_t> words = words_of(d);
          (void)apply(dev.receive(words[0]));
          ++characters;
          ++words_received;
          ++collisions_made;
          link_checks.expect(!dev.transmit(w), "a word to send after a collision");
          feed(d, 1, false);
          return;
        }
        (void)apply(dev.receive(w));
        ++characters;
        ++words_received;
        if (sent.size() == cut_at && dev.sending()) {  // its read-back stops: the gap timer ends it
          (void)expire();
          ++own_lost;
          return;
        }
      }
      link_checks.expect(!dev.sending(), "its transmission stopped before its Stop");
      own_whole.push_back(std::move(sent));
    };

    h.start();
    (void)apply(dev.power_on());
    while (characters < cfg.link_steps) {
      if (timer_on && dev.turn_armed() && rng() % 3 == 0) {
        turn(true);
      } else if (timer_on && !dev.turn_armed() && rng() % 20 == 0) {  // the quiet bus: an idle restart
        ++idle_expiries;
        (void)expire();
      } else {
        feed(other(rng, ++serial), 0, true);
      }
      if ((++events & 63) == 0) std::this_thread::yield();
    }
    // Until the program has run enough and sent every directed transmission: traffic for nobody, and its turns.
    const auto cycle = [&] {
      feed(other(rng, ++serial, true), 0, false);
      if (timer_on && dev.turn_armed()) turn(false);
    };
    h.end_feeding(cfg.link_steps / 40, cycle);
    while (!h.program_done.load(std::memory_order_acquire)) cycle();
    rep.link_steps = characters;
  });

  // The program side.
  checks program_checks;
  std::vector<record> read;
  std::vector<std::vector<std::uint16_t>> directed_expected;
  std::uint32_t turn_serial_set = 0;
  std::uint64_t program_calls = 0;
  std::thread program([&] {
    std::mt19937_64 rng(cfg.seed * 7727 + 11);
    std::uint32_t directed_serial = 0;
    genius::device_counters before{};
    std::uint8_t buffer[255];
    h.start();
    const auto read_all = [&] {
      for (;;) {
        ++program_calls;
        const genius::delivery_result r = dev.read(byte_buffer(buffer, sizeof buffer));
        if (!r) {
          program_checks.expect(r.status == genius::delivery_status::none_waiting, "read refused a 255-byte buffer");
          return;
        }
        read.push_back({r.kind, r.sender, std::vector<std::uint8_t>(buffer, buffer + r.length)});
      }
    };
    while (!h.fed.load(std::memory_order_acquire)) {
      ++program_calls;
      h.program_calls.store(program_calls, std::memory_order_relaxed);
      const unsigned pick = static_cast<unsigned>(rng() % 100);
      if (pick < 20) {
        const described d = turn_data(++turn_serial_set);
        std::vector<genius::segment> segments;
        for (const auto& p : d.parts) {
          segments.push_back(genius::segment{p.block, p.destination, byte_view(p.data.data(), p.data.size())});
        }
        program_checks.expect(dev.set_turn_data(span<const genius::segment>(segments.data(), segments.size())) ==
                                  genius::turn_data_status::ok,
                              "set_turn_data refused turn data that fits");
      } else if (pick < 21) {
        dev.clear_turn_data();
      } else if (pick < 31) {
        const described d = directed(directed_serial + 1);
        const auto& data = d.parts.front().data;
        const genius::queue_status s = dev.queue_directed(d.destination, byte_view(data.data(), data.size()));
        if (s == genius::queue_status::ok) {
          ++directed_serial;
          directed_expected.push_back(words_of(d));
        } else {
          program_checks.expect(s == genius::queue_status::full, "queue_directed failed for another reason than full");
        }
        program_checks.expect(dev.directed_waiting() <= device_type::directed_slots, "more directed waiting than slots");
      } else if (pick < 70) {
        read_all();
      } else if (pick < 85) {
        const std::uint8_t n = dev.netstat();
        program_checks.expect((n & (genius::netstat_wire_error | 0x80u)) == 0,
                              "NETSTAT shows a bit the traffic cannot raise");
        if ((rng() & 1) != 0) dev.clear_netstat();
      } else {
        const genius::device_counters now = dev.counters();
        program_checks.expect(grew_or_same(now, before), "a counter went back");
        program_checks.expect(now.wire_errors == 0, "a wire error out of nothing");
        before = now;
      }
    }
    // Everything is fed: read the rest, and wait until every directed transmission has gone whole.
    while (dev.directed_waiting() != 0) {
      read_all();
      std::this_thread::yield();
    }
    read_all();
    h.program_done.store(true, std::memory_order_release);
  });
  link.join();
  program.join();

  // Both sides have ended: check what was sent, delivered and counted.
  checks c;
  {  // the rest of the deliveries
    std::uint8_t buffer[255];
    for (genius::delivery_result r; (r = dev.read(byte_buffer(buffer, sizeof buffer)));) {
      read.push_back({r.kind, r.sender, std::vector<std::uint8_t>(buffer, buffer + r.length)});
    }
  }
  // Its own whole transmissions: the turn data (a serial that never goes back) and the directed ones in order.
  std::size_t next_directed = 0;
  std::uint32_t last_turn_serial = 0;
  for (const auto& words : own_whole) {
    const genius::control_fields start = genius::read_control(genius::from_uart_word(words[0]).byte,
                                                              genius::control_layout{});
    c.expect(start.kind == genius::control_kind::start && start.sba == own_sba, "its transmission has no Start of its own");
    if (!start.broadcast) {
      c.expect(next_directed < directed_expected.size() && words == directed_expected[next_directed],
               "directed transmission " + std::to_string(next_directed) + " sent torn, twice or out of order");
      ++next_directed;
      continue;
    }
    const auto byte_at = [&](std::size_t k) { return genius::from_uart_word(words[k]).byte; };
    const std::uint32_t serial = words.size() > 4 ? (std::uint32_t{byte_at(1)} | std::uint32_t{byte_at(2)} << 8 |
                                                     std::uint32_t{byte_at(3)} << 16)
                                                  : 0;
    if (serial == 0 || serial > turn_serial_set || words != words_of(turn_data(serial))) {
      c.expect(false, "turn data sent that the program never set whole (serial " + std::to_string(serial) + ")");
      continue;
    }
    c.expect(serial >= last_turn_serial, "turn data went back from " + std::to_string(last_turn_serial) + " to " +
                                             std::to_string(serial));
    last_turn_serial = serial;
  }
  c.expect(next_directed == directed_expected.size(),
           std::to_string(directed_expected.size() - next_directed) + " directed transmissions never sent whole");
  // The deliveries: the records of the transmissions for it, each transmission whole or dropped whole.
  std::size_t at = 0, dropped = 0, records = 0;
  for (const auto& expected : fed_for_me) {
    const bool whole = at + expected.size() <= read.size() &&
                       std::equal(expected.begin(), expected.end(), read.begin() + static_cast<std::ptrdiff_t>(at));
    if (whole) {
      at += expected.size();
      records += expected.size();
    } else {
      ++dropped;
    }
  }
  c.expect(records != 0, "no delivery read: none was checked");
  c.expect(at == read.size(), std::to_string(read.size() - at) + " deliveries of " + std::to_string(read.size()) +
                                  " no transmission carried, or out of order, or torn");
  const genius::device_counters n = dev.counters();
  const auto same = [&](std::uint64_t counted, std::uint64_t done, const char* what) {
    c.expect(counted == (done & 0xFFFFFFFFu),
             std::string(what) + ": counted " + std::to_string(counted) + ", happened " + std::to_string(done));
  };
  same(n.delivery_overflows, dropped, "transmissions for it dropped whole (delivery overflows)");
  same(n.deliveries, records, "deliveries");
  same(n.transmissions_sent, own_whole.size(), "its transmissions sent whole");
  same(n.collisions, collisions_made, "collisions");
  same(n.turns_taken + n.turns_passed, turn_expiries, "turns taken + turns passed");
  same(n.turns_taken, own_whole.size() + collisions_made + own_lost, "turns taken");
  same(n.lost_transmissions, lost_fed + own_lost, "lost transmissions");
  same(n.crc_errors, crc_fed, "CRC errors");
  same(n.framing_errors, framing_fed, "framing errors");
  same(n.transmissions_heard, heard, "others' transmissions heard whole");
  same(n.idle_restarts, idle_expiries, "idle restarts");
  same(n.characters, words_received, "characters received");
  same(n.wire_errors, 0, "wire errors");
  // NETSTAT, now that both sides are quiet: cleared it is 0, and one CRC error raises exactly its bit.
  dev.clear_netstat();
  c.expect(dev.netstat() == 0, "NETSTAT not clear after clear_netstat");
  std::mt19937_64 rng(cfg.seed);
  std::vector<std::uint16_t> bad = words_of(other(rng, 1));
  bad[bad.size() - 2] = static_cast<std::uint16_t>(bad[bad.size() - 2] ^ 0x02u);
  for (const std::uint16_t w : bad) (void)dev.receive(w);
  c.expect(dev.netstat() == genius::netstat_crc_error, "a CRC error did not raise exactly its NETSTAT bit");

  rep.link_calls = link_calls;
  rep.program_calls = program_calls;
  rep.messages_in = heard + crc_fed + framing_fed + lost_fed;
  rep.frames_out = own_whole.size();
  rep.own_frames = next_directed;
  rep.dropped_whole = dropped;
  for (checks* each : {&link_checks, &program_checks, &c}) {
    for (auto& f : each->failures) rep.failures.push_back("Genius device: " + f);
  }
  return rep;
}

}  // namespace trionet::stress
