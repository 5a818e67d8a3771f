// The simulated ring network of ring_network.hpp, and the adapter that gives a BASIC program
// (basic/controller.hpp) a Motion Coordinator of the library (ring::motion_coordinator + a vr_table). Every use
// of the ring nodes' API by the BASIC tools is in this file.
#include "ring_network.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>

#include "basic/controller.hpp"
#include "basic/number_format.hpp"
#include "basic/program.hpp"
#include "basic/task.hpp"
#include "trionet/host/text.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace trionet::host {
namespace {

using event_sink = std::function<void(const network_event&)>;

// The nodes check and send direct variable transfers with the configured CRC (an object chosen at run time)
// and layout (a template parameter of the library's nodes, one of seven). The simulation reaches them
// through these interfaces, implemented once per layout and chosen when the ring is built.
template <class Layout>
using mc_node = ring::motion_coordinator<256, 32, 32, ring::default_max_characters, ring::crc16_runtime, Layout>;
template <class Layout>
using keypad_node = ring::keypad<16, 16, ring::default_max_characters, ring::crc16_runtime, Layout>;
constexpr std::size_t mc_max_own_frame = mc_node<ring::default_variable_layout>::max_own_frame;

class mc_api {
 public:
  virtual ~mc_api() = default;
  virtual byte_port& port() = 0;
  virtual ring::print_result print(int n, byte_view text) = 0;
  virtual ring::send_status send_variable(int n, std::uint16_t vr, double value) = 0;
  virtual ring::send_status send_keypad_offset(int n, int offset) = 0;
  virtual bool key(int channel) const = 0;
  virtual ring::get_result get(int channel) = 0;
  virtual std::uint8_t netstat() const = 0;
  virtual void clear_netstat() = 0;
  virtual std::size_t transmit_free() const = 0;
};

template <class Layout>
class mc_of final : public mc_api {
 public:
  mc_of(vr_store& vr, const ring::defkey_table& defkey, const ring::crc16_runtime& crc) : node_(vr, defkey, crc) {}
  byte_port& port() override { return node_; }
  ring::print_result print(int n, byte_view text) override { return node_.print(n, text); }
  ring::send_status send_variable(int n, std::uint16_t vr, double value) override {
    return node_.send_variable(n, vr, value);
  }
  ring::send_status send_keypad_offset(int n, int offset) override { return node_.send_keypad_offset(n, offset); }
  bool key(int channel) const override { return node_.key(channel); }
  ring::get_result get(int channel) override { return node_.get(channel); }
  std::uint8_t netstat() const override { return node_.netstat(); }
  void clear_netstat() override { node_.clear_netstat(); }
  std::size_t transmit_free() const override { return node_.transmit_free(); }

 private:
  mc_node<Layout> node_;
};

class keypad_api {
 public:
  virtual ~keypad_api() = default;
  virtual byte_port& port() = 0;
  virtual ring::key_status press(ring::key k) = 0;
  virtual ring::key_status release(ring::key k) = 0;
  virtual bool network_mode() const = 0;
  virtual std::uint8_t offset() const = 0;
  virtual const ring::keypad_display& display() const = 0;
  virtual ring::keypad_counters counters() const = 0;
  virtual ring::link_counters forwarding_counters() const = 0;
};

template <class Layout>
class keypad_of final : public keypad_api {
 public:
  keypad_of(const ring::keypad_config& config, const ring::crc16_runtime& crc) : node_(config, crc) {}
  byte_port& port() override { return node_; }
  ring::key_status press(ring::key k) override { return node_.press(k); }
  ring::key_status release(ring::key k) override { return node_.release(k); }
  bool network_mode() const override { return node_.network_mode(); }
  std::uint8_t offset() const override { return node_.offset(); }
  const ring::keypad_display& display() const override { return node_.display(); }
  ring::keypad_counters counters() const override { return node_.counters(); }
  ring::link_counters forwarding_counters() const override { return node_.forwarding_counters(); }

 private:
  keypad_node<Layout> node_;
};

// The trace's decoder of one link, with the same CRC and layout.
class decoder_api {
 public:
  virtual ~decoder_api() = default;
  virtual ring::decode_result push(std::uint8_t byte) = 0;
};

template <class Layout>
class decoder_of final : public decoder_api {
 public:
  explicit decoder_of(const ring::crc16_runtime& crc) : decoder_(crc) {}
  ring::decode_result push(std::uint8_t byte) override { return decoder_.push(byte); }

