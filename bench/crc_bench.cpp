// CRC-16/CCITT-FALSE: trionet's table, sliced and table-free policies against Boost.CRC's crc_optimal, in the
// same run.
//
// "12 bytes": 256 independent 12-byte messages per iteration (the CRC of a direct variable transfer covers
// V0..X9, 12 bytes); "4096 bytes": one 4 KiB buffer per iteration. Every variant gets the same bytes, and the
// results are checked against each other once before timing.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "boost_crc.hpp"
#include "trionet/ring/crc.hpp"
#include "workloads.hpp"

namespace {

using trionet::ring::crc16_ccitt_false_table;
using trionet::ring::crc16_ccitt_false_bitwise;
namespace tb = trionet::bench;

constexpr std::size_t short_length = 12;
constexpr std::size_t short_messages = 256;
constexpr std::size_t long_length = 4096;

struct table_crc {
  static std::uint16_t compute(const std::uint8_t* data, std::size_t size) noexcept {
    return crc16_ccitt_false_table::compute(data, size);
  }
};
struct sliced_crc {
  static std::uint16_t compute(const std::uint8_t* data, std::size_t size) noexcept {
    return trionet::ring::crc16_ccitt_false_sliced::compute(data, size);
  }
};
struct bitwise_crc {
  static std::uint16_t compute(const std::uint8_t* data, std::size_t size) noexcept {
    return crc16_ccitt_false_bitwise::compute(data, size);
  }
};
struct boost_reference {
  static std::uint16_t compute(const std::uint8_t* data, std::size_t size) noexcept {
    return tb::boost_crc16_ccitt_false(data, size);
  }
};

// The three must agree, or the comparison means nothing.
void check_agreement(benchmark::State& state, const std::vector<std::uint8_t>& bytes, std::size_t length) {
  for (std::size_t start = 0; start + length <= bytes.size(); start += length) {
    const std::uint16_t reference = tb::boost_crc16_ccitt_false(&bytes[start], length);
    if (table_crc::compute(&bytes[start], length) != reference ||
        sliced_crc::compute(&bytes[start], length) != reference ||
        bitwise_crc::compute(&bytes[start], length) != reference) {
      state.SkipWithError("trionet's CRC differs from Boost.CRC");
      return;
    }
  }
}

template <class Crc>
void BM_crc_12_bytes(benchmark::State& state) {
  const std::vector<std::uint8_t> bytes = tb::random_bytes(short_length * short_messages);
  check_agreement(state, bytes, short_length);
  for (auto _ : state) {
    benchmark::DoNotOptimize(bytes.data());
    for (std::size_t m = 0; m < short_messages; ++m) {
      std::uint16_t crc = Crc::compute(&bytes[m * short_length], short_length);
      benchmark::DoNotOptimize(crc);
    }
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(bytes.size()));
}

template <class Crc>
void BM_crc_4096_bytes(benchmark::State& state) {
  const std::vector<std::uint8_t> bytes = tb::random_bytes(long_length);
  check_agreement(state, bytes, long_length);
  for (auto _ : state) {
    benchmark::DoNotOptimize(bytes.data());
    std::uint16_t crc = Crc::compute(bytes.data(), bytes.size());
    benchmark::DoNotOptimize(crc);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(bytes.size()));
}

BENCHMARK_TEMPLATE(BM_crc_12_bytes, table_crc)->Name("BM_crc_12_bytes/trionet_table");
BENCHMARK_TEMPLATE(BM_crc_12_bytes, sliced_crc)->Name("BM_crc_12_bytes/trionet_sliced");
BENCHMARK_TEMPLATE(BM_crc_12_bytes, bitwise_crc)->Name("BM_crc_12_bytes/trionet_bitwise");
BENCHMARK_TEMPLATE(BM_crc_12_bytes, boost_reference)->Name("BM_crc_12_bytes/boost_crc_optimal");
BENCHMARK_TEMPLATE(BM_crc_4096_bytes, table_crc)->Name("BM_crc_4096_bytes/trionet_table");
BENCHMARK_TEMPLATE(BM_crc_4096_bytes, sliced_crc)->Name("BM_crc_4096_bytes/trionet_sliced");
BENCHMARK_TEMPLATE(BM_crc_4096_bytes, bitwise_crc)->Name("BM_crc_4096_bytes/trionet_bitwise");
BENCHMARK_TEMPLATE(BM_crc_4096_bytes, boost_reference)->Name("BM_crc_4096_bytes/boost_crc_optimal");

}  // namespace
