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
    "      standard input: send J VR VALUE | vr V [VALUE] | counters | quit\n"
    "IFACE: a SocketCAN interface (can0, vcan0), or - for candump text: frames are read from standard input\n"
    "(`candump -L` lines or compact ID#DATA) and written to standard output as log lines\n"
    "\"(secs.micros) NAME ID#DATA\" (NAME from --interface-name, default can0, for canplayer); with `can node -`\n"
    "standard input carries both frames and commands, and the events go to standard error.\n"
    "K is the number of controllers, 2..11 (default 5).\n";

namespace {

const std::set<std::string> common_values = {"--nodes", "--pcap", "--interface-name"};

bool node_count_of(const arguments& args, std::uint8_t& out, std::string& error) {
  out = can::default_node_count;
  if (!args.has("--nodes")) return true;
  long long value = 0;
  if (!parse_integer(args.options.at("--nodes"), can::min_node_count, can::max_node_count, value)) {
    error = "--nodes must be an integer from 2 to 11, got '" + args.options.at("--nodes") + "'";
    return false;
  }
  out = static_cast<std::uint8_t>(value);
  return true;
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
    error = "cannot open CAN interface " + iface + ": " + host::to_string(opened.status);
    if (opened.system_error != 0) error += std::string(" (") + std::strerror(opened.system_error) + ")";
    if (opened.status == host::socketcan_status::socket)
      error += "; this kernel has no SocketCAN support: use - and candump text instead";
    return false;
  }
  [[nodiscard]] bool text() const noexcept { return iface_ == "-"; }
  [[nodiscard]] const std::string& name() const noexcept { return iface_; }
  host::socketcan_port& socket() noexcept { return socket_; }

