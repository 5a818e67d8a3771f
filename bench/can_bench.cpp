// CAN VR exchange benchmarks, per frame: encoding a VR message (from parts, and from a double with decimal
// rounding), decoding a received frame, and a node's whole receive (route, decode, write VR()).
// Throughput is in frames per second (SetItemsProcessed) and data bytes per second (8 per frame).
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "trionet/can/frame.hpp"
#include "trionet/can/node.hpp"
#include "trionet/can/port.hpp"
#include "trionet/can/vr_codec.hpp"
#include "trionet/vr.hpp"
#include "workloads.hpp"

namespace {

using namespace trionet::can;
namespace tb = trionet::bench;

constexpr std::size_t frames_per_iteration = 256;

void per_frame(benchmark::State& state) {
  const auto frames = static_cast<std::int64_t>(state.iterations()) * std::int64_t{frames_per_iteration};
  state.SetItemsProcessed(frames);
  state.SetBytesProcessed(frames * std::int64_t{vr_message_size});
}

std::vector<vr_message> messages_of(const std::vector<frame>& frames) {
  std::vector<vr_message> messages;
  for (const frame& f : frames) messages.push_back(decode_vr_frame(f).message);
  return messages;
}

void BM_can_encode_parts(benchmark::State& state) {
  const std::vector<vr_message> messages = messages_of(tb::vr_frames(frames_per_iteration));
  frame out;
  for (auto _ : state) {
    for (const vr_message& m : messages) {
      const encode_status error = encode_vr_message(m, out.data);
      benchmark::DoNotOptimize(error);
      benchmark::DoNotOptimize(out);
    }
  }
  per_frame(state);
}
BENCHMARK(BM_can_encode_parts);

void BM_can_encode_double(benchmark::State& state) {
  std::vector<double> values;
  for (const vr_message& m : messages_of(tb::vr_frames(frames_per_iteration)))
    values.push_back(to_double(m.value));
  frame out;
  for (auto _ : state) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      const encode_status error = encode_vr(static_cast<std::uint16_t>(i), values[i], out.data);
      benchmark::DoNotOptimize(error);
      benchmark::DoNotOptimize(out);
    }
  }
  per_frame(state);
}
BENCHMARK(BM_can_encode_double);

void BM_can_decode(benchmark::State& state) {
  const std::vector<frame> frames = tb::vr_frames(frames_per_iteration);
  for (auto _ : state) {
    for (const frame& f : frames) {
      const decode_result r = decode_vr_frame(f);
      benchmark::DoNotOptimize(r);
    }
  }
  per_frame(state);
}
BENCHMARK(BM_can_decode);

void BM_can_node_receive(benchmark::State& state) {
  struct null_port final : port {
    transmit_status send(const frame&) noexcept override { return transmit_status::ok; }
  } bus;
  trionet::vr_table<256> vr;
  vr_exchange_node node(make_node_address(5, 1).address, bus, vr);
  const std::vector<frame> frames = tb::vr_frames(frames_per_iteration);
  for (auto _ : state) {
    for (const frame& f : frames) {
      const receive_result r = node.receive(f);
      benchmark::DoNotOptimize(r);
    }
  }
  const auto expected = static_cast<std::uint64_t>(state.iterations()) * frames_per_iteration;
  if (node.counters().written != static_cast<std::uint32_t>(expected)) {
    state.SkipWithError("the node did not write every frame");
  }
  per_frame(state);
}
BENCHMARK(BM_can_node_receive);

}  // namespace