 private:
  ring::decoder<ring::default_max_characters, ring::crc16_runtime, Layout> decoder_;
};

constexpr std::size_t vr_table_size = 16384;  // every VR number the ring can address (14 bits)
constexpr std::size_t max_terminal_line = 4096;
constexpr std::size_t max_in_transit = 64;

// A message without its hop count, as the trace and the drop reports show it.
std::string describe(const ring::message& m) {
  switch (m.type) {
    case ring::message_type::character:
      return "PRINT \"" + escaped_text(m.text) + "\"";
    case ring::message_type::variable:
      return "VR(" + std::to_string(m.vr) + ") = " + basic::format_value(trionet::q32_to_double(m.value));
    case ring::message_type::keypad_offset:
      return "keypad offset " + std::to_string(m.offset) + " (keys go " + std::to_string(m.offset) +
             (m.offset == 1 ? " hop" : " hops") + " along)";
    case ring::message_type::keypad_mode:
      return "keypad mode " + std::to_string(m.mode);
  }
  return "?";
}

std::string netstat_bits(std::uint32_t bits) {
  static constexpr const char* names[] = {"TX timeout", "TX buffer error", "RX CRC error", "RX frame error",
                                          "RX overflow"};
  std::string out;
  for (std::size_t i = 0; i < 5; ++i) {
    if ((bits & (1u << i)) == 0) continue;
    if (!out.empty()) out += ", ";
    out += names[i];
  }
  return out;
}

const char* basic_spelling(basic::wait_reason reason) {
  switch (reason) {
    case basic::wait_reason::none:
      return "";
    case basic::wait_reason::print:
      return "PRINT #";
    case basic::wait_reason::send:
      return "SEND";
    case basic::wait_reason::get:
      return "GET #";
    case basic::wait_reason::wait_until:
      return "WAIT UNTIL";
    case basic::wait_reason::wa:
      return "WA";
    case basic::wait_reason::motion:
      return "the axes: a move, WAIT IDLE or WAIT LOADED";
  }
  return "";
}

basic::io_status io_status_of(ring::send_status r) {
  switch (r) {
    case ring::send_status::ok:
      return basic::io_status::ok;
    case ring::send_status::bad_address:
      return basic::io_status::bad_address;
    case ring::send_status::character_out_of_range:
    case ring::send_status::empty_text:
      return basic::io_status::character_out_of_range;
    case ring::send_status::vr_out_of_range:
      return basic::io_status::vr_out_of_range;
    case ring::send_status::value_out_of_range:
      return basic::io_status::value_out_of_range;
    case ring::send_status::offset_out_of_range:
      return basic::io_status::offset_out_of_range;
    case ring::send_status::mode_out_of_range:
      return basic::io_status::bad_type;
    case ring::send_status::queue_full:
      return basic::io_status::busy;
  }
  return basic::io_status::bad_type;
}

bool find_key(const std::string& name, ring::key& out) {
  return ring::key_named(name.data(), name.size(), out);
}

// The channels a program's PRINT # writes as lines of text: the terminal (#0), the serial ports (#1, #2) and
// Motion Perfect's channels (#5 to #7).
bool terminal_channel(int channel) {
  return channel == 0 || channel == 1 || channel == 2 || (channel >= 5 && channel <= 7);
}

// A BASIC program's controller: a Motion Coordinator of the library with its VR table, its machine (axes, I/O,
// TABLE, servo clock) and its terminal and serial channels.
class mc_adapter final : public basic::controller {
 public:
  mc_adapter(std::size_t vr_count, const network_config& config,
             std::function<void(int channel, const std::string&)> terminal_line)
      : vr_(&mc_adapter::network_write, this),
        node_(ring::with_variable_layout(config.layout,
                                         [&](auto layout) -> std::unique_ptr<mc_api> {
                                           return std::make_unique<mc_of<decltype(layout)>>(
                                               vr_, config.defkey, ring::crc16_runtime(config.crc));
                                         })),
        vr_count_(vr_count),
        machine_(machine_config_of(config)),
        terminal_line_(std::move(terminal_line)) {}
  mc_adapter(const mc_adapter&) = delete;
  mc_adapter& operator=(const mc_adapter&) = delete;

  byte_port& port() { return node_->port(); }
  std::uint8_t node_netstat() const { return node_->netstat(); }

  // Direct variable transfers applied since the last call: (vr, value).
  std::vector<std::pair<std::uint16_t, double>> take_network_writes() { return std::exchange(network_writes_, {}); }

  // Lines the program printed on its terminal and serial channels and did not end yet.
  void flush_terminal() {
    for (auto& [channel, line] : terminal_) {
      if (!line.empty()) terminal_line_(channel, std::exchange(line, {}));
    }
  }

