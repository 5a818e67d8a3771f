// The BASIC interpreter's speed beside the plain C++ ring simulator, measured in the same run; medians of
// seven repetitions, the three measurements taking turns in each (so a busy machine slows all of them), in
// CPU time of the process (time the shared machine gives to others counts less).
//
//   interpreter      a statement-heavy program (arithmetic, IF/ELSE, VR(), GOSUB, FOR) on a simulated Motion
//                    Coordinator of a two-node ring, 1000 statements per byte-time: statements per second
//   simulator alone  bench/simulated_ring.hpp: four Motion Coordinators with continuous traffic and no
//                    programs: node-byte steps per second
//   machine minute   the manual's Example 1 (one MC running its program, two keypads, a key every 0.8 s) for
//                    750000 byte-times, one minute at 125 kbit/s, at the default 1 statement per byte-time
//   ring minute      15 Motion Coordinators, each running a program that moves two axes back and forth
//                    (MOVE, WAIT IDLE), counts its cycles and SENDs the count to the next node, for one minute
//                    of ring time at the defaults (1 statement per byte-time, 1 ms servo period)
//
// Usage: trionet_basic_speed [--quick]. Exit status 1 if a run goes wrong (the program stops, the ring flags an
// error), 0 otherwise, whether or not the target (5 M statements per second) is met.
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "embedded_files.hpp"
#include "ring_network.hpp"
#include "simulated_ring.hpp"

