// Ring benchmarks: the streaming decoder (byte at a time and bulk) on character streams and on direct
// variable transfers, and a Motion Coordinator's receive path for messages passing through and for messages
// to it. Throughput is in bytes of ring traffic per second (SetBytesProcessed).
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "trionet/ring/decoder.hpp"
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/vr.hpp"
#include "workloads.hpp"

namespace {

using trionet::byte_view;
using namespace trionet::ring;
namespace tb = trionet::bench;

// What a consumer of decoded messages keeps: enough of every result that nothing can be optimised away.
struct tally {
  std::uint64_t messages = 0;
  std::uint64_t characters = 0;
  std::uint64_t fields = 0;
  std::uint64_t other = 0;

  void operator()(const decode_result& r) noexcept {
    if (r.status == decode_status::ok) {
      ++messages;
      characters += r.msg.text.size();
      fields += r.msg.vr ^ static_cast<std::uint64_t>(r.msg.value);
    } else {
      ++other;
    }
  }
};

// Every message decoded, none in error, every character delivered (none in a variable stream).
void report(benchmark::State& state, const tally& t, const std::vector<std::uint8_t>& stream) {
  const bool characters = type_of(stream[0]) == static_cast<std::uint8_t>(message_type::character);
  if (t.other != 0 || t.characters != (characters ? t.messages * tb::characters_per_message : 0)) {
    state.SkipWithError("the decoder reported an error or lost characters on a valid stream");
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(stream.size()));
  state.counters["messages"] =
      benchmark::Counter(static_cast<double>(t.messages), benchmark::Counter::kIsRate);
}

void decoder_bytewise(benchmark::State& state, const std::vector<std::uint8_t>& stream) {
  decoder<> d;
  tally t;
  for (auto _ : state) {
    for (std::uint8_t b : stream) {
      const decode_result r = d.push(b);
      if (r.status != decode_status::incomplete) t(r);
    }
    benchmark::DoNotOptimize(t);
    benchmark::ClobberMemory();
  }
  report(state, t, stream);
}

void decoder_bulk(benchmark::State& state, const std::vector<std::uint8_t>& stream) {
  decoder<> d;
  tally t;
  for (auto _ : state) {
    benchmark::DoNotOptimize(stream.data());
    d.push(byte_view(stream.data(), stream.size()), t);
    benchmark::DoNotOptimize(t);
    benchmark::ClobberMemory();
  }
  report(state, t, stream);
}

void BM_ring_decoder_characters_bytewise(benchmark::State& state) {
  decoder_bytewise(state, tb::character_stream(1));
}
void BM_ring_decoder_characters_bulk(benchmark::State& state) {
  decoder_bulk(state, tb::character_stream(1));
}
void BM_ring_decoder_variables_bytewise(benchmark::State& state) {
  decoder_bytewise(state, tb::variable_stream(1));
}
void BM_ring_decoder_variables_bulk(benchmark::State& state) {
  decoder_bulk(state, tb::variable_stream(1));
}
BENCHMARK(BM_ring_decoder_characters_bytewise);
BENCHMARK(BM_ring_decoder_characters_bulk);
BENCHMARK(BM_ring_decoder_variables_bytewise);
BENCHMARK(BM_ring_decoder_variables_bulk);

// A node that forwards everything (hops 2): each received byte goes into the forward buffer and the link's
// transmitter takes it straight out again, as a UART interrupt with both RX and TX ready would.
void mc_forward(benchmark::State& state, const std::vector<std::uint8_t>& stream) {
  trionet::vr_table<256> vr;
  motion_coordinator<> mc(vr);
  std::uint64_t sent = 0;
  for (auto _ : state) {
    for (std::uint8_t b : stream) {
      mc.receive(b);
      std::uint8_t out = 0;
      if (mc.transmit(out)) sent += out;
    }
    benchmark::DoNotOptimize(sent);
    benchmark::ClobberMemory();
  }
  if (mc.forwarding_counters().forwards_lost != 0 || mc.netstat() != 0) {
    state.SkipWithError("the node lost or rejected forwarded traffic");
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(stream.size()));
}

// The same through the calls a DMA-fed node uses, dma_chunk bytes at a time with room for twice that to send:
// `chunk(mc, in, out)` is receive(byte_view) then transmit(byte_buffer).
template <class Chunk>
void mc_forward_dma(benchmark::State& state, const std::vector<std::uint8_t>& stream, Chunk chunk) {
  trionet::vr_table<256> vr;
  motion_coordinator<> mc(vr);
  std::uint8_t out[tb::dma_chunk * 2];
  std::uint64_t sent = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < stream.size(); i += tb::dma_chunk) {
      const std::size_t n = stream.size() - i < tb::dma_chunk ? stream.size() - i : tb::dma_chunk;
      sent += chunk(mc, byte_view(&stream[i], n), trionet::byte_buffer(out, sizeof out));
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  const auto bytes = static_cast<std::uint64_t>(state.iterations()) * stream.size();
  if (mc.forwarding_counters().forwards_lost != 0 || mc.netstat() != 0 || sent != bytes) {
    state.SkipWithError("the node lost, rejected or held back forwarded traffic");
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
void mc_forward_bulk(benchmark::State& state, const std::vector<std::uint8_t>& stream) {
  mc_forward_dma(state, stream, [](motion_coordinator<>& mc, byte_view in, trionet::byte_buffer out) {
    mc.receive(in);
    return mc.transmit(out);
  });
}
void BM_ring_mc_forward_characters(benchmark::State& state) {
  mc_forward(state, tb::character_stream(2));
}
void BM_ring_mc_forward_variables(benchmark::State& state) {
  mc_forward(state, tb::variable_stream(2));
}
void BM_ring_mc_forward_characters_bulk(benchmark::State& state) {
  mc_forward_bulk(state, tb::character_stream(2));
}
void BM_ring_mc_forward_variables_bulk(benchmark::State& state) {
  mc_forward_bulk(state, tb::variable_stream(2));
}
BENCHMARK(BM_ring_mc_forward_characters);
BENCHMARK(BM_ring_mc_forward_variables);
BENCHMARK(BM_ring_mc_forward_characters_bulk);
BENCHMARK(BM_ring_mc_forward_variables_bulk);
// A host's POSIX link (src/host/posix_link.cpp): each read() of up to 256 bytes into the node, then what one
// write() of 256 bytes takes, a byte at a time through the byte port (as it was) or with the bulk calls.
void host_link(benchmark::State& state, bool bulk) {
  const std::vector<std::uint8_t> stream = tb::character_stream(2);
  trionet::vr_table<256> vr;
  tb::host_mc mc(vr);
  trionet::byte_port& port = mc;
  std::uint8_t out[tb::host_chunk];
  std::uint64_t sent = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < stream.size(); i += tb::host_chunk) {
      const std::size_t n = stream.size() - i < tb::host_chunk ? stream.size() - i : tb::host_chunk;
      if (bulk) {
        mc.receive(byte_view(&stream[i], n));
        sent += mc.transmit(trionet::byte_buffer(out, sizeof out));
      } else {
        for (std::size_t j = 0; j < n; ++j) port.receive(stream[i + j]);
        std::size_t m = 0;
        while (m < sizeof out && port.transmit(out[m])) ++m;
        sent += m;
      }
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  const auto bytes = static_cast<std::uint64_t>(state.iterations()) * stream.size();
  if (mc.forwarding_counters().forwards_lost != 0 || mc.netstat() != 0 || sent != bytes) {
    state.SkipWithError("the node lost, rejected or held back forwarded traffic");
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
void BM_ring_host_link_characters_bytewise(benchmark::State& state) { host_link(state, false); }
void BM_ring_host_link_characters_bulk(benchmark::State& state) { host_link(state, true); }
BENCHMARK(BM_ring_host_link_characters_bytewise);
BENCHMARK(BM_ring_host_link_characters_bulk);

// Character transfers to the node (hops 1). The program reads them with GET#4 after each message (the
// receive buffer holds 256 characters), and that reading is part of the time measured here.
void BM_ring_mc_deliver_characters_with_get(benchmark::State& state) {
  const std::vector<std::uint8_t> stream = tb::character_stream(1);
  const std::size_t frame = tb::characters_per_message + framing_length;
  trionet::vr_table<256> vr;
  motion_coordinator<> mc(vr);
  std::uint64_t read = 0;
  for (auto _ : state) {
    for (std::size_t start = 0; start < stream.size(); start += frame) {
      for (std::size_t i = start; i < start + frame; ++i) mc.receive(stream[i]);
      while (const get_result g = mc.get(4)) read += g.value;
    }
    benchmark::DoNotOptimize(read);
    benchmark::ClobberMemory();
  }
  if (mc.netstat() != 0) state.SkipWithError("the node flagged an error on a valid stream");
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(stream.size()));
}
BENCHMARK(BM_ring_mc_deliver_characters_with_get);

// Direct variable transfers to the node: decoded, CRC checked and written into VR().
void BM_ring_mc_deliver_variables(benchmark::State& state) {
  const std::vector<std::uint8_t> stream = tb::variable_stream(1);
  trionet::vr_table<256> vr;
  motion_coordinator<> mc(vr);
  for (auto _ : state) {
    for (std::uint8_t b : stream) mc.receive(b);
    benchmark::DoNotOptimize(vr[0]);
    benchmark::ClobberMemory();
  }
  if (mc.netstat() != 0) state.SkipWithError("the node flagged an error on a valid stream");
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(stream.size()));
}
BENCHMARK(BM_ring_mc_deliver_variables);

}  // namespace
