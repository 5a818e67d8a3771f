// The fault-injection soak of a Genius bus (genius_soak.hpp).
#include "genius_soak.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "genius_bus.hpp"
#include "genius_plan.hpp"

namespace trionet::host {
namespace {

namespace genius = trionet::genius;

void fail_round(genius_soak_report& report, std::uint32_t round, const std::string& what) {
  if (report.failures.size() < 20) report.failures.push_back("round " + std::to_string(round) + ": " + what);
}

}  // namespace

std::uint64_t binomial_upper_bound(std::uint64_t n, double p, double confidence) {
  if (n == 0 || p <= 0) return 0;
  const double nd = static_cast<double>(n);
  const double mean = nd * p, sigma = std::sqrt(nd * p * (1 - p));
  // Start well below the mean (the mass below is negligible) and add up the probabilities.
  auto k = static_cast<std::uint64_t>(std::max(0.0, std::floor(mean - 40 * sigma - 1)));
  double cdf = 0;
  for (; k <= n; ++k) {
    const double kd = static_cast<double>(k);
    const double log_pmf = std::lgamma(nd + 1) - std::lgamma(kd + 1) - std::lgamma(nd - kd + 1) + kd * std::log(p) +
                           (nd - kd) * std::log1p(-p);
    cdf += std::exp(log_pmf);
    if (cdf >= confidence) return k;
  }
  return n;
}

genius_soak_report run_genius_soak(const genius_soak_config& config,
                                   const std::function<void(std::uint32_t, const genius_soak_report&)>& progress) {
  genius_soak_report report;
  std::mt19937_64 rng(config.seed);
  const genius::rate rates[] = {genius::rate::standard_153k6, genius::rate::extended_153k6, genius::rate::baud_76k8,
                                genius::rate::baud_38k4};
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  for (std::uint32_t round = 0; round < config.rounds; ++round) {
    // A layout, planned without collision risk.
    const genius::rate asked = rates[rng() % 4];
    const genius::rate_properties asked_props = genius::properties(asked);
    const std::size_t n = 2 + rng() % 7;
    std::vector<genius_plan_device> devices;
    for (std::size_t i = 0; i < n; ++i)
      devices.push_back({"D" + std::to_string(i), std::floor(uniform(0, asked_props.max_length_ft)), -1});
    genius_plan_options plan_options;
    plan_options.rate = asked;
    const genius_plan_result plan = plan_genius_bus(devices, plan_options);
    if (!plan.found) {
      fail_round(report, round, "no plan for a layout within the rate's limits: " + plan.why_not);
      continue;
    }
    const genius::rate rate = plan.plan.rate;
    std::vector<genius_station> stations;
    for (std::size_t i = 0; i < n; ++i) {
      stations.push_back({plan.plan.sba[i], devices[i].position_ft, static_cast<std::uint16_t>(1 + rng() % 8),
                          static_cast<std::uint16_t>(rng() % 5)});
    }
    genius_bus_config bus;
    bus.rate = rate;
    bus.seed = config.seed * 1000003u + round;
    bus.check_losses = true;
    if (rng() % 2 == 0) {
      const std::size_t k = rng() % n;
      bus.controller = stations[k].sba;
      stations[k].input_bytes = 0;
      stations[(k + 1) % n].output_bytes = static_cast<std::uint16_t>(1 + rng() % 4);  // it opens the scans
    }
    // Roughly one scan, to place the faults: the characters of every turn and the skip times.
    const double character_us = 11 * genius::bit_time_us(rate);
    double scan_us = 32 * genius::rule_skip_us(rate);
    for (const genius_station& s : stations) {
      scan_us += character_us * (s.input_bytes + 2);
      if (bus.controller >= 0) scan_us += character_us * (s.output_bytes + 2);
    }
    const double idle_us = 32 * genius::rule_skip_us(rate) + 2 * character_us;
    const double faults_from = (config.clean_scans + 2) * scan_us + idle_us, faults_to = faults_from + 4 * scan_us;
    double lowest = 1e300, highest = 0;
    for (const genius_station& s : stations) {
      lowest = std::min(lowest, s.position_ft);
      highest = std::max(highest, s.position_ft);
    }
    for (std::uint32_t f = 0; f < config.faults_per_round; ++f) {
      genius_fault fault;
      fault.kind = static_cast<genius_fault_kind>(rng() % 4);
      fault.at_us = uniform(faults_from, faults_to);
      fault.sba = stations[rng() % n].sba;
      switch (fault.kind) {
        case genius_fault_kind::noise:
          fault.position_ft = uniform(lowest, highest);
          fault.duration_us = uniform(5, 300);
          break;
        case genius_fault_kind::power_off:
          fault.duration_us = uniform(0.2, 3) * scan_us;
          break;
        case genius_fault_kind::stop:
          fault.duration_us = uniform(0.2, 2) * scan_us;
          break;
        case genius_fault_kind::cut:
          fault.position_ft = uniform(lowest, highest);
          fault.duration_us = uniform(0.2, 3) * scan_us;
          break;
      }
      ++report.faults[static_cast<std::size_t>(fault.kind)];
      bus.faults.push_back(fault);
    }
    bus.scans = 1000000;  // the time bound ends the run
    bus.max_us = faults_to + 4 * scan_us + idle_us + (2.0 * config.clean_scans + 4) * scan_us;
    const std::string problem = check_genius_bus(stations, bus);
    if (!problem.empty()) {
      fail_round(report, round, "bad layout: " + problem);
      continue;
    }
    genius_bus sim(stations, bus);
    const genius_bus_result r = sim.run();
    ++report.rounds;
    report.simulated_s += r.end_us / 1e6;
    report.transmissions += r.transmissions_started;
    report.deliveries += r.deliveries;
    report.collisions += r.collisions;
    report.wrong_data += r.wrong_data;
    report.wrong_header += r.wrong_deliveries - r.wrong_data;
    report.losses_checked += r.losses_checked;
    report.losses_uncounted += r.losses_uncounted;
    for (const std::string& detail : r.loss_details) fail_round(report, round, detail);
    std::uint64_t crc_errors = 0;
    for (const genius_device_report& d : r.devices) {
      crc_errors += d.counters.crc_errors;
      report.framing_errors += d.counters.framing_errors;
      report.lost_transmissions += d.counters.lost_transmissions;
      report.idle_restarts += d.counters.idle_restarts;
    }
    report.crc_errors += crc_errors;
    report.crc_checked_corrupt += crc_errors + r.wrong_data;
    report.corrupt_events += r.corrupt_events;
    report.escape_events += r.escape_events;

    // One scan, as the bus ran before the first fault (the longest), plus the idle time.
    double first_fault = 1e300;
    for (const genius_fault& f : bus.faults) first_fault = std::min(first_fault, f.at_us);
    double nominal = 0;
    for (std::size_t k = 1; k < r.scan_ends_us.size(); ++k) {
      if (r.scan_ends_us[k] > first_fault) break;
      nominal = std::max(nominal, r.scan_ends_us[k] - r.scan_ends_us[k - 1]);
    }
    if (nominal == 0) {
      fail_round(report, round, "no clean scan before the faults");
      continue;
    }
    const double bound = nominal + idle_us;
    const double quiet = r.faults_end_us;
    // A device that comes back in the middle of a transmission cannot tell whose Stop ends it (docs/protocol.md
    // 3.4: a Stop whose Start it missed hands no turn on), so the rest of the transmission under way when the
    // faults stopped comes on top.
    double under_way = 0;
    for (const genius_transmission_record& t : r.transmissions) {
      if (t.start_us < quiet && t.end_us > quiet) under_way = std::max(under_way, t.end_us - quiet);
    }
    // The run of characters under way: that transmission and every one that began less than a character time
    // after the last ended. A UART that starts listening inside such a run (powered on, a cut mended, thrown
    // out of step by noise) may take a data bit for a start bit, and then stays out of step, character after
    // character, until a silence of a character time makes a start bit the next falling edge it sees; it misses
    // every Start until then (docs/genius.md, "Soak").
    double run_end = quiet;
    for (const genius_transmission_record& t : r.transmissions) {
      if (t.start_us < run_end + character_us && t.end_us > run_end) run_end = t.end_us;
    }
    const double run = run_end - quiet;
    // Every device that sends takes its turn again, whole, within the bound.
    double recovered = quiet;
    for (const genius_station& s : stations) {
      const bool sends = bus.controller == s.sba ? true : s.input_bytes > 0;
      if (!sends) continue;
      double first = -1;
      for (const genius_transmission_record& t : r.transmissions) {
        if (t.sba == s.sba && t.whole && !t.collided && t.start_us >= quiet) {
          first = t.start_us;
          break;
        }
      }
      ++report.recoveries;
      if (first < 0) {
        fail_round(report, round, "SBA " + std::to_string(s.sba) + " never sent again after the faults");
        ++report.lost_recoveries;
        continue;
      }
      const double ratio = (first - quiet) / (bound + under_way);
      report.worst_recovery_ratio = std::max(report.worst_recovery_ratio, ratio);
      // Collisions once the faults stopped, before this device's turn (two halves of a mended bus that took
      // turns on their own, or an idle restart counted from different moments): the colliding devices wait for
      // a Stop that does not come, so the bus starts again after the idle time at most.
      double collided_from = 1e300, collided_to = -1;
      for (const genius_transmission_record& t : r.transmissions) {
        if (t.collided && t.end_us > quiet && t.start_us < first) {
          collided_from = std::min(collided_from, t.start_us);
          collided_to = std::max(collided_to, t.end_us);
        }
      }
      const double collisions = collided_to < 0 ? 0 : std::max(0.0, collided_to - std::max(collided_from, run_end)) + idle_us;
      const double implied = bound + std::max(under_way, run) + collisions;
      report.worst_implied_ratio = std::max(report.worst_implied_ratio, (first - quiet) / implied);
      const std::string what = "SBA " + std::to_string(s.sba) + " took its turn " + std::to_string(first - quiet) +
                               " us after the faults stopped (one scan + idle time: " +
                               std::to_string(bound + under_way) + " us)";
      if (ratio > 2) {
        ++report.lost_recoveries;
        fail_round(report, round, what);
      } else if (ratio > 1) {
        ++report.late_recoveries;
        std::string why;
        if (first - quiet <= bound + std::max(under_way, run)) {
          ++report.late_out_of_step;
          why = "; within the run of characters under way (" + std::to_string(run) + " us) + one scan + idle time";
        } else if (first - quiet <= implied) {
          ++report.late_after_collision;
          why = "; after a collision once the faults stopped (" + std::to_string(collisions) + " us with the idle time)";
        } else {
          ++report.late_unexplained;
          fail_round(report, round, what + "; beyond the run under way and the collisions (" + std::to_string(implied) + " us)");
        }
        if (report.notes.size() < 20) report.notes.push_back("round " + std::to_string(round) + ": " + what + why);
      }
      recovered = std::max(recovered, first);
    }
    // After that, every scan holds a whole transmission from every device that sends.
    for (std::size_t k = 1; k < r.scan_ends_us.size(); ++k) {
      const double from = r.scan_ends_us[k - 1], to = r.scan_ends_us[k];
      if (from < recovered) continue;
      for (const genius_station& s : stations) {
        const bool sends = bus.controller == s.sba ? true : s.input_bytes > 0;
        if (!sends) continue;
        bool seen = false;
        for (const genius_transmission_record& t : r.transmissions) {
          if (t.sba == s.sba && t.whole && !t.collided && t.start_us >= from && t.start_us < to) seen = true;
        }
        if (!seen) {
          ++report.wedged_scans;
          fail_round(report, round, "the scan from " + std::to_string(from) + " us has no turn of SBA " +
                                        std::to_string(s.sba));
        }
      }
    }
    if (progress) progress(round, report);
  }
  report.expected_escapes = static_cast<double>(report.corrupt_events) / 64.0;
  report.escape_bound = binomial_upper_bound(report.corrupt_events, 1.0 / 64.0, 0.999);
  return report;
}

}  // namespace trionet::host
