// `trionet ring join PORT --as mc|keypad`: a full node of a live ring. The node is the library's own
// (motion_coordinator, keypad); this file pumps it over the port, watches both directions of the link for
// events and the capture, and drives it from standard input or the keyboard.
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "basic/number_format.hpp"
#include "cli.hpp"
#include "keypad_terminal.hpp"
#include "learn/profile.hpp"
#include "live.hpp"
#include "profile_cli.hpp"
#include "ring_cli.hpp"
#include "ring_live.hpp"
#include "trionet/host/posix_link.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace trionet::cli {
namespace {

// A host reads the link in chunks, not a byte per byte-time as a UART does, so the forward buffer must hold
// a whole read (and what waits behind it) where firmware needs 32 bytes; the port is not read while the
// forward buffer has less room than one read, and the kernel holds the bytes meanwhile.
constexpr std::size_t host_forward_capacity = 4096;
constexpr std::size_t host_read_chunk = 256;  // what fd_link reads at once
// The nodes check and send direct variable transfers with the profile's CRC (an object chosen at run time)
// and variable layout (a policy: one instantiation for each, picked by ring::with_variable_layout).
template <class Layout>
using host_mc = ring::motion_coordinator<256, host_forward_capacity, 256, ring::default_max_characters,
                                         ring::crc16_runtime, Layout>;
template <class Layout>
using host_keypad =
    ring::keypad<host_forward_capacity, 64, ring::default_max_characters, ring::crc16_runtime, Layout>;

// The node with the host watching both directions of its link: every byte in and out also goes through a
// tap (events, capture, counters).
class watched_node final : public byte_port {
 public:
  watched_node(byte_port& node, ring_tap& in, ring_tap& out, ring_tap::sink on_in, ring_tap::sink on_out)
      : node_(&node), in_(&in), out_(&out), on_in_(std::move(on_in)), on_out_(std::move(on_out)) {}

  void set_time(std::uint64_t time_ns) noexcept { time_ = time_ns; }

  void receive(std::uint8_t byte) noexcept override {
    in_->push(byte, time_, on_in_);
    node_->receive(byte);
  }
  bool transmit(std::uint8_t& byte) noexcept override {
    if (!node_->transmit(byte)) return false;
    out_->push(byte, time_, on_out_);
    return true;
  }
  bool transmit_pending() const noexcept override { return node_->transmit_pending(); }
  void line_idle() noexcept override {
    node_->line_idle();
    in_->idle(time_, on_in_);
  }
  bool in_message() const noexcept override { return node_->in_message() || in_->open(); }

 private:
  byte_port* node_;
  ring_tap* in_;
  ring_tap* out_;
  ring_tap::sink on_in_;
  ring_tap::sink on_out_;
  std::uint64_t time_ = 0;
};

// A node on the port: opens it, pumps it, watches it. `Node` is host_mc or host_keypad.
template <class Node>
class station {
 public:
  // `log` gets the link's events: what arrives for this node (hops 1) and stray bytes; with --trace also
  // what passes through and what the node sends. Each carries "link": "in" or "out" after its time. The log
  // is flushed before every wait.
  station(Node& node, const join_settings& settings, live::capture_file* capture, live::event_log& log)
      : node_(&node),
        settings_(settings),
        in_(capture, "received on " + settings.port),
        out_(capture, "sent on " + settings.port),
        log_(&log),
        watched_(
            node, in_, out_,
            [this](const ring::decode_result& r, std::uint64_t time_ns) {
              if (settings_.trace || in_.last_hops() <= 1) show(r, time_ns, "in");
            },
            [this](const ring::decode_result& r, std::uint64_t time_ns) {
              if (settings_.trace) show(r, time_ns, "out");
            }),
        link_(-1, watched_) {}
  station(const station&) = delete;
  station& operator=(const station&) = delete;

  bool open(std::string& error) {
    if (!port_.open(settings_.port, settings_.link, error)) return false;
    if (port_.kind() == host::link_kind::standard_stream) {
      port_.close();
      error = "a node needs a port it can read and write (a serial port, a pty or a socket), not -";
      return false;
    }
    link_ = host::fd_link(port_.fd(), watched_);
    last_byte_ = live::now_ns();
    return true;
  }

