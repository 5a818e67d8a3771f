// A Genius bus of real device nodes (docs/genius.md, "A bus of devices"): N `genius::device`s, each behind a
// modelled UART and timer, on one line with positions in feet, on one deterministic clock.
//
// Time is integer picoseconds. A signal travels `propagation_us_per_2000ft` per 2000 ft. The line is 1 when
// idle; every transmitter (and a noise burst) pulls it to 0 for its 0 bits, as seen at each point after
// the propagation delay (a collision is the AND of the signals). Each device's receiver is a UART: a 1 -> 0
// edge, confirmed as a start bit `detection_us` later (the device's `start_bit`), then ten more samples one
// bit time apart (control, data, stop): a word (`receive`) or a framing error (`framing_error`), delivered
// at the stop bit's sample; a timer the device arms then runs from the end of that character. A device's
// transmitter sends its words back to back; the next one is asked for when the last is read back.
// Nothing is a formula of turn times: turns happen because the devices' timers expire.
//
// Host side (heap). Not for firmware.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "trionet/genius/bus_access.hpp"
#include "trionet/genius/device.hpp"

namespace trionet::host {

/// One device on the simulated bus.
struct genius_station {
  std::uint8_t sba = 0;            ///< its SBA, 0..31
  double position_ft = 0;          ///< where it sits on the line
  std::uint16_t input_bytes = 1;   ///< its inputs: a broadcast of this many bytes every turn (0: none)
  std::uint16_t output_bytes = 0;  ///< its outputs: a block of this many bytes from the bus controller
};

/// A fault injected into the bus.
enum class genius_fault_kind : std::uint8_t {
  noise,      ///< a burst of random levels at `position_ft` for `duration_us`
  power_off,  ///< device `sba` off (silent, deaf) for `duration_us`, then on again (a fresh device)
  stop,       ///< device `sba` stops in the middle of its next transmission from `at_us` on, off for
              ///< `duration_us`
  cut,        ///< the line cut at `position_ft` for `duration_us`: no signal crosses it
};

constexpr const char* to_string(genius_fault_kind kind) noexcept {
  switch (kind) {
    case genius_fault_kind::noise:
      return "noise";
    case genius_fault_kind::power_off:
      return "power_off";
    case genius_fault_kind::stop:
      return "stop";
    case genius_fault_kind::cut:
      return "cut";
  }
  return "unknown";
}

struct genius_fault {
  genius_fault_kind kind = genius_fault_kind::noise;
  double at_us = 0;        ///< when it begins (microseconds from the start of the run)
  double duration_us = 0;  ///< how long it lasts
  std::uint8_t sba = 0;    ///< power_off, stop: the device
  double position_ft = 0;  ///< noise, cut: where
};

struct genius_bus_config {
  genius::rate rate = genius::rate::standard_153k6;
  double skip_us = 0;                      ///< the skip time; 0: the rule (1 bit, 2 at 153.6e)
  double propagation_us_per_2000ft = 3.0;  ///< docs/protocol.md 3.3
  double detection_us = -1;                ///< start bit confirmed this long after its edge; < 0: half a bit
  int controller = -1;                     ///< the bus controller's SBA (one of the stations), or -1
  std::uint32_t scans = 10;                ///< the run ends when this many scans are complete
  double max_us = 0;                       ///< and at the latest after this long (0: a bound from the layout)
  std::vector<genius_fault> faults;
  std::uint64_t seed = 1;         ///< noise patterns and the data the devices send
  bool new_data_every_turn = true;  ///< each device's inputs (and the controller's outputs) change every turn
  bool record_turns = true;       ///< keep the turns, transmissions and scans (off for long soaks and benches)
  /// With record_turns: the turns and transmissions are kept for this many scans from the start only (the scan
  /// times are kept for every scan), so that a long run's memory does not grow with its turns.
  std::uint32_t record_scans = 0xFFFFFFFFU;
  /// A listener alone with one transmission takes its characters in a batch, and a sender that every other
  /// device follows reads its own back ahead (the same calls at the same simulated times; genius_bus.cpp,
  /// "following" and read_back_ahead). Off: an event per start bit and per word, always.
  bool follow = true;
  /// Check every whole transmission against every device that listened while it passed (powered throughout,
  /// not cut off from the sender): it heard it, or counted an error (genius_bus_result::losses_*).
  bool check_losses = false;
};

/// The scan's time origin: the end of a Stop of the scan's opener (the controller, else the lowest SBA that
/// sends), at the opener's position.
struct genius_turn_record {
  std::uint8_t sba = 0;
  double due_us = 0;           ///< when its turn timer, armed by the opening Stop, expires (or would)
  bool cancelled = false;      ///< a start bit came first
  std::uint8_t by = 0;         ///< cancelled: whose start bit
  double arrived_us = 0;       ///< cancelled: when that start bit's edge reached it
  double detected_us = 0;      ///< cancelled: when it detected it
  bool transmitted = false;    ///< it sent at that turn
  bool passed = false;         ///< its turn passed in silence (nothing to send)
};

struct genius_transmission_record {
  std::uint8_t sba = 0;
  double start_us = 0;       ///< its first character begins (absolute, microseconds from the start)
  double end_us = 0;         ///< its last character ends
  std::size_t characters = 0;
  bool whole = false;        ///< it ended with its Stop
  bool collided = false;     ///< its signal overlapped another transmission somewhere on the line
};

/// One Stop put on the bus, and the turns every other device armed when it heard it.
struct genius_stop_record {
  std::uint8_t sender = 0;
  double end_us = 0;  ///< the end of the Stop at the sender (absolute)
  struct armed {
    std::uint8_t sba;
    double due_us;     ///< absolute
    bool cancelled;
    std::uint8_t by;
    double arrived_us;
    double detected_us;
    bool transmitted;
    bool passed;
  };
  std::vector<armed> turns;
};

struct genius_device_report {
  std::uint8_t sba = 0;
  genius::device_counters counters{};
  std::uint8_t netstat = 0;
  std::uint64_t deliveries_checked = 0;  ///< deliveries compared with what their sender sent
  std::uint64_t wrong_deliveries = 0;    ///< of which did not match (passed the CRC-6 all the same)
  std::uint64_t wrong_data = 0;          ///< of those, wrong in bytes the CRC-6 covers
  std::uint64_t power_cycles = 0;
};

struct genius_bus_result {
  std::uint8_t opener = 0;                           ///< whose Stops open the scans
  std::vector<genius_turn_record> first_scan_turns;  ///< in turn order (SBA order after the opener)
  std::vector<double> scan_us;                       ///< each complete scan's length
  std::vector<double> scan_ends_us;                  ///< the opening Stop of each scan (absolute); one more than scans
  std::vector<genius_transmission_record> transmissions;
  std::vector<genius_stop_record> stops;
  std::size_t collisions = 0;            ///< groups of transmissions whose signals overlapped on the line
  std::size_t colliding_transmissions = 0;
  std::uint64_t transmissions_started = 0;
  std::uint64_t deliveries = 0;
  std::uint64_t wrong_deliveries = 0;
  std::uint64_t wrong_data = 0;
  /// Corrupted transmissions that reached a CRC-6 check, counted once however many devices checked them (a
  /// corruption on the line is the same for every device that samples it): those that failed it somewhere,
  /// and those delivered somewhere with bytes their sender did not send (escapes).
  std::uint64_t corrupt_events = 0;
  std::uint64_t escape_events = 0;
  std::vector<genius_device_report> devices;
  double faults_end_us = 0;   ///< when the last fault ended (a `stop` from when it took effect)
  std::uint64_t losses_checked = 0;    ///< check_losses: (transmission, listener) pairs checked
  std::uint64_t losses_uncounted = 0;  ///< of which the listener neither heard it nor counted an error
  std::vector<std::string> loss_details;  ///< the first few uncounted losses, described
  double end_us = 0;          ///< simulated time at the end (the time bound, if the run stopped there)
  std::uint64_t events = 0;   ///< simulation events processed
  std::uint64_t line_steps = 0;  ///< steps taken finding where the line goes back to 1 (linear in its edges)
  bool complete = false;      ///< all `scans` scans completed (else the time bound ended the run)
};

/// Validates a layout and configuration; "" when fine, else what is wrong.
std::string check_genius_bus(const std::vector<genius_station>& stations, const genius_bus_config& config);

/// One simulated bus. `on_word(time_us, word, framing_ok)` (optional) sees every character a passive monitor
/// at `monitor_ft` receives (the 11-bit wire word), for a capture; `on_trace(line)` (optional) every event.
class genius_bus {
 public:
  /// Precondition: check_genius_bus(stations, config) is "".
  genius_bus(const std::vector<genius_station>& stations, const genius_bus_config& config);
  ~genius_bus();
  genius_bus(const genius_bus&) = delete;
  genius_bus& operator=(const genius_bus&) = delete;

  void monitor(double position_ft, std::function<void(double time_us, std::uint16_t wire_word)> on_word);
  void trace(std::function<void(const std::string& line)> on_trace);

  /// Runs until `scans` scans are complete or the time bound; returns what happened.
  genius_bus_result run();

  /// Picoseconds per bit, per skip time, the detection time, and the propagation between two positions.
  std::int64_t bit_ps() const;
  std::int64_t skip_ps() const;
  std::int64_t detection_ps() const;

 private:
  struct state;
  std::unique_ptr<state> s_;
};

}  // namespace trionet::host