  basic::print_result print(int channel, std::string_view text) override {
    if (terminal_channel(channel)) {
      std::string& line = terminal_[channel];
      for (char c : text) {
        if (c == '\n' || line.size() == max_terminal_line) {
          terminal_line_(channel, std::exchange(line, {}));
          if (c == '\n') continue;
        }
        if (c != '\r') line += c;
      }
      return {basic::io_status::ok, text.size()};
    }
    if (!ring::hops_from_basic_address(channel)) return {basic::io_status::bad_channel, 0};
    for (char c : text) {
      if (static_cast<unsigned char>(c) > 127) return {basic::io_status::character_out_of_range, 0};
    }
    // BASIC's PRINT# waits for room (docs/protocol.md 1.6, long PRINT#): the node's own split into messages,
    // each queued once there is room for it whole, so never a refused call, which would set NETSTAT bit 0.
    const std::size_t longest = std::min(mc_max_own_frame - ring::framing_length, ring::default_max_characters);
    std::size_t queued = 0;
    while (queued < text.size()) {
      const std::size_t n = std::min(text.size() - queued, longest);
      if (node_->transmit_free() < n + ring::framing_length) break;
      const auto r = node_->print(channel, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()) + queued, n));
      if (r.status != ring::send_status::ok) {
        if (queued == 0) return {io_status_of(r.status), 0};
        break;
      }
      queued += n;
    }
    return {basic::io_status::ok, queued};
  }

  basic::io_status send_variable(int address, int vr, double value) override {
    if (!ring::hops_from_basic_address(address)) return basic::io_status::bad_address;
    if (vr < 0 || vr > static_cast<int>(ring::max_vr)) return basic::io_status::vr_out_of_range;
    if (!trionet::q32_from_double(value)) return basic::io_status::value_out_of_range;
    if (node_->transmit_free() < ring::framing_length + ring::variable_data_length) return basic::io_status::busy;
    return io_status_of(node_->send_variable(address, static_cast<std::uint16_t>(vr), value));
  }

  basic::io_status send_keypad_offset(int address, int offset) override {
    if (!ring::hops_from_basic_address(address)) return basic::io_status::bad_address;
    if (!ring::hops_from_basic_address(offset)) return basic::io_status::offset_out_of_range;
    if (node_->transmit_free() < ring::framing_length + 1) return basic::io_status::busy;
    return io_status_of(node_->send_keypad_offset(address, offset));
  }

  basic::key_result key(int channel) override {
    if (channel != 3 && channel != 4) return {basic::io_status::bad_channel, false};
    return {basic::io_status::ok, node_->key(channel)};
  }

  basic::get_result get(int channel) override {
    const ring::get_result r = node_->get(channel);
    switch (r.status) {
      case ring::get_status::ok:
        return {basic::io_status::ok, r.value};
      case ring::get_status::nothing_yet:
        return {basic::io_status::busy, 0};
      case ring::get_status::bad_channel:
        break;
    }
    return {basic::io_status::bad_channel, 0};
  }

  std::uint32_t netstat() override { return node_->netstat(); }
  void clear_netstat() override { node_->clear_netstat(); }

  std::size_t vr_count() const override { return vr_count_; }
  double vr(std::size_t index) const override { return vr_[index]; }
  void set_vr(std::size_t index, double value) override { vr_[index] = value; }

  basic::machine& hardware() override { return machine_; }
  const basic::machine& hardware() const { return machine_; }

 private:
  // The VR table's write policy: a direct variable transfer to a VR this controller has is applied, and
  // reported; one past them is refused (counted by the node).
  static bool network_write(void* context, std::uint16_t vr, double value) noexcept {
    auto* self = static_cast<mc_adapter*>(context);
    if (vr >= self->vr_count_) return false;
    self->network_writes_.emplace_back(vr, value);
    return true;
  }

  vr_table<vr_table_size> vr_;
  std::unique_ptr<mc_api> node_;
  static basic::machine_config machine_config_of(const network_config& config) {
    basic::machine_config m;
    m.servo_period_us = config.servo_period_us;
    m.axes = config.axes;
    return m;
  }

  std::size_t vr_count_;
  basic::machine machine_;
  std::function<void(int, const std::string&)> terminal_line_;
  std::map<int, std::string> terminal_;
  std::vector<std::pair<std::uint16_t, double>> network_writes_;
};

struct script_step {
  std::size_t keypad;  // 1-based among keypads; 0: a wait or an input
  ring::key key;
  std::string name;
  std::uint64_t wait;
  std::size_t input_node = 0;  // 1-based ring position: an input word (nodeN:inM=on|off)
  std::size_t input = 0;
  bool on = false;
};

// A message on its way through a node: what it is, the hops it will carry on, and the node that sent it.
struct transit {
  std::string what;
  unsigned hops;
  std::size_t origin;
};

}  // namespace