  // One wait of at most `wait_ms` for the port (and standard input, if `input` >= 0). False when the port
  // closed or failed (`ended` says why).
  bool step(int wait_ms, int input, short& input_events, std::string& ended) {
    input_events = 0;
    pollfd fds[2] = {{port_.fd(), link_.poll_events(), 0}, {input, POLLIN, 0}};
    if (node_->forward_backlog() + host_read_chunk > host_forward_capacity) {
      fds[0].events = static_cast<short>(fds[0].events & ~POLLIN);
    }
    const std::uint64_t now = live::now_ns();
    int timeout = wait_ms;
    if (watched_.in_message()) {
      const std::uint64_t idle_at = last_byte_ + static_cast<std::uint64_t>(settings_.idle_ms) * 1000000u;
      const long long left = idle_at > now ? static_cast<long long>((idle_at - now + 999999u) / 1000000u) : 0;
      if (left < timeout) timeout = static_cast<int>(left);
    }
    log_->flush();
    const int ready = ::poll(fds, input >= 0 ? 2 : 1, timeout);
    if (ready < 0 && errno != EINTR) {
      ended = std::string("poll: ") + std::strerror(errno);
      return false;
    }
    const std::uint64_t after = live::now_ns();
    watched_.set_time(after);
    if (ready > 0 && fds[0].revents != 0) {
      const host::pump_result r = link_.service(fds[0].revents);
      if (r.received != 0) last_byte_ = after;
      if (r.closed || r.error == EIO) {
        ended = settings_.port + " closed";
        return false;
      }
      if (r.error != 0) {
        ended = settings_.port + ": " + std::strerror(r.error);
        return false;
      }
    }
    if (ready > 0 && input >= 0) input_events = fds[1].revents;
    if (after - last_byte_ >= static_cast<std::uint64_t>(settings_.idle_ms) * 1000000u &&
        watched_.in_message()) {
      (void)link_.idle();
      last_byte_ = after;
    }
    return true;
  }

  // Lets what the node has queued go out (at most `ms` milliseconds).
  void flush_out(int ms) {
    std::string ended;
    short ignored = 0;
    const std::uint64_t until = live::now_ns() + static_cast<std::uint64_t>(ms) * 1000000u;
    while ((node_->transmit_pending() || link_.unsent() != 0) && live::now_ns() < until) {
      if (!step(10, -1, ignored, ended)) return;
    }
  }

  void finish() {
    watched_.set_time(live::now_ns());
    out_.idle(live::now_ns(), [](const ring::decode_result&, std::uint64_t) {});
    port_.close();
  }

  ring_tap& in() { return in_; }
  ring_tap& out() { return out_; }
  const std::string& port_name() const { return settings_.port; }

 private:
  void show(const ring::decode_result& r, std::uint64_t time_ns, const char* link) {
    append_ring_event(log_->text(), r, [&](event& e) { e.time(time_ns).text("link", link); });
  }

  Node* node_;
  join_settings settings_;
  host::link_device port_;
  ring_tap in_;
  ring_tap out_;
  live::event_log* log_;
  watched_node watched_;
  host::fd_link link_;
  std::uint64_t last_byte_ = 0;
};

// The Motion Coordinator's VR(): every VR the ring may name, and each write from the ring reported.
class reported_vrs final : public vr_store {
 public:
  struct write_record {
    std::uint16_t vr;
    double value;
    vr_write_status status;
  };

  vr_write_status write(std::uint16_t vr, const network_value& value) noexcept override {
    const vr_write_status status = table_.write(vr, value);
    writes_.push_back({vr, value.to_double(), status});
    return status;
  }
  vr_table<ring::max_vr + 1>::reference operator[](std::size_t vr) noexcept { return table_[vr]; }
  std::vector<write_record> take() { return std::exchange(writes_, {}); }

