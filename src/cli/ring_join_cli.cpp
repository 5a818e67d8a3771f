// `trionet ring join PORT --as mc|keypad`: a full node of a live ring. The node is the library's own
// (motion_coordinator, keypad); this file pumps it over the port, watches both directions of the link for
// events and the capture, and drives it from standard input or the keyboard. One session loop serves both
// kinds of node: a role (mc_role, keypad_role) says what the node does with its input and what it reports.
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
#include "trionet/host/q32_text.hpp"
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

  ring::receive_status receive(std::uint8_t byte) noexcept override {
    in_->push(byte, time_, on_in_);
    return node_->receive(byte);
  }
  bool transmit(std::uint8_t& byte) noexcept override {
    if (!node_->transmit(byte)) return false;
    out_->push(byte, time_, on_out_);
    return true;
  }
  bool transmit_pending() const noexcept override { return node_->transmit_pending(); }
  ring::receive_status line_idle() noexcept override {
    const ring::receive_status ended = node_->line_idle();
    in_->idle(time_, on_in_);
    return ended;
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

// A node on the port: opens it, pumps it in the command's event loop, watches it. `Node` is host_mc or
// host_keypad.
template <class Node>
class station {
 public:
  // `log` gets the link's events: what arrives for this node (hops 1) and stray bytes; with --trace also
  // what passes through and what the node sends. Each carries "link": "in" or "out" after its time.
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

  // Opens the port and watches it in `loop`.
  bool open(live::event_loop& loop, std::string& error) {
    if (!port_.open(settings_.port, settings_.link, error)) return false;
    if (port_.kind() == host::link_kind::standard_stream) {
      port_.close();
      error = "a node needs a port it can read and write (a serial port, a pty or a socket), not -";
      return false;
    }
    link_ = host::fd_link(port_.fd(), watched_);
    last_byte_ = live::now_ns();
    loop_ = &loop;
    slot_ = loop.watch(port_.fd(), POLLIN);
    return true;
  }

  // Before a wait: what to wait for on the port, and how long the wait may be (at most `wait_ms`; less
  // while a message is open, so that the idle line is seen in time).
  int prepare(int wait_ms) {
    short events = link_.poll_events();
    if (node_->forward_backlog() + host_read_chunk > host_forward_capacity) events = static_cast<short>(events & ~POLLIN);
    loop_->set(slot_, port_.fd(), events);
    if (!watched_.in_message()) return wait_ms;
    const std::uint64_t now = live::now_ns();
    const std::uint64_t idle_at = last_byte_ + static_cast<std::uint64_t>(settings_.idle_ms) * 1000000U;
    const long long left = idle_at > now ? static_cast<long long>((idle_at - now + 999999U) / 1000000U) : 0;
    return left < wait_ms ? static_cast<int>(left) : wait_ms;
  }

  // After a wait: moves the bytes the port has, and ends a message the idle line cut. A closed or failed
  // port ends the loop (the link is lost).
  void serve() {
    const std::uint64_t after = live::now_ns();
    watched_.set_time(after);
    const short revents = loop_->events(slot_);
    if (revents != 0) {
      const host::pump_result r = link_.service(revents);
      if (r.received != 0) last_byte_ = after;
      if (r.closed || r.error == EIO) {
        loop_->lost(host::printable(settings_.port) + " closed");
        return;
      }
      if (r.error != 0) {
        loop_->lost(host::printable(settings_.port) + ": " + std::strerror(r.error));
        return;
      }
    }
    if (after - last_byte_ >= static_cast<std::uint64_t>(settings_.idle_ms) * 1000000U && watched_.in_message()) {
      (void)link_.idle();
      last_byte_ = after;
    }
  }

  // One wait of at most `wait_ms` with only the port moving (the loop's other descriptors are for the
  // caller to mute). False when the loop has ended.
  bool pump(int wait_ms) {
    if (!loop_->wait(prepare(wait_ms))) return false;
    serve();
    return loop_->running();
  }

  // Lets what the node has queued go out (at most `ms` milliseconds).
  void flush_out(int ms) {
    const std::uint64_t until = live::now_ns() + static_cast<std::uint64_t>(ms) * 1000000U;
    while ((node_->transmit_pending() || link_.unsent() != 0) && live::now_ns() < until && pump(10)) {
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
  live::event_loop* loop_ = nullptr;
  std::size_t slot_ = 0;
  std::uint64_t last_byte_ = 0;
};

void add_link_counters(event& e, const ring::link_counters& c) {
  e.number("messages_forwarded", c.messages_forwarded);
  e.number("forwards_lost", c.forwards_lost);
  e.number("forwards_cut", c.forwards_cut);
  e.number("forwards_ended_idle", c.forwards_ended_idle);
  e.number("messages_dropped", c.messages_dropped);
  e.number("messages_sent", c.messages_sent);
}

// The session of either kind of node: opens the port, then waits for the port, standard input and the
// signals in one loop; `Role` (mc_role, keypad_role) does what its kind of node does with the input and
// says what it reports. Ends when the role is done (quit, or its input ended: what the node queued is sent
// first), when asked to stop (Ctrl-C ...), when the link is lost or the output fails. Returns the exit
// status (docs/cli.md).
template <class Node, class Role>
int run_session(const join_settings& settings, Node& node, live::capture_file& capture, live::event_log& log,
                Role& role) {
  live::event_loop loop(&log);
  station<Node> st(node, settings, capture.is_open() ? &capture : nullptr, log);
  std::string error;
  if (!st.open(loop, error)) {
    role.leave();
    return fail_io("ring join: " + error);
  }
  const std::size_t input = loop.watch(STDIN_FILENO, POLLIN);
  role.begin(st, loop, input);
  while (loop.running()) {
    if (live::event_loop::report_requested()) role.report(st);
    loop.set(input, role.reading() ? STDIN_FILENO : -1, POLLIN);
    if (!loop.wait(st.prepare(role.wait_ms()))) break;
    st.serve();
    role.after_wait(st);
    if (loop.running() && loop.readable(input)) role.read_input();
    role.act();
    if (role.done() && loop.running()) {
      loop.set(input, -1, 0);
      st.flush_out(2000);
      loop.stop();
    }
  }
  role.leave();
  role.counters(st);
  log.flush();
  st.finish();
  const int status = loop.finish("ring join");
  if (status == exit_ok && !capture.good()) return fail_io("ring join: writing the capture " + settings.pcap + " failed: " + capture.cause());
  return status;
}

// ---- the Motion Coordinator ----

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

template <class Mc, class Station>
void mc_counters(std::string& out, const Mc& mc, Station& st) {
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

// A Motion Coordinator driven by command lines on standard input (ring_live_usage lists them): done at
// `quit` or when standard input ends.
template <class Mc>
class mc_role {
 public:
  mc_role(Mc& mc, reported_vrs& vrs, live::event_log& log) : mc_(&mc), vrs_(&vrs), log_(&log) {}

  void begin(station<Mc>& st, live::event_loop& loop, std::size_t input) {
    st_ = &st;
    loop_ = &loop;
    input_slot_ = input;
  }
  [[nodiscard]] bool reading() const noexcept { return !quit_ && !input_.ended(); }
  [[nodiscard]] static int wait_ms() noexcept { return 1000; }
  void report(station<Mc>& st) { mc_counters(log_->text(), *mc_, st); }
  void after_wait(station<Mc>&) {
    for (const reported_vrs::write_record& w : vrs_->take()) {
      event(log_->text(), "vr_write")
          .time(live::now_ns())
          .number("vr", w.vr)
          .real("value", w.value)
          .text("status", to_string(w.status));
    }
    if (mc_->netstat() != netstat_shown_) {
      netstat_shown_ = mc_->netstat();
      event(log_->text(), "netstat").time(live::now_ns()).number("netstat", netstat_shown_);
    }
  }
  void read_input() {
    input_.read_some();
    std::string line;
    while (!quit_ && input_.next(line)) run(line);
  }
  void act() {}
  [[nodiscard]] bool done() const noexcept { return quit_ || input_.ended(); }
  void leave() {}
  void counters(station<Mc>& st) { mc_counters(log_->text(), *mc_, st); }

 private:
  void reply_error(const std::string& command, const std::string& reason) {
    event(log_->text(), "error").time(live::now_ns()).text("command", command).text("reason", reason);
  }
  void sent(const std::string& command, ring::send_status status) {
    if (status == ring::send_status::ok) {
      event(log_->text(), "queued").time(live::now_ns()).text("command", command);
    } else {
      reply_error(command, ring::to_string(status));
    }
  }
  // Waits for room in the transmit queue: the link runs meanwhile, standard input waits. Gives up after
  // 2 s without room.
  bool wait_for_room() {
    if (wait_started_ == 0) wait_started_ = live::now_ns();
    loop_->set(input_slot_, -1, 0);
    return st_->pump(10) && live::now_ns() - wait_started_ < 2000000000U;
  }
  template <class Send>
  ring::send_status with_room(Send&& send) {
    ring::send_status s = ring::send_status::queue_full;
    while ((s = send()) == ring::send_status::queue_full && wait_for_room()) {
    }
    return s;
  }

  void run(const std::string& line) {
    const std::vector<std::string> w = live::words_of(line);
    if (w.empty() || w[0][0] == '#') return;
    const std::string& command = w[0];
    int n = 0;
    long long number = 0;
    double value = 0;
    std::string error;
    wait_started_ = 0;
    if (command == "print") {
      std::string address;
      std::string raw;
      std::string text;
      if (!print_parts(line, address, raw) || !basic_address_word(address, n))
        return reply_error(command, "usage: print N TEXT (N a BASIC address 10..24)");
      if (!live::unescape(raw, text, error)) return reply_error(command, error);
      const ring::print_result r = mc_->print_all(
          n, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), [this] { return wait_for_room(); });
      return sent(command, r.status);
    }
    if (command == "send") {
      if (w.size() != 4 || !basic_address_word(w[1], n) || !parse_integer(w[2], 0, ring::max_vr, number))
        return reply_error(command, "usage: send N VR VALUE (N 10..24, VR 0..16383)");
      // VALUE read exactly to Q32.32, not through a double (q32_text.hpp).
      const host::q32_text_result q = host::parse_q32(w[3]);
      if (q.status == host::q32_text_status::too_long)
        return reply_error(command, "VALUE has more than " + std::to_string(host::max_q32_text) + " characters");
      if (q.status == host::q32_text_status::not_a_number)
        return reply_error(command, "usage: send N VR VALUE (N 10..24, VR 0..16383)");
      if (!q) return sent(command, ring::send_status::value_out_of_range);  // as send_variable says it
      return sent(command,
                  with_room([&] { return mc_->send_variable_q32(n, static_cast<std::uint16_t>(number), q.raw); }));
    }
    if (command == "offset" || command == "mode") {
      if (w.size() != 3 || !basic_address_word(w[1], n) || !parse_integer(w[2], 0, 127, number))
        return reply_error(command,
                           command == "offset" ? "usage: offset N M (N, M 10..24)" : "usage: mode N 0|127");
      return sent(command, with_room([&] {
                    return command == "offset" ? mc_->send_keypad_offset(n, static_cast<int>(number))
                                               : mc_->send_keypad_mode(n, static_cast<int>(number));
                  }));
    }
    if (command == "key" || command == "get") {
      if (w.size() != 2 || !parse_integer(w[1], 3, 4, number))
        return reply_error(command, "usage: " + command + " 3|4");
      const int channel = static_cast<int>(number);
      if (command == "key") {
        event(log_->text(), "key")
            .time(live::now_ns())
            .signed_number("channel", channel)
            .boolean("waiting", mc_->key(channel))
            .number("characters", mc_->characters_waiting());
        return;
      }
      const ring::get_result got = mc_->get(channel);
      event e(log_->text(), "get");
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
        (*vrs_)[static_cast<std::size_t>(number)] = value;
      }
      event(log_->text(), "vr")
          .time(live::now_ns())
          .signed_number("vr", number)
          .real("value", (*vrs_)[static_cast<std::size_t>(number)]);
      return;
    }
    if (command == "netstat") {
      if (w.size() == 2 && w[1] == "clear") {
        mc_->clear_netstat();
      } else if (w.size() != 1) {
        return reply_error(command, "usage: netstat [clear]");
      }
      netstat_shown_ = mc_->netstat();
      event(log_->text(), "netstat").time(live::now_ns()).number("netstat", mc_->netstat());
      return;
    }
    if (command == "counters") return mc_counters(log_->text(), *mc_, *st_);
    if (command == "quit") {
      quit_ = true;
      return;
    }
    reply_error(command, "unknown command (print, send, offset, mode, key, get, vr, netstat, counters, quit)");
  }

  Mc* mc_;
  reported_vrs* vrs_;
  live::event_log* log_;
  station<Mc>* st_ = nullptr;
  live::event_loop* loop_ = nullptr;
  std::size_t input_slot_ = 0;
  live::line_reader input_{STDIN_FILENO};
  std::uint8_t netstat_shown_ = 0;
  bool quit_ = false;
  std::uint64_t wait_started_ = 0;
};

// `--learn-keypad N`: puts the keypad at BASIC address N in network mode (keypad offset M back to this MC)
// and keypad mode 127, asks for each key in turn, and takes its key ON and key OFF characters from the
// receive buffer. Writes the profile in effect with the codes found (docs/profile.md). Returns the exit
// status: 3 when the characters fit no profile (two keys alike, a key OFF rule the profile cannot say).
template <class Mc>
int learn_keypad_codes(const join_settings& settings, Mc& mc, live::capture_file& capture, live::event_log& log) {
  live::event_loop loop(&log);
  station<Mc> st(mc, settings, capture.is_open() ? &capture : nullptr, log);
  std::string error;
  if (!st.open(loop, error)) return fail_io("ring join: " + error);
  const auto finish = [&](int status) {
    st.flush_out(500);
    log.flush();
    st.finish();
    const int ended = loop.finish("ring join");
    return ended != exit_ok ? ended : status;
  };
  const auto queued = [&](ring::send_status status, const char* what) {
    if (status == ring::send_status::ok) return true;
    error = std::string("cannot send the keypad ") + what + ": " + ring::to_string(status);
    return false;
  };
  if (!queued(mc.send_keypad_offset(settings.learn_keypad, settings.keypad_offset), "offset") ||
      !queued(mc.send_keypad_mode(settings.learn_keypad, 127), "mode")) {
    return finish(fail_io("ring join: " + error));
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
      while ((r = mc.get(4)).status != ring::get_status::ok) {
        if (!st.pump(100)) {
          if (loop.link_lost() || output_failed()) return finish(exit_io);
          return finish(fail_io("ring join: stopped before every key was learned"));
        }
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
  bool plus_64 = true;
  bool same = true;
  for (std::size_t k = 0; k < ring::key_count; ++k) {
    plus_64 = plus_64 && off[k] == ring::default_key_off_code(codes.raw[k]);
    same = same && off[k] == codes.raw[k];
    for (std::size_t other = 0; other < k; ++other) {
      if (codes.raw[other] != codes.raw[k]) continue;
      note("ring join: keys " + std::string(learn::keypad_key_names[other]) + " and " +
                             learn::keypad_key_names[k] + " both sent character " + std::to_string(codes.raw[k]) +
                             ": no profile written");
      return finish(exit_check);
    }
  }
  if (!plus_64 && !same) {
    note(
        "ring join: the key OFF characters follow neither rule a profile can hold (key ON + 64, or the same): no "
        "profile written");
    return finish(exit_check);
  }
  learn::profile p = active_profile();
  const ring::defkey_table from_old_codes = ring::make_default_defkey(p.keypad.codes);
  const bool defkey_from_codes = std::equal(std::begin(from_old_codes.value), std::end(from_old_codes.value),
                                            std::begin(p.keypad.defkey.value));
  p.keypad.codes = codes;
  p.keypad.key_off = plus_64 ? learn::key_off_rule::plus_64 : learn::key_off_rule::same;
  if (defkey_from_codes) p.keypad.defkey = ring::make_default_defkey(codes);
  return finish(write_profile_file(p, settings.learn_output));
}

template <class Layout>
int join_mc_with(const join_settings& settings) {
  live::capture_file capture;
  std::string error;
  if (!settings.pcap.empty() && !capture.open(settings.pcap, error)) return fail_io("ring join: " + error);
  auto vrs = std::make_unique<reported_vrs>();
  // GET#3 through the profile's DEFKEY; its CRC for direct variable transfers.
  auto mc = std::make_unique<host_mc<Layout>>(*vrs, active_profile().keypad.defkey,
                                              ring::crc16_runtime(active_profile().ring.crc));
  live::event_log log(settings.json);
  if (settings.learn_keypad != 0) return learn_keypad_codes(settings, *mc, capture, log);
  mc_role<host_mc<Layout>> role(*mc, *vrs, log);
  return run_session(settings, *mc, capture, log, role);
}

// ---- the keypad ----

template <class Keypad>
std::string keypad_status(const Keypad& k) {
  if (!k.network_mode()) return "local mode (no keypad offset yet)";
  return "network mode: keys to BASIC " + std::to_string(k.offset() + 9) + " (" + std::to_string(k.offset()) +
         (k.offset() == 1 ? " hop)" : " hops)") + ", keypad mode " + std::to_string(k.mode());
}

// A membrane keypad: on a terminal its display drawn in place and the keyboard as its keys (done at q);
// otherwise key words from standard input (done at `quit`, or when standard input has ended and every key
// word, waits included, has been taken).
template <class Keypad>
class keypad_role {
 public:
  keypad_role(Keypad& keypad, live::event_log& log) : keypad_(&keypad), log_(&log) {
    interactive_ = terminal_.enter(STDIN_FILENO);
    if (interactive_) log.keep_last(4);  // the last events, under the drawing
  }

  void begin(station<Keypad>& st, live::event_loop&, std::size_t) {
    port_name_ = st.port_name();
    show();
  }
  [[nodiscard]] bool reading() const noexcept { return !quit_ && !input_.ended(); }
  [[nodiscard]] int wait_ms() const {
    const int due = script_.due_in_ms(live::now_ns());
    return due >= 0 ? due : interactive_ ? 200 : 1000;
  }
  // The keypad's counters and its link's, on SIGUSR1 and at the end.
  void report(station<Keypad>& st) { counters(st); }
  void after_wait(station<Keypad>&) {}
  void read_input() {
    if (interactive_) {
      for (const std::string& word : keys_.read(STDIN_FILENO)) {
        if (word == "quit") quit_ = true;
        if (word != "quit" && word != "next") press(word);
      }
      return;
    }
    input_.read_some();
    std::string line;
    while (input_.next(line)) script_.add_line(line);
  }
  void act() {
    std::string word;
    bool bad_wait = false;
    while (!quit_ && script_.next(live::now_ns(), word, bad_wait)) {
      if (bad_wait) {
        event(log_->text(), "error")
            .time(live::now_ns())
            .text("word", word)
            .text("reason", "wait=MS takes 0..3600000");
      } else if (word == "quit") {
        quit_ = true;
      } else {
        press(word);
      }
    }
    show();
  }
  [[nodiscard]] bool done() const {
    return quit_ || (!interactive_ && input_.ended() && script_.done(live::now_ns()));
  }
  void leave() {
    log_->flush();
    screen_.leave();
    terminal_.restore();
    log_->keep_last(0);  // the counters go to standard output, screen or not
  }
  void counters(station<Keypad>& st) {
    event e(log_->text(), "counters");
    e.time(live::now_ns()).boolean("network", keypad_->network_mode()).signed_number("offset", keypad_->offset());
    const ring::keypad_counters& c = keypad_->counters();
    e.number("keys_sent", c.keys_sent).number("keys_lost", c.keys_lost).number("display_messages", c.display_messages);
    e.number("dropped_in_local_mode", c.dropped_in_local_mode).number("frame_errors", c.frame_errors);
    e.number("crc_errors", c.crc_errors);
    e.number("netstat", keypad_->netstat());
    add_link_counters(e, keypad_->forwarding_counters());
    st.in().add_counters(e, "in_");
    st.out().add_counters(e, "out_");
  }

 private:
  void press(const std::string& word) {
    ring::key k = ring::key::digit_0;
    if (!keypad_key(word, k)) {
      event(log_->text(), "error")
          .time(live::now_ns())
          .text("word", word)
          .text("reason", "not a key (0..9 . up down clr y n start stop)");
      return;
    }
    const ring::key_status on = keypad_->press(k);
    const ring::key_status off = keypad_->release(k);
    event(log_->text(), "key")
        .time(live::now_ns())
        .text("key", to_string(k))
        .text("press", ring::to_string(on))
        .text("release", ring::to_string(off));
  }
  // Events for a new mode or display; on a terminal the drawing, redrawn.
  void show() {
    const std::string lines[2] = {keypad_->display().line(0), keypad_->display().line(1)};
    const std::string status = keypad_status(*keypad_);
    const bool changed = first_ || lines[0] != shown_lines_[0] || lines[1] != shown_lines_[1] || status != shown_status_;
    if (!changed && !interactive_) return;
    if ((status != shown_status_ || first_) && (!first_ || keypad_->network_mode())) {
      event(log_->text(), "mode")
          .time(live::now_ns())
          .boolean("network", keypad_->network_mode())
          .signed_number("offset", keypad_->offset())
          .signed_number("keypad_mode", keypad_->mode());
    }
    if (lines[0] != shown_lines_[0] || lines[1] != shown_lines_[1]) {
      event(log_->text(), "display").time(live::now_ns()).text("line1", lines[0]).text("line2", lines[1]);
    }
    shown_lines_[0] = lines[0];
    shown_lines_[1] = lines[1];
    shown_status_ = status;
    first_ = false;
    if (!interactive_) return;
    keypad_panel panel;
    panel.title = "trionet keypad on " + port_name_;
    panel.lines[0] = lines[0];
    panel.lines[1] = lines[1];
    panel.status = status + "; keys sent " + std::to_string(keypad_->counters().keys_sent) + ", lost " +
                   std::to_string(keypad_->counters().keys_lost);
    log_->flush();
    screen_.draw({panel}, keyboard_help(screen_.size().columns, false),
                 std::vector<std::string>(log_->kept().begin(), log_->kept().end()));
  }

  Keypad* keypad_;
  live::event_log* log_;
  raw_terminal terminal_;
  bool interactive_ = false;
  live::line_reader input_{STDIN_FILENO};
  key_decoder keys_;
  terminal_screen screen_;
  key_script script_;
  std::string port_name_;
  std::string shown_lines_[2];
  std::string shown_status_;
  bool first_ = true;
  bool quit_ = false;
};

template <class Layout>
int join_keypad_with(const join_settings& settings) {
  live::capture_file capture;
  std::string error;
  if (!settings.pcap.empty() && !capture.open(settings.pcap, error)) return fail_io("ring join: " + error);
  const learn::keypad_profile& codes = active_profile().keypad;
  auto keypad = std::make_unique<host_keypad<Layout>>(
      ring::keypad_config{&codes.codes, learn::key_off_function(codes.key_off), codes.display},
      ring::crc16_runtime(active_profile().ring.crc));
  live::event_log log(settings.json);
  keypad_role<host_keypad<Layout>> role(*keypad, log);
  return run_session(settings, *keypad, capture, log, role);
}

}  // namespace

int join_mc(const join_settings& settings) {
  return ring::with_variable_layout(active_profile().ring.layout,
                                    [&](auto layout) { return join_mc_with<decltype(layout)>(settings); });
}

int join_keypad(const join_settings& settings) {
  return ring::with_variable_layout(active_profile().ring.layout, [&](auto layout) {
    return join_keypad_with<decltype(layout)>(settings);
  });
}

}  // namespace trionet::cli