struct ring_network::state {
  struct node_slot {
    node_spec::kind what = node_spec::kind::mc;
    std::string program_name;
    std::unique_ptr<mc_adapter> mc;
    std::unique_ptr<basic::program> program;
    std::unique_ptr<basic::task> task;
    std::uint32_t netstat_seen = 0;
    std::unique_ptr<keypad_api> keypad;
    std::size_t keypad_number = 0;
    std::uint32_t drops_seen = 0;
    std::uint32_t displays_seen = 0;
    std::uint32_t drops_pending = 0;
    std::deque<transit> in_transit;
    std::uint64_t errors_seen = 0;  // runtime errors ON BASICERROR took, reported
  };

  network_config config;
  std::vector<node_slot> nodes;
  std::size_t keypad_count = 0;
  ring::simulator<15> sim;
  std::vector<std::unique_ptr<decoder_api>> decoders;  // one per link, for the trace and the drop reports
  std::vector<script_step> script;
  std::size_t script_next = 0;
  std::uint64_t script_due = 0;
  event_sink events;
  std::function<void(std::uint64_t, std::size_t, std::uint8_t)> link_bytes;
  std::uint64_t bytes_this_step = 0;
  std::uint64_t clock = 0;  // the byte-time being simulated (events during a step carry it)
  bool settled = false;
  // The servo clock: each byte-time adds servo_step to servo_phase, and a servo tick passes each time it
  // reaches servo_whole (exact integers when the bit rate and the servo period are whole numbers).
  std::uint64_t servo_step = 0;
  std::uint64_t servo_whole = 1;
  double servo_step_real = 0;  // otherwise: ticks per byte-time
  std::uint64_t servo_phase = 0;
  double servo_phase_real = 0;

  void set_servo_clock() {
    const double step = static_cast<double>(config.bits_per_byte) * 1e6;
    const double whole = config.bit_rate * config.servo_period_us;
    if (whole == std::floor(whole) && whole < 1e18) {
      servo_step = static_cast<std::uint64_t>(step);
      servo_whole = static_cast<std::uint64_t>(whole);
    } else {
      servo_whole = 0;
      servo_step_real = step / whole;
    }
  }

  // The servo ticks that pass in the byte-time that ends now.
  std::uint64_t servo_ticks_due() {
    if (servo_whole == 0) {
      servo_phase_real += servo_step_real;
      const double ticks = std::floor(servo_phase_real);
      servo_phase_real -= ticks;
      return static_cast<std::uint64_t>(ticks);
    }
    servo_phase += servo_step;
    const std::uint64_t ticks = servo_phase / servo_whole;
    servo_phase %= servo_whole;
    return ticks;
  }

  void emit(event_kind kind, std::uint64_t time, std::size_t node, std::string text,
            std::vector<std::string> display = {}) {
    if (events) events(network_event{kind, time, node + 1, std::move(text), std::move(display)});
  }

  std::size_t after(std::size_t node, std::size_t hops) const { return (node + hops) % nodes.size(); }

  // What the controller's axes, outputs and watchdog did, as events: motion for the trace, the rest always.
  void emit_machine_events(std::size_t node) {
    for (basic::machine_event& e : nodes[node].mc->hardware().take_events()) {
      const bool axes = e.text.compare(0, 4, "axis") == 0 || e.text.compare(0, 4, "axes") == 0;
      emit(axes ? event_kind::motion : event_kind::io, clock, node, std::move(e.text));
    }
  }

  void set_input(std::size_t node, std::size_t input, bool on) {
    nodes[node].mc->hardware().set_input(input, on);
    emit(event_kind::io, clock, node, "input " + std::to_string(input) + (on ? " on" : " off"));
  }

  bool script_done() const { return script_next == script.size() && clock >= script_due; }

