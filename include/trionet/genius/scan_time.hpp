// Genius scan time (docs/protocol.md 3.3): GE's published contribution of each device to the bus scan
// (GE Fanuc GFK-0825F), one device at a time and summed over a bus.
//
//   device(n) = fixed + per_byte * n        n = bytes of inputs + outputs of the device
//   bus       = sum over its devices
//
//   rate     fixed      per byte
//   153.6s   0.943 ms   0.0715 ms
//   153.6e   1.015 ms   0.0715 ms
//   76.8     1.538 ms   0.143 ms
//   38.4     2.583 ms   0.286 ms
//
//   scan time = max(3 ms, bus)   GE: a Bus Controller imposes a minimum scan of 3 ms (configurable)
//
// GE's figures have at most four decimals of a millisecond, so in integer nanoseconds they and every sum of
// them are exact: the results are GE's formula to the nanosecond, with no floating point (GE's printed table
// differs from its own formula in six cells: `published_table_centi_ms`, docs/genius.md). The per-byte terms
// are close to, but not equal to, one 11-bit character time (character_time_us in bus_access.hpp: 71.615,
// 71.615, 143.229, 286.458 us); that computed figure is a separate number and is not used here.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/genius/bus_access.hpp"
#include "trionet/span.hpp"

namespace trionet::genius {

/// GE's published scan-time terms of one rate (GFK-0825F), in nanoseconds.
struct scan_time_terms {
  std::uint32_t fixed_ns;     ///< per device: 943000 at 153.6s (0.943 ms)
  std::uint32_t per_byte_ns;  ///< per byte of inputs + outputs: 71500 at 153.6s (0.0715 ms)
};

/// GE's terms for `r`. Cost: a table lookup; ISR-safe.
[[nodiscard]] constexpr scan_time_terms published_scan_time_terms(rate r) noexcept {
  switch (r) {
    case rate::standard_153k6:
      return {943000, 71500};
    case rate::extended_153k6:
      return {1015000, 71500};
    case rate::baud_76k8:
      return {1538000, 143000};
    case rate::baud_38k4:
      return {2583000, 286000};
  }
  return {0, 0};
}

/// One device's scan-time contribution in nanoseconds, by GE's formula: fixed + per_byte * io_bytes, where
/// `io_bytes` counts the device's input and output bytes together. Exact for every `io_bytes` (at most
/// about 1.2e15 ns). Cost: one multiply-add; ISR-safe.
[[nodiscard]] constexpr std::uint64_t device_scan_time_ns(rate r, std::uint32_t io_bytes) noexcept {
  const scan_time_terms terms = published_scan_time_terms(r);
  return terms.fixed_ns + std::uint64_t{terms.per_byte_ns} * io_bytes;
}

/// Why a bus's scan time was not computed (misuse of the API).
enum class scan_time_status : std::uint8_t {
  ok,                ///< computed
  too_many_devices,  ///< more devices than the rate allows (32, or 16 at 38.4 kbaud)
};

/// The name of `value`, e.g. "too_many_devices".
constexpr const char* to_string(scan_time_status value) noexcept {
  switch (value) {
    case scan_time_status::ok:
      return "ok";
    case scan_time_status::too_many_devices:
      return "too_many_devices";
  }
  return "unknown";
}

/// GE's minimum bus scan time (docs/protocol.md 3.3): a Bus Controller never lets a scan be shorter than
/// 3 ms. Configurable: `bus_scan_time` takes another minimum, 0 for none.
constexpr std::uint64_t default_minimum_scan_ns = 3000000;

/// A bus's scan time: the sum of its devices' contributions, and the scan time, which is never below the
/// minimum.
struct [[nodiscard]] scan_time_result {
  scan_time_status status;  ///< `ok`, or why nothing was computed (then the other fields are 0)
  std::uint64_t sum_ns;     ///< the sum of the devices' contributions, in nanoseconds
  std::uint64_t scan_ns;    ///< the bus's scan time: max(minimum, sum)
  std::uint64_t io_bytes;   ///< the devices' input + output bytes together
  std::size_t devices;      ///< how many devices were summed
  bool minimum_applies;     ///< the sum is below the minimum, so the scan time is the minimum

  /// True when the scan time was computed.
  constexpr explicit operator bool() const noexcept { return status == scan_time_status::ok; }
};

/// The scan time of a bus at rate `r` whose devices have `io_bytes[i]` input + output bytes each: the sum of
/// GE's figure for each device (no devices: 0), and the scan time max(`minimum_ns`, sum) (docs/protocol.md
/// 3.3; default 3 ms, 0 for none). More devices than the rate allows is `too_many_devices`. Exact.
/// Cost: O(devices); ISR-safe.
[[nodiscard]] constexpr scan_time_result bus_scan_time(rate r, span<const std::uint32_t> io_bytes,
                                                       std::uint64_t minimum_ns = default_minimum_scan_ns) noexcept {
  if (io_bytes.size() > properties(r).max_devices) return {scan_time_status::too_many_devices, 0, 0, 0, 0, false};
  scan_time_result result{scan_time_status::ok, 0, 0, 0, io_bytes.size(), false};
  for (const std::uint32_t bytes : io_bytes) {
    result.sum_ns += device_scan_time_ns(r, bytes);
    result.io_bytes += bytes;
  }
  result.minimum_applies = result.sum_ns < minimum_ns;
  result.scan_ns = result.minimum_applies ? minimum_ns : result.sum_ns;
  return result;
}

/// The byte counts of GE's printed scan-time table (GFK-0825F): a device with 16, 32, 64, 128 and 256 bytes of
/// inputs and outputs.
constexpr std::uint32_t published_table_bytes[5] = {16, 32, 64, 128, 256};

/// GE's printed scan-time table (GFK-0825F), in hundredths of a millisecond, one row per
/// `published_table_bytes`, one column per rate in the order of `rate`. The formula (`device_scan_time_ns`)
/// is what this library computes; six of these cells are not the formula rounded to 0.01 ms (docs/genius.md).
constexpr std::uint16_t published_table_centi_ms[5][4] = {
    {209, 216, 383, 716},      // 16 bytes
    {324, 331, 612, 1174},     // 32
    {552, 560, 1069, 2089},    // 64
    {1010, 1017, 1985, 3920},  // 128
    {1925, 1932, 3815, 7580},  // 256
};

/// The formula's figure rounded to hundredths of a millisecond, half up, as GE's table prints them.
[[nodiscard]] constexpr std::uint64_t formula_centi_ms(rate r, std::uint32_t io_bytes) noexcept {
  return (device_scan_time_ns(r, io_bytes) + 5000) / 10000;
}

}  // namespace trionet::genius
