// `trionet can monitor|send|node IFACE ...`: the TN20-17 VR exchange on a live CAN bus, over a SocketCAN raw
// socket (can0, vcan0 ...) or, with IFACE `-`, over candump text on standard input and output, so that
// `candump -L can0 | trionet can monitor -` and `trionet can send - ... | canplayer` work without SocketCAN.
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "can_cli.hpp"
#include "cli.hpp"
#include "live.hpp"
#include "trionet/can.hpp"
#include "trionet/host/candump.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/socketcan.hpp"

namespace trionet::cli {

const char* const can_live_usage =
    "usage:\n"
    "  trionet can monitor IFACE [--nodes K] [--json] [--pcap FILE]\n"
    "      decode every frame on the bus, one event per line as it arrives; counters at the end, on Ctrl-C\n"
    "      and on SIGUSR1\n"
    "  trionet can send IFACE --from I --to J --vr V --value X [--nodes K] [--interface-name NAME]\n"
    "      put one VR frame on the bus and print it\n"
    "  trionet can node IFACE --node I [--nodes K] [--json] [--trace] [--pcap FILE] [--interface-name NAME]\n"
    "      be node I of the exchange: write the VRs it receives (events), and send the ones asked on\n"
    "      standard input: send J VR VALUE | vr V [VALUE] | counters | quit (it ends at quit or when\n"
    "      standard input ends)\n"
    "IFACE: a SocketCAN interface (can0, vcan0), or - for candump text: frames are read from standard input\n"
    "(`candump -L` lines or compact ID#DATA) and written to standard output as log lines\n"
    "\"(secs.micros) NAME ID#DATA\" (NAME from --interface-name, default can0, for canplayer); with `can node -`\n"
    "standard input carries both frames and commands, and the events go to standard error.\n"
    "K is the number of controllers, 2..11 (default 5). IFACE and NAME are interface names as Linux has them:\n"
    "1..15 bytes, no whitespace, control character, '/' or ':' (else exit status 2).\n";

namespace {

const option_list& interface_option() {
  static const option_list options = {
      {"IFACE", nullptr, "@interface", "a SocketCAN interface (can0, vcan0), or - for candump text"}};
  return options;
}

// Functions, not globals: the command table in can_cli.cpp uses these tables while it is initialised.
const option_list& pcap_option() {
  static const option_list options = {{"--pcap", "FILE", "@file", "also write every frame to a pcapng capture"}};
  return options;
}

const option_list& json_option() {
  static const option_list options = {{"--json", nullptr, "", "events as JSON lines"}};
  return options;
}

const option_list& interface_name_option() {
  static const option_list options = {
      {"--interface-name", "NAME", "", "with -: the interface name written in the log lines (default can0)"}};
  return options;
}

// What is wrong with `name` as a network interface name, empty when nothing: Linux's rule (dev_valid_name:
// 1..15 bytes, IFNAMSIZ 16 with its NUL; not . or ..; no '/', ':' or whitespace), and no control character,
// so that a candump log line "(SECS.MICROS) NAME ID#DATA" holds it as one word that reads back.
std::string interface_name_error(const std::string& name, const char* what) {
  const std::string named = std::string(what) + " '" + host::printable(name) + "'";
  if (name.empty()) return std::string(what) + " is empty: an interface name has 1..15 bytes";
  if (name.size() > 15) {
    return named + " has " + std::to_string(name.size()) +
           " bytes: a Linux interface name has at most 15 (IFNAMSIZ 16 with its NUL)";
  }
  if (name == "." || name == "..") return named + " is not an interface name (Linux refuses . and ..)";
  for (const char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte <= 0x20 || byte == 0x7F || c == '/' || c == ':') {
      return named + " holds " + (c == ' ' ? std::string("a space") : c == '/' || c == ':' ? std::string("'") + c + "'"
                                                                                               : "a control character") +
             ": an interface name has no whitespace, control character, '/' or ':' (Linux's rule; a candump line "
             "holds it as one word)";
    }
  }
  return "";
}

// The first wrong name among the command's IFACE (unless it is -, candump text) and its --interface-name, or "".
std::string interface_names_error(const arguments& args) {
  if (args.positionals[0] != "-") {
    std::string wrong = interface_name_error(args.positionals[0], "IFACE");
    if (!wrong.empty()) return wrong;
  }
  if (args.has("--interface-name")) return interface_name_error(args.options.at("--interface-name"), "--interface-name");
  return "";
}

// Where frames come from and go to: a SocketCAN socket, or candump text on standard input and output.
class bus {
 public:
  bool open(const std::string& iface, const std::string& name_for_text, std::string& error) {
    iface_ = iface;
    text_name_ = name_for_text;
    if (iface == "-") return true;
    const host::socketcan_open_result opened = socket_.open(iface);
    if (opened) return true;
    error = "cannot open CAN interface " + host::printable(iface) + ": " + host::to_string(opened.status);
    if (opened.system_error != 0) error += std::string(" (") + std::strerror(opened.system_error) + ")";
    if (opened.status == host::socketcan_status::socket)
      error += "; this kernel has no SocketCAN support: use - and candump text instead";
    return false;
  }
  [[nodiscard]] bool text() const noexcept { return iface_ == "-"; }
  [[nodiscard]] const std::string& name() const noexcept { return iface_; }
  /// The descriptor frames arrive on: the socket, or standard input for candump text.
  [[nodiscard]] int fd() const noexcept { return text() ? STDIN_FILENO : socket_.fd(); }
  host::socketcan_port& socket() noexcept { return socket_; }