  std::string press(std::size_t keypad, ring::key k, const std::string& name) {
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      node_slot& n = nodes[i];
      if (n.keypad_number != keypad) continue;
      const ring::key_status r = n.keypad->press(k);
      (void)n.keypad->release(k);
      std::string text = "keypad " + std::to_string(keypad) + ": key " + name + " ";
      switch (r) {
        case ring::key_status::ok:
          text += "sent to node " + std::to_string(after(i, n.keypad->offset()) + 1);
          break;
        case ring::key_status::nothing_to_send:
          text += "not sent";
          break;
        case ring::key_status::local_mode:
          text += "lost: the keypad is in local mode (no keypad offset yet), it sends nothing";
          break;
        case ring::key_status::queue_full:
          text += "lost: the keypad's transmit queue is full";
          break;
      }
      emit(event_kind::key, clock, i, text);
      return text;
    }
    return {};
  }

  void on_link_byte(const ring::link_byte& b) {
    ++bytes_this_step;
    if (link_bytes) link_bytes(b.time, b.link, b.sent);
    if (!b.delivered) return;
    const std::size_t to = after(b.link, 1);
    node_slot& receiver = nodes[to];
    if (receiver.keypad) {
      const std::uint32_t drops =
          receiver.keypad->counters().dropped_in_local_mode + receiver.keypad->forwarding_counters().messages_dropped;
      receiver.drops_pending += drops - receiver.drops_seen;
      receiver.drops_seen = drops;
    }
    const ring::decode_result r = decoders[b.link]->push(b.received);
    if (r.status != ring::decode_status::incomplete) on_message(b, r);
    if (receiver.keypad && receiver.keypad->counters().display_messages != receiver.displays_seen) {
      receiver.displays_seen = receiver.keypad->counters().display_messages;
      const ring::keypad_display& d = receiver.keypad->display();
      emit(event_kind::display, b.time, to, "display", {d.line(0), d.line(1)});
    }
  }

  void on_message(const ring::link_byte& b, const ring::decode_result& r) {
    const std::size_t from = b.link;
    const std::size_t to = after(from, 1);
    const std::string route = std::to_string(from + 1) + " -> " + std::to_string(to + 1);
    node_slot& receiver = nodes[to];
    if (r.status != ring::decode_status::ok) {
      const std::string what = r.status == ring::decode_status::crc_error
                                   ? "CRC error (VR " + std::to_string(r.msg.vr) + ")"
                                   : std::string("frame error: ") + ring::to_string(r.error);
      emit(event_kind::frame_error, b.time, from, route + "  " + what);
      if (receiver.drops_pending > 0) {
        --receiver.drops_pending;
        emit(event_kind::dropped, b.time, to, "dropped a damaged message: the keypad is in local mode");
      }
      return;
    }
    const ring::message& m = r.msg;
    const std::string what = describe(m);
    // Which node sent it: the first matching message waiting to pass through the sending node, else that node.
    std::size_t origin = from;
    std::deque<transit>& passing = nodes[from].in_transit;
    const auto match = std::find_if(passing.begin(), passing.end(),
                                    [&](const transit& t) { return t.hops == m.hops && t.what == what; });
    if (match != passing.end()) {
      origin = match->origin;
      passing.erase(passing.begin(), match + 1);
    }
    std::string text = route + "  hops " + std::to_string(m.hops) + "  " + what;
    if (origin != from) text += "  (from node " + std::to_string(origin + 1) + ")";
    emit(event_kind::message, b.time, from, text);
    if (receiver.drops_pending > 0) {
      --receiver.drops_pending;
      std::string why = "dropped " + what + " from node " + std::to_string(origin + 1);
      if (m.hops == 1) {
        why += ", sent to this keypad";
      } else {
        why += ", passing through to node " + std::to_string(after(to, m.hops - 1u) + 1);
      }
      why += ": the keypad is in local mode (it has had no keypad offset yet), in which it takes only its keypad "
             "offset and forwards nothing (docs/protocol.md 1.7)";
      emit(event_kind::dropped, b.time, to, why);
      return;
    }
    if (m.hops > 1) {
      receiver.in_transit.push_back({what, m.hops - 1u, origin});
      if (receiver.in_transit.size() > max_in_transit) receiver.in_transit.pop_front();
    }
  }
};

ring_network::ring_network(std::unique_ptr<state> s) : s_(std::move(s)) {}
ring_network::~ring_network() = default;

std::unique_ptr<ring_network> ring_network::build(const std::vector<node_spec>& nodes, const network_config& config,
                                                  std::string& error) {
  if (nodes.size() < 2 || nodes.size() > 15) {
    error = "a ring has 2 to 15 nodes, not " + std::to_string(nodes.size());
    return nullptr;
  }
  if (std::none_of(nodes.begin(), nodes.end(), [](const node_spec& n) { return n.what == node_spec::kind::mc; })) {
    error = "a ring needs at least one Motion Coordinator";
    return nullptr;
  }
  if (config.vr_count == 0 || config.vr_count > vr_table_size) {
    error = "a Motion Coordinator has 1 to 16384 VRs";
    return nullptr;
  }
  if (!(config.bit_rate > 0) || config.bits_per_byte == 0 || config.statements_per_byte_time == 0) {
    error = "the bit rate, bits per byte and statements per byte-time must be above 0";
    return nullptr;
  }
  if (!(config.servo_period_us >= 1 && config.servo_period_us <= 1000000) || config.axes == 0 || config.axes > 64) {
    error = "the servo period must be 1 to 1000000 us, and a Motion Coordinator has 1 to 64 axes";
    return nullptr;
  }
  auto s = std::make_unique<state>();
  s->config = config;
  s->set_servo_clock();
  s->nodes.resize(nodes.size());
  basic::task_config task_config;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    state::node_slot& slot = s->nodes[i];
    state* owner = s.get();
    slot.what = nodes[i].what;
    if (nodes[i].what == node_spec::kind::keypad) {
      slot.keypad = ring::with_variable_layout(config.layout, [&](auto layout) -> std::unique_ptr<keypad_api> {
        return std::make_unique<keypad_of<decltype(layout)>>(
            ring::keypad_config{&s->config.keypad_codes, config.key_off_code, config.display},
            ring::crc16_runtime(config.crc));
      });
      slot.keypad_number = ++s->keypad_count;
      (void)s->sim.add(slot.keypad->port());
      continue;
    }
    slot.mc = std::make_unique<mc_adapter>(config.vr_count, s->config, [owner, i](int channel, const std::string& line) {
      const std::string shown = escaped_text(byte_view(reinterpret_cast<const std::uint8_t*>(line.data()), line.size()));
      owner->emit(event_kind::output, owner->clock, i,
                  (channel == 0 ? "prints: " : "prints on #" + std::to_string(channel) + ": ") + shown);
    });
    (void)s->sim.add(slot.mc->port());
    if (nodes[i].program_name.empty() && nodes[i].program_text.empty()) continue;
    basic::compile_result compiled = basic::compile(nodes[i].program_name, nodes[i].program_text);
    if (!compiled) {
      error = compiled.located_message();
      return nullptr;
    }
    slot.program_name = nodes[i].program_name;
    slot.program = std::make_unique<basic::program>(std::move(compiled.compiled));
    slot.task = std::make_unique<basic::task>(*slot.program, *slot.mc, task_config);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    s->decoders.push_back(ring::with_variable_layout(config.layout, [&](auto layout) -> std::unique_ptr<decoder_api> {
      return std::make_unique<decoder_of<decltype(layout)>>(ring::crc16_runtime(config.crc));
    }));
  }
  return std::unique_ptr<ring_network>(new ring_network(std::move(s)));
}