 private:
  vr_table<ring::max_vr + 1> table_;
  std::vector<write_record> writes_;
};

void add_link_counters(event& e, const ring::link_counters& c) {
  e.number("messages_forwarded", c.messages_forwarded);
  e.number("forwards_lost", c.forwards_lost);
  e.number("forwards_cut", c.forwards_cut);
  e.number("forwards_ended_idle", c.forwards_ended_idle);
  e.number("messages_dropped", c.messages_dropped);
  e.number("messages_sent", c.messages_sent);
}

template <class Mc>
void mc_counters(std::string& out, const Mc& mc, station<Mc>& st) {
  event e(out, "counters");
  e.time(live::now_ns()).number("netstat", mc.netstat());
  const ring::motion_coordinator_counters& c = mc.counters();
  e.number("frame_errors", c.frame_errors);
  e.number("crc_errors", c.crc_errors);
  e.number("character_messages", c.character_messages);
  e.number("receive_overflows", c.receive_overflows);
  e.number("variables_written", c.variables_written);
  e.number("variables_refused", c.variables_refused);
  e.number("variables_out_of_range", c.variables_out_of_range);
  e.number("keypad_messages_ignored", c.keypad_messages_ignored);
  e.number("sends_refused", c.sends_refused);
  add_link_counters(e, mc.forwarding_counters());
  e.number("characters_waiting", mc.characters_waiting());
  st.in().add_counters(e, "in_");
  st.out().add_counters(e, "out_");
}

bool basic_address_word(const std::string& word, int& out) {
  long long n = 0;
  if (!parse_integer(word, ring::first_basic_address, ring::last_basic_address, n)) return false;
  out = static_cast<int>(n);
  return true;
}

// Splits "print 11 SOME TEXT" into the address word and the text after exactly one blank.
bool print_parts(const std::string& line, std::string& address, std::string& text) {
  std::size_t i = line.find_first_not_of(" \t");
  i = line.find_first_of(" \t", i);  // after "print"
  if (i == std::string::npos) return false;
  i = line.find_first_not_of(" \t", i);
  if (i == std::string::npos) return false;
  const std::size_t end = line.find_first_of(" \t", i);
  if (end == std::string::npos) return false;
  address = line.substr(i, end - i);
  text = line.substr(end + 1);
  return true;
}

// `--learn-keypad N`: puts the keypad at BASIC address N in network mode (keypad offset M back to this MC)
// and keypad mode 127, asks for each key in turn, and takes its key ON and key OFF characters from the
// receive buffer. Writes the profile in effect with the codes found (docs/profile.md). Returns the exit
// status: 3 when the characters fit no profile (two keys alike, a key OFF rule the profile cannot say).
template <class Mc>
int learn_keypad_codes(const join_settings& settings, Mc& mc, station<Mc>& st, live::event_log& log,
                       std::string& ended) {
  bool port_open = true;
  short ignored = 0;
  // Waits for the link until `done` or the end (a closed port, Ctrl-C).
  const auto run_until = [&](const auto& done) {
    while (!done()) {
      if (!port_open || live::signal_watch::stop_requested()) return false;
      port_open = st.step(100, -1, ignored, ended);
    }
    return true;
  };
  const auto queued = [&](ring::send_status status, const char* what) {
    if (status == ring::send_status::ok) return true;
    ended = std::string("cannot send the keypad ") + what + ": " + ring::to_string(status);
    return false;
  };
  if (!queued(mc.send_keypad_offset(settings.learn_keypad, settings.keypad_offset), "offset") ||
      !queued(mc.send_keypad_mode(settings.learn_keypad, 127), "mode")) {
    return fail_io("ring join: " + ended);
  }
  event(log.text(), "learning")
      .time(live::now_ns())
      .signed_number("keypad", settings.learn_keypad)
      .signed_number("offset", settings.keypad_offset);
  ring::keypad_codes codes{};
  std::uint8_t off[ring::key_count] = {};
  for (std::size_t k = 0; k < ring::key_count; ++k) {
    const char* name = learn::keypad_key_names[k];
    event(log.text(), "press").time(live::now_ns()).text("key", name);
    log.flush();
    std::fprintf(stderr, "press key %s and release it\n", name);
    std::uint8_t got[2] = {};
    for (std::uint8_t& c : got) {
      ring::get_result r{ring::get_status::nothing_yet, 0};
      if (!run_until([&] { return (r = mc.get(4)).status == ring::get_status::ok; })) {
        if (!port_open) return fail_io("ring join: " + ended);
        return fail_io("ring join: stopped before every key was learned");
      }
      c = r.value;
    }
    codes.raw[k] = got[0];
    off[k] = got[1];
    event(log.text(), "learned")
        .time(live::now_ns())
        .text("key", name)
        .number("on", got[0])
        .number("off", got[1]);
  }
  log.flush();
  bool plus_64 = true;
  bool same = true;
  for (std::size_t k = 0; k < ring::key_count; ++k) {
    plus_64 = plus_64 && off[k] == ring::default_key_off_code(codes.raw[k]);
    same = same && off[k] == codes.raw[k];
    for (std::size_t other = 0; other < k; ++other) {
      if (codes.raw[other] != codes.raw[k]) continue;
      std::fprintf(stderr, "trionet: ring join: keys %s and %s both sent character %u: no profile written\n",
                   learn::keypad_key_names[other], learn::keypad_key_names[k], codes.raw[k]);
      return exit_check;
    }
  }
  if (!plus_64 && !same) {
    std::fprintf(
        stderr,
        "trionet: ring join: the key OFF characters follow neither rule a profile can hold (key ON + 64, "
        "or the same): no profile written\n");
    return exit_check;
  }
  learn::profile p = active_profile();
  const ring::defkey_table from_old_codes = ring::make_default_defkey(p.keypad.codes);
  const bool defkey_from_codes = std::equal(std::begin(from_old_codes.value), std::end(from_old_codes.value),
                                            std::begin(p.keypad.defkey.value));
  p.keypad.codes = codes;
  p.keypad.key_off = plus_64 ? learn::key_off_rule::plus_64 : learn::key_off_rule::same;
  if (defkey_from_codes) p.keypad.defkey = ring::make_default_defkey(codes);
  return write_profile_file(p, settings.learn_output);
}

template <class Layout>
int join_mc_with(const join_settings& settings) {
  live::capture_file capture;
  std::string error;
  if (!settings.pcap.empty() && !capture.open(settings.pcap, error)) return fail("ring join: " + error);
  auto vrs = std::make_unique<reported_vrs>();
  // GET#3 through the profile's DEFKEY; its CRC for direct variable transfers.
  auto mc = std::make_unique<host_mc<Layout>>(*vrs, active_profile().keypad.defkey,
                                              ring::crc16_runtime(active_profile().ring.crc));
  live::event_log log(settings.json);
  auto st =
      std::make_unique<station<host_mc<Layout>>>(*mc, settings, capture.is_open() ? &capture : nullptr, log);
  if (!st->open(error)) return fail("ring join: " + error);

  live::signal_watch signals;
  std::string ended;
  if (settings.learn_keypad != 0) {
    const int status = learn_keypad_codes(settings, *mc, *st, log, ended);
    st->flush_out(500);
    log.flush();
    st->finish();
    return status;
  }
  live::line_reader input(STDIN_FILENO);
  bool port_open = true;
  bool quit = false;
  std::uint8_t netstat_shown = 0;

  const auto reply_error = [&](const std::string& command, const std::string& reason) {
    event(log.text(), "error").time(live::now_ns()).text("command", command).text("reason", reason);
  };
  // Waits for room in the transmit queue: the link runs meanwhile. Gives up after 2 s without room.
  std::uint64_t wait_started = 0;
  const auto wait_for_room = [&]() {
    if (wait_started == 0) wait_started = live::now_ns();
    short ignored = 0;
    if (!port_open || live::signal_watch::stop_requested()) return false;
    port_open = st->step(10, -1, ignored, ended);
    return port_open && live::now_ns() - wait_started < 2000000000u;
  };
  const auto sent = [&](const std::string& command, ring::send_status status) {
    if (status == ring::send_status::ok) {
      event(log.text(), "queued").time(live::now_ns()).text("command", command);
    } else {
      reply_error(command, ring::to_string(status));
    }
  };
  const auto run = [&](const std::string& line) {
    const std::vector<std::string> w = live::words_of(line);
    if (w.empty() || w[0][0] == '#') return;
    const std::string& command = w[0];
    int n = 0;
    long long number = 0;
    double value = 0;
    wait_started = 0;
    if (command == "print") {
      std::string address;
      std::string raw;
      std::string text;
      if (!print_parts(line, address, raw) || !basic_address_word(address, n))
        return reply_error(command, "usage: print N TEXT (N a BASIC address 10..24)");
      if (!live::unescape(raw, text, error)) return reply_error(command, error);
      const ring::print_result r = mc->print_all(
          n, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), wait_for_room);
      return sent(command, r.status);
    }
    if (command == "send") {
      if (w.size() != 4 || !basic_address_word(w[1], n) || !parse_integer(w[2], 0, ring::max_vr, number) ||
          !parse_real(w[3], value))
        return reply_error(command, "usage: send N VR VALUE (N 10..24, VR 0..16383)");
      ring::send_status s = ring::send_status::queue_full;
      while ((s = mc->send_variable(n, static_cast<std::uint16_t>(number), value)) ==
                 ring::send_status::queue_full &&
             wait_for_room()) {
      }
      return sent(command, s);
    }
    if (command == "offset" || command == "mode") {
      if (w.size() != 3 || !basic_address_word(w[1], n) || !parse_integer(w[2], 0, 127, number))
        return reply_error(command,
                           command == "offset" ? "usage: offset N M (N, M 10..24)" : "usage: mode N 0|127");
      ring::send_status s = ring::send_status::queue_full;
      const auto once = [&]() {
        return command == "offset" ? mc->send_keypad_offset(n, static_cast<int>(number))
                                   : mc->send_keypad_mode(n, static_cast<int>(number));
      };
      while ((s = once()) == ring::send_status::queue_full && wait_for_room()) {
      }
      return sent(command, s);
    }
    if (command == "key" || command == "get") {
      if (w.size() != 2 || !parse_integer(w[1], 3, 4, number))
        return reply_error(command, "usage: " + command + " 3|4");
      const int channel = static_cast<int>(number);
      if (command == "key") {
        event(log.text(), "key")
            .time(live::now_ns())
            .signed_number("channel", channel)
            .boolean("waiting", mc->key(channel))
            .number("characters", mc->characters_waiting());
        return;
      }
      const ring::get_result got = mc->get(channel);
      event e(log.text(), "get");
      e.time(live::now_ns()).signed_number("channel", channel);
      if (got) {
        e.signed_number("value", got.value);
      } else {
        e.text("status", ring::to_string(got.status));
      }
      return;
    }
    if (command == "vr") {
      if ((w.size() != 2 && w.size() != 3) || !parse_integer(w[1], 0, ring::max_vr, number))
        return reply_error(command, "usage: vr V [VALUE] (V 0..16383)");
      if (w.size() == 3) {
        if (!parse_real(w[2], value)) return reply_error(command, "VALUE must be a real number");
        (*vrs)[static_cast<std::size_t>(number)] = value;
      }
      event(log.text(), "vr")
          .time(live::now_ns())
          .signed_number("vr", number)
          .real("value", (*vrs)[static_cast<std::size_t>(number)]);
      return;
    }
    if (command == "netstat") {
      if (w.size() == 2 && w[1] == "clear") {
        mc->clear_netstat();
      } else if (w.size() != 1) {
        return reply_error(command, "usage: netstat [clear]");
      }
      netstat_shown = mc->netstat();
      event(log.text(), "netstat").time(live::now_ns()).number("netstat", mc->netstat());
      return;
    }
    if (command == "counters") return mc_counters(log.text(), *mc, *st);
    if (command == "quit") {
      quit = true;
      return;
    }
    reply_error(command,
                "unknown command (print, send, offset, mode, key, get, vr, netstat, counters, quit)");
  };

