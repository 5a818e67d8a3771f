// `trionet genius simulate` (a bus of genius::device nodes, src/sim/genius_bus.hpp) and `trionet genius plan`
// (SBAs without collision risk, src/sim/genius_plan.hpp). Formats are documented in docs/genius.md.
#include "genius_bus_cli.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <trionet/genius.hpp>

#include "genius_bus.hpp"
#include "genius_plan.hpp"
#include "profile_cli.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/host/text.hpp"

namespace trionet::cli {
namespace {

namespace genius = trionet::genius;
using host::genius_bus;
using host::genius_bus_config;
using host::genius_bus_result;
using host::genius_device_report;
using host::genius_fault;
using host::genius_fault_kind;
using host::genius_plan_device;
using host::genius_plan_options;
using host::genius_plan_result;
using host::genius_assignment;
using host::genius_remedy;
using host::genius_station;
using host::genius_transmission_record;
using host::genius_turn_record;

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string pad(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
}

// JSON numbers rounded to the nanosecond (0.001 us) in their shortest form, no "-0".
std::string json_us(double value) {
  double rounded = std::round(value * 1000.0) / 1000.0;
  if (rounded == 0.0) rounded = 0.0;
  return format_real(rounded);
}

// Milliseconds as exact decimal text from nanoseconds.
std::string exact_ms(std::uint64_t ns) {
  std::string text = std::to_string(ns / 1000000u);
  std::string fraction = std::to_string(ns % 1000000u);
  fraction.insert(0, 6 - fraction.size(), '0');
  while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
  return fraction.empty() ? text : text + "." + fraction;
}

bool parse_rate(const arguments& args, genius::rate& rate, int& status) {
  if (!args.has("--rate")) {
    status = fail("needs --rate 153.6s|153.6e|76.8|38.4");
    return false;
  }
  if (!genius::rate_from_name(args.options.at("--rate"), rate)) {
    status = fail("unknown rate '" + host::printable(args.options.at("--rate")) +
                  "' (expected 153.6s, 153.6e, 76.8 or 38.4)");
    return false;
  }
  return true;
}

constexpr double max_feet = 1e6;

// ---------------------------------------------------------------------------------------------------
// simulate

// A fault: KIND:WHERE@START+DURATION, times in microseconds from the start of the run.
bool parse_fault(const std::string& text, genius_fault& f, std::string& error) {
  error = "--fault '" + host::printable(text) +
          "' must be noise:FEET@T+D, off:SBA@T+D, stop:SBA@T+D or cut:FEET@T+D (T, D in microseconds)";
  const std::size_t colon = text.find(':');
  const std::size_t at = text.find('@');
  const std::size_t plus = text.find('+', at == std::string::npos ? 0 : at);
  if (colon == std::string::npos || at == std::string::npos || plus == std::string::npos || !(colon < at)) return false;
  const std::string kind = text.substr(0, colon);
  const std::string where = text.substr(colon + 1, at - colon - 1);
  // A number in range; one that is a number but out of range names its range, anything else the format.
  const auto in_range = [&](const std::string& value, double low, double high, const char* what, const char* range,
                            double& out) {
    if (host::parse_real(value, low, high, out)) return true;
    double any = 0;
    if (host::parse_real(value, -1e300, 1e300, any)) {
      error = "--fault '" + host::printable(text) + "': " + what + " must be " + range + ", got '" +
              host::printable(value) + "'";
    }
    return false;
  };
  const bool located = kind == "noise" || kind == "cut";
  if (!located && kind != "off" && kind != "stop") return false;
  if (!in_range(text.substr(at + 1, plus - at - 1), 0, 1e9, "the start T", "0..1000000000 us", f.at_us) ||
      !in_range(text.substr(plus + 1), 0, 1e9, "the duration D", "0..1000000000 us", f.duration_us)) {
    return false;
  }
  long long sba = 0;
  if (located) {
    f.kind = kind == "noise" ? genius_fault_kind::noise : genius_fault_kind::cut;
    static_assert(max_feet == 1e6, "the range in the message");
    if (!in_range(where, 0, max_feet, "the place FEET", "0..1000000 feet", f.position_ft)) return false;
  } else if (kind == "off" || kind == "stop") {
    f.kind = kind == "off" ? genius_fault_kind::power_off : genius_fault_kind::stop;
    if (!parse_integer(where, 0, 31, sba)) {
      double any = 0;
      if (host::parse_real(where, -1e300, 1e300, any)) {
        error = "--fault '" + host::printable(text) + "': the SBA must be 0..31, got '" + host::printable(where) + "'";
      }
      return false;
    }
    f.sba = static_cast<std::uint8_t>(sba);
  } else {
    return false;
  }
  if (f.kind == genius_fault_kind::noise && f.duration_us > 1e6) {
    error = "--fault '" + host::printable(text) + "': a noise burst lasts at most 1000000 us";
    return false;
  }
  return true;
}

// SBA@FEET[:IN_BYTES[/OUT_BYTES]]
bool parse_station(const std::string& text, genius_station& s) {
  const std::size_t at = text.find('@');
  if (at == std::string::npos) return false;
  long long sba = 0;
  if (!parse_integer(text.substr(0, at), 0, 31, sba)) return false;
  s.sba = static_cast<std::uint8_t>(sba);
  const std::size_t colon = text.find(':', at);
  if (!host::parse_real(text.substr(at + 1, colon == std::string::npos ? std::string::npos : colon - at - 1), 0,
                        max_feet, s.position_ft)) {
    return false;
  }
  s.input_bytes = 1;
  s.output_bytes = 0;
  if (colon == std::string::npos) return true;
  const std::size_t slash = text.find('/', colon);
  long long in = 0, out = 0;
  if (!parse_integer(text.substr(colon + 1, slash == std::string::npos ? std::string::npos : slash - colon - 1), 0,
                     255, in)) {
    return false;
  }
  if (slash != std::string::npos && !parse_integer(text.substr(slash + 1), 0, 255, out)) return false;
  s.input_bytes = static_cast<std::uint16_t>(in);
  s.output_bytes = static_cast<std::uint16_t>(out);
  return true;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

std::string what_of(const genius_turn_record& t) {
  if (t.cancelled) {
    return "cancelled: SBA " + std::to_string(t.by) + "'s start bit arrived at " + fixed(t.arrived_us, 3) +
           " us, margin " + fixed(t.due_us - t.arrived_us, 3) + " us";
  }
  if (t.transmitted) return "transmitted";
  if (t.passed) return "passed (nothing to send)";
  return "not reached in the run";
}

const char* what_name(const genius_turn_record& t) {
  if (t.cancelled) return "cancelled";
  if (t.transmitted) return "transmitted";
  if (t.passed) return "passed";
  return "not_reached";
}

// The simulated devices are the library's genius::device, built for CRC-6/G-704 and the control layout of
// docs/protocol.md 3.2: a profile with other Genius keys is refused (cli.md: a command never ignores a field it
// cannot honour). "" when the profile keeps the defaults, else the message.
std::string simulate_profile_refusal() {
  const learn::genius_profile& g = active_profile().genius;
  const auto hex = [](unsigned v) {
    char text[8];
    std::snprintf(text, sizeof text, "0x%02x", v);
    return std::string(text);
  };
  const auto crc_text = [&](const genius::crc6_parameters& c) {
    return "polynomial " + hex(c.polynomial) + ", initial " + hex(c.initial) + ", reflect_in " +
           (c.reflect_in ? "true" : "false") + ", reflect_out " + (c.reflect_out ? "true" : "false") + ", xor_out " +
           hex(c.xor_out);
  };
  const auto layout_text = [](const genius::control_layout& l) {
    return "start " + std::to_string(l.start) + ", stop " + std::to_string(l.stop) + ", start_of_block " +
           std::to_string(l.start_of_block) + ", end_of_block " + std::to_string(l.end_of_block) + ", tag_position " +
           (l.position == genius::tag_position::high ? "high" : "low");
  };
  const std::string why = ": `trionet genius simulate` supports only ";
  const std::string built = " (its devices are the library's genius::device, built for the defaults)";
  if (!(g.crc == genius::crc6_parameters{}))
    return "the profile's genius.crc6 is " + crc_text(g.crc) + why + crc_text(genius::crc6_parameters{}) + built;
  if (!(g.control == genius::control_layout{}))
    return "the profile's genius.control is " + layout_text(g.control) + why + layout_text(genius::control_layout{}) +
           built;
  return "";
}

int simulate_main(const words& all) {
  arguments args;
  std::string error;
  if (!parse_arguments(all, genius_simulate_option_list(), args, error)) return fail(error);
  const std::string refused = simulate_profile_refusal();
  if (!refused.empty()) return fail(refused);
  if (!args.positionals.empty()) return fail("unexpected argument '" + host::printable(args.positionals[0]) + "'");
  genius_bus_config config;
  int status = exit_ok;
  if (!parse_rate(args, config.rate, status)) return status;
  if (!args.has("--device")) return fail("simulate needs at least one --device SBA@FEET[:IN_BYTES[/OUT_BYTES]]");
  std::vector<genius_station> stations;
  for (const std::string& text : values_of(args.options["--device"])) {
    genius_station s;
    if (!parse_station(text, s)) {
      return fail("--device '" + host::printable(text) +
                  "' must be SBA@FEET[:IN_BYTES[/OUT_BYTES]] with SBA 0..31, FEET 0..1000000, bytes 0..255");
    }
    stations.push_back(s);
  }
  if (args.has("--controller")) {
    long long sba = 0;
    if (!parse_integer(args.options["--controller"], 0, 31, sba)) return fail("--controller must be an SBA 0..31");
    config.controller = static_cast<int>(sba);
  }
  if (args.has("--skip-us") &&
      !host::parse_real(args.options["--skip-us"], 0.01, 1000, config.skip_us)) {
    return fail("--skip-us must be a number of microseconds from 0.01 (the resolution of the results) to 1000");
  }
  if (args.has("--prop-us-per-2000ft") &&
      !host::parse_real(args.options["--prop-us-per-2000ft"], 0, 1000, config.propagation_us_per_2000ft)) {
    return fail("--prop-us-per-2000ft must be a number of microseconds 0..1000");
  }
  const double bit_us = genius::bit_time_us(config.rate);
  if (args.has("--detect-us") &&
      (!host::parse_real(args.options["--detect-us"], 0, 1000, config.detection_us) || config.detection_us >= bit_us)) {
    return fail("--detect-us must be 0 or more and below one bit time (" + fixed(bit_us, 2) + " us)");
  }
  if (args.has("--scans")) {
    long long scans = 0;
    if (!parse_integer(args.options["--scans"], 1, 100000, scans)) return fail("--scans must be 1..100000");
    config.scans = static_cast<std::uint32_t>(scans);
  }
  config.record_scans = 2;  // the first scan's turns and transmissions are shown: memory stays flat over --scans
  if (args.has("--seed")) {
    long long seed = 0;
    if (!parse_integer(args.options["--seed"], 0, 9223372036854775807LL, seed)) return fail("--seed must be 0..9223372036854775807, got '" + host::printable(args.options["--seed"]) + "'");
    config.seed = static_cast<std::uint64_t>(seed);
  }
  if (args.has("--fault")) {
    for (const std::string& text : values_of(args.options["--fault"])) {
      genius_fault f;
      if (!parse_fault(text, f, error)) return fail(error);
      config.faults.push_back(f);
    }
  }
  const std::string problem = host::check_genius_bus(stations, config);
  if (!problem.empty()) return fail(problem);
  if (config.controller >= 0) {
    // The controller sends the others' OUT_BYTES as blocks, nothing of its own (s37 item 5): bytes given to
    // it would be dropped, and with no OUT_BYTES anywhere it never sends, so no scan opens.
    const std::vector<std::string> texts = values_of(args.options["--device"]);
    bool outputs = false;
    for (std::size_t i = 0; i < stations.size(); ++i) {
      const genius_station& st = stations[i];
      if (st.sba != config.controller) {
        outputs = outputs || st.output_bytes > 0;
      } else if (texts[i].find(':') != std::string::npos && (st.input_bytes > 0 || st.output_bytes > 0)) {
        return fail("--device '" + host::printable(texts[i]) + "' is the controller: it sends the other devices' " +
                    "OUT_BYTES as blocks and no bytes of its own; give it as SBA@FEET or SBA@FEET:0");
      }
    }
    if (!outputs) {
      return fail("--controller " + std::to_string(config.controller) +
                  ": no other device has OUT_BYTES (SBA@FEET:IN_BYTES/OUT_BYTES), so the controller would " +
                  "never send and no scan would open");
    }
  }
  const bool json = args.flag("--json");
  const bool trace = args.flag("--trace");

  genius_bus bus(stations, config);
  if (trace) {
    bus.trace([&](const std::string& line) {
      std::printf("%s\n", line.c_str());
    });
  }
  // --pcap: what a receiver at the scans' opener's place hears, each transmission a record.
  std::ofstream capture_file;
  std::unique_ptr<host::pcapng_writer> writer;
  std::unique_ptr<host::genius_record_splitter> splitter;
  std::uint32_t interface = 0;
  host::pcapng_write_status written = host::pcapng_write_status::ok;
  int write_errno = 0;  // the system's cause of the first failed write
  const auto sink = [&](byte_view record, std::uint64_t time_ns) {
    errno = 0;
    const host::pcapng_write_status s = writer->write(interface, time_ns, record);
    if (written == host::pcapng_write_status::ok) {
      written = s;
      if (s != host::pcapng_write_status::ok) write_errno = errno;
    }
  };
  if (args.has("--pcap")) {
    const std::string& path = args.options.at("--pcap");
    errno = 0;
    capture_file.open(path, std::ios::binary | std::ios::trunc);
    if (!capture_file) {
      return fail_io("cannot write the capture " + host::printable(path) + ": " + std::strerror(errno != 0 ? errno : EIO));
    }
    writer = std::make_unique<host::pcapng_writer>(capture_file, version_line());
    const host::pcapng_interface_result line = writer->add_interface(
        std::string("genius ") + genius::properties(config.rate).name + " (simulated bus)", host::capture_network::genius);
    if (!line) return fail_io("cannot write the capture " + host::printable(path));
    interface = line.id;
    splitter = std::make_unique<host::genius_record_splitter>();
    // Where the scans' opener is: the controller, else the lowest SBA that sends (as the simulator picks it).
    const genius_station* opener = nullptr;
    for (const genius_station& s : stations) {
      if (config.controller >= 0 ? s.sba == config.controller
                                 : s.input_bytes > 0 && (opener == nullptr || s.sba < opener->sba)) {
        opener = &s;
      }
    }
    const double at_ft = (opener != nullptr ? opener : &stations.front())->position_ft;
    bus.monitor(at_ft, [&](double time_us, std::uint16_t word) {
      splitter->push(word, static_cast<std::uint64_t>(std::llround(time_us * 1000.0)), sink);
    });
  }
  const genius_bus_result r = bus.run();
  // A fault timed after the run's end never happened: said, not dropped silently (s37 item 7).
  {
    const std::vector<std::string> texts = values_of(args.options["--fault"]);
    for (std::size_t k = 0; k < config.faults.size() && k < texts.size(); ++k) {
      if (config.faults[k].at_us <= r.end_us) continue;
      note("genius simulate: --fault " + host::printable(texts[k]) + " never happened: the run ended at " +
                   fixed(r.end_us, 3) + " us");
    }
  }
  // The run's time bound (room for every scan, the faults and idle restarts) cut it short: said on stderr,
  // exit 4 with --fail-on-limit (cli.md).
  const auto bound_reached = [&] {
    if (r.complete) return exit_ok;
    return limit_reached("genius simulate: stopped at the run's time bound, " + fixed(r.end_us / 1000.0, 3) +
                         " ms (room for " + std::to_string(config.scans) + " scans), with " +
                         std::to_string(r.scan_us.size()) + " of " + std::to_string(config.scans) +
                         " scans complete");
  };
  if (splitter) {
    // A transmission still under way when the run ends stays out of the capture (it has no Stop yet).
    errno = 0;
    capture_file.flush();
    const int cause = write_errno != 0 ? write_errno : errno;
    if (written != host::pcapng_write_status::ok || !capture_file) {
      return fail_io("cannot write the capture " + host::printable(args.options.at("--pcap")) + ": " +
                     std::strerror(cause != 0 ? cause : EIO));
    }
  }

  // GE's published figure for this bus (docs/protocol.md 3.3): each device's inputs + outputs.
  std::vector<std::uint32_t> io_bytes;
  for (const genius_station& s : stations) {
    io_bytes.push_back(config.controller == s.sba ? 0u : static_cast<std::uint32_t>(s.input_bytes + s.output_bytes));
  }
  const genius::scan_time_result ge =
      genius::bus_scan_time(config.rate, span<const std::uint32_t>(io_bytes.data(), io_bytes.size()));
  const double skip_us = config.skip_us > 0 ? config.skip_us : genius::rule_skip_us(config.rate);
  const double detection_us = config.detection_us >= 0 ? config.detection_us : bit_us / 2;
  std::uint64_t crc_errors = 0, framing_errors = 0, lost = 0;
  for (const genius_device_report& d : r.devices) {
    crc_errors += d.counters.crc_errors;
    framing_errors += d.counters.framing_errors;
    lost += d.counters.lost_transmissions;
  }

  if (json) {
    std::string out = "{\"rate\":" + json_string(genius::properties(config.rate).name) +
                      ",\"skip_us\":" + json_us(skip_us) + ",\"detection_us\":" + json_us(detection_us) +
                      ",\"opener\":" + std::to_string(r.opener) + ",\"scans\":" + std::to_string(r.scan_us.size()) +
                      ",\"complete\":" + (r.complete ? "true" : "false") + ",\"turns\":[";
    for (std::size_t i = 0; i < r.first_scan_turns.size(); ++i) {
      const genius_turn_record& t = r.first_scan_turns[i];
      if (i != 0) out += ',';
      out += "{\"sba\":" + std::to_string(t.sba) + ",\"start_us\":" + json_us(t.due_us) + ",\"what\":\"" +
             what_name(t) + "\"";
      if (t.cancelled) {
        out += ",\"by\":" + std::to_string(t.by) + ",\"arrived_us\":" + json_us(t.arrived_us) +
               ",\"margin_us\":" + json_us(t.due_us - t.arrived_us);
      }
      out += "}";
    }
    out += "],\"scan_ms\":";
    if (r.scan_us.empty()) {
      out += "{\"median\":null,\"max\":null}";
    } else {
      out += "{\"median\":" + json_us(median(r.scan_us) / 1000.0) + ",\"max\":" +
             json_us(*std::max_element(r.scan_us.begin(), r.scan_us.end()) / 1000.0) + "}";
    }
    out += ",\"ge_scan_ms\":{\"sum\":" + exact_ms(ge.sum_ns) + ",\"scan\":" + exact_ms(ge.scan_ns) +
           ",\"minimum_applies\":" + (ge.minimum_applies ? "true" : "false") + "}";
    out += ",\"collisions\":" + std::to_string(r.collisions) +
           ",\"transmissions\":" + std::to_string(r.transmissions_started) +
           ",\"deliveries\":" + std::to_string(r.deliveries) +
           ",\"wrong_deliveries\":" + std::to_string(r.wrong_deliveries) + ",\"crc_errors\":" +
           std::to_string(crc_errors) + ",\"framing_errors\":" + std::to_string(framing_errors) +
           ",\"lost_transmissions\":" + std::to_string(lost) + ",\"devices\":[";
    for (std::size_t i = 0; i < r.devices.size(); ++i) {
      const genius_device_report& d = r.devices[i];
      const genius::device_counters& c = d.counters;
      if (i != 0) out += ',';
      out += "{\"sba\":" + std::to_string(d.sba) + ",\"turns_taken\":" + std::to_string(c.turns_taken) +
             ",\"turns_passed\":" + std::to_string(c.turns_passed) +
             ",\"transmissions_sent\":" + std::to_string(c.transmissions_sent) +
             ",\"collisions\":" + std::to_string(c.collisions) +
             ",\"transmissions_heard\":" + std::to_string(c.transmissions_heard) +
             ",\"crc_errors\":" + std::to_string(c.crc_errors) +
             ",\"framing_errors\":" + std::to_string(c.framing_errors) +
             ",\"wire_errors\":" + std::to_string(c.wire_errors) +
             ",\"lost_transmissions\":" + std::to_string(c.lost_transmissions) +
             ",\"idle_restarts\":" + std::to_string(c.idle_restarts) +
             ",\"deliveries\":" + std::to_string(c.deliveries) + ",\"netstat\":" + std::to_string(d.netstat) + "}";
    }
    out += "]}";
    std::printf("%s\n", out.c_str());
    return bound_reached();
  }

  const genius::rate_properties props = genius::properties(config.rate);
  std::printf("bus: %s (%s), bit %s us, skip %s us (%s), detection %s us, propagation %s us per 2000 ft\n", props.name,
              props.description, fixed(bit_us, 2).c_str(), fixed(skip_us, 2).c_str(),
              config.skip_us > 0 ? "explicit" : "rule", fixed(detection_us, 2).c_str(),
              format_real(config.propagation_us_per_2000ft).c_str());
  std::printf("first scan, after the Stop of SBA %u (time 0):\n", static_cast<unsigned>(r.opener));
  if (r.first_scan_turns.empty()) {
    std::printf("  no turns (%s)\n", stations.size() == 1 ? "no other device" : "the scan's opening Stop never came");
  }
  if (!r.first_scan_turns.empty()) std::printf("  SBA  turn_us  what\n");
  for (const genius_turn_record& t : r.first_scan_turns) {
    std::printf("  %s  %s  %s\n", pad(std::to_string(t.sba), 3).c_str(), pad(fixed(t.due_us, 3), 7).c_str(),
                what_of(t).c_str());
  }
  // The transmissions of the first scan, from its opening Stop to the next.
  if (r.scan_ends_us.size() >= 2) {
    std::printf("transmissions of the first scan (from its opening Stop):\n");
    std::printf("  SBA  start_us    end_us  characters  what\n");
    for (const genius_transmission_record& t : r.transmissions) {
      if (t.start_us < r.scan_ends_us[0] || t.start_us > r.scan_ends_us[1]) continue;
      std::printf("  %s  %s  %s  %s  %s\n", pad(std::to_string(t.sba), 3).c_str(),
                  pad(fixed(t.start_us - r.scan_ends_us[0], 3), 8).c_str(),
                  pad(fixed(t.end_us - r.scan_ends_us[0], 3), 8).c_str(), pad(std::to_string(t.characters), 10).c_str(),
                  t.collided ? "collision" : t.whole ? "whole" : "cut short");
    }
  }
  if (r.scan_us.empty()) {
    std::printf("scans: none complete in %s ms\n", fixed(r.end_us / 1000.0, 3).c_str());
  } else {
    std::printf("scans: %zu%s; scan time median %s ms, max %s ms (simulated)\n", r.scan_us.size(),
                r.complete ? "" : " (the run's time ran out)", fixed(median(r.scan_us) / 1000.0, 3).c_str(),
                fixed(*std::max_element(r.scan_us.begin(), r.scan_us.end()) / 1000.0, 3).c_str());
  }
  std::printf("GE's published figure: sum %s ms, scan time %s ms%s\n", exact_ms(ge.sum_ns).c_str(),
              exact_ms(ge.scan_ns).c_str(), ge.minimum_applies ? " (the bus controller's 3 ms minimum)" : "");
  std::printf("collisions: %zu; transmissions: %llu; deliveries: %llu, %llu not what their sender sent\n", r.collisions,
              static_cast<unsigned long long>(r.transmissions_started), static_cast<unsigned long long>(r.deliveries),
              static_cast<unsigned long long>(r.wrong_deliveries));
  std::printf("  SBA  turns  passed  sent  collisions  heard  crc  framing  wire  lost  idle  deliveries\n");
  for (const genius_device_report& d : r.devices) {
    const genius::device_counters& c = d.counters;
    std::printf("  %s  %s  %s  %s  %s  %s  %s  %s  %s  %s  %s  %s\n", pad(std::to_string(d.sba), 3).c_str(),
                pad(std::to_string(c.turns_taken), 5).c_str(), pad(std::to_string(c.turns_passed), 6).c_str(),
                pad(std::to_string(c.transmissions_sent), 4).c_str(), pad(std::to_string(c.collisions), 10).c_str(),
                pad(std::to_string(c.transmissions_heard), 5).c_str(), pad(std::to_string(c.crc_errors), 3).c_str(),
                pad(std::to_string(c.framing_errors), 7).c_str(), pad(std::to_string(c.wire_errors), 4).c_str(),
                pad(std::to_string(c.lost_transmissions), 4).c_str(), pad(std::to_string(c.idle_restarts), 4).c_str(),
                pad(std::to_string(c.deliveries), 10).c_str());
  }
  return bound_reached();
}

// ---------------------------------------------------------------------------------------------------
// plan

int plan_main(const words& all) {
  arguments args;
  std::string error;
  if (!parse_arguments(all, genius_plan_option_list(), args, error)) return fail(error);
  if (!args.positionals.empty()) return fail("unexpected argument '" + host::printable(args.positionals[0]) + "'");
  genius_plan_options options;
  int status = exit_ok;
  if (!parse_rate(args, options.rate, status)) return status;
  if (!args.has("--device")) return fail("plan needs at least one --device NAME@FEET[=SBA]");
  std::vector<genius_plan_device> devices;
  for (const std::string& text : values_of(args.options["--device"])) {
    genius_plan_device d;
    const std::size_t at = text.rfind('@');
    const std::size_t equals = text.find('=', at == std::string::npos ? 0 : at);
    long long sba = -1;
    if (at == std::string::npos || at == 0 ||
        !host::parse_real(text.substr(at + 1, equals == std::string::npos ? std::string::npos : equals - at - 1), 0,
                          max_feet, d.position_ft) ||
        (equals != std::string::npos && !parse_integer(text.substr(equals + 1), 0, 31, sba))) {
      return fail("--device '" + host::printable(text) + "' must be NAME@FEET or NAME@FEET=SBA (FEET 0..1000000, SBA 0..31)");
    }
    d.name = text.substr(0, at);
    for (const char c : d.name) {
      if (static_cast<unsigned char>(c) < 0x21 || static_cast<unsigned char>(c) > 0x7e || c == '@' || c == '=')
        return fail("--device '" + host::printable(text) +
                    "': a NAME is printable characters without blanks, '@' or '=' (they mark FEET and SBA)");
    }
    d.sba = static_cast<int>(sba);
    devices.push_back(d);
  }
  if (args.has("--prop-us-per-2000ft") &&
      !host::parse_real(args.options["--prop-us-per-2000ft"], 0, 1000, options.propagation_us_per_2000ft)) {
    return fail("--prop-us-per-2000ft must be a number of microseconds 0..1000");
  }
  if (args.has("--detect-us") && !host::parse_real(args.options["--detect-us"], 0, 1000, options.detection_us)) {
    return fail("--detect-us must be a number of microseconds 0..1000");
  }
  const genius_plan_result r = host::plan_genius_bus(devices, options);
  if (!r.error.empty()) return fail(r.error);
  const int verdict = args.flag("--check") && r.checked && !r.given_ok ? exit_check : exit_ok;
  const auto detection_at = [&](genius::rate rate) {
    return options.detection_us >= 0 ? options.detection_us : genius::bit_time_us(rate) / 2;
  };

  if (args.flag("--json")) {
    const auto assignment = [&](const genius_assignment& a) {
      std::string out = "{\"rate\":" + json_string(genius::properties(a.rate).name) + ",\"devices\":[";
      for (std::size_t i = 0; i < devices.size(); ++i) {
        if (i != 0) out += ',';
        out += "{\"name\":" + json_string(devices[i].name) + ",\"feet\":" + format_real(devices[i].position_ft) +
               ",\"sba\":" + std::to_string(a.sba[i]) + "}";
      }
      out += "],\"margins_below_detection\":" + std::to_string(a.too_small) +
             ",\"idle_restart_margins_below_detection\":" + std::to_string(a.restart_too_small) +
             ",\"smallest_margin_us\":" + (a.worst.any ? json_us(a.worst.margin_us) : std::string("null")) +
             ",\"smallest_margin_at_idle_restart\":" + (a.worst.any && a.worst.idle_restart ? "true" : "false") +
             ",\"detection_us\":" + json_us(detection_at(a.rate)) + ",\"overhead_us\":" + json_us(a.overhead_us) +
             ",\"fits_rate\":" + (a.fits_rate ? "true" : "false") + "}";
      return out;
    };
    std::string out = std::string("{\"checked\":") + (r.checked ? "true" : "false") + ",\"given\":" +
                      assignment(r.given) + ",\"given_ok\":" + (r.given_ok ? "true" : "false") +
                      ",\"found\":" + (r.found ? "true" : "false");
    if (r.found) out += ",\"plan\":" + assignment(r.plan);
    out += ",\"remedies\":[";
    for (std::size_t i = 0; i < r.remedies.size(); ++i) {
      if (i != 0) out += ',';
      out += "{\"remedy\":" + json_string(r.remedies[i].name) + ",\"why\":" + json_string(r.remedies[i].reason) + "}";
    }
    out += "]";
    if (!r.found) out += ",\"why_not\":" + json_string(r.why_not);
    out += "}";
    std::printf("%s\n", out.c_str());
    return verdict;
  }

  const auto show = [&](const genius_assignment& a) {
    std::size_t width = 4;
    for (const genius_plan_device& d : devices) width = std::max(width, d.name.size());
    std::printf("  %s  %s  SBA\n", (std::string("name") + std::string(width - 4, ' ')).c_str(), pad("feet", 7).c_str());
    for (std::size_t i = 0; i < devices.size(); ++i) {
      std::printf("  %s  %s  %s\n", (devices[i].name + std::string(width - devices[i].name.size(), ' ')).c_str(),
                  pad(format_real(devices[i].position_ft), 7).c_str(), pad(std::to_string(a.sba[i]), 3).c_str());
    }
    if (a.worst.any) {
      std::printf("  smallest margin %s us (%s %s's Stop, %s's turn after %s's start bit); detection %s us\n",
                  fixed(a.worst.margin_us, 2).c_str(),
                  a.worst.idle_restart ? "at an idle restart after" : "after", devices[a.worst.after].name.c_str(),
                  devices[a.worst.second].name.c_str(), devices[a.worst.first].name.c_str(),
                  fixed(detection_at(a.rate), 2).c_str());
    }
  };
  const genius::rate_properties asked = genius::properties(options.rate);
  std::printf("%s at %s (%s):\n", r.checked ? "the SBAs given" : "the devices in the order given, from SBA 0",
              asked.name, asked.description);
  show(r.given);
  if (r.given_ok) {
    std::printf("no collision risk: every margin after every device's Stop and at an idle restart is at least the "
                "detection time\n");
  } else if (!r.given.fits_rate) {
    std::printf("not possible at %s: the bus is %s ft long with %zu devices (%s allows %u ft and %u devices)\n", asked.name,
                format_real(r.given.bus_length_ft).c_str(), devices.size(), asked.name,
                static_cast<unsigned>(asked.max_length_ft), static_cast<unsigned>(asked.max_devices));
  } else {
    std::printf("collision risk: %zu margin%s below the detection time\n", r.given.too_small,
                r.given.too_small == 1 ? "" : "s");
  }
  if (r.given_ok) return verdict;
  if (!r.found) {
    std::printf("no plan: %s\n", r.why_not.c_str());
    return verdict;
  }
  const genius::rate_properties used = genius::properties(r.plan.rate);
  std::printf("plan at %s (%s), without collision risk:\n", used.name, used.description);
  show(r.plan);
  for (const genius_remedy& m : r.remedies) std::printf("remedy: %s: %s\n", m.name.c_str(), m.reason.c_str());
  std::printf("turn overhead per scan: %s us (32 skip times and the propagation between turns)\n",
              fixed(r.plan.overhead_us, 2).c_str());
  return verdict;
}

}  // namespace

const char* const genius_simulate_usage =
    "usage: trionet genius simulate --rate 153.6s|153.6e|76.8|38.4 --device SBA@FEET[:IN_BYTES[/OUT_BYTES]] ...\n"
    "                               [--controller SBA] [--skip-us U] [--scans N] [--fault SPEC] ... [--trace]\n"
    "                               [--pcap FILE] [--json] [--prop-us-per-2000ft P] [--detect-us D] [--seed S]\n"
    "Runs a Genius bus of device nodes (the library's genius::device; the controller a genius::bus_controller)\n"
    "on a modelled line: each device at FEET sends IN_BYTES of inputs (default 1) as a broadcast at its turns;\n"
    "with --controller, that device sends every other device its OUT_BYTES as a block once a scan, and no\n"
    "bytes of its own (bytes given to it, or no OUT_BYTES on any other device, are refused). The run\n"
    "starts with every device powered up and lasts N scans (default 10): a scan runs from a Stop of the\n"
    "controller (else of the lowest SBA that sends) to its next. A fault timed after the run's end (it never\n"
    "happened) and a run its time bound cut short are said on stderr. Prints the turns after the first scan's\n"
    "opening Stop (each device's turn, and the start bit that cancelled it), the transmissions of that scan,\n"
    "the measured scan time beside GE's published figure, collisions, deliveries (each checked against what\n"
    "its sender sent) and every device's counters. SPEC (times in microseconds from the start):\n"
    "  noise:FEET@T+D   random levels on the line at FEET for D us      off:SBA@T+D   device SBA off for D us\n"
    "  stop:SBA@T+D     SBA stops in the middle of its next transmission from T on, then is off for D us\n"
    "  cut:FEET@T+D     the line cut at FEET for D us\n"
    "--trace prints every transmission, collision, fault and passed turn as it happens; --pcap writes the\n"
    "characters a receiver at the opener's place heard, one record per transmission (a transmission still\n"
    "under way when the run ends is left out; docs/wireshark.md); --json prints one object.\n";

const char* const genius_plan_usage =
    "usage: trionet genius plan --rate 153.6s|153.6e|76.8|38.4 --device NAME@FEET[=SBA] ... [--json] [--check]\n"
    "                           [--prop-us-per-2000ft P] [--detect-us D]\n"
    "Assigns SBAs so that every margin between consecutive turns is at least the detection time, after every\n"
    "device's Stop (genius timing) and at an idle restart, with the shortest turn overhead per scan; with\n"
    "NAME@FEET=SBA for every device, checks those first. Removes a collision risk by resequencing SBAs along\n"
    "the bus and skipping an SBA (free: a scan's skip times add up to 32 whatever the SBAs), then by 153.6e,\n"
    "then by a lower rate, in that order of cost, and says which it used and why. --check: exit status 3 when\n"
    "the SBAs given have a collision risk.\n";

const option_list& genius_simulate_option_list() {
  static const option_list options = {
      {"--rate", "R", "153.6s 153.6e 76.8 38.4", "the bus's bit rate: 153.6s, 153.6e, 76.8 or 38.4"},
      {"--device", "SBA@FEET[:IN_BYTES[/OUT_BYTES]]", "", "a device node, its position and its bytes", true},
      {"--controller", "SBA", "", "the device that is the bus controller (sends outputs as blocks)"},
      {"--skip-us", "U", "", "the skip time in microseconds"},
      {"--scans", "N", "", "the scans to run (default 10)"},
      {"--fault", "SPEC", "", "a fault: noise:FEET@T+D, off:SBA@T+D, stop:SBA@T+D or cut:FEET@T+D", true},
      {"--trace", nullptr, "", "print every transmission, collision, fault and passed turn"},
      {"--pcap", "FILE", "@file", "write the characters heard at the opener's place to a capture"},
      {"--json", nullptr, "", "the results as one JSON object"},
      {"--prop-us-per-2000ft", "P", "", "the propagation delay per 2000 feet in microseconds"},
      {"--detect-us", "D", "", "the detection time in microseconds"},
      {"--seed", "S", "", "the seed of the noise faults' random levels"},
  };
  return options;
}

const option_list& genius_plan_option_list() {
  static const option_list options = {
      {"--rate", "R", "153.6s 153.6e 76.8 38.4", "the bus's bit rate: 153.6s, 153.6e, 76.8 or 38.4"},
      {"--device", "NAME@FEET[=SBA]", "", "a device, its position and (to check) its SBA", true},
      {"--json", nullptr, "", "the plan as JSON"},
      {"--check", nullptr, "", "exit status 3 when the SBAs given have a collision risk"},
      {"--prop-us-per-2000ft", "P", "", "the propagation delay per 2000 feet in microseconds"},
      {"--detect-us", "D", "", "the detection time in microseconds"},
  };
  return options;
}

int genius_simulate_main(const words& args) { return simulate_main(args); }
int genius_plan_main(const words& args) { return plan_main(args); }

}  // namespace trionet::cli