  // Sends one frame: the socket (retrying a full queue for up to a second), or a candump log line.
  can::transmit_status send(const can::frame& frame, std::uint64_t time_ns) {
    if (text()) {
      host::candump_record record;
      record.has_timestamp = true;
      record.seconds = time_ns / 1000000000U;
      record.nanoseconds = static_cast<std::uint32_t>(time_ns % 1000000000U / 1000U * 1000U);
      record.fraction_digits = 6;
      record.interface_name = text_name_;
      record.frame = frame;
      return write_stdout(host::format_candump_line(record) + "\n") ? can::transmit_status::ok
                                                                    : can::transmit_status::failed;
    }
    can::transmit_status status = can::transmit_status::busy;
    for (int tries = 0; tries < 100 && (status = socket_.send(frame)) == can::transmit_status::busy; ++tries) {
      ::usleep(10000);
    }
    return status;
  }

 private:
  std::string iface_;
  std::string text_name_;
  host::socketcan_port socket_;
};

// Bus counters for the end, a signal, or `counters`: every frame read, by what it is.
struct bus_counters {
  std::uint64_t frames = 0;        // every frame read, error frames included
  std::uint64_t vr_frames = 0;     // TN20-17 VR messages
  std::uint64_t vr_errors = 0;     // frames on an exchange identifier that are no VR message (bad_dlc ...)
  std::uint64_t other = 0;         // valid frames that are not the exchange's (foreign, extended, remote, FD ...)
  std::uint64_t error_frames = 0;  // error frames (controller reports), from SocketCAN or candump text
  std::uint64_t syntax = 0;        // candump lines that are not frames

  void count(can_frame_class kind) {
    ++frames;
    switch (kind) {
      case can_frame_class::vr:
        ++vr_frames;
        break;
      case can_frame_class::vr_error:
        ++vr_errors;
        break;
      case can_frame_class::other:
        ++other;
        break;
      case can_frame_class::error_frame:
        ++error_frames;
        break;
    }
  }
  void add(event& e) const {
    e.number("frames", frames).number("vr", vr_frames).number("vr_errors", vr_errors).number("other", other);
    e.number("error_frames", error_frames).number("syntax", syntax);
  }
};

// One input line of candump text as a record, with its time (the line's own, else now).
host::candump_status record_of_line(const std::string& line, host::candump_record& record, std::uint64_t& time_ns) {
  const host::candump_status status = host::parse_candump_line(line, record);
  if (status != host::candump_status::ok) return status;
  time_ns = record.has_timestamp ? record.seconds * 1000000000U + record.nanoseconds : live::now_ns();
  return host::candump_status::ok;
}

// A frame into the capture: classic, error and CAN FD frames as SocketCAN records (a CAN XL frame has no
// record here and is left out).
void capture_frame(live::capture_file& capture, std::uint32_t interface, std::uint64_t time_ns,
                   const host::candump_record& r) {
  if (!capture.is_open()) return;
  const std::vector<std::uint8_t> record = host::socketcan_record_of(r);
  if (!record.empty()) capture.write(interface, time_ns, byte_view(record.data(), record.size()));
}

// A line of candump text that is not a frame: the event `can decode` prints for it, with its time.
void syntax_event(std::string& out, std::uint64_t line_number, host::candump_status status) {
  event(out, "error").time(live::now_ns()).number("line", line_number).text("reason", "syntax").text(
      "detail", host::to_string(status));
}

// Frames from the bus as records: candump lines from standard input (`-`) or SocketCAN frames, read after
// the event loop found the bus readable. `frame(record, time_ns, line)` gets each frame (`line` 0 for
// SocketCAN), `other_line(text, line, status)` each line of candump text that is not a frame and why (with
// `can node -` those are the commands). Ends the loop when the input ends (`-`: a normal end) or the socket
// fails (the link is lost).
class bus_reader {
 public:
  explicit bus_reader(bus& b) : bus_(&b) {}

