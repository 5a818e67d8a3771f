// The SBA planner (genius_plan.hpp).
#include "genius_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "trionet/host/text.hpp"

namespace trionet::host {
namespace {

namespace genius = trionet::genius;

genius::bus_timing timing_of(genius::rate rate, const genius_plan_options& options) {
  genius::bus_timing timing = genius::default_timing(rate);
  timing.propagation_us_per_2000ft = options.propagation_us_per_2000ft;
  if (options.detection_us >= 0) timing.detection_us = options.detection_us;
  return timing;
}

std::string us_text(double us) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", us);
  return text;
}

// Devices in the cyclic order of their SBAs.
std::vector<std::size_t> order_of(const std::vector<std::uint8_t>& sba) {
  std::vector<std::size_t> order(sba.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sba[a] < sba[b]; });
  return order;
}

// SBAs for devices in cyclic `order` with the offsets `gaps` (gap k from order[k] to order[k + 1]), the first
// at `first_sba`.
std::vector<std::uint8_t> sbas_of(const std::vector<std::size_t>& order, const std::vector<unsigned>& gaps,
                                  unsigned first_sba) {
  std::vector<std::uint8_t> sba(order.size());
  unsigned at = first_sba;
  for (std::size_t k = 0; k < order.size(); ++k) {
    sba[order[k]] = static_cast<std::uint8_t>(at % 32u);
    if (k < gaps.size()) at += gaps[k];
  }
  return sba;
}

// The margins of the idle restart (docs/protocol.md 3.4). Every device acts as if SBA 31's Stop had ended, each
// counting the idle time from the last character it heard, so the turns go in SBA order from the lowest, timed
// from the last sender L's Stop as it reached each device. For consecutive turns a < b the margin is
// skip x (b - a) - (p(L,a) + p(a,b) - p(L,b)): the margin after L's own Stop when L is neither of them, and
// smallest when L is b itself, skip x (b - a) - 2 p(a,b): the start bit goes from b to a and back. No Stop's
// analysis has that pair (a sender takes no turn after its own Stop), so it is checked here.
struct restart_margin {
  std::size_t first = 0, second = 0;  // indices into the devices; `second` is the last sender
  double margin_us = 0;
};

std::vector<restart_margin> restart_margins(const std::vector<genius_plan_device>& devices,
                                            const std::vector<std::uint8_t>& sba, const genius::bus_timing& timing) {
  std::vector<restart_margin> margins;
  const std::vector<std::size_t> by_sba = order_of(sba);
  for (std::size_t k = 1; k < by_sba.size(); ++k) {
    const std::size_t a = by_sba[k - 1], b = by_sba[k];
    const double round_trip = 2 * genius::propagation_us(timing, devices[a].position_ft, devices[b].position_ft);
    margins.push_back({a, b, timing.skip_us * (sba[b] - sba[a]) - round_trip});
  }
  return margins;
}

struct candidate {
  genius_assignment assignment;
  std::vector<std::size_t> order;
  std::vector<unsigned> gaps;  // between consecutive devices of `order`, the wrap excluded
  bool feasible = false;
};

// The least gaps that keep every margin in `order`: start from `gaps`, and widen the gap before every
// second turn of a pair whose margin is too small (a margin grows by one skip time per SBA skipped before
// its second turn, whatever the Stop), until none is too small or the 32 SBAs are used up.
candidate widen(const std::vector<genius_plan_device>& devices, std::vector<std::size_t> order,
                std::vector<unsigned> gaps, unsigned first_sba, genius::rate rate,
                const genius_plan_options& options) {
  candidate c;
  c.order = std::move(order);
  const std::size_t n = devices.size();
  const genius::bus_timing timing = timing_of(rate, options);
  for (int round = 0; round < 64; ++round) {
    const unsigned used = std::accumulate(gaps.begin(), gaps.end(), 0u);
    if (used > 31) break;  // the wrap back to the first needs at least one
    std::vector<std::uint8_t> sba = sbas_of(c.order, gaps, first_sba);
    c.assignment = assess_genius_assignment(devices, sba, rate, options);
    c.gaps = gaps;
    std::vector<genius::device_position> positions;
    for (std::size_t i = 0; i < n; ++i) positions.push_back({sba[i], devices[i].position_ft, 1});
    // Which gaps to widen: the one before each too-small pair's second turn.
    std::vector<bool> widen_before(n, false);
    for (const restart_margin& m : restart_margins(devices, sba, timing)) {
      if (!(m.margin_us < timing.detection_us)) continue;
      for (std::size_t k = 1; k < n; ++k) widen_before[k] = widen_before[k] || c.order[k] == m.second;
    }
    for (std::size_t s = 0; s < n; ++s) {
      const genius::turn_analysis a = genius::analyse_turns(
          span<const genius::device_position>(positions.data(), positions.size()), timing, sba[s]);
      for (std::size_t m = 0; m < a.margin_count; ++m) {
        if (!a.margins[m].too_small) continue;
        for (std::size_t k = 0; k < n; ++k) {
          if (sba[c.order[k]] != a.margins[m].second) continue;
          if (k != 0) widen_before[k] = true;  // k == 0: the wrap, which takes what is left
        }
      }
    }
    if (c.assignment.too_small == 0) {
      c.feasible = c.assignment.fits_rate;
      return c;
    }
    bool changed = false;
    for (std::size_t k = 1; k < n; ++k) {
      if (widen_before[k]) {
        ++gaps[k - 1];
        changed = true;
      }
    }
    if (!changed) break;  // only the wrap is short, and it already has every SBA the others leave
  }
  c.feasible = false;
  return c;
}

