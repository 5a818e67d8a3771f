// What `trionet ring simulate` and the Python package's `trionet.basic` share: the networks built into the
// tool and the JSON summary of a run (docs/basic.md), so that both give the same result for the same ring.
// Host side.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "ring_network.hpp"
#include "trionet/span.hpp"

namespace trionet::host {

/// A network built into the tool: its programs are files under examples/ built in at build time
/// (embedded_files.hpp).
struct builtin_network {
  const char* name;                ///< "example1"
  const char* title;               ///< one line for people
  std::vector<const char*> nodes;  ///< in ring order: "keypad", "mc" or "mc:FILE"
  const char* keys;                ///< the key script it runs with when none is given
};

/// The networks built into the tool: example1, example2, example3, example3-fixed.
span<const builtin_network> builtin_networks() noexcept;

/// The built-in network called `name`, or nullptr.
const builtin_network* find_builtin_network(std::string_view name) noexcept;

/// The summary of a run as one line of JSON (no newline): byte_times, seconds, end, and every node's state
/// (`trionet ring simulate --json`'s last line).
std::string summary_json(const ring_network& net, run_end end);

}  // namespace trionet::host
