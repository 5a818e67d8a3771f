// A simulated fibre ring whose Motion Coordinators run BASIC programs and whose membrane keypads are pressed by
// a script, all on one deterministic clock (docs/basic.md):
//
//   each byte-time:  the script's key presses and inputs due now -> the servo ticks due (axes move) -> every
//                    program runs its statements -> the ring moves one byte per link -> what happened is
//                    reported as events
//
// The run ends after a number of byte-times, or as soon as every program has ended, failed or waits for ever
// (GET# or WAIT UNTIL with nothing left to come, or a loop that changes nothing), the script is done and the
// ring is quiet. Host side (heap, std::function). The ring's nodes are those of the library; everything that
// touches their API is in ring_network.cpp, so this header has no ring node types.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "trionet/ring/crc.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/ring/keypad_display.hpp"
#include "trionet/ring/variable_layout.hpp"

namespace trionet::host {

/// One node of the ring, in ring order.
struct node_spec {
  enum class kind : std::uint8_t { mc, keypad };
  kind what = kind::mc;
  std::string program_name;  ///< mc: the program's file name, for messages ("" with no program)
  std::string program_text;  ///< mc: the program (empty and no name: a plain node)
};

struct network_config {
  std::uint32_t statements_per_byte_time = 1;  ///< per program
  double bit_rate = 125000;                    ///< bits per second on every link
  unsigned bits_per_byte = 10;                 ///< start bit, 8 data bits, stop bit
  std::uint64_t key_gap = 1000;                ///< byte-times a key press takes before the script goes on
  std::size_t vr_count = 1024;                 ///< VR(0) .. VR(vr_count - 1) on every Motion Coordinator
  ring::crc16_parameters crc{};                ///< the CRC of direct variable transfers (a profile's)
  ring::variable_layout_parameters layout{};   ///< their layout (a profile's)
  ring::keypad_codes keypad_codes = ring::default_keypad_codes;  ///< what every keypad sends for each key
  std::uint8_t (*key_off_code)(std::uint8_t) noexcept = ring::default_key_off_code;  ///< the key OFF rule
  ring::defkey_table defkey = ring::default_defkey;  ///< every MC's GET#3 translation
  ring::display_model display{};                     ///< what every keypad's display does with 13, 10, 27 'H'
  double servo_period_us = 1000;  ///< every MC's SERVO_PERIOD: the clock of its axes, TICKS and WA
  std::size_t axes = 8;           ///< axes per Motion Coordinator
};

enum class event_kind : std::uint8_t {
  message,       ///< a whole message went over a link (trace)
  frame_error,   ///< bytes on a link that are no valid message (trace)
  display,       ///< a keypad's display changed (trace): `display` holds its two lines
  key,           ///< the script pressed a key
  dropped,       ///< a keypad dropped a message: what, where and why
  vr_from_ring,  ///< a direct variable transfer wrote a VR
  output,        ///< a line a program printed on its terminal or a serial channel (PRINT, PRINT #0, #1 ...)
  netstat,       ///< NETSTAT gained error bits
  io,            ///< an input set by the script, an output set by OP, WDOG switched
  motion,        ///< a move started, ended or was cancelled (trace)
  error,         ///< a runtime error that ON BASICERROR GOTO took
  ended,         ///< a program ended
  failed,        ///< a program stopped with a runtime error
};

constexpr const char* to_string(event_kind kind) noexcept {
  switch (kind) {
    case event_kind::message:
      return "message";
    case event_kind::frame_error:
      return "frame_error";
    case event_kind::display:
      return "display";
    case event_kind::key:
      return "key";
    case event_kind::dropped:
      return "dropped";
    case event_kind::vr_from_ring:
      return "vr_from_ring";
    case event_kind::output:
      return "output";
    case event_kind::netstat:
      return "netstat";
    case event_kind::io:
      return "io";
    case event_kind::motion:
      return "motion";
    case event_kind::error:
      return "error";
    case event_kind::ended:
      return "ended";
    case event_kind::failed:
      return "failed";
  }
  return "unknown";
}

struct network_event {
  event_kind kind;
  std::uint64_t time;                ///< byte-time
  std::size_t node;                  ///< 1-based ring position (message, frame_error: the sending node)
  std::string text;                  ///< what happened, readable
  std::vector<std::string> display;  ///< display: its two lines
};

/// Why a run ended.
enum class run_end : std::uint8_t {
  settled,  ///< every program ended, failed or waits for ever; the script is done; the ring is quiet
  limit,    ///< the byte-time limit
};

constexpr const char* to_string(run_end end) noexcept {
  switch (end) {
    case run_end::settled:
      return "settled";
    case run_end::limit:
      return "limit";
  }
  return "unknown";
}

/// An axis a program used, for summaries.
struct axis_report {
  std::size_t axis = 0;
  double dpos = 0;
  double mpos = 0;
  double speed = 0;  ///< VP_SPEED now
  unsigned mtype = 0;  ///< the running move's type (0: idle)
  bool idle = true;
  std::vector<std::pair<std::string, double>> parameters;  ///< those set to other than their default
};

/// A node's state, for summaries.
struct node_report {
  node_spec::kind what = node_spec::kind::mc;
  // mc
  std::string program;   ///< program name ("" for a plain node)
  std::string state;     ///< "running", "waiting", "ended", "failed" ("ended" for a plain node)
  std::string waiting;   ///< what a waiting program waits for, as BASIC writes it ("GET #", "WAIT UNTIL", ...)
  bool idle = false;     ///< running round a loop that changes nothing
  std::uint32_t line = 0;
  std::string error;
  std::uint32_t netstat = 0;
  std::vector<std::pair<std::size_t, double>> vrs;             ///< every VR that is not 0
  std::vector<std::pair<std::string, double>> variables;       ///< every named variable
  std::vector<axis_report> axes;                               ///< the axes the program used
  std::vector<std::size_t> inputs_on;                          ///< IN channels that are on
  std::vector<std::size_t> outputs_on;                         ///< OP channels that are on
  bool wdog = false;
  std::vector<std::pair<std::size_t, double>> table;           ///< TABLE entries that are not 0 (at most 64)
  std::size_t table_nonzero = 0;                               ///< how many there are
  std::uint64_t statements = 0;                                ///< statements run
  // keypad
  std::size_t keypad_number = 0;  ///< 1-based among the keypads, as the key script counts them
  bool network_mode = false;
  unsigned offset = 0;  ///< hops to where key presses go (0 in local mode)
  std::vector<std::string> display;
  bool cursor_visible = true;
  std::uint32_t dropped = 0;  ///< messages dropped in local mode (to it or through it)
  std::uint32_t keys_sent = 0;
  std::uint32_t keys_lost = 0;
};

class ring_network {
 public:
  /// Builds the ring (2..15 nodes, at least one Motion Coordinator) and compiles its programs. Null with
  /// `error` set ("NAME:LINE:COLUMN: message" for a program that does not compile).
  static std::unique_ptr<ring_network> build(const std::vector<node_spec>& nodes, const network_config& config,
                                             std::string& error);
  ~ring_network();
  ring_network(const ring_network&) = delete;
  ring_network& operator=(const ring_network&) = delete;