std::size_t changed_sbas(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) if (a[i] != b[i]) ++n;
  return n;
}

bool same_cyclic_order(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  const std::vector<std::size_t> x = order_of(a);
  const std::vector<std::size_t> y = order_of(b);
  for (std::size_t shift = 0; shift < x.size(); ++shift) {
    bool same = true;
    for (std::size_t k = 0; k < x.size() && same; ++k) same = x[k] == y[(k + shift) % y.size()];
    if (same) return true;
  }
  return false;
}

}  // namespace

genius_assignment assess_genius_assignment(const std::vector<genius_plan_device>& devices,
                                           const std::vector<std::uint8_t>& sba, genius::rate rate,
                                           const genius_plan_options& options) {
  genius_assignment out;
  out.rate = rate;
  out.sba = sba;
  const genius::bus_timing timing = timing_of(rate, options);
  std::vector<genius::device_position> positions;
  for (std::size_t i = 0; i < devices.size(); ++i) positions.push_back({sba[i], devices[i].position_ft, 1});
  const span<const genius::device_position> view(positions.data(), positions.size());
  for (std::size_t s = 0; s < devices.size(); ++s) {
    const genius::turn_analysis a = genius::analyse_turns(view, timing, sba[s]);
    out.too_small += a.too_small_count;
    out.bus_length_ft = a.bus_length_ft;
    for (std::size_t m = 0; m < a.margin_count; ++m) {
      if (out.worst.any && a.margins[m].margin_us >= out.worst.margin_us) continue;
      out.worst.any = true;
      out.worst.margin_us = a.margins[m].margin_us;
      out.worst.after = s;
      for (std::size_t i = 0; i < devices.size(); ++i) {
        if (sba[i] == a.margins[m].first) out.worst.first = i;
        if (sba[i] == a.margins[m].second) out.worst.second = i;
      }
    }
  }
  for (const restart_margin& m : restart_margins(devices, sba, timing)) {
    if (m.margin_us < timing.detection_us) {
      ++out.too_small;
      ++out.restart_too_small;
    }
    if (out.worst.any && m.margin_us >= out.worst.margin_us) continue;
    out.worst = genius_worst_margin{true, m.margin_us, m.second, m.first, m.second, true};
  }
  const std::vector<std::size_t> order = order_of(sba);
  double propagation = 0;
  for (std::size_t k = 0; k < order.size() && order.size() > 1; ++k) {
    propagation += genius::propagation_us(timing, devices[order[k]].position_ft,
                                          devices[order[(k + 1) % order.size()]].position_ft);
  }
  out.overhead_us = 32 * timing.skip_us + propagation;
  const genius::rate_properties props = genius::properties(rate);
  out.fits_rate = out.bus_length_ft <= props.max_length_ft && devices.size() <= props.max_devices;
  return out;
}

