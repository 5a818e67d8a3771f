// Simulator speed: a ring of four Motion Coordinators with continuous traffic. Each node, whenever its
// transmit queue has room, SENDs a direct variable transfer, alternately to the next node (hops 1) and to the
// one after (hops 2, forwarded by the next node). Reported: node-byte steps per second = nodes x byte-times
// simulated per second (items), and bytes delivered over links per second.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>

#include "simulated_ring.hpp"

namespace {

void BM_ring_simulator_4_nodes(benchmark::State& state) {
  trionet::bench::simulated_ring ring;
  constexpr std::uint64_t steps_per_iteration = 1024;
  for (auto _ : state) {
    ring.run(steps_per_iteration);
    benchmark::ClobberMemory();
  }
  if (!ring.healthy()) state.SkipWithError("a node flagged an error or the ring went quiet");
  const auto steps = static_cast<std::int64_t>(state.iterations()) * std::int64_t{steps_per_iteration};
  state.SetItemsProcessed(steps * static_cast<std::int64_t>(trionet::bench::simulated_ring::nodes));
  state.counters["byte_times"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["delivered"] =
      benchmark::Counter(static_cast<double>(ring.delivered()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ring_simulator_4_nodes);

}  // namespace
