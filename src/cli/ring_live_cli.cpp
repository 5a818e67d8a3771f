// `trionet ring monitor|send|join PORT ...`: the fibre ring on a live port (a serial port, a pty, a FIFO, a
// Unix socket): watch what arrives, put one message on the ring, or be a node of it (a Motion Coordinator
// driven from standard input, or a membrane keypad driven from the keyboard).
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "cli.hpp"
#include "keypad_terminal.hpp"
#include "live.hpp"
#include "profile_cli.hpp"
#include "ring_cli.hpp"
#include "ring_live.hpp"
#include "ring_message_arguments.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/link_device.hpp"
#include "trionet/host/posix_link.hpp"
#include "trionet/ring.hpp"

namespace trionet::cli {

const char* const ring_live_usage =
    "usage:\n"
    "  trionet ring monitor PORT [port options] [--json] [--pcap FILE]\n"
    "      decode what arrives on PORT, one event per line as soon as it is complete; counters at the end,\n"
    "      on Ctrl-C and on SIGUSR1\n"
    "  trionet ring send PORT print|var|offset|mode ... [port options] [--pcap FILE]\n"
    "      put one message on the ring (the arguments of `trionet ring encode`), wait until it has left,\n"
    "      print its bytes\n"
    "  trionet ring join PORT --as mc [port options] [--json] [--trace] [--pcap FILE]\n"
    "      be a Motion Coordinator on the ring: forward, deliver, and take commands on standard input (it\n"
    "      ends at quit or when standard input ends, once what it queued has been sent):\n"
    "        print N TEXT | send N VR VALUE | offset N M | mode N 0|127 | key 3|4 | get 3|4 |\n"
    "        vr V [VALUE] | netstat [clear] | counters | quit        (TEXT escapes: \\r \\n \\t \\\\ \\xNN)\n"
    "  trionet ring join PORT --as mc --learn-keypad N [--keypad-offset M] -o PROFILE [port options] [--json]\n"
    "      learn a real keypad's codes: put the keypad at BASIC address N in network mode (keys sent to\n"
    "      BASIC address M from the keypad, default N: right for a ring of two) and keypad mode 127, ask for\n"
    "      each key in turn (press and release it), and write the profile in effect with the key ON\n"
    "      characters and the key OFF rule found to PROFILE (exit 3 if no profile can hold them)\n"
    "  trionet ring join PORT --as keypad [port options] [--json] [--trace] [--pcap FILE]\n"
    "      be a membrane keypad: on a terminal, its display drawn in place and the keyboard as its keys;\n"
    "      otherwise key words from standard input (0..9 . up down clr y n start stop, wait=MS, quit; it ends\n"
    "      at quit, or when standard input has ended and its key words are done)\n"
    "PORT: a serial port or pty, a FIFO, a Unix socket, or - (standard input; standard output for send).\n"
    "port options:\n"
    "  --baud B        serial ports: bits per second, any rate 50..4000000 (default 125000)\n"
    "  --flow F        serial ports: none (default), rtscts or xonxoff\n"
    "  --idle-ms T     no byte for T ms with a message open is the idle line (docs/protocol.md 1.10);\n"
    "                  default 50\n";

namespace {

struct port_arguments {
  host::link_options link;
  int idle_ms = 50;
  bool json = false;
  bool trace = false;
  std::string pcap;
};

bool port_arguments_of(const arguments& args, port_arguments& out, std::string& error) {
  long long number = 0;
  if (args.has("--baud")) {
    if (!parse_integer(args.options.at("--baud"), host::min_serial_baud, host::max_serial_baud, number)) {
      error = "--baud must be a rate 50..4000000, got '" + host::printable(args.options.at("--baud")) + "'";
      return false;
    }
    out.link.baud = static_cast<unsigned>(number);
  }
  if (args.has("--flow")) {
    const std::string& flow = args.options.at("--flow");
    if (flow == "none") {
      out.link.flow = host::flow_control::none;
    } else if (flow == "rtscts") {
      out.link.flow = host::flow_control::hardware;
    } else if (flow == "xonxoff") {
      out.link.flow = host::flow_control::software;
    } else {
      error = "--flow must be none, rtscts or xonxoff, got '" + host::printable(flow) + "'";
      return false;
    }
  }
  if (args.has("--idle-ms")) {
    if (!parse_integer(args.options.at("--idle-ms"), 1, 60000, number)) {
      error = "--idle-ms must be 1..60000, got '" + host::printable(args.options.at("--idle-ms")) + "'";
      return false;
    }
    out.idle_ms = static_cast<int>(number);
  }
  out.json = args.flags.count("--json") != 0;
  out.trace = args.flags.count("--trace") != 0;
  if (args.has("--pcap")) out.pcap = args.options.at("--pcap");
  return true;
}

// The options every live ring command takes: the port's, and the capture.
const option_list& port_options() {
  static const option_list options = {
      {"PORT", nullptr, "@port", "a serial port or pty, a FIFO, a Unix socket, or - (standard input)"},
      {"--baud", "B", "9600 19200 38400 57600 115200 125000 250000 500000 1000000",
       "serial ports: bits per second, any rate 50..4000000 (default 125000)"},
      {"--flow", "F", "none rtscts xonxoff", "serial ports: none (default), rtscts or xonxoff"},
      {"--idle-ms", "T", "", "no byte for T ms with a message open is the idle line (default 50)"},
      {"--pcap", "FILE", "@file", "also write what the port carries to a pcapng capture"},
  };
  return options;
}

// Functions, not globals: the command tables of other files use these tables while they are initialised.
const option_list& json_option() {
  static const option_list options = {{"--json", nullptr, "", "events as JSON lines"}};
  return options;
}

// ---- ring monitor ----

int monitor_main(const words& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, ring_monitor_options(), args, error)) return fail("ring monitor: " + error);
  if (args.positionals.size() != 1) return fail("ring monitor takes one PORT");
  const int capacities = check_ring_capacities("ring monitor", ring_capacity_use::decoder);
  if (capacities != exit_ok) return capacities;
  port_arguments options;
  if (!port_arguments_of(args, options, error)) return fail("ring monitor: " + error);
  host::link_device port;
  if (!port.open(args.positionals[0], options.link, error)) return fail_io("ring monitor: " + error);
  live::capture_file capture;
  if (!options.pcap.empty() && !capture.open(options.pcap, error)) return fail_io("ring monitor: " + error);
  ring_tap tap(capture.is_open() ? &capture : nullptr, "received on " + port.name());
  live::event_log log(options.json);
  live::event_loop loop(&log);
  const std::size_t link = loop.watch(port.fd(), POLLIN);
  const auto print = [&log](const ring::decode_result& r, std::uint64_t time_ns) {
    append_ring_event(log.text(), r, [time_ns](event& e) { e.time(time_ns); });
  };
  while (loop.running()) {
    if (live::event_loop::report_requested()) tap.counters(log.text(), live::now_ns());
    if (!loop.wait(options.idle_ms)) break;
    if (!loop.readable(link)) {
      tap.idle(live::now_ns(), print);
      continue;
    }
    std::uint8_t in[4096];
    const ssize_t got = ::read(port.fd(), in, sizeof in);
    if (got < 0 && (errno == EAGAIN || errno == EINTR)) continue;
    if (got == 0 && port.kind() == host::link_kind::standard_stream) {
      loop.stop();  // standard input ended: all is read
    } else if (got == 0 || (got < 0 && errno == EIO)) {
      loop.lost(host::printable(port.name()) + " closed");
    } else if (got < 0) {
      loop.lost(host::printable(port.name()) + ": " + std::strerror(errno));
    } else {
      tap.push(byte_view(in, static_cast<std::size_t>(got)), live::now_ns(), print);
    }
  }
  tap.idle(live::now_ns(), print);  // a message cut short by the end is reported as such
  tap.counters(log.text(), live::now_ns());
  port.close();
  const int status = loop.finish("ring monitor");
  if (status == exit_ok && !capture.good()) return fail_io("ring monitor: writing the capture " + options.pcap + " failed: " + capture.cause());
  return status;
}

