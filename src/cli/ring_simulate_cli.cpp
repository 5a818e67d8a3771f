// `trionet ring simulate`: a ring of Motion Coordinators running BASIC programs and membrane keypads pressed
// by a key script, on the simulated ring (ring_network.hpp). Prints what happens as it happens (key presses,
// messages dropped and why, VRs written by the ring, program ends and errors, NETSTAT; with --trace every
// message on every link and every display change), then every node's state; --json ends with one JSON line.
#include <cmath>
#include <cstdint>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "basic/number_format.hpp"
#include "basic/program.hpp"
#include "cli.hpp"
#include "embedded_files.hpp"
#include "profile_cli.hpp"
#include "ring_cli.hpp"
#include "ring_network.hpp"
#include "simulation.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/files.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/host/progress.hpp"
#include "trionet/host/text.hpp"
#include "trionet/ring.hpp"

namespace trionet::cli {

const char* const simulate_usage =
    "usage: trionet ring simulate example1|example2|example3|example3-fixed [options]\n"
    "       trionet ring simulate --node mc:FILE.bas|mc|keypad ... [options]   (nodes in ring order)\n"
    "options:\n"
    "  --keys SCRIPT            key presses and inputs, e.g. \"wait=500 1:7 1:up node1:in3=on 2:start\"\n"
    "                           (docs/basic.md)\n"
    "  --byte-times N           stop after N byte-times (default 1000000)\n"
    "  --bit-rate B             bits per second on every link (default 125000; 10 bits per byte)\n"
    "  --statements-per-byte-time S   BASIC statements each program runs per byte-time (default 1)\n"
    "  --key-gap N              byte-times each key press takes (default 1000)\n"
    "  --servo-period US        every controller's SERVO_PERIOD in microseconds: its axes, TICKS and WA\n"
    "                           (default 1000)\n"
    "  --trace                  also every message on every link and every display change\n"
    "  --json                   a JSON summary as the last line (alone, unless --trace)\n"
    "  --pcap FILE              write every byte of every link to a pcapng capture: one interface per link\n"
    "                           (\"link 0: node 1 (mc) -> node 2 (keypad)\"), one record per message, times\n"
    "                           from the byte-times at --bit-rate since the start (docs/wireshark.md)\n"
    "  --interactive            run in real time with the keypads' displays on the terminal and the keyboard as\n"
    "                           their keys (Tab: next keypad; q: quit); without a terminal, key words from\n"
    "                           standard input (\"1:up 2:7 wait=MS\", until they are done) and display changes\n"
    "                           printed\n"
    "Exit status 0 when the run ended without a program failing, 1 when a program failed, a program file\n"
    "could not be read or the output or the capture could not be written, 2 for bad arguments or a program\n"
    "that does not compile.\n";

const option_list& ring_simulate_options() {
  static const option_list options = {
      {"NETWORK", nullptr, "example1 example2 example3 example3-fixed", "a network built into the tool"},
      {"--node", "mc:FILE.bas|mc|keypad", "mc:@file mc keypad",
       "the next node in ring order: a Motion Coordinator running FILE.bas, an idle one, or a keypad", true},
      {"--keys", "SCRIPT", "@keys", "key presses, e.g. \"wait=500 1:7 1:up 1:Y wait=2000 2:start\""},
      {"--byte-times", "N", "", "stop after N byte-times (default 1000000)"},
      {"--bit-rate", "B", "", "bits per second on every link (default 125000; 10 bits per byte)"},
      {"--statements-per-byte-time", "S", "", "BASIC statements each program runs per byte-time (default 1)"},
      {"--key-gap", "N", "", "byte-times each key press takes (default 1000)"},
      {"--servo-period", "US", "", "every controller's SERVO_PERIOD in microseconds (default 1000)"},
      {"--trace", nullptr, "", "also every message on every link and every display change"},
      {"--json", nullptr, "", "a JSON summary as the last line"},
      {"--pcap", "FILE", "@file", "write every byte of every link to a pcapng capture, one interface per link"},
      {"--interactive", nullptr, "", "run in real time with the keypads on the terminal"},
  };
  return options;
}

namespace {

// A node of --node: "keypad", "mc" or "mc:FILE". Exit status 0, 2 for a bad spec or a file not built in, 1 for
// a program file that cannot be read (the cause in `error`).
int node_of(const std::string& spec, bool builtin, host::node_spec& node, std::string& error) {
  if (spec == "keypad") {
    node.what = host::node_spec::kind::keypad;
    return exit_ok;
  }
  if (spec == "mc") {
    node.what = host::node_spec::kind::mc;
    return exit_ok;
  }
  if (spec.compare(0, 3, "mc:") != 0 || spec.size() == 3) {
    error = "--node takes mc:FILE, mc or keypad, not '" + host::printable(spec) + "'";
    return exit_usage;
  }
  node.what = host::node_spec::kind::mc;
  node.program_name = spec.substr(3);
  if (!builtin) {
    // Read with a bound before compiling: a directory or a device is refused, an endless pipe stops there.
    const host::file_result read = host::read_bounded_file(node.program_name, basic::max_program_text, node.program_text);
    if (read) return exit_ok;
    error = read.message(node.program_name, "program");
    return exit_io;
  }
  const host::embedded_file* file = host::find_embedded_file(node.program_name);
  if (file == nullptr) {
    error = host::printable(node.program_name) + " is not built into this tool";
    return exit_usage;
  }
  node.program_text = std::string(file->text());
  return exit_ok;
}

std::string box(const std::vector<std::string>& lines, const char* indent) {
  std::string out = std::string(indent) + "+--------------------+\n";
  for (const std::string& line : lines) out += std::string(indent) + "|" + line + "|\n";
  out += std::string(indent) + "+--------------------+\n";
  return out;
}

std::string basic_address_text(unsigned hops) {
  return std::to_string(hops) + (hops == 1 ? " hop" : " hops") + " along (BASIC " + std::to_string(hops + 9) + ")";
}

std::string list_of(const std::vector<std::size_t>& numbers) {
  std::string out;
  for (std::size_t n : numbers) out += " " + std::to_string(n);
  return out;
}

void append_summary(std::string& out, const host::ring_network& net) {
  const auto line = [&out](const std::string& text) { out += text + "\n"; };
  for (std::size_t i = 1; i <= net.size(); ++i) {
    const host::node_report r = net.report(i);
    if (r.what == host::node_spec::kind::keypad) {
      line("node " + std::to_string(i) + "  keypad " + std::to_string(r.keypad_number) + ": " +
           (r.network_mode ? "network mode, keys go " + basic_address_text(r.offset)
                           : std::string("local mode (no keypad offset received)")));
      out += box(r.display, "        ");
      if (r.dropped != 0 || r.keys_lost != 0) {
        line("        dropped in local mode: " + std::to_string(r.dropped) +
             " message(s); keys lost: " + std::to_string(r.keys_lost));
      }
      continue;
    }
    std::string head = "node " + std::to_string(i) + "  mc";
    if (r.state == "none") {
      head += " (no program)";
    } else {
      head += " " + r.program + ": ";
      if (r.state == "failed") {
        head += "stopped at line " + std::to_string(r.line) + ": " + r.error;
      } else if (r.state == "ended") {
        head += "ended at line " + std::to_string(r.line);
      } else if (r.state == "waiting") {
        head += "waiting at line " + std::to_string(r.line) + " (" + r.waiting + ")";
      } else {
        head += "running at line " + std::to_string(r.line) + (r.idle ? ", round a loop that changes nothing" : "");
      }
    }
    line(head);
    line("        NETSTAT " + std::to_string(r.netstat) + (r.wdog ? "  WDOG ON" : ""));
    const auto list = [&line](const char* title, const std::string& items) {
      if (!items.empty()) line(std::string("        ") + title + ":" + items);
    };
    std::string text;
    for (const auto& [vr, value] : r.vrs) text += " VR(" + std::to_string(vr) + ")=" + basic::format_value(value);
    list("VR", text);
    text.clear();
    for (const auto& [index, value] : r.table) text += " TABLE(" + std::to_string(index) + ")=" + basic::format_value(value);
    if (r.table_nonzero > r.table.size()) text += " ... (" + std::to_string(r.table_nonzero) + " not 0)";
    list("TABLE", text);
    text.clear();
    for (const auto& [name, value] : r.variables) text += " " + name + "=" + basic::format_value(value);
    list("variables", text);
    list("inputs on", list_of(r.inputs_on));
    list("outputs on", list_of(r.outputs_on));
    for (const host::axis_report& a : r.axes) {
      std::string axis = "        axis " + std::to_string(a.axis) + ": DPOS " + basic::format_value(a.dpos) + " MPOS " +
                         basic::format_value(a.mpos) + ", ";
      axis += a.idle ? std::string("idle")
                     : "moving (MTYPE " + std::to_string(a.mtype) + ", VP_SPEED " + basic::format_value(a.speed) + ")";
      for (const auto& [name, value] : a.parameters) axis += " " + name + "=" + basic::format_value(value);
      line(axis);
    }
  }
}


}  // namespace

int ring_simulate_main(const words& all) {
  arguments args;
  std::string error;
  if (!parse_arguments(all, ring_simulate_options(), args, error)) return fail(error);
  const int capacities = check_ring_capacities("ring simulate", ring_capacity_use::receive_buffer);
  if (capacities != exit_ok) return capacities;
  const host::builtin_network* builtin = nullptr;
  if (args.positionals.size() > 1) return fail("ring simulate takes one built-in network name at most");
  if (args.positionals.size() == 1) {
    builtin = host::find_builtin_network(args.positionals[0]);
    if (builtin == nullptr)
      return fail("unknown network '" + host::printable(args.positionals[0]) + "' (expected example1, example2, example3 or "
                  "example3-fixed, or --node options)");
    if (args.has("--node")) return fail("--node cannot be used with a built-in network");
  } else if (!args.has("--node")) {
    return fail("ring simulate needs a built-in network (example1, example2, example3, example3-fixed) or --node "
                "options (see trionet ring simulate --help)");
  }

  std::vector<std::string> specs;
  if (builtin != nullptr) {
    specs.assign(builtin->nodes.begin(), builtin->nodes.end());
  } else {
    const std::string& node_list = args.options.at("--node");
    for (std::size_t start = 0; start <= node_list.size();) {
      const std::size_t end = node_list.find('\n', start);
      specs.push_back(node_list.substr(start, end == std::string::npos ? std::string::npos : end - start));
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  std::vector<host::node_spec> nodes(specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const int status = node_of(specs[i], builtin != nullptr, nodes[i], error);
    if (status == exit_io) return fail_io(error);
    if (status != exit_ok) return fail(error);
  }

  host::network_config config;
  config.crc = active_profile().ring.crc;  // the nodes check and send direct variable transfers with them
  config.layout = active_profile().ring.layout;
  config.keypad_codes = active_profile().keypad.codes;
  config.key_off_code = learn::key_off_function(active_profile().keypad.key_off);
  config.defkey = active_profile().keypad.defkey;
  config.display = active_profile().keypad.display;
  long long number = 0;
  std::uint64_t max_byte_times = 1000000;
  if (args.has("--byte-times")) {
    if (!parse_integer(args.options.at("--byte-times"), 1, 1000000000000LL, number))
      return fail("--byte-times must be a whole number 1..10^12, got '" + host::printable(args.options.at("--byte-times")) + "'");
    max_byte_times = static_cast<std::uint64_t>(number);
  }
  if (args.has("--bit-rate")) {
    double rate = 0;
    if (!parse_real(args.options.at("--bit-rate"), rate) || !(rate >= 1 && rate <= 1e9))
      return fail("--bit-rate must be a number of bits per second 1..10^9, got '" + host::printable(args.options.at("--bit-rate")) +
                  "'");
    config.bit_rate = rate;
  }
  if (args.has("--statements-per-byte-time")) {
    if (!parse_integer(args.options.at("--statements-per-byte-time"), 1, 1000000, number))
      return fail("--statements-per-byte-time must be a whole number 1..1000000, got '" +
                  host::printable(args.options.at("--statements-per-byte-time")) + "'");
    config.statements_per_byte_time = static_cast<std::uint32_t>(number);
  }
  if (args.has("--servo-period")) {
    double period = 0;
    if (!parse_real(args.options.at("--servo-period"), period) || !(period >= 1 && period <= 1000000))
      return fail("--servo-period must be a number of microseconds 1..1000000, got '" +
                  host::printable(args.options.at("--servo-period")) + "'");
    config.servo_period_us = period;
  }
  if (args.has("--key-gap")) {
    if (!parse_integer(args.options.at("--key-gap"), 0, 1000000000LL, number))
      return fail("--key-gap must be a whole number of byte-times 0..10^9, got '" + host::printable(args.options.at("--key-gap")) + "'");
    config.key_gap = static_cast<std::uint64_t>(number);
  }

  std::unique_ptr<host::ring_network> net = host::ring_network::build(nodes, config, error);
  if (!net) return fail(error);
  const bool interactive = args.flags.count("--interactive") != 0;  // the keys are the user's, live
  const std::string keys = args.has("--keys")                      ? args.options.at("--keys")
                           : builtin != nullptr && !interactive ? builtin->keys
                                                                : "";
  if (!net->set_keys(keys, error)) return fail(error);

  // The capture: one interface per link, named after the nodes it joins.
  std::ofstream capture_file;
  std::unique_ptr<host::pcapng_writer> writer;
  std::vector<host::ring_link_recorder> links;
  if (args.has("--pcap")) {
    capture_file.open(args.options.at("--pcap"), std::ios::binary | std::ios::trunc);
    if (!capture_file) {
      return fail_io("cannot write " + host::printable(args.options.at("--pcap")) + ": " + std::strerror(errno));
    }
    writer = std::make_unique<host::pcapng_writer>(capture_file, version_line());
    const auto node_name = [&](std::size_t i) {
      return "node " + std::to_string(i + 1) +
             (net->report(i + 1).what == host::node_spec::kind::keypad ? " (keypad)" : " (mc)");
    };
    links.reserve(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string name = "link " + std::to_string(i) + ": " + node_name(i) + " -> " + node_name((i + 1) % nodes.size());
      const host::pcapng_interface_result added = writer->add_interface(name, host::capture_network::ring);
      if (!added) return fail_io("cannot write " + host::printable(args.options.at("--pcap")) + ": " + host::to_string(added.status));
      links.emplace_back(*writer, added.id, config.bit_rate, config.bits_per_byte);
    }
    net->on_link_byte([&links](std::uint64_t time, std::size_t link, std::uint8_t byte) {
      links[link].byte_at(time, byte);
    });
  }

  if (interactive) {
    return ring_simulate_interactive(*net, config.bit_rate, args.has("--byte-times") ? max_byte_times : UINT64_MAX);
  }
  const bool json = args.flags.count("--json") != 0;
  const bool trace = args.flags.count("--trace") != 0;
  const bool narrate = trace || !json;
  output out;
  std::string& text = out.text();
  if (narrate) {
    if (builtin != nullptr) text += std::string(builtin->name) + ": " + builtin->title + "\n";
    text += "ring:";
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const host::node_report r = net->report(i + 1);
      if (r.what == host::node_spec::kind::keypad) {
        text += " " + std::to_string(i + 1) + " keypad " + std::to_string(r.keypad_number) + " ->";
      } else {
        text += " " + std::to_string(i + 1) + " mc" + (nodes[i].program_name.empty() ? "" : " ") +
                nodes[i].program_name + " ->";
      }
    }
    text += " back to 1\n";
    text += "clock: one byte per link per byte-time, " + basic::format_value(1e6 * 10 / config.bit_rate) + " us at " +
            basic::format_value(config.bit_rate) + " bit/s (10 bits per byte); " +
            std::to_string(config.statements_per_byte_time) +
            " BASIC statement(s) per byte-time per program" +
            (config.servo_period_us == 1000 ? std::string()
                                            : "; servo period " + basic::format_value(config.servo_period_us) + " us") +
            "\n";
    if (!keys.empty()) text += "keys: " + keys + "\n";
    text += "\n";
    net->on_event([trace, &out](const host::network_event& e) {
      const bool traced_only = e.kind == host::event_kind::message || e.kind == host::event_kind::frame_error ||
                               e.kind == host::event_kind::display || e.kind == host::event_kind::motion;
      if (traced_only && !trace) return;
      char head[64];
      std::snprintf(head, sizeof head, "t=%8llu  node %-2zu ", static_cast<unsigned long long>(e.time), e.node);
      if (e.kind == host::event_kind::display) {
        out.text() += std::string(head) + "display\n" + box(e.display, "                      ");
      } else {
        out.text() += head + e.text + "\n";
      }
      (void)out.maybe_flush();
    });
  }
  // The run, in pieces so that a closed output ends it and a long one shows its progress on a terminal.
  host::run_end end = host::run_end::limit;
  {
    const double total_seconds = ring::byte_times_to_seconds(max_byte_times, config.bit_rate, config.bits_per_byte);
    host::progress shown("ring simulate", "s of ring time", total_seconds);
    constexpr std::uint64_t piece = 1u << 14;  // about 10 ms of work at a time
    for (;;) {
      const std::uint64_t until = std::min<std::uint64_t>(max_byte_times, net->now() + piece);
      end = net->run(until, until == max_byte_times);
      if (out.failed()) return fail_io("cannot write standard output");
      if (end == host::run_end::settled || net->now() >= max_byte_times) break;
      shown.update(net->seconds());
    }
  }
  if (narrate) {
    char head[32];
    std::snprintf(head, sizeof head, "t=%8llu  ", static_cast<unsigned long long>(net->now()));
    if (end == host::run_end::settled) {
      text += std::string(head) + "settled: every program has ended or waits for ever, the keys are done and the "
                                  "ring is quiet\n";
    } else {
      text += std::string(head) + "stopped after --byte-times " + std::to_string(max_byte_times) +
              ": the run had not settled\n";
    }
    text += "\n" + std::to_string(net->now()) + " byte-times = " + basic::format_value(net->seconds()) +
            " s of ring time\n\n";
    append_summary(text, *net);
  }
  if (json) text += host::summary_json(*net, end) + "\n";
  if (!out.flush()) return fail_io("cannot write standard output");
  if (writer) {
    for (host::ring_link_recorder& link : links) {
      link.flush();
      if (link.status() != host::pcapng_write_status::ok) {
        return fail_io("cannot write " + host::printable(args.options.at("--pcap")) + ": " + host::to_string(link.status()));
      }
    }
    errno = 0;
    capture_file.flush();
    if (!capture_file) {
      return fail_io("cannot write " + host::printable(args.options.at("--pcap")) + ": " +
                     std::strerror(errno != 0 ? errno : EIO));
    }
  }
  for (std::size_t i = 1; i <= net->size(); ++i) {
    if (net->report(i).state == "failed") return 1;
  }
  if (end != host::run_end::settled) {
    return limit_reached("ring simulate: stopped after --byte-times " + std::to_string(max_byte_times) +
                         ": the run had not settled");
  }
  return exit_ok;
}

}  // namespace trionet::cli