  while (port_open && !quit && !live::signal_watch::stop_requested()) {
    if (live::signal_watch::take_report_request()) mc_counters(log.text(), *mc, *st);
    short input_events = 0;
    port_open = st->step(1000, input.ended() ? -1 : input.fd(), input_events, ended);
    for (const reported_vrs::write_record& w : vrs->take()) {
      event(log.text(), "vr_write")
          .time(live::now_ns())
          .number("vr", w.vr)
          .real("value", w.value)
          .text("status", to_string(w.status));
    }
    if (mc->netstat() != netstat_shown) {
      netstat_shown = mc->netstat();
      event(log.text(), "netstat").time(live::now_ns()).number("netstat", netstat_shown);
    }
    if (port_open && (input_events & (POLLIN | POLLHUP | POLLERR)) != 0) {
      input.read_some();
      std::string line;
      while (!quit && input.next(line)) run(line);
    }
  }
  if (quit && port_open) st->flush_out(2000);
  mc_counters(log.text(), *mc, *st);
  log.flush();
  st->finish();
  if (!port_open) std::fprintf(stderr, "trionet: ring join: %s\n", ended.c_str());
  if (!capture.good()) return fail("ring join: writing the capture " + settings.pcap + " failed");
  return exit_ok;
}

}  // namespace