  template <class Frame, class OtherLine>
  void read(live::event_loop& loop, Frame&& frame, OtherLine&& other_line) {
    if (bus_->text()) {
      input_.read_some();
      std::string line;
      while (loop.running() && input_.next(line)) {
        ++line_number_;
        const host::candump_status status = record_of_line(line, record_, time_ns_);
        if (status == host::candump_status::ok) {
          frame(record_, time_ns_, line_number_);
        } else {
          other_line(line, line_number_, status);
        }
      }
      if (input_.ended()) loop.stop();
      return;
    }
    can::frame got;
    const host::socketcan_receive_status status = bus_->socket().receive(got, 0);
    if (status == host::socketcan_receive_status::ok) {
      frame(candump_record_of(got), live::now_ns(), 0);
    } else if (status == host::socketcan_receive_status::error_frame) {
      frame(candump_record_of(got, true), live::now_ns(), 0);
    } else if (status == host::socketcan_receive_status::failed && errno != EINTR && errno != EAGAIN) {
      loop.lost(host::printable(bus_->name()) + ": " + std::strerror(errno));
    }
  }

 private:
  bus* bus_;
  live::line_reader input_{STDIN_FILENO};
  std::uint64_t line_number_ = 0;
  host::candump_record record_;
  std::uint64_t time_ns_ = 0;
};

// ---- can monitor ----

int monitor_main(const words& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, can_monitor_options(), args, error)) return fail("can monitor: " + error);
  if (args.positionals.size() != 1) return fail("can monitor takes one IFACE (or - for candump text)");
  std::uint8_t nodes = 0;
  if (!parse_node_count(args, nodes, error)) return fail("can monitor: " + error);
  bus can_bus;
  if (const std::string wrong = interface_names_error(args); !wrong.empty()) return fail("can monitor: " + wrong);
  if (!can_bus.open(args.positionals[0], "can0", error)) return fail_io("can monitor: " + error);
  live::capture_file capture;
  std::uint32_t interface = 0;
  if (args.has("--pcap")) {
    if (!capture.open(args.options.at("--pcap"), error)) return fail_io("can monitor: " + error);
    interface = capture.add(can_bus.text() ? "candump" : can_bus.name(), host::capture_network::can);
  }
  live::event_log log(args.flag("--json"));
  live::event_loop loop(&log);
  const std::size_t input = loop.watch(can_bus.fd(), POLLIN);
  bus_counters counters;
  const auto counters_event = [&]() {
    event e(log.text(), "counters");
    e.time(live::now_ns());
    counters.add(e);
  };
  bus_reader reader(can_bus);
  while (loop.running()) {
    if (live::event_loop::report_requested()) counters_event();
    if (!loop.wait(1000)) break;
    if (!loop.readable(input)) continue;
    reader.read(
        loop,
        [&](const host::candump_record& record, std::uint64_t time_ns, std::uint64_t line) {
          capture_frame(capture, interface, time_ns, record);
          counters.count(append_can_frame_event(log.text(), nodes, record, [&](event& e) {
            e.time(time_ns);
            if (line != 0) e.number("line", line);
          }));
        },
        [&](const std::string&, std::uint64_t number, host::candump_status status) {
          if (status == host::candump_status::empty) return;
          ++counters.syntax;
          syntax_event(log.text(), number, status);
        });
  }
  counters_event();
  const int status = loop.finish("can monitor");
  if (status == exit_ok && !capture.good()) return fail_io("can monitor: writing the capture failed: " + capture.cause());
  return status;
}

// ---- can send ----

