// The Genius bus the simulator is measured on, by the timed benchmark (BM_genius_simulator) and by the
// instruction counter (genius_bus_30_devices): a bus controller at 0 ft that sends every device its outputs
// as blocks once a scan, and `devices` devices spread over 2000 ft that broadcast their inputs at their turns
// (2..8 bytes in, 1..4 out), at 153.6 kbit/s, new data every turn; every start bit and character reaches each
// device at its own time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "genius_bus.hpp"

namespace trionet::bench {

inline std::vector<host::genius_station> genius_layout(std::size_t devices) {
  std::vector<host::genius_station> stations;
  stations.push_back({31, 0.0, 0, 0});  // the bus controller: it only sends outputs (blocks)
  for (std::size_t i = 0; i < devices; ++i) {
    host::genius_station st;
    st.sba = static_cast<std::uint8_t>(i);
    st.position_ft = 2000.0 * static_cast<double>(i + 1) / static_cast<double>(devices);
    st.input_bytes = static_cast<std::uint16_t>(2 + i % 7);
    st.output_bytes = static_cast<std::uint16_t>(1 + i % 4);
    stations.push_back(st);
  }
  return stations;
}

inline host::genius_bus_config genius_config(std::uint32_t scans) {
  host::genius_bus_config config;
  config.controller = 31;
  config.scans = scans;
  config.record_turns = false;
  return config;
}

}  // namespace trionet::bench