int join_mc(const join_settings& settings) {
  return ring::with_variable_layout(active_profile().ring.layout,
                                    [&](auto layout) { return join_mc_with<decltype(layout)>(settings); });
}

// ---- the keypad ----

namespace {

template <class Keypad>
std::string keypad_status(const Keypad& k) {
  if (!k.network_mode()) return "local mode (no keypad offset yet)";
  return "network mode: keys to BASIC " + std::to_string(k.offset() + 9) + " (" + std::to_string(k.offset()) +
         (k.offset() == 1 ? " hop)" : " hops)") + ", keypad mode " + std::to_string(k.mode());
}

template <class Layout>
int join_keypad_with(const join_settings& settings) {
  live::capture_file capture;
  std::string error;
  if (!settings.pcap.empty() && !capture.open(settings.pcap, error)) return fail("ring join: " + error);
  const learn::keypad_profile& codes = active_profile().keypad;
  auto keypad = std::make_unique<host_keypad<Layout>>(
      ring::keypad_config{&codes.codes, learn::key_off_function(codes.key_off), codes.display},
      ring::crc16_runtime(active_profile().ring.crc));
  raw_terminal terminal;
  const bool interactive = terminal.enter(STDIN_FILENO);
  live::event_log log(settings.json);
  if (interactive) log.keep_last(4);  // the last events, under the drawing
  auto st = std::make_unique<station<host_keypad<Layout>>>(*keypad, settings,
                                                           capture.is_open() ? &capture : nullptr, log);
  if (!st->open(error)) {
    terminal.restore();
    return fail("ring join: " + error);
  }

  live::signal_watch signals;
  live::line_reader input(STDIN_FILENO);
  key_decoder keys;
  terminal_screen screen;
  key_script script;
  std::string ended;
  bool port_open = true;
  bool quit = false;
  std::string shown_lines[2];
  std::string shown_status;
  bool first = true;

  const auto press = [&](const std::string& word) {
    ring::key k = ring::key::digit_0;
    if (!keypad_key(word, k)) {
      event(log.text(), "error")
          .time(live::now_ns())
          .text("word", word)
          .text("reason", "not a key (0..9 . up down clr y n start stop)");
      return;
    }
    const ring::key_status on = keypad->press(k);
    const ring::key_status off = keypad->release(k);
    event(log.text(), "key")
        .time(live::now_ns())
        .text("key", to_string(k))
        .text("press", ring::to_string(on))
        .text("release", ring::to_string(off));
  };
  const auto show = [&]() {
    const std::string lines[2] = {keypad->display().line(0), keypad->display().line(1)};
    const std::string status = keypad_status(*keypad);
    const bool changed =
        first || lines[0] != shown_lines[0] || lines[1] != shown_lines[1] || status != shown_status;
    if (!changed && !interactive) return;
    if ((status != shown_status || first) && (!first || keypad->network_mode())) {
      event(log.text(), "mode")
          .time(live::now_ns())
          .boolean("network", keypad->network_mode())
          .signed_number("offset", keypad->offset())
          .signed_number("keypad_mode", keypad->mode());
    }
    if (lines[0] != shown_lines[0] || lines[1] != shown_lines[1]) {
      event(log.text(), "display").time(live::now_ns()).text("line1", lines[0]).text("line2", lines[1]);
    }
    shown_lines[0] = lines[0];
    shown_lines[1] = lines[1];
    shown_status = status;
    first = false;
    if (interactive) {
      keypad_panel panel;
      panel.title = "trionet keypad on " + st->port_name();
      panel.lines[0] = lines[0];
      panel.lines[1] = lines[1];
      panel.status = status + "; keys sent " + std::to_string(keypad->counters().keys_sent) + ", lost " +
                     std::to_string(keypad->counters().keys_lost);
      log.flush();
      screen.draw({panel}, keyboard_help(screen.size().columns, false),
                  std::vector<std::string>(log.kept().begin(), log.kept().end()));
    }
  };

  // The keypad's counters and its link's, on SIGUSR1 and at the end.
  const auto counters = [&]() {
    event e(log.text(), "counters");
    e.time(live::now_ns())
        .boolean("network", keypad->network_mode())
        .signed_number("offset", keypad->offset());
    const ring::keypad_counters& c = keypad->counters();
    e.number("keys_sent", c.keys_sent)
        .number("keys_lost", c.keys_lost)
        .number("display_messages", c.display_messages);
    e.number("dropped_in_local_mode", c.dropped_in_local_mode).number("frame_errors", c.frame_errors);
    e.number("crc_errors", c.crc_errors);
    e.number("netstat", keypad->netstat());
    add_link_counters(e, keypad->forwarding_counters());
    st->in().add_counters(e, "in_");
    st->out().add_counters(e, "out_");
  };
  show();
  while (port_open && !quit && !live::signal_watch::stop_requested()) {
    if (live::signal_watch::take_report_request()) counters();
    const int due = script.due_in_ms(live::now_ns());
    const int wait = due >= 0 ? due : interactive ? 200 : 1000;
    short input_events = 0;
    port_open = st->step(wait, input.ended() ? -1 : input.fd(), input_events, ended);
    if (port_open && (input_events & (POLLIN | POLLHUP | POLLERR)) != 0) {
      if (interactive) {
        for (const std::string& word : keys.read(STDIN_FILENO)) {
          if (word == "quit") quit = true;
          if (word != "quit" && word != "next") press(word);
        }
      } else {
        input.read_some();
        std::string line;
        while (input.next(line)) script.add_line(line);
      }
    }
    std::string word;
    std::string bad_wait;
    while (!quit && script.next(live::now_ns(), word, bad_wait)) {
      if (word == "quit") {
        quit = true;
      } else {
        press(word);
      }
    }
    if (!bad_wait.empty()) {
      event(log.text(), "error")
          .time(live::now_ns())
          .text("word", bad_wait)
          .text("reason", "wait=MS takes 0..3600000");
    }
    show();
  }
  if (quit && port_open) st->flush_out(2000);
  log.flush();
  screen.leave();
  terminal.restore();
  log.keep_last(0);  // the counters go to standard output, screen or not
  counters();
  log.flush();
  st->finish();
  if (!port_open) std::fprintf(stderr, "trionet: ring join: %s\n", ended.c_str());
  if (!capture.good()) return fail("ring join: writing the capture " + settings.pcap + " failed");
  return exit_ok;
}

}  // namespace

int join_keypad(const join_settings& settings) {
  return ring::with_variable_layout(active_profile().ring.layout, [&](auto layout) {
    return join_keypad_with<decltype(layout)>(settings);
  });
}

}  // namespace trionet::cli