  /// The operator's key script (grammar in docs/basic.md), e.g. "wait=500 1:7 1:up 1:Y wait=2000 2:start";
  /// also the inputs: "node1:in7=on".
  /// False with `error` naming the bad word.
  bool set_keys(const std::string& script, std::string& error);

  /// Every event as it happens.
  void on_event(std::function<void(const network_event&)> sink);
  /// Every byte sent on a link (link i runs from node i + 1 to the next node), e.g. for a capture file.
  void on_link_byte(std::function<void(std::uint64_t time, std::size_t link, std::uint8_t byte)> sink);

  /// One byte-time.
  void step();
  /// Steps until the run settles or `max_byte_times` have passed since the start; then reports the lines
  /// programs left unfinished on their terminals, unless this is not the `last_piece` of a longer run.
  run_end run(std::uint64_t max_byte_times, bool last_piece = true);
  /// True after a step that met the end condition.
  bool settled() const;
  std::uint64_t now() const;
  double seconds() const;

  std::size_t size() const;
  std::size_t keypads() const;
  node_report report(std::size_t node) const;  ///< 1-based

  /// Presses and releases a key now on keypad `keypad` (1-based among keypads); false with `error` for an
  /// unknown keypad or key name. For an interactive front end.
  bool press(std::size_t keypad, const std::string& key_name, std::string& error);

 private:
  struct state;
  explicit ring_network(std::unique_ptr<state> s);
  std::unique_ptr<state> s_;
};

}  // namespace trionet::host