int send_main(const words& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, can_send_options(), args, error)) return fail("can send: " + error);
  if (args.positionals.size() != 1) return fail("can send takes one IFACE (or - for candump text)");
  can::frame frame;
  if (!can_message_frame(args, frame, error)) return fail("can send: " + error);
  const std::string name = args.has("--interface-name") ? args.options.at("--interface-name") : "can0";
  bus can_bus;
  if (const std::string wrong = interface_names_error(args); !wrong.empty()) return fail("can send: " + wrong);
  if (!can_bus.open(args.positionals[0], name, error)) return fail_io("can send: " + error);
  const can::transmit_status sent = can_bus.send(frame, live::now_ns());
  if (can_bus.text() && output_failed()) return fail_output();
  if (sent != can::transmit_status::ok)
    return fail_io("can send: " + host::printable(can_bus.name()) + " did not take the frame: " + can::to_string(sent));
  if (!can_bus.text() && !write_stdout(host::format_candump_frame(frame) + "\n")) return fail_output();
  return exit_ok;
}

// ---- can node ----

// The node's VR(): the 256 VRs a CAN message can name.
using node_vrs = vr_table<can::max_message_vr + 1>;

// The node's port: the bus, with every frame sent also captured (and shown with --trace).
class node_port final : public can::port {
 public:
  node_port(bus& b, live::capture_file& capture, std::uint32_t interface) : bus_(&b), capture_(&capture), interface_(interface) {}
  can::transmit_status send(const can::frame& outgoing) noexcept override {
    const std::uint64_t t = live::now_ns();
    const can::transmit_status status = bus_->send(outgoing, t);
    if (status == can::transmit_status::ok) capture_frame(*capture_, interface_, t, candump_record_of(outgoing));
    return status;
  }

 private:
  bus* bus_;
  live::capture_file* capture_;
  std::uint32_t interface_;
};

