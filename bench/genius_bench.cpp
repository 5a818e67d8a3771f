// Simulator speed: a Genius bus of real device nodes (src/sim/genius_bus.hpp), laid out as genius_layout.hpp
// says. Reported: simulated bit times per second (items: bus time / one bit time), and device-bit steps per
// second (stations x bit times).
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "genius_bus.hpp"
#include "genius_layout.hpp"

namespace {

void BM_genius_simulator(benchmark::State& state) {
  const std::size_t devices = static_cast<std::size_t>(state.range(0));
  const auto stations = trionet::bench::genius_layout(devices);
  const trionet::host::genius_bus_config config = trionet::bench::genius_config(50);
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
