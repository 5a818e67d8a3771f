// Genius bus access (docs/protocol.md 3.3): rates, turn timing after a Stop, margins between turns and a
// discrete-event bus scan that finds collisions. GE's scan-time figures are in scan_time.hpp.
//
// Bus model. Devices sit on one line at positions in feet; a signal needs `propagation_us_per_2000ft`
// (default 3 us) per 2000 ft. Time 0 is the end of the Stop character of SBA s at s's position. Device d
// hears that end p(s, d) later and starts a timer of skip * ((d - s) mod 32); its turn starts when the
// timer expires, at its own position, unless it has detected another device's start bit first:
//
//   turn(d)     = p(s, d) + skip * ((d - s) mod 32)
//   margin(a,b) = turn(b) - (turn(a) + p(a, b))      for a, b consecutive in SBA order after s
//
//   SBA 4 (0 ft) Stop ends at 0 ----3 us----> SBA 5 (2000 ft) hears it at 3, turn at 3 + 1 skip
//   SBA 6 (0 ft) hears it at 0, turn at 0 + 2 skip; SBA 5's start bit reaches SBA 6 at turn(5) + 3
//
// A device needs `detection_us` after a start bit arrives to detect it, so a margin below the detection
// time means the second device may transmit on top of the first: a collision. All times are doubles in
// microseconds, positions doubles in feet; nothing reads a clock.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "trionet/span.hpp"

