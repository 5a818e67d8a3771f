// An SBA planner for a Genius bus (docs/genius.md, "Planning SBAs"): given where each device sits, SBAs (and
// if need be a rate) such that after every device's Stop, and at an idle restart (docs/protocol.md 3.4), every
// margin between consecutive turns is at least the detection time (analyse_turns, docs/protocol.md 3.3), with
// the shortest turn overhead per scan; or a check of SBAs given. It removes a collision risk in this order of cost: resequencing SBAs along the bus
// and skipping SBAs (neither lengthens a scan: the skip times of a whole scan add up to 32 whatever the
// SBAs), then 153.6 extended, then a lower rate (each lengthens every scan).
//
// Host side (heap).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "trionet/genius/bus_access.hpp"

namespace trionet::host {

struct genius_plan_device {
  std::string name;
  double position_ft = 0;
  int sba = -1;  ///< given (0..31), or -1 to be assigned
};

struct genius_plan_options {
  genius::rate rate = genius::rate::standard_153k6;  ///< the rate asked for
  double propagation_us_per_2000ft = 3.0;
  double detection_us = -1;  ///< < 0: half a bit time at each rate
};

/// A remedy the plan used, with why.
struct genius_remedy {
  std::string name;    ///< "resequence", "skip an SBA", "153.6e", "lower rate"
  std::string reason;  ///< a sentence
};

/// The smallest margin of an assignment, and where.
struct genius_worst_margin {
  bool any = false;   ///< there is at least one margin (two devices or more besides the sender)
  double margin_us = 0;
  std::size_t after = 0;   ///< whose Stop (index into the devices)
  std::size_t first = 0;   ///< the turn that comes first
  std::size_t second = 0;  ///< the turn that must detect its start bit
  bool idle_restart = false;  ///< the margin of an idle restart that follows `after`'s Stop (`after` == `second`)
};

struct genius_assignment {
  genius::rate rate = genius::rate::standard_153k6;
  std::vector<std::uint8_t> sba;  ///< per device, in the order given
  genius_worst_margin worst;
  std::size_t too_small = 0;      ///< margins below the detection time, over every device's Stop and the idle restart
  std::size_t restart_too_small = 0;  ///< of those, margins of the idle restart
  double overhead_us = 0;         ///< turn overhead of one scan: 32 skip times + the propagation between turns
  double bus_length_ft = 0;
  bool fits_rate = true;          ///< length and device count within the rate's limits
};

struct genius_plan_result {
  std::string error;                  ///< misuse (then nothing else is set)
  bool checked = false;               ///< SBAs were given: `given` is their check
  genius_assignment given;            ///< the SBAs given, or the devices in the order given from SBA 0
  bool given_ok = false;              ///< `given` has no margin below the detection time and fits the rate
  bool found = false;                 ///< a plan without collision risk exists (at some rate)
  genius_assignment plan;             ///< it (`given` itself when that is fine)
  std::vector<genius_remedy> remedies;  ///< what the plan changed, with why (empty: nothing)
  std::string why_not;                ///< no plan: why
};

/// The margins of one assignment at its rate (every device's Stop and the idle restart, every pair of
/// consecutive turns).
genius_assignment assess_genius_assignment(const std::vector<genius_plan_device>& devices,
                                           const std::vector<std::uint8_t>& sba, genius::rate rate,
                                           const genius_plan_options& options);

/// Plans (or checks, when every device has an SBA) as the file comment says.
genius_plan_result plan_genius_bus(const std::vector<genius_plan_device>& devices, const genius_plan_options& options);

}  // namespace trionet::host
