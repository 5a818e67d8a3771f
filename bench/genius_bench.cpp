// Simulator speed: a Genius bus of real device nodes (src/sim/genius_bus.hpp) at 153.6 kbit/s, a bus
// controller sending every device its outputs as blocks once a scan, every device broadcasting its inputs at
// its turn, new data every turn; the stations spread over 2000 ft, so that every start bit and character
// reaches each device at its own time. Reported: simulated bit times per second (items: bus time / one bit
// time), and device-bit steps per second (stations x bit times).
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "genius_bus.hpp"

namespace {

std::vector<trionet::host::genius_station> layout(std::size_t devices) {
  std::vector<trionet::host::genius_station> stations;
  stations.push_back({31, 0.0, 0, 0});  // the bus controller: it only sends outputs (blocks)
  for (std::size_t i = 0; i < devices; ++i) {
    trionet::host::genius_station st;
    st.sba = static_cast<std::uint8_t>(i);
    st.position_ft = 2000.0 * static_cast<double>(i + 1) / static_cast<double>(devices);
    st.input_bytes = static_cast<std::uint16_t>(2 + i % 7);
    st.output_bytes = static_cast<std::uint16_t>(1 + i % 4);
    stations.push_back(st);
  }
  return stations;
}

void BM_genius_simulator(benchmark::State& state) {
  const std::size_t devices = static_cast<std::size_t>(state.range(0));
  const auto stations = layout(devices);
  trionet::host::genius_bus_config config;
  config.controller = 31;
  config.scans = 50;
  config.record_turns = false;
  if (!trionet::host::check_genius_bus(stations, config).empty()) {
    state.SkipWithError("the layout is refused");
    return;
  }
  double bit_times = 0;
  std::uint64_t events = 0;
  for (auto _ : state) {
    trionet::host::genius_bus bus(stations, config);
    const trionet::host::genius_bus_result r = bus.run();
    if (!r.complete || r.collisions != 0 || r.wrong_deliveries != 0 || r.scan_us.size() < config.scans) {
      state.SkipWithError("the bus did not complete its scans cleanly");
      return;
    }
    bit_times += r.end_us * 1e6 / static_cast<double>(bus.bit_ps());
    events += r.events;
    benchmark::DoNotOptimize(r.deliveries);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(bit_times));
  state.counters["bit_times"] = benchmark::Counter(bit_times, benchmark::Counter::kIsRate);
  state.counters["device_bit_steps"] =
      benchmark::Counter(bit_times * static_cast<double>(stations.size()), benchmark::Counter::kIsRate);
  state.counters["events"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_genius_simulator)->Arg(8)->Arg(30)->Unit(benchmark::kMillisecond);

}  // namespace