  // Sends one frame: the socket (retrying a full queue for up to a second), or a candump log line.
  can::transmit_status send(const can::frame& frame, std::uint64_t time_ns) {
    if (text()) {
      host::candump_record record;
      record.has_timestamp = true;
      record.seconds = time_ns / 1000000000u;
      record.nanoseconds = static_cast<std::uint32_t>(time_ns % 1000000000u / 1000u * 1000u);
      record.fraction_digits = 6;
      record.interface_name = text_name_;
      record.frame = frame;
      const std::string line = host::format_candump_line(record) + "\n";
      std::fwrite(line.data(), 1, line.size(), stdout);
      return std::fflush(stdout) == 0 ? can::transmit_status::ok : can::transmit_status::failed;
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

// Bus counters for the end, a signal, or `counters`.
struct bus_counters {
  std::uint64_t frames = 0;
  std::uint64_t vr_frames = 0;
  std::uint64_t errors = 0;
  std::uint64_t error_frames = 0;  // SocketCAN error frames (controller reports)
  std::uint64_t syntax = 0;        // candump lines that are not frames

  void count(const live::event& e) {
    ++frames;
    if (e.name == "vr") {
      ++vr_frames;
    } else {
      ++errors;
    }
  }
  live::event as_event(const std::string& name = "counters") const {
    live::event e(live::now_ns(), name);
    e.number("frames", static_cast<unsigned long long>(frames)).number("vr", static_cast<unsigned long long>(vr_frames));
    e.number("errors", static_cast<unsigned long long>(errors));
    e.number("error_frames", static_cast<unsigned long long>(error_frames));
    e.number("syntax", static_cast<unsigned long long>(syntax));
    return e;
  }
};

// One input line of candump text: the frame and its time (the line's own, else now); false if not a frame.
bool frame_of_line(const std::string& line, can::frame& frame, std::uint64_t& time_ns) {
  const host::candump_result parsed = host::parse_candump_line(line);
  if (!parsed) return false;
  frame = parsed.record.frame;
  time_ns = parsed.record.has_timestamp
                ? parsed.record.seconds * 1000000000u + parsed.record.nanoseconds
                : live::now_ns();
  return true;
}

void capture_frame(live::capture_file& capture, std::uint32_t interface, std::uint64_t time_ns, const can::frame& frame) {
  if (!capture.is_open()) return;
  const auto record = host::socketcan_record(frame);
  capture.write(interface, time_ns, byte_view(record.data(), record.size()));
}

// ---- can monitor ----

int monitor_main(const std::vector<std::string>& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, common_values, {"--json"}, args, error)) return fail("can monitor: " + error);
  if (args.positionals.size() != 1) return fail("can monitor takes one IFACE (or - for candump text)");
  std::uint8_t nodes = 0;
  if (!node_count_of(args, nodes, error)) return fail("can monitor: " + error);
  const bool json = args.flags.count("--json") != 0;
  bus can_bus;
  if (!can_bus.open(args.positionals[0], "can0", error)) return fail("can monitor: " + error);
  live::capture_file capture;
  std::uint32_t interface = 0;
  if (args.has("--pcap")) {
    if (!capture.open(args.options.at("--pcap"), error)) return fail("can monitor: " + error);
    interface = capture.add(can_bus.text() ? "candump" : can_bus.name(), host::capture_network::can);
  }
  live::signal_watch signals;
  bus_counters counters;
  live::line_reader input(STDIN_FILENO);
  std::size_t line_number = 0;
  const auto seen = [&](const can::frame& frame, std::uint64_t time_ns) {
    capture_frame(capture, interface, time_ns, frame);
    const live::event e = live::can_event(time_ns, frame, nodes);
    counters.count(e);
    live::emit(e, json);
  };
  std::string ended;
  while (!live::signal_watch::stop_requested()) {
    if (live::signal_watch::take_report_request()) live::emit(counters.as_event(), json);
    if (can_bus.text()) {
      pollfd p{STDIN_FILENO, POLLIN, 0};
      if (::poll(&p, 1, 1000) <= 0) continue;
      const bool more = input.read_some();
      std::string line;
      while (input.next(line)) {
        ++line_number;
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        can::frame frame;
        std::uint64_t time_ns = 0;
        if (frame_of_line(line, frame, time_ns)) {
          seen(frame, time_ns);
        } else {
          ++counters.syntax;
          live::emit(live::event(live::now_ns(), "error").text("reason", "syntax").number(
                         "line", static_cast<unsigned long long>(line_number)),
                     json);
        }
      }
      if (!more) break;
      continue;
    }
    can::frame frame;
    const host::socketcan_receive_status got = can_bus.socket().receive(frame, 1000);
    if (got == host::socketcan_receive_status::ok) {
      seen(frame, live::now_ns());
    } else if (got == host::socketcan_receive_status::error_frame) {
      ++counters.error_frames;
      live::emit(live::event(live::now_ns(), "error_frame").text("frame", host::format_candump_frame(frame)), json);
    } else if (got == host::socketcan_receive_status::failed && !live::signal_watch::stop_requested() &&
               errno != EINTR) {
      ended = can_bus.name() + ": " + std::strerror(errno);
      break;
    }
  }
  live::emit(counters.as_event(), json);
  if (!ended.empty()) std::fprintf(stderr, "trionet: can monitor: %s\n", ended.c_str());
  if (!capture.good()) return fail("can monitor: writing the capture failed");
  return exit_ok;
}

// ---- can send ----

int send_main(const std::vector<std::string>& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, {"--nodes", "--from", "--to", "--vr", "--value", "--interface-name"}, {}, args, error))
    return fail("can send: " + error);
  if (args.positionals.size() != 1) return fail("can send takes one IFACE (or - for candump text)");
  std::uint8_t nodes = 0;
  if (!node_count_of(args, nodes, error)) return fail("can send: " + error);
  for (const char* required : {"--from", "--to", "--vr", "--value"}) {
    if (!args.has(required)) return fail(std::string("can send needs ") + required);
  }
  long long from = 0;
  long long to = 0;
  long long vr = 0;
  double value = 0;
  if (!parse_integer(args.options.at("--from"), 1, nodes, from) || !parse_integer(args.options.at("--to"), 1, nodes, to))
    return fail("can send: --from and --to must be nodes 1.." + std::to_string(nodes));
  if (!parse_integer(args.options.at("--vr"), 0, can::max_message_vr, vr))
    return fail("can send: --vr must be an integer from 0 to 255, got '" + args.options.at("--vr") + "'");
  if (!parse_real(args.options.at("--value"), value))
    return fail("can send: --value must be a finite decimal number, got '" + args.options.at("--value") + "'");
  const std::string name = args.has("--interface-name") ? args.options.at("--interface-name") : "can0";
  bus can_bus;
  if (!can_bus.open(args.positionals[0], name, error)) return fail("can send: " + error);
  // The node's own send path: the frame node `from` sends to node `to`.
  struct frame_keeper final : can::port {
    can::frame frame;
    can::transmit_status send(const can::frame& outgoing) noexcept override {
      frame = outgoing;
      return can::transmit_status::ok;
    }
  } keeper;
  vr_table<1> unused;
  can::vr_exchange_node sender(can::make_node_address(nodes, static_cast<std::uint8_t>(from)).address, keeper, unused);
  const can::send_status encoded = sender.send_to_node(static_cast<std::uint8_t>(to), static_cast<std::uint16_t>(vr), value);
  if (encoded != can::send_status::ok) return fail(std::string("can send: cannot send this frame: ") + can::to_string(encoded));
  const can::transmit_status sent = can_bus.send(keeper.frame, live::now_ns());
  if (sent != can::transmit_status::ok)
    return fail("can send: " + can_bus.name() + " did not take the frame: " + can::to_string(sent));
  if (!can_bus.text()) std::printf("%s\n", host::format_candump_frame(keeper.frame).c_str());
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
    if (status == can::transmit_status::ok) capture_frame(*capture_, interface_, t, outgoing);
    return status;
  }

 private:
  bus* bus_;
  live::capture_file* capture_;
  std::uint32_t interface_;
};