bool ring_network::set_keys(const std::string& script, std::string& error) {
  std::vector<script_step> steps;
  std::size_t i = 0;
  std::size_t word = 0;
  while (i < script.size()) {
    if (script[i] == ' ' || script[i] == '\t' || script[i] == '\n') {
      ++i;
      continue;
    }
    const std::size_t end = script.find_first_of(" \t\n", i);
    const std::string w = script.substr(i, end == std::string::npos ? std::string::npos : end - i);
    i = end == std::string::npos ? script.size() : end;
    ++word;
    const std::string where = "key script, word " + std::to_string(word) + " '" + printable(w) + "': ";
    const auto whole_number = [](const std::string& digits, std::uint64_t limit, std::uint64_t& out) {
      if (digits.empty() || digits.size() > 13 || digits.find_first_not_of("0123456789") != std::string::npos)
        return false;
      out = std::stoull(digits);
      return out <= limit;
    };
    if (w.compare(0, 5, "wait=") == 0) {
      std::uint64_t n = 0;
      if (!whole_number(w.substr(5), 1000000000000ull, n)) {
        error = where + "wait=N takes a whole number of byte-times 0..10^12";
        return false;
      }
      steps.push_back({0, ring::key::digit_0, "", n});
      continue;
    }
    if (w.compare(0, 4, "node") == 0) {  // nodeN:inM=on|off
      const std::size_t colon_at = w.find(':');
      const std::size_t equals = w.find('=');
      std::uint64_t node = 0;
      std::uint64_t input = 0;
      const std::string level = equals == std::string::npos ? "" : w.substr(equals + 1);
      if (colon_at == std::string::npos || equals == std::string::npos || equals < colon_at ||
          w.compare(colon_at + 1, 2, "in") != 0 || !whole_number(w.substr(4, colon_at - 4), 1000000000000ull, node) ||
          !whole_number(w.substr(colon_at + 3, equals - colon_at - 3), 1000, input) ||
          (level != "on" && level != "off")) {
        error = where + "expected nodeN:inM=on or nodeN:inM=off (e.g. node1:in7=on)";
        return false;
      }
      if (node < 1 || node > s_->nodes.size() || !s_->nodes[node - 1].mc) {
        error = where + "node " + std::to_string(node) + " is not a Motion Coordinator of this ring";
        return false;
      }
      if (input >= s_->nodes[node - 1].mc->hardware().io_count()) {
        error = where + "a Motion Coordinator has inputs 0 to " +
                std::to_string(s_->nodes[node - 1].mc->hardware().io_count() - 1);
        return false;
      }
      script_step step{0, ring::key::digit_0, "", 0};
      step.input_node = static_cast<std::size_t>(node);
      step.input = static_cast<std::size_t>(input);
      step.on = level == "on";
      steps.push_back(step);
      continue;
    }
    const std::size_t colon = w.find(':');
    std::uint64_t keypad = 0;
    if (colon == std::string::npos || !whole_number(w.substr(0, colon), 1000000000000ull, keypad)) {
      error = where + "expected KEYPAD:KEY (e.g. 1:up), nodeN:inM=on|off or wait=N";
      return false;
    }
    if (keypad < 1 || keypad > s_->keypad_count) {
      error = where + "there is no keypad " + std::to_string(keypad) + " (the ring has " +
              std::to_string(s_->keypad_count) + (s_->keypad_count == 1 ? " keypad)" : " keypads)");
      return false;
    }
    ring::key k = ring::key::digit_0;
    const std::string name = w.substr(colon + 1);
    if (!find_key(name, k)) {
      error = where + "no key '" + printable(name) + "' (keys: 0..9 up + down - clr y enter n . start stop)";
      return false;
    }
    steps.push_back({static_cast<std::size_t>(keypad), k, name, 0});
  }
  s_->script = std::move(steps);
  s_->script_next = 0;
  s_->script_due = s_->clock;
  return true;
}