// ---- ring send ----

int send_main(const words& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, ring_send_options(), args, error)) return fail("ring send: " + error);
  if (args.positionals.size() < 2) return fail("ring send needs PORT and a message kind: print, var, offset or mode");
  const int capacities = check_ring_capacities("ring send", ring_capacity_use::text_limit);
  if (capacities != exit_ok) return capacities;
  port_arguments options;
  if (!port_arguments_of(args, options, error)) return fail("ring send: " + error);
  arguments message_args = args;
  message_args.positionals.assign(args.positionals.begin() + 2, args.positionals.end());
  std::vector<std::uint8_t> frame;
  if (!ring_message_frame(args.positionals[1], message_args, frame, error)) return fail("ring send: " + error);

  options.link.standard_stream = 1;
  options.link.shared = true;  // a sender writes where a monitor may listen
  host::link_device port;
  if (!port.open(args.positionals[0], options.link, error)) return fail_io("ring send: " + error);
  live::capture_file capture;
  if (!options.pcap.empty() && !capture.open(options.pcap, error)) return fail_io("ring send: " + error);
  const std::uint64_t sent_at = live::now_ns();
  std::size_t done = 0;
  live::event_loop loop(nullptr);
  loop.watch(port.fd(), POLLOUT);
  while (done < frame.size() && loop.wait(1000)) {
    const ssize_t wrote = ::write(port.fd(), frame.data() + done, frame.size() - done);
    if (wrote > 0) {
      done += static_cast<std::size_t>(wrote);
    } else if (wrote < 0 && errno != EAGAIN && errno != EINTR) {
      loop.lost("cannot write to " + host::printable(port.name()) + ": " + std::strerror(errno));
    }
  }
  if (loop.link_lost() || done < frame.size()) {
    const int status = loop.finish("ring send");
    return status != exit_ok ? status : fail_io("ring send: interrupted after " + std::to_string(done) + " bytes");
  }
  if (!port.drain()) return fail_io("ring send: cannot drain " + host::printable(port.name()) + ": " + std::strerror(errno));
  if (capture.is_open()) {
    ring_tap tap(&capture, "sent on " + port.name());
    const ring_tap::sink ignore = [](const ring::decode_result&, std::uint64_t) {};
    tap.push(byte_view(frame.data(), frame.size()), sent_at, ignore);
    tap.idle(sent_at, ignore);
  }
  port.close();
  if (args.positionals[0] != "-" && !write_stdout(hex_line(frame.data(), frame.size()) + "\n")) return fail_output();
  if (!capture.good()) return fail_io("ring send: writing the capture " + options.pcap + " failed: " + capture.cause());
  return exit_ok;
}

}  // namespace

