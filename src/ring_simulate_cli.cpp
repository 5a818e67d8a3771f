// `trionet ring simulate example1|example2`: the manual's example networks on the simulated ring, with a
// readable trace: every message on every link with its hop count, VR changes, the keypad displays drawn as
// 2 x 20 boxes, and NETSTAT at the end.
#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

#include "cli.hpp"
#include "ring_cli.hpp"
#include "ring_manual_examples.hpp"

namespace trionet::cli {
namespace {

std::string readable(byte_view text) {
  std::string out;
  for (std::uint8_t c : text) {
    if (c == '\r') {
      out += "\\r";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c < 32 || c == 127) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02x", c);
      out += escape;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string event_text(const ring::decode_result& r) {
  if (r.status == ring::decode_status::frame_error)
    return std::string("frame error: ") + ring::to_string(r.error);
  if (r.status == ring::decode_status::crc_error) return "CRC error (vr " + std::to_string(r.msg.vr) + ")";
  const std::string hops = "hops " + std::to_string(r.msg.hops) + "  ";
  switch (r.msg.type) {
    case ring::message_type::character:
      return hops + "PRINT   \"" + readable(r.msg.text) + "\"";
    case ring::message_type::variable:
      return hops + "VR(" + std::to_string(r.msg.vr) +
             ") = " + format_real(trionet::q32_to_double(r.msg.value));
    case ring::message_type::keypad_offset:
      return hops + "keypad offset " + std::to_string(r.msg.offset);
    case ring::message_type::keypad_mode:
      return hops + "keypad mode " + std::to_string(r.msg.mode);
  }
  return hops;
}

/// Prints every message on every link as it completes, and watched VR changes.
class tracer {
 public:
  tracer(const char* const* names, std::size_t count) : names_(names), count_(count), decoders_(count) {}

  void on_byte(const ring::link_byte& b) {
    if (!b.delivered) return;
    const ring::decode_result r = decoders_[b.link].push(b.received);
    if (r.status == ring::decode_status::incomplete) return;
    const std::string route = std::string(names_[b.link]) + " -> " + names_[(b.link + 1) % count_];
    std::printf("t=%6" PRIu64 "  %-24s %s\n", b.time, route.c_str(), event_text(r).c_str());
  }

  struct watch {
    const char* node;
    const vr_table<1024>* table;
    std::size_t vr;
    double last;
  };
  void watch_vr(const char* node, const vr_table<1024>& table, std::size_t vr) {
    watches_.push_back({node, &table, vr, table[vr]});
  }
  void check_vrs(std::uint64_t now) {
    for (auto& w : watches_) {
      const double value = (*w.table)[w.vr];
      if (value == w.last) continue;
      w.last = value;
      std::printf("t=%6" PRIu64 "  %-24s VR(%zu) is now %s\n", now, w.node, w.vr, format_real(value).c_str());
    }
  }

 private:
  const char* const* names_;
  std::size_t count_;
  std::vector<ring::decoder<>> decoders_;
  std::vector<watch> watches_;
};

void print_box(const char* title, const ring::keypad_display& display) {
  std::printf("%s\n%s", title, examples::draw_display(display).c_str());
}

template <class Node>
void print_netstat(const char* name, const Node& mc) {
  const auto& c = mc.counters();
  std::printf("NETSTAT %-10s %u   (frame errors %u, CRC errors %u, receive overflows %u, sends refused %u)\n",
              name, static_cast<unsigned>(mc.netstat()), static_cast<unsigned>(c.frame_errors),
              static_cast<unsigned>(c.crc_errors), static_cast<unsigned>(c.receive_overflows),
              static_cast<unsigned>(c.sends_refused));
}

int run_example1() {
  examples::example1 ex;
  tracer t(examples::example1::node_names, 3);
  t.watch_vr("MC", ex.vr, 2);
  const examples::trace_fn trace = [&](const ring::link_byte& b) {
    t.on_byte(b);
    t.check_vrs(b.time);
  };
  std::printf("Manual example 1: one Motion Coordinator and two keypads\n");
  std::printf("ring: MC -> keypad 1 -> keypad 2 -> MC   (1 byte per link per byte-time)\n\n");
  ex.settle(trace);
  print_box("\nkeypad 1 and keypad 2 after the program's set-up:", ex.keypad1.display());
  struct {
    ring::keypad<>* keypad;
    ring::key key;
    const char* what;
  } presses[] = {
      {&ex.keypad1, ring::key::digit_1, "keypad 1: 1"}, {&ex.keypad2, ring::key::digit_2, "keypad 2: 2"},
      {&ex.keypad1, ring::key::digit_5, "keypad 1: 5"}, {&ex.keypad2, ring::key::up, "keypad 2: up"},
      {&ex.keypad1, ring::key::up, "keypad 1: up"},     {&ex.keypad2, ring::key::up, "keypad 2: up"},
      {&ex.keypad1, ring::key::down, "keypad 1: down"}};
  for (const auto& p : presses) {
    std::printf("\n[key] %s\n", p.what);
    examples::press(ex, *p.keypad, p.key, trace);
  }
  std::printf("\n");
  print_box("keypad 1:", ex.keypad1.display());
  print_box("keypad 2:", ex.keypad2.display());
  std::printf("\nVR(length) = VR(2) = %s, a = %s\n", format_real(ex.vr[2]).c_str(),
              format_real(ex.a).c_str());
  print_netstat("MC", ex.mc);
  std::printf("%" PRIu64 " byte-times (%.3f s at 125 kbit/s, 10 bits per byte)\n", ex.sim.now(),
              ring::byte_times_to_seconds(ex.sim.now(), 125000.0));
  return exit_ok;
}

int run_example2() {
  examples::example2 ex;
  tracer t(examples::example2::node_names, 3);
  for (std::size_t vr : {0u, 1u, 200u}) t.watch_vr("3-axis MC", ex.vr_three, vr);
  for (std::size_t vr : {0u, 1u, 200u}) t.watch_vr("2-axis MC", ex.vr_two, vr);
  const examples::trace_fn trace = [&](const ring::link_byte& b) {
    t.on_byte(b);
    t.check_vrs(b.time);
  };
  std::printf("Manual example 2: two Motion Coordinators and one keypad\n");
  std::printf("ring: 3-axis MC -> 2-axis MC -> keypad -> 3-axis MC   (1 byte per link per byte-time)\n\n");
  const bool ok = ex.operate(trace, [&](const std::string& phase) {
    std::printf("\n== %s\n", phase.c_str());
    print_box("keypad display:", ex.keypad.display());
    std::printf("\n");
  });
  print_netstat("3-axis MC", ex.three_axis);
  print_netstat("2-axis MC", ex.two_axis);
  std::printf("keypad: offset %u, %u display messages, %u keys sent\n",
              static_cast<unsigned>(ex.keypad.offset()),
              static_cast<unsigned>(ex.keypad.counters().display_messages),
              static_cast<unsigned>(ex.keypad.counters().keys_sent));
  std::printf("2-axis SPEED = %s\n", format_real(ex.speed).c_str());
  std::printf("%" PRIu64 " byte-times (%.3f s at 125 kbit/s, 10 bits per byte)\n", ex.sim.now(),
              ring::byte_times_to_seconds(ex.sim.now(), 125000.0));
  if (!ok) {
    std::fprintf(stderr, "trionet: example 2 did not complete its handshake\n");
    return 1;
  }
  return exit_ok;
}

}  // namespace

int ring_simulate_main(const std::vector<std::string>& args) {
  if (args.size() != 1) return fail("ring simulate takes one example: example1 or example2");
  if (args[0] == "example1") return run_example1();
  if (args[0] == "example2") return run_example2();
  return fail("unknown example '" + args[0] + "' (expected example1 or example2)");
}

}  // namespace trionet::cli