int node_main(const std::vector<std::string>& given) {
  arguments args;
  std::string error;
  std::set<std::string> values = common_values;
  values.insert("--node");
  if (!parse_arguments(given, values, {"--json", "--trace"}, args, error)) return fail("can node: " + error);
  if (args.positionals.size() != 1) return fail("can node takes one IFACE (or - for candump text)");
  std::uint8_t nodes = 0;
  if (!node_count_of(args, nodes, error)) return fail("can node: " + error);
  long long own = 0;
  if (!args.has("--node") || !parse_integer(args.options.at("--node"), 1, nodes, own))
    return fail("can node needs --node I, a node 1.." + std::to_string(nodes));
  const bool json = args.flags.count("--json") != 0;
  const bool trace = args.flags.count("--trace") != 0;
  const std::string name = args.has("--interface-name") ? args.options.at("--interface-name") : "can0";
  bus can_bus;
  if (!can_bus.open(args.positionals[0], name, error)) return fail("can node: " + error);
  std::FILE* events = can_bus.text() ? stderr : stdout;  // with candump text, standard output carries frames
  live::capture_file capture;
  std::uint32_t interface = 0;
  if (args.has("--pcap")) {
    if (!capture.open(args.options.at("--pcap"), error)) return fail("can node: " + error);
    interface = capture.add(can_bus.text() ? "candump" : can_bus.name(), host::capture_network::can);
  }
  auto vrs = std::make_unique<node_vrs>();
  node_port port(can_bus, capture, interface);
  can::vr_exchange_node node(can::make_node_address(nodes, static_cast<std::uint8_t>(own)).address, port, *vrs);
  const auto print = [&](const live::event& e) { live::emit(e, json, events); };
  bus_counters counters;

  const auto received = [&](const can::frame& frame, std::uint64_t time_ns) {
    capture_frame(capture, interface, time_ns, frame);
    const live::event seen = live::can_event(time_ns, frame, nodes);
    counters.count(seen);
    const can::receive_result r = node.receive(frame);
    if (r.status == can::receive_status::foreign) {
      if (trace) print(seen);
      return;
    }
    live::event e(time_ns, "vr_write");
    e.number("from", static_cast<long long>(r.sender)).number("vr", static_cast<long long>(r.message.vr));
    if (r.status == can::receive_status::ok || r.status == can::receive_status::refused ||
        r.status == can::receive_status::out_of_range || r.status == can::receive_status::value_out_of_range) {
      e.real("value", trionet::to_double(r.message.value));
    } else {
      e = live::event(time_ns, "error");
      e.number("from", static_cast<long long>(r.sender)).text("frame", host::format_candump_frame(frame));
    }
    e.text("status", can::to_string(r.status));
    print(e);
  };
  const auto node_counters = [&]() {
    live::event e = counters.as_event();
    const can::node_counters& c = node.counters();
    e.number("sent", static_cast<unsigned long long>(c.sent)).number("send_busy", static_cast<unsigned long long>(c.send_busy));
    e.number("send_failed", static_cast<unsigned long long>(c.send_failed));
    e.number("written", static_cast<unsigned long long>(c.written)).number("refused", static_cast<unsigned long long>(c.refused));
    e.number("out_of_range", static_cast<unsigned long long>(c.out_of_range));
    e.number("foreign", static_cast<unsigned long long>(c.foreign));
    e.number("bad_dlc", static_cast<unsigned long long>(c.bad_dlc)).number("bad_sign", static_cast<unsigned long long>(c.bad_sign));
    e.number("bad_fraction", static_cast<unsigned long long>(c.bad_fraction));
    return e;
  };
  bool quit = false;
  const auto reply_error = [&](const std::string& command, const std::string& reason) {
    print(live::event(live::now_ns(), "error").text("command", command).text("reason", reason));
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
      if (s != can::send_status::ok) return reply_error(w[0], can::to_string(s));
      print(live::event(live::now_ns(), "sent").number("to", a).number("vr", b).real("value", value));
      return;
    }
    if (w[0] == "vr") {
      if ((w.size() != 2 && w.size() != 3) || !parse_integer(w[1], 0, can::max_message_vr, a))
        return reply_error(w[0], "usage: vr V [VALUE] (V 0..255)");
      if (w.size() == 3) {
        if (!parse_real(w[2], value)) return reply_error(w[0], "VALUE must be a real number");
        (*vrs)[static_cast<std::size_t>(a)] = value;
      }
      print(live::event(live::now_ns(), "vr").number("vr", a).real("value", (*vrs)[static_cast<std::size_t>(a)]));
      return;
    }
    if (w[0] == "counters") return print(node_counters());
    if (w[0] == "quit") {
      quit = true;
      return;
    }
    reply_error(w[0], "unknown command (send, vr, counters, quit)");
  };

  live::signal_watch signals;
  live::line_reader input(STDIN_FILENO);
  std::string ended;
  while (!quit && !live::signal_watch::stop_requested()) {
    if (live::signal_watch::take_report_request()) print(node_counters());
    pollfd fds[2] = {{STDIN_FILENO, POLLIN, 0}, {can_bus.text() ? -1 : can_bus.socket().fd(), POLLIN, 0}};
    const bool input_open = !input.ended();
    if (!input_open) fds[0].fd = -1;
    if (!input_open && can_bus.text()) break;  // candump text ended: the bus is gone
    if (::poll(fds, 2, 1000) <= 0) continue;
    if ((fds[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      input.read_some();
      std::string line;
      while (!quit && input.next(line)) {
        can::frame frame;
        std::uint64_t time_ns = 0;
        if (can_bus.text() && frame_of_line(line, frame, time_ns)) {
          received(frame, time_ns);
        } else {
          run(line);
        }
      }
    }
    if ((fds[1].revents & POLLIN) != 0) {
      can::frame frame;
      const host::socketcan_receive_status got = can_bus.socket().receive(frame, 0);
      if (got == host::socketcan_receive_status::ok) {
        received(frame, live::now_ns());
      } else if (got == host::socketcan_receive_status::error_frame) {
        ++counters.error_frames;
      } else if (got == host::socketcan_receive_status::failed) {
        ended = can_bus.name() + ": " + std::strerror(errno);
        break;
      }
    }
  }
  print(node_counters());
  if (!ended.empty()) std::fprintf(stderr, "trionet: can node: %s\n", ended.c_str());
  if (!capture.good()) return fail("can node: writing the capture failed");
  return exit_ok;
}

}  // namespace

int can_live_main(const std::string& command, const std::vector<std::string>& args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs(can_live_usage, stdout);
    return exit_ok;
  }
  if (command == "monitor") return monitor_main(args);
  if (command == "send") return send_main(args);
  if (command == "node") return node_main(args);
  std::fputs(can_live_usage, stderr);
  return exit_usage;
}

int can_monitor_main(const std::vector<std::string>& args) { return can_live_main("monitor", args); }
int can_send_main(const std::vector<std::string>& args) { return can_live_main("send", args); }
int can_node_main(const std::vector<std::string>& args) { return can_live_main("node", args); }

}  // namespace trionet::cli