int node_main(const words& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, can_node_options(), args, error)) return fail("can node: " + error);
  if (args.positionals.size() != 1) return fail("can node takes one IFACE (or - for candump text)");
  std::uint8_t nodes = 0;
  if (!parse_node_count(args, nodes, error)) return fail("can node: " + error);
  long long own = 0;
  if (!args.has("--node") || !parse_integer(args.options.at("--node"), 1, nodes, own))
    return fail("can node needs --node I, a node 1.." + std::to_string(nodes));
  const bool trace = args.flag("--trace");
  const std::string name = args.has("--interface-name") ? args.options.at("--interface-name") : "can0";
  bus can_bus;
  if (const std::string wrong = interface_names_error(args); !wrong.empty()) return fail("can node: " + wrong);
  if (!can_bus.open(args.positionals[0], name, error)) return fail_io("can node: " + error);
  live::capture_file capture;
  std::uint32_t interface = 0;
  if (args.has("--pcap")) {
    if (!capture.open(args.options.at("--pcap"), error)) return fail_io("can node: " + error);
    interface = capture.add(can_bus.text() ? "candump" : can_bus.name(), host::capture_network::can);
  }
  auto vrs = std::make_unique<node_vrs>();
  node_port port(can_bus, capture, interface);
  can::vr_exchange_node node(can::make_node_address(nodes, static_cast<std::uint8_t>(own)).address, port, *vrs,
                             active_profile().can.byte_order);
  // With candump text, standard output carries the frames: the events go to standard error.
  live::event_log log(args.flag("--json"), can_bus.text() ? STDERR_FILENO : STDOUT_FILENO);
  live::event_loop loop(&log);
  bus_counters counters;

  // A frame from the bus: what the node makes of it, and with --trace also a frame for another node.
  std::string seen;
  const auto received = [&](const host::candump_record& record, std::uint64_t time_ns, std::uint64_t) {
    capture_frame(capture, interface, time_ns, record);
    seen.clear();
    counters.count(append_can_frame_event(seen, nodes, record, [time_ns](event& e) { e.time(time_ns); }));
    const can::receive_result r = record.classic_frame() ? node.receive(record.frame) : can::receive_result{};
    if (r.status == can::receive_status::foreign) {
      if (trace) log.text() += seen;
      return;
    }
    const bool written = r.status == can::receive_status::ok || r.status == can::receive_status::refused ||
                         r.status == can::receive_status::out_of_range ||
                         r.status == can::receive_status::value_out_of_range;
    event e(log.text(), written ? "vr_write" : "error");
    e.time(time_ns).number("from", r.sender);
    if (written) {
      e.number("vr", r.message.vr).real("value", trionet::to_double(r.message.value));
    } else {
      e.text("frame", host::format_candump_frame(record.frame));
    }
    e.text("status", can::to_string(r.status));
  };
  const auto node_counters = [&]() {
    event e(log.text(), "counters");
    e.time(live::now_ns());
    counters.add(e);
    const can::node_counters& c = node.counters();
    e.number("sent", c.sent).number("send_busy", c.send_busy).number("send_failed", c.send_failed);
    e.number("written", c.written).number("refused", c.refused).number("out_of_range", c.out_of_range);
    e.number("foreign", c.foreign).number("bad_dlc", c.bad_dlc).number("bad_sign", c.bad_sign);
    e.number("bad_fraction", c.bad_fraction);
  };
  const auto reply_error = [&](const std::string& command, const std::string& reason) {
    event(log.text(), "error").time(live::now_ns()).text("command", command).text("reason", reason);
  };
  const auto run = [&](const std::string& line) {
    const std::vector<std::string> w = live::words_of(line);
    if (w.empty() || w[0][0] == '#') return;
    long long a = 0;
    long long b = 0;
    double value = 0;
    if (w[0] == "send") {
      if (w.size() != 4 || !parse_integer(w[1], 1, nodes, a) || !parse_integer(w[2], 0, can::max_message_vr, b) ||
          !parse_real(w[3], value))
        return reply_error(w[0], "usage: send J VR VALUE (J a node 1.." + std::to_string(nodes) + ", VR 0..255)");
      const can::send_status s = node.send_to_node(static_cast<std::uint8_t>(a), static_cast<std::uint16_t>(b), value);
      if (can_bus.text() && output_failed()) return;  // the loop ends: the output is gone
      if (s != can::send_status::ok) return reply_error(w[0], can::to_string(s));
      event(log.text(), "sent").time(live::now_ns()).signed_number("to", a).signed_number("vr", b).real("value", value);
      return;
    }
    if (w[0] == "vr") {
      if ((w.size() != 2 && w.size() != 3) || !parse_integer(w[1], 0, can::max_message_vr, a))
        return reply_error(w[0], "usage: vr V [VALUE] (V 0..255)");
      if (w.size() == 3) {
        if (!parse_real(w[2], value)) return reply_error(w[0], "VALUE must be a real number");
        (*vrs)[static_cast<std::size_t>(a)] = value;
      }
      event(log.text(), "vr").time(live::now_ns()).signed_number("vr", a).real("value", (*vrs)[static_cast<std::size_t>(a)]);
      return;
    }
    if (w[0] == "counters") return node_counters();
    if (w[0] == "quit") return loop.stop();
    reply_error(w[0], "unknown command (send, vr, counters, quit)");
  };

  // Commands come on standard input; with candump text, so do the frames (bus_reader tells them apart).
  // The node ends at `quit` or when its commands end.
  bus_reader frames(can_bus);
  const auto command_line = [&](const std::string& line, std::uint64_t, host::candump_status) { run(line); };
  live::line_reader commands(STDIN_FILENO);
  const std::size_t bus_slot = loop.watch(can_bus.fd(), POLLIN);
  const std::size_t input_slot = loop.watch(can_bus.text() ? -1 : STDIN_FILENO, POLLIN);
  while (loop.running()) {
    if (live::event_loop::report_requested()) node_counters();
    if (!loop.wait(1000)) break;
    if (loop.readable(bus_slot)) frames.read(loop, received, command_line);
    if (loop.running() && loop.readable(input_slot)) {
      commands.read_some();
      std::string line;
      while (loop.running() && commands.next(line)) run(line);
      if (commands.ended()) loop.stop();
    }
  }
  node_counters();
  const int status = loop.finish("can node");
  if (status == exit_ok && !capture.good()) return fail_io("can node: writing the capture failed: " + capture.cause());
  return status;
}

}  // namespace

const option_list& can_monitor_options() {
  static const option_list options = joined(joined(joined(interface_option(), node_count_option()), json_option()),
                                             pcap_option());
  return options;
}

const option_list& can_send_options() {
  static const option_list options = joined(joined(interface_option(), can_message_options()), interface_name_option());
  return options;
}

const option_list& can_node_options() {
  static const option_list options = joined(
      joined(joined(joined(interface_option(),
                           {{"--node", "I", "1 2 3 4 5 6 7 8 9 10 11", "the node to be, 1..K"}}),
                    node_count_option()),
             joined(json_option(), {{"--trace", nullptr, "", "also every frame the node sends and every frame between other nodes"}})),
      joined(pcap_option(), interface_name_option()));
  return options;
}

int can_monitor_main(const words& args) {
  return monitor_main(args);
}
int can_send_main(const words& args) {
  return send_main(args);
}
int can_node_main(const words& args) {
  return node_main(args);
}

}  // namespace trionet::cli