void ring_network::on_event(std::function<void(const network_event&)> sink) {
  s_->events = std::move(sink);
}

void ring_network::on_link_byte(std::function<void(std::uint64_t, std::size_t, std::uint8_t)> sink) {
  s_->link_bytes = std::move(sink);
}

void ring_network::step() {
  state& s = *s_;
  s.clock = s.sim.now();
  bool active = false;
  while (s.script_next < s.script.size() && s.script_due <= s.clock) {
    const script_step& next = s.script[s.script_next++];
    if (next.input_node != 0) {
      s.set_input(next.input_node - 1, next.input, next.on);
      active = true;
    } else if (next.keypad == 0) {
      s.script_due = s.clock + next.wait;
    } else {
      s.press(next.keypad, next.key, next.name);
      s.script_due = s.clock + s.config.key_gap;
      active = true;
    }
  }
  // The servo ticks of the byte-time that ended: every controller's axes move, TICKS counts down.
  const std::uint64_t ticks = s.clock == 0 ? 0 : s.servo_ticks_due();
  for (std::size_t i = 0; i < s.nodes.size() && ticks != 0; ++i) {
    state::node_slot& n = s.nodes[i];
    if (!n.mc) continue;
    basic::machine& hw = n.mc->hardware();
    const bool moving = hw.any_motion();
    for (std::uint64_t k = 0; k < ticks; ++k) hw.servo_tick();
    if (moving) active = true;
    if (n.task && (moving || n.program->reads_clock)) n.task->world_changed();
    s.emit_machine_events(i);
  }
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    state::node_slot& n = s.nodes[i];
    if (!n.task) continue;
    const std::uint64_t effects = n.task->effects();
    n.task->run(s.config.statements_per_byte_time);
    if (n.task->effects() == effects) continue;
    active = true;
    s.emit_machine_events(i);
    if (n.task->handled_errors() != n.errors_seen) {
      n.errors_seen = n.task->handled_errors();
      s.emit(event_kind::error, s.clock, i,
             "runtime error: " + n.task->error() + " (ON BASICERROR GOTO: on at line " +
                 std::to_string(n.task->line()) + ")");
    }
    if (n.task->state() == basic::task_state::ended) {
      s.emit(event_kind::ended, s.clock, i, "program ended at line " + std::to_string(n.task->line()));
    } else if (n.task->state() == basic::task_state::failed) {
      s.emit(event_kind::failed, s.clock, i,
             "program stopped at line " + std::to_string(n.task->line()) + ": " + n.task->error());
    }
  }
  s.bytes_this_step = 0;
  s.sim.step([&s](const ring::link_byte& b) { s.on_link_byte(b); });
  if (s.bytes_this_step != 0) active = true;
  bool all_quiet = true;
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    state::node_slot& n = s.nodes[i];
    if (!n.mc) continue;
    for (const auto& [vr, value] : n.mc->take_network_writes()) {
      s.emit(event_kind::vr_from_ring, s.clock, i,
             "VR(" + std::to_string(vr) + ") is now " + basic::format_value(value) + " (from the ring)");
    }
    const std::uint32_t netstat = n.mc->node_netstat();
    if ((netstat & ~n.netstat_seen) != 0) {
      s.emit(event_kind::netstat, s.clock, i,
             "NETSTAT " + std::to_string(netstat) + " (" + netstat_bits(netstat & ~n.netstat_seen) + ")");
    }
    n.netstat_seen = netstat;
    if (n.mc->hardware().any_motion()) all_quiet = false;
    if (!n.task) continue;
    if (active) n.task->world_changed();
    switch (n.task->state()) {
      case basic::task_state::ended:
      case basic::task_state::failed:
        break;
      case basic::task_state::waiting:
        // Waiting for ever: for a character that nothing will send, or for a condition that nothing will
        // change (one that reads TICKS changes with time; one that reads the axes, while they move).
        all_quiet = all_quiet && (n.task->waiting_for() == basic::wait_reason::get ||
                                  (n.task->waiting_for() == basic::wait_reason::wait_until &&
                                   (n.task->waiting_reads() & basic::reads_clock) == 0));
        break;
      case basic::task_state::running:
        all_quiet = all_quiet && n.task->idle();
        break;
    }
  }
  s.settled = !active && all_quiet && s.script_done();
}