namespace {

constexpr const char* heavy_program =
    "loop:\n"
    "  i=i+1\n"
    "  x=(x*3+i) MOD 1000\n"
    "  IF x>500 THEN y=y+1 ELSE y=y-1\n"
    "  VR(10)=x/7\n"
    "  GOSUB sub\n"
    "  FOR j=1 TO 3\n"
    "    s=s+j*VR(10)\n"
    "  NEXT j\n"
    "  GOTO loop\n"
    "sub:\n"
    "  z=z+1\n"
    "  RETURN\n";

// A station of the 15-node ring: two axes always on the move, a direct variable transfer every cycle.
constexpr const char* station_program =
    "WDOG=ON\n"
    "BASE(0): SERVO=ON: UNITS=100: SPEED=200: ACCEL=2000: DECEL=2000\n"
    "BASE(1): SERVO=ON: UNITS=10: SPEED=50: ACCEL=500: DECEL=500\n"
    "BASE(0)\n"
    "cycle:\n"
    "  MOVE(40)\n"
    "  MOVE(25) AXIS(1)\n"
    "  WAIT IDLE\n"
    "  MOVE(-40)\n"
    "  MOVE(-25) AXIS(1)\n"
    "  WAIT IDLE\n"
    "  WAIT IDLE AXIS(1)\n"
    "  n=n+1\n"
    "  SEND(10,1,100,n)\n"
    "  GOTO cycle\n";

[[noreturn]] void fail(const std::string& why) {
  std::fprintf(stderr, "trionet_basic_speed: %s\n", why.c_str());
  std::exit(1);
}

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

double seconds_since(double start) {
  return cpu_seconds() - start;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::unique_ptr<trionet::host::ring_network> network(const std::vector<trionet::host::node_spec>& nodes,
                                                     std::uint32_t statements_per_byte_time) {
  trionet::host::network_config config;
  config.statements_per_byte_time = statements_per_byte_time;
  std::string error;
  auto net = trionet::host::ring_network::build(nodes, config, error);
  if (!net) fail(error);
  return net;
}

trionet::host::node_spec mc(const std::string& name, const std::string& text) {
  trionet::host::node_spec n;
  n.program_name = name;
  n.program_text = text;
  return n;
}

// Statements per second.
double interpreter(std::uint64_t byte_times) {
  constexpr std::uint32_t per_byte_time = 1000;
  auto net = network({mc("heavy.bas", heavy_program), trionet::host::node_spec{}}, per_byte_time);
  const double start = cpu_seconds();
  for (std::uint64_t t = 0; t < byte_times; ++t) net->step();
  const double elapsed = seconds_since(start);
  const trionet::host::node_report r = net->report(1);
  if (r.state != "running" || r.statements != byte_times * per_byte_time)
    fail("the statement-heavy program did not run all its statements: " + r.state + " " + r.error);
  return static_cast<double>(r.statements) / elapsed;
}

// Node-byte steps per second.
double simulator(std::uint64_t byte_times) {
  static trionet::bench::simulated_ring ring;  // static: four nodes with their VR tables
  const double start = cpu_seconds();
  ring.run(byte_times);
  const double elapsed = seconds_since(start);
  if (!ring.healthy()) fail("the plain simulator's ring flagged an error");
  return static_cast<double>(byte_times * trionet::bench::simulated_ring::nodes) / elapsed;
}

// Seconds to simulate `byte_times` of the manual's Example 1 with a key every 10000 byte-times.
double machine_time(std::uint64_t byte_times) {
  const trionet::host::embedded_file* file = trionet::host::find_embedded_file("examples/manual/example1.bas");
  if (file == nullptr) fail("examples/manual/example1.bas is not built in");
  trionet::host::node_spec keypad;
  keypad.what = trionet::host::node_spec::kind::keypad;
  auto net = network({mc(file->path, std::string(file->text())), keypad, keypad}, 1);
  std::string keys = "wait=200";
  for (std::uint64_t t = 200; t + 10000 < byte_times; t += 10000) keys += (t / 10000) % 2 == 0 ? " 1:up" : " 2:3";
  std::string error;
  if (!net->set_keys(keys, error)) fail(error);
  const double start = cpu_seconds();
  for (std::uint64_t t = 0; t < byte_times; ++t) net->step();
  const double elapsed = seconds_since(start);
  const trionet::host::node_report r = net->report(1);
  if (r.state != "running" || r.netstat != 0 || r.statements < byte_times - 1000)
    fail("Example 1 did not keep running: " + r.state + " " + r.error);
  return elapsed;
}

// Seconds to simulate `byte_times` of 15 stations, each of which must complete `min_cycles` cycles (about 40 in
// a minute of ring time, 4 in the tenth of it that --quick times).
double ring_time(std::uint64_t byte_times, double min_cycles) {
  std::vector<trionet::host::node_spec> nodes;
  for (int i = 0; i < 15; ++i) nodes.push_back(mc("station.bas", station_program));
  auto net = network(nodes, 1);
  const double start = cpu_seconds();
  for (std::uint64_t t = 0; t < byte_times; ++t) net->step();
  const double elapsed = seconds_since(start);
  for (std::size_t i = 1; i <= 15; ++i) {
    const trionet::host::node_report r = net->report(i);
    double cycles = 0;
    for (const auto& [name, value] : r.variables) {
      if (name == "n") cycles = value;
    }
    if (r.state == "failed" || r.netstat != 0 || cycles < min_cycles || r.vrs.empty())
      fail("station " + std::to_string(i) + " of the 15-node ring did not keep moving: " + r.state + ", " +
           std::to_string(cycles) + " cycles, NETSTAT " + std::to_string(r.netstat) + " " + r.error);
  }
  return elapsed;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int repetitions = 7;
  const std::uint64_t interpreter_byte_times = quick ? 2000 : 20000;  // x 1000 statements
  const std::uint64_t simulator_byte_times = quick ? 500000 : 5000000;
  const std::uint64_t minute = 750000;  // 60 s at 125 kbit/s, 10 bits per byte
  std::vector<double> statements, steps, minutes, rings;
  for (int i = 0; i < repetitions; ++i) {
    statements.push_back(interpreter(interpreter_byte_times));
    steps.push_back(simulator(simulator_byte_times));
    minutes.push_back(machine_time(minute));
    rings.push_back(ring_time(quick ? minute / 10 : minute, quick ? 3 : 10));
  }
  const double per_second = median(statements);
  const double steps_per_second = median(steps);
  const double minute_seconds = median(minutes);
  std::printf("BASIC interpreter beside the plain simulator: medians of %d repetitions in one run%s\n", repetitions,
              quick ? " (quick)" : "");
  std::printf("  interpreter, statement-heavy program, 1000 statements per byte-time: %7.1f M statements/s"
              "  (%.1f ns per statement)\n",
              per_second / 1e6, 1e9 / per_second);
  std::printf("  simulator alone, 4 MCs with continuous traffic, no programs:        %7.1f M node-byte steps/s"
              "  (%.1f ns per step)\n",
              steps_per_second / 1e6, 1e9 / steps_per_second);
  std::printf("  ratio: one BASIC statement costs %.2f node-byte steps of the plain simulator\n",
              steps_per_second / per_second);
  std::printf("  one minute of ring time (750000 byte-times at 125 kbit/s), the manual's Example 1 at 1 statement "
              "per byte-time: %.3f s\n",
              minute_seconds);
  const double ring_seconds = median(rings) * (quick ? 10 : 1);
  std::printf("  one minute of ring time, 15 Motion Coordinators with programs and moving axes: %.3f s%s\n",
              ring_seconds, quick ? " (a tenth of it timed, x 10)" : "");
  std::printf("  target >= 5 M statements/s: %s\n", per_second >= 5e6 ? "PASS" : "MISS");
  std::printf("  target 15-node minute < 1 s: %s\n", ring_seconds < 1 ? "PASS" : "MISS");
  return 0;
}