const option_list& ring_monitor_options() {
  static const option_list options = joined(port_options(), json_option());
  return options;
}

const option_list& ring_send_options() {
  static const option_list options = joined(
      joined(port_options(), {{"KIND", nullptr, "print var offset mode", "the message, as `trionet ring encode` takes it"},
                              {"TEXT", nullptr, "", "print: the characters"}}),
      ring_message_options());
  return options;
}

const option_list& ring_join_options() {
  static const option_list options = joined(
      joined(port_options(), json_option()),
      {
          {"--as", "mc|keypad", "mc keypad", "the node to be: a Motion Coordinator or a membrane keypad"},
          {"--trace", nullptr, "", "also every message the node forwards"},
          {"--learn-keypad", "N", "10 11 12 13 14 15 16 17 18 19 20 21 22 23 24",
           "with --as mc: learn the codes of the keypad at BASIC address N"},
          {"--keypad-offset", "M", "10 11 12 13 14 15 16 17 18 19 20 21 22 23 24",
           "with --learn-keypad: the BASIC address the keypad sends its keys to (default N)"},
          {"-o", "PROFILE", "@file", "with --learn-keypad: where the profile with the codes found is written"},
      });
  return options;
}

int ring_monitor_main(const words& args) {
  return monitor_main(args);
}

int ring_send_main(const words& args) {
  return send_main(args);
}

int ring_join_main(const words& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, ring_join_options(), args, error)) return fail("ring join: " + error);
  if (args.positionals.size() != 1) return fail("ring join takes one PORT");
  if (!args.has("--as")) return fail("ring join needs --as mc or --as keypad");
  if (args.positionals[0] == "-") {
    return fail("ring join: a node needs a port it can read and write (a serial port, a pty or a socket), not -");
  }
  port_arguments options;
  if (!port_arguments_of(args, options, error)) return fail("ring join: " + error);
  const std::string& as = args.options.at("--as");
  const int capacities = check_ring_capacities(
      "ring join", as == "keypad" ? ring_capacity_use::decoder : ring_capacity_use::receive_buffer);
  if (capacities != exit_ok) return capacities;
  join_settings settings{args.positionals[0], options.link, options.idle_ms, options.json, options.trace,
                         options.pcap, 0, 0, ""};
  const bool learning = args.has("--learn-keypad");
  if (!learning && (args.has("--keypad-offset") || args.has("-o"))) {
    return fail("ring join: --keypad-offset and -o go with --learn-keypad");
  }
  if (learning) {
    if (as != "mc") return fail("ring join: --learn-keypad goes with --as mc (the MC learns the keypad's codes)");
    if (!args.has("-o")) return fail("ring join: --learn-keypad needs -o PROFILE (where the codes go)");
    long long n = 0;
    const std::string& address = args.options.at("--learn-keypad");
    if (!parse_integer(address, ring::first_basic_address, ring::last_basic_address, n)) {
      return fail("ring join: --learn-keypad takes the keypad's BASIC address 10..24, got '" + host::printable(address) +
                  "'");
    }
    settings.learn_keypad = static_cast<int>(n);
    const std::string& back = args.has("--keypad-offset") ? args.options.at("--keypad-offset") : address;
    if (!parse_integer(back, ring::first_basic_address, ring::last_basic_address, n)) {
      return fail("ring join: --keypad-offset takes a BASIC address 10..24, got '" + host::printable(back) + "'");
    }
    settings.keypad_offset = static_cast<int>(n);
    settings.learn_output = args.options.at("-o");
  }
  if (as == "mc") return join_mc(settings);
  if (as == "keypad") return join_keypad(settings);
  return fail("ring join: --as must be mc or keypad, got '" + host::printable(as) + "'");
}

}  // namespace trionet::cli