namespace trionet::genius {

/// The four Genius bus rates.
enum class rate : std::uint8_t {
  standard_153k6,  ///< 153.6 kbaud standard ("153.6s")
  extended_153k6,  ///< 153.6 kbaud extended ("153.6e"): two-bit skip time for longer buses
  baud_76k8,       ///< 76.8 kbaud ("76.8")
  baud_38k4,       ///< 38.4 kbaud ("38.4")
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(rate value) noexcept {
  switch (value) {
    case rate::standard_153k6:
      return "standard_153k6";
    case rate::extended_153k6:
      return "extended_153k6";
    case rate::baud_76k8:
      return "baud_76k8";
    case rate::baud_38k4:
      return "baud_38k4";
  }
  return "unknown";
}

/// One row of docs/protocol.md 3.3's rate table.
struct rate_properties {
  const char* name;         ///< the CLI name: "153.6s", "153.6e", "76.8", "38.4"
  const char* description;  ///< e.g. "153.6 kbaud standard"
  std::uint32_t baud;       ///< bits per second
  std::uint8_t skip_bits;  ///< the skip-time rule, in bit times
  std::uint16_t max_length_ft;  ///< the longest bus the rate allows, in feet
  std::uint8_t max_devices;     ///< the most devices the rate allows
};

/// The properties of `r`. Cost: a table lookup; ISR-safe.
[[nodiscard]] constexpr rate_properties properties(rate r) noexcept {
  switch (r) {
    case rate::standard_153k6:
      return {"153.6s", "153.6 kbaud standard", 153600, 1, 2000, 32};
    case rate::extended_153k6:
      return {"153.6e", "153.6 kbaud extended", 153600, 2, 3500, 32};
    case rate::baud_76k8:
      return {"76.8", "76.8 kbaud", 76800, 1, 4500, 32};
    case rate::baud_38k4:
      return {"38.4", "38.4 kbaud", 38400, 1, 7500, 16};
  }
  return {"?", "?", 1, 1, 0, 0};
}

/// Looks a rate up by its CLI name ("153.6s", "153.6e", "76.8", "38.4"). Returns false if unknown.
[[nodiscard]] constexpr bool rate_from_name(std::string_view name, rate& out) noexcept {
  constexpr rate all[] = {rate::standard_153k6, rate::extended_153k6, rate::baud_76k8, rate::baud_38k4};
  for (rate r : all) {
    if (name == properties(r).name) {
      out = r;
      return true;
    }
  }
  return false;
}

/// One bit period in microseconds (1e6 / baud, e.g. 6.5104 us at 153.6 kbaud).
[[nodiscard]] constexpr double bit_time_us(rate r) noexcept {
  return 1e6 / static_cast<double>(properties(r).baud);
}
/// The skip time by GE's rule: one bit time, two at 153.6 extended.
[[nodiscard]] constexpr double rule_skip_us(rate r) noexcept {
  return properties(r).skip_bits * bit_time_us(r);
}
/// One 11-bit character in microseconds.
[[nodiscard]] constexpr double character_time_us(rate r) noexcept {
  return 11.0 * bit_time_us(r);
}

/// The timing parameters of a bus. Start from `default_timing(rate)` and override what differs.
struct bus_timing {
  rate bus_rate = rate::standard_153k6;    ///< the rate (limits of length and devices)
  double bit_time_us = 0;                  ///< one bit period (the character time is 11 bits)
  double skip_us = 0;                      ///< the skip time (rule by default, or explicit)
  double propagation_us_per_2000ft = 3.0;  ///< docs/protocol.md 3.3, configurable
  double detection_us = 0;                 ///< time a device needs to detect a start bit
};

/// The defaults for `r`: skip time by the rule, 3 us per 2000 ft, and (Decision) a detection time of
/// half a bit time, the point at which a UART-style receiver samples and confirms a start bit.
[[nodiscard]] constexpr bus_timing default_timing(rate r) noexcept {
  return bus_timing{r, bit_time_us(r), rule_skip_us(r), 3.0, bit_time_us(r) / 2.0};
}

/// The signal delay between two positions in feet.
[[nodiscard]] inline double propagation_us(const bus_timing& timing, double from_ft, double to_ft) noexcept {
  return std::fabs(to_ft - from_ft) * timing.propagation_us_per_2000ft / 2000.0;
}

/// Where a device sits on the bus, for the analysis. `data_bytes` is used only by the bus scan (length of its transmission).
struct device_position {
  std::uint8_t sba = 0;          ///< its Serial Bus Address, 0..31
  double position_ft = 0;        ///< where it sits on the line, in feet
  std::uint16_t data_bytes = 1;  ///< data characters it sends per turn (bus scan only)
};

/// Why a layout cannot be analysed (misuse of the API).
enum class layout_status : std::uint8_t {
  ok,                 ///< the layout can be analysed
  sba_out_of_range,   ///< an SBA > 31
  duplicate_sba,      ///< two devices with the same SBA
  sender_not_on_bus,  ///< the SBA whose Stop ended is not one of the devices
  bad_position,       ///< a position that is negative or not finite
  bad_timing,         ///< skip <= 0, or a negative or non-finite propagation, detection or bit time
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(layout_status value) noexcept {
  switch (value) {
    case layout_status::ok:
      return "ok";
    case layout_status::sba_out_of_range:
      return "sba_out_of_range";
    case layout_status::duplicate_sba:
      return "duplicate_sba";
    case layout_status::sender_not_on_bus:
      return "sender_not_on_bus";
    case layout_status::bad_position:
      return "bad_position";
    case layout_status::bad_timing:
      return "bad_timing";
  }
  return "unknown";
}

/// The offset of `d` after `s` in SBA order: (d - s) mod 32, 1..31 for d != s.
[[nodiscard]] constexpr unsigned sba_offset(std::uint8_t s, std::uint8_t d) noexcept {
  return (static_cast<unsigned>(d) + 32u - static_cast<unsigned>(s)) % 32u;
}

/// When a device's turn starts, at its own position, after the Stop.
struct turn {
  std::uint8_t sba = 0;    ///< the device
  double position_ft = 0;  ///< its position, in feet
  double start_us = 0;     ///< when its turn starts, after the Stop
};

/// The margin between two consecutive turns: time from the arrival of `first`'s start bit at `second`
/// to `second`'s own turn. `too_small` when below the detection time (negative: certain collision).
struct turn_margin {
  std::uint8_t first = 0;   ///< the SBA whose turn comes first
  std::uint8_t second = 0;  ///< the SBA whose turn follows
  double margin_us = 0;     ///< second's turn minus the arrival of first's start bit
  bool too_small = false;   ///< below the detection time
};

/// Turns and margins after one Stop. Turns are in SBA order after the sender (the order the protocol
/// intends), the sender excluded. Cost: about 1.5 KB; fill it with `analyse_turns`.
struct turn_analysis {
  layout_status status = layout_status::ok;    ///< `ok`, or why nothing was analysed
  std::uint8_t after = 0;                      ///< the SBA whose Stop starts the turns
  turn turns[31] = {};                         ///< the turns, in SBA order after `after`
  std::size_t turn_count = 0;                  ///< how many of `turns` are used
  turn_margin margins[30] = {};                ///< the margin between each consecutive pair
  std::size_t margin_count = 0;                ///< how many of `margins` are used
  std::size_t too_small_count = 0;             ///< margins below the detection time
  double bus_length_ft = 0;                    ///< from the first to the last device
  bool longer_than_rate_allows = false;        ///< bus length over the rate's maximum
  bool more_devices_than_rate_allows = false;  ///< more devices than the rate's maximum
};

namespace detail {

inline bool finite(double x) noexcept {
  return std::isfinite(x);
}

inline layout_status check_layout(span<const device_position> devices, const bus_timing& timing,
                                  std::uint8_t after) noexcept {
  if (!finite(timing.skip_us) || !(timing.skip_us > 0) || !finite(timing.propagation_us_per_2000ft) ||
      timing.propagation_us_per_2000ft < 0 || !finite(timing.detection_us) || timing.detection_us < 0 ||
      !finite(timing.bit_time_us) || !(timing.bit_time_us > 0)) {
    return layout_status::bad_timing;
  }
  std::uint32_t seen = 0;
  for (const device_position& d : devices) {
    if (d.sba > 31) return layout_status::sba_out_of_range;
    if (!finite(d.position_ft) || d.position_ft < 0) return layout_status::bad_position;
    const std::uint32_t bit = 1u << d.sba;
    if ((seen & bit) != 0) return layout_status::duplicate_sba;
    seen |= bit;
  }
  if (after > 31 || (seen & (1u << after)) == 0) return layout_status::sender_not_on_bus;
  return layout_status::ok;
}

inline const device_position* find_device(span<const device_position> devices, std::uint8_t sba) noexcept {
  for (const device_position& d : devices) {
    if (d.sba == sba) return &d;
  }
  return nullptr;
}

}  // namespace detail

/// Computes every other device's turn start after the Stop of SBA `after` ended at its position (time 0),
/// the margin between each consecutive pair of turns, and flags margins below `timing.detection_us`.
/// Cost: O(32 * devices); no allocation. Not meant for an ISR (floating point, ~1.5 KB result).
[[nodiscard]] inline turn_analysis analyse_turns(span<const device_position> devices, const bus_timing& timing,
                                                 std::uint8_t after) noexcept {
  turn_analysis result;
  result.after = after;
  result.status = detail::check_layout(devices, timing, after);
  if (result.status != layout_status::ok) return result;
  const device_position* sender = detail::find_device(devices, after);
  double lowest = sender->position_ft, highest = sender->position_ft;
  for (unsigned offset = 1; offset < 32; ++offset) {
    const auto sba = static_cast<std::uint8_t>((after + offset) % 32u);
    const device_position* d = detail::find_device(devices, sba);
    if (d == nullptr) continue;
    lowest = d->position_ft < lowest ? d->position_ft : lowest;
    highest = d->position_ft > highest ? d->position_ft : highest;
    const double start =
        propagation_us(timing, sender->position_ft, d->position_ft) + timing.skip_us * offset;
    result.turns[result.turn_count++] = turn{sba, d->position_ft, start};
  }
  for (std::size_t i = 1; i < result.turn_count; ++i) {
    const turn& a = result.turns[i - 1];
    const turn& b = result.turns[i];
    const double margin = b.start_us - (a.start_us + propagation_us(timing, a.position_ft, b.position_ft));
    const bool small = margin < timing.detection_us;
    result.margins[result.margin_count++] = turn_margin{a.sba, b.sba, margin, small};
    if (small) ++result.too_small_count;
  }
  const rate_properties props = properties(timing.bus_rate);
  result.bus_length_ft = highest - lowest;
  result.longer_than_rate_allows = result.bus_length_ft > props.max_length_ft;
  result.more_devices_than_rate_allows = devices.size() > props.max_devices;
  return result;
}

/// One transmission in a simulated bus scan, times at the transmitter.
struct scan_transmission {
  std::uint8_t sba = 0;   ///< the transmitting device
  double start_us = 0;    ///< its Start begins
  double end_us = 0;      ///< its Stop ends
  bool collided = false;  ///< another device transmitted at the same time
};

/// The most transmissions a scan records (a full rotation needs at most 32).
constexpr std::size_t max_scan_transmissions = 64;

/// The result of `simulate_scan`. Cost: about 2 KB.
struct bus_scan {
  layout_status status = layout_status::ok;                      ///< `ok`, or why nothing was simulated
  scan_transmission transmissions[max_scan_transmissions] = {};  ///< in the order they started
  std::size_t count = 0;                                         ///< how many of `transmissions` are used
  std::size_t collisions = 0;  ///< turns in which two or more devices transmitted
  bool complete = false;       ///< the scan came round to the starting device again
};

/// Discrete-event run of one bus scan: starting when the Stop of SBA `after` ends (time 0), each device
/// arms its skip timer when it hears the end of the last Stop and transmits when it expires, unless it
/// detected (arrival + `detection_us`) the start bit of a device that is already transmitting. If two or
/// more devices transmit in the same turn, that is a collision; the model then carries on as if the
/// collider latest in SBA order had sent the Stop that the others hear. A transmission lasts
/// (data_bytes + 2) characters: Start, data, Stop. The scan ends when `after` has transmitted again.
/// Cost: O(steps * devices^2), at most 64 steps; no allocation. Not meant for an ISR.
[[nodiscard]] inline bus_scan simulate_scan(span<const device_position> devices, const bus_timing& timing,
                                            std::uint8_t after) noexcept {
  bus_scan result;
  result.status = detail::check_layout(devices, timing, after);
  if (result.status != layout_status::ok) return result;
  const double character_us = 11.0 * timing.bit_time_us;
  const device_position* last = detail::find_device(devices, after);
  double last_end = 0;
  while (result.count < max_scan_transmissions) {
    // Timer expiry of each other device, in time order (insertion sort; at most 31 entries).
    const device_position* order[32];
    double expiry[32];
    std::size_t candidates = 0;
    for (const device_position& d : devices) {
      if (d.sba == last->sba) continue;
      const double at = last_end + propagation_us(timing, last->position_ft, d.position_ft) +
                        timing.skip_us * sba_offset(last->sba, d.sba);
      std::size_t i = candidates++;
      while (i > 0 && expiry[i - 1] > at) {
        order[i] = order[i - 1];
        expiry[i] = expiry[i - 1];
        --i;
      }
      order[i] = &d;
      expiry[i] = at;
    }
    if (candidates == 0) break;
    std::size_t sending[32];
    std::size_t senders = 0;
    for (std::size_t i = 0; i < candidates; ++i) {
      bool detected = false;
      for (std::size_t k = 0; k < senders && !detected; ++k) {
        const std::size_t x = sending[k];
        const double noticed = expiry[x] +
                               propagation_us(timing, order[x]->position_ft, order[i]->position_ft) +
                               timing.detection_us;
        detected = noticed <= expiry[i];
      }
      if (!detected) sending[senders++] = i;
    }
    const device_position* next = order[sending[0]];
    double next_end = 0;
    bool back_to_start = false;
    if (senders > 1) ++result.collisions;
    for (std::size_t k = 0; k < senders && result.count < max_scan_transmissions; ++k) {
      const device_position* d = order[sending[k]];
      const double start = expiry[sending[k]];
      const double end = start + character_us * (d->data_bytes + 2.0);
      result.transmissions[result.count++] = scan_transmission{d->sba, start, end, senders > 1};
      if (sba_offset(last->sba, d->sba) >= sba_offset(last->sba, next->sba)) {
        next = d;
        next_end = end;
      }
      if (d->sba == after) back_to_start = true;
    }
    last = next;
    last_end = next_end;
    if (back_to_start) {
      result.complete = true;
      break;
    }
  }
  return result;
}

}  // namespace trionet::genius