genius_plan_result plan_genius_bus(const std::vector<genius_plan_device>& devices, const genius_plan_options& options) {
  genius_plan_result result;
  const std::size_t n = devices.size();
  if (n == 0) {
    result.error = "no devices";
    return result;
  }
  if (n > 32) {
    result.error = std::to_string(n) + " devices: a Genius bus has 32 SBAs";
    return result;
  }
  std::size_t given = 0;
  std::uint32_t seen = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const genius_plan_device& d = devices[i];
    if (!std::isfinite(d.position_ft) || d.position_ft < 0) {
      result.error = "device '" + d.name + "': a position must be a number of feet >= 0";
      return result;
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (devices[j].name == d.name) {
        result.error = "device '" + d.name + "' is given twice";
        return result;
      }
    }
    if (d.sba < 0) continue;
    if (d.sba > 31) {
      result.error = "device '" + d.name + "': an SBA is 0..31";
      return result;
    }
    if ((seen >> d.sba) & 1u) {
      result.error = "SBA " + std::to_string(d.sba) + " is given twice";
      return result;
    }
    seen |= 1u << d.sba;
    ++given;
  }
  if (given != 0 && given != n) {
    result.error = "give an SBA to every device (to check them) or to none (to plan them)";
    return result;
  }
  result.checked = given == n;
  std::vector<std::uint8_t> start(n);
  for (std::size_t i = 0; i < n; ++i)
    start[i] = static_cast<std::uint8_t>(result.checked ? static_cast<std::size_t>(devices[i].sba) : i);
  result.given = assess_genius_assignment(devices, start, options.rate, options);
  result.given_ok = result.given.too_small == 0 && result.given.fits_rate;
  if (result.given_ok) {
    result.found = true;
    result.plan = result.given;
    return result;
  }

  // The rates to try, cheapest first, from the one asked for.
  const genius::rate ladder[] = {genius::rate::standard_153k6, genius::rate::extended_153k6,
                                 genius::rate::baud_76k8, genius::rate::baud_38k4};
  std::size_t from = 0;
  while (ladder[from] != options.rate) ++from;

  // The orders to try: as given (keeping its gaps), along the bus, and out along the bus and back.
  const std::vector<std::size_t> given_order = order_of(start);
  std::vector<unsigned> given_gaps;
  for (std::size_t k = 0; k + 1 < n; ++k)
    given_gaps.push_back((start[given_order[k + 1]] + 32u - start[given_order[k]]) % 32u);
  std::vector<std::size_t> along(n);
  std::iota(along.begin(), along.end(), 0);
  std::stable_sort(along.begin(), along.end(),
                   [&](std::size_t a, std::size_t b) { return devices[a].position_ft < devices[b].position_ft; });
  std::vector<std::size_t> out_and_back;  // every other device going out, the rest coming back
  for (std::size_t k = 0; k < n; k += 2) out_and_back.push_back(along[k]);
  for (long k = static_cast<long>(n) - ((n - 1) % 2 == 1 ? 1 : 2); k >= 1; k -= 2)
    out_and_back.push_back(along[static_cast<std::size_t>(k)]);
  const std::vector<unsigned> ones(n > 0 ? n - 1 : 0, 1u);

  for (std::size_t step = from; step < 4; ++step) {
    const genius::rate rate = ladder[step];
    std::vector<candidate> candidates;
    candidates.push_back(widen(devices, given_order, given_gaps, start[given_order[0]], rate, options));
    candidates.push_back(widen(devices, along, ones, result.checked ? start[along[0]] : 0, rate, options));
    if (out_and_back.size() == n)
      candidates.push_back(widen(devices, out_and_back, ones, result.checked ? start[out_and_back[0]] : 0, rate, options));
    // SBAs given: also every plan that moves one device to a free SBA (where one keeps every margin, the fewest
    // changes).
    std::uint32_t taken = 0;
    for (const std::uint8_t sba : start) taken |= 1u << sba;
    for (std::size_t i = 0; i < n && result.checked; ++i) {
      for (unsigned free_sba = 0; free_sba < 32; ++free_sba) {
        if ((taken >> free_sba) & 1u) continue;
        std::vector<std::uint8_t> moved = start;
        moved[i] = static_cast<std::uint8_t>(free_sba);
        candidate c;
        c.assignment = assess_genius_assignment(devices, moved, rate, options);
        c.feasible = c.assignment.too_small == 0 && c.assignment.fits_rate;
        if (c.feasible) candidates.push_back(std::move(c));
      }
    }
    const candidate* best = nullptr;
    for (const candidate& c : candidates) {
      if (!c.feasible) continue;
      if (best == nullptr) {
        best = &c;
        continue;
      }
      const double overhead = c.assignment.overhead_us, best_overhead = best->assignment.overhead_us;
      if (overhead < best_overhead - 1e-9 ||
          (std::fabs(overhead - best_overhead) <= 1e-9 &&
           changed_sbas(c.assignment.sba, start) < changed_sbas(best->assignment.sba, start))) {
        best = &c;
      }
    }
    if (best == nullptr) continue;
    result.found = true;
    result.plan = best->assignment;
    // What changed, and why.
    const genius::rate_properties asked = genius::properties(options.rate);
    if (rate != options.rate) {
      const genius::rate_properties used = genius::properties(rate);
      std::string reason;
      if (result.given.bus_length_ft > asked.max_length_ft) {
        reason = "the bus is " + format_real(result.given.bus_length_ft) + " ft long and " + asked.name + " allows " +
                 std::to_string(asked.max_length_ft) + " ft";
      } else if (n > asked.max_devices) {
        reason = std::to_string(n) + " devices and " + asked.name + " allows " + std::to_string(asked.max_devices);
      } else {
        reason = std::string("no SBA assignment at ") + asked.name +
                 " gives every device the detection time to hear the turn before its own";
      }
      result.remedies.push_back({rate == genius::rate::extended_153k6 ? "153.6e" : "lower rate",
                                 std::string("from ") + asked.name + " to " + used.name + ": " + reason +
                                     (rate == genius::rate::extended_153k6 ? " (153.6e has a skip time of two bits)"
                                                                           : " (a longer bit time and skip time)")});
    }
    if (!same_cyclic_order(result.plan.sba, start)) {
      std::size_t moved = 0;
      for (std::size_t i = 0; i < n; ++i) moved = result.plan.sba[i] != start[i] ? i : moved;
      result.remedies.push_back(
          {"resequence", changed_sbas(result.plan.sba, start) == 1
                             ? devices[moved].name + " from SBA " + std::to_string(start[moved]) + " to SBA " +
                                   std::to_string(result.plan.sba[moved]) + ": one change that keeps every margin"
                             : "SBAs in the order of the devices along the bus, so that no turn has to reach back past "
                               "a device that has just sent"});
    }
    // Skipped SBAs: gaps wider than the SBAs started with (the gap that wraps back to the first device is
    // where the unused SBAs go anyway) that the pair needs: one skip time is less than the detection time and
    // the start bit's way there and back (the idle restart after the second's own Stop, the smallest of the
    // pair's margins).
    const std::vector<std::size_t> order = order_of(result.plan.sba);
    const genius::bus_timing timing = timing_of(rate, options);
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const std::size_t a = order[k], b = order[k + 1];
      const unsigned gap = (result.plan.sba[b] + 32u - result.plan.sba[a]) % 32u;
      const unsigned before = (start[b] + 32u - start[a]) % 32u;
      const double away = genius::propagation_us(timing, devices[a].position_ft, devices[b].position_ft);
      if (gap <= 1 || (same_cyclic_order(result.plan.sba, start) && gap <= before) ||
          !(timing.skip_us - 2 * away < timing.detection_us)) {
        continue;
      }
      std::string unused;
      for (unsigned u = 1; u < gap; ++u) {
        if (!unused.empty()) unused += ", ";
        unused += std::to_string((result.plan.sba[a] + u) % 32u);
      }
      result.remedies.push_back(
          {"skip an SBA", "SBA " + unused + " left unused: " + devices[b].name + "'s turn comes " + std::to_string(gap) +
                              " skip times after " + devices[a].name + "'s, so that " + devices[b].name +
                              " detects " + devices[a].name + "'s start bit (" + us_text(away) +
                              " us away) before its own turn, also at an idle restart that follows " +
                              devices[b].name + "'s own Stop (the start bit's way there and back: " +
                              us_text(2 * away) + " us)"});
    }
    return result;
  }
  const genius::rate_properties slowest = genius::properties(genius::rate::baud_38k4);
  if (n > slowest.max_devices && options.rate != genius::rate::baud_38k4) {
    result.why_not = "no assignment keeps every margin at the rates down to 76.8, and 38.4 allows " +
                     std::to_string(slowest.max_devices) + " devices";
  } else if (n > slowest.max_devices) {  // the margins are not why (s37 item 11): the rate cannot take them
    result.why_not = std::to_string(n) + " devices, and 38.4 allows " + std::to_string(slowest.max_devices);
  } else {
    result.why_not = "no assignment of SBAs keeps every margin at least the detection time at any rate from " +
                     std::string(genius::properties(options.rate).name) + " down to 38.4" +
                     (result.given.bus_length_ft > slowest.max_length_ft ? " (the bus is longer than 38.4 allows)" : "");
  }
  return result;
}

}  // namespace trionet::host