run_end ring_network::run(std::uint64_t max_byte_times, bool last_piece) {
  run_end end = run_end::limit;
  while (s_->sim.now() < max_byte_times) {
    step();
    if (s_->settled) {
      end = run_end::settled;
      break;
    }
  }
  s_->clock = s_->sim.now();
  if (!last_piece && end == run_end::limit) return end;
  for (auto& n : s_->nodes) {
    if (n.mc) n.mc->flush_terminal();
  }
  return end;
}

bool ring_network::settled() const {
  return s_->settled;
}

std::uint64_t ring_network::now() const {
  return s_->sim.now();
}

double ring_network::seconds() const {
  return ring::byte_times_to_seconds(s_->sim.now(), s_->config.bit_rate, s_->config.bits_per_byte);
}

std::size_t ring_network::size() const {
  return s_->nodes.size();
}

std::size_t ring_network::keypads() const {
  return s_->keypad_count;
}

node_report ring_network::report(std::size_t node) const {
  node_report r;
  if (node < 1 || node > s_->nodes.size()) return r;
  const state::node_slot& n = s_->nodes[node - 1];
  r.what = n.what;
  if (n.keypad) {
    const keypad_api& k = *n.keypad;
    r.keypad_number = n.keypad_number;
    r.network_mode = k.network_mode();
    r.offset = k.offset();
    r.display = {k.display().line(0), k.display().line(1)};
    r.cursor_visible = k.display().cursor_visible();
    r.dropped = k.counters().dropped_in_local_mode + k.forwarding_counters().messages_dropped;
    r.keys_sent = k.counters().keys_sent;
    r.keys_lost = k.counters().keys_lost;
    return r;
  }
  const mc_adapter& mc = *n.mc;
  r.netstat = mc.node_netstat();
  for (std::size_t i = 0; i < mc.vr_count(); ++i) {
    if (mc.vr(i) != 0) r.vrs.emplace_back(i, mc.vr(i));
  }
  const basic::machine& hw = mc.hardware();
  for (std::size_t axis = 0; axis < hw.axis_count(); ++axis) {
    if (!hw.used(axis)) continue;
    axis_report a;
    a.axis = axis;
    a.dpos = hw.axis_value(axis, basic::axis_parameter::dpos);
    a.mpos = hw.axis_value(axis, basic::axis_parameter::mpos);
    a.speed = hw.axis_value(axis, basic::axis_parameter::vp_speed);
    a.mtype = static_cast<unsigned>(hw.axis_value(axis, basic::axis_parameter::mtype));
    a.idle = hw.idle(axis);
    for (std::size_t p = 0; p < basic::axis_parameter_count; ++p) {
      const auto parameter = static_cast<basic::axis_parameter>(p);
      const basic::axis_parameter_info& info = basic::info(parameter);
      const double value = hw.axis_value(axis, parameter);
      if (!info.read_only && value != info.default_value) a.parameters.emplace_back(info.name, value);
    }
    r.axes.push_back(std::move(a));
  }
  for (std::size_t io = 0; io < hw.io_count(); ++io) {
    if (hw.output(io)) r.outputs_on.push_back(io);
    if (hw.input_signal(io)) r.inputs_on.push_back(io);
  }
  r.wdog = hw.wdog();
  for (std::size_t i = 0; i < hw.table_size(); ++i) {
    if (hw.table(i) == 0) continue;
    ++r.table_nonzero;
    if (r.table.size() < 64) r.table.emplace_back(i, hw.table(i));
  }
  if (!n.task) {
    r.state = "none";
    return r;
  }
  const basic::task& t = *n.task;
  r.program = n.program_name;
  r.state = basic::to_string(t.state());
  r.waiting = basic_spelling(t.waiting_for());
  r.idle = t.state() == basic::task_state::running && t.idle();
  r.line = t.line();
  r.error = t.error();
  r.statements = t.statements();
  for (std::size_t i = 0; i < t.variable_count(); ++i) r.variables.emplace_back(t.variable_name(i), t.variable(i));
  return r;
}

bool ring_network::press(std::size_t keypad, const std::string& key_name, std::string& error) {
  ring::key k = ring::key::digit_0;
  if (keypad < 1 || keypad > s_->keypad_count) {
    error = "there is no keypad " + std::to_string(keypad);
    return false;
  }
  if (!find_key(key_name, k)) {
    error = "no key '" + key_name + "'";
    return false;
  }
  s_->clock = s_->sim.now();
  s_->press(keypad, k, key_name);
  return true;
}

}  // namespace trionet::host
