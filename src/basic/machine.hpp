// The part of a simulated Motion Coordinator that is not the ring: its servo clock, its axes, its digital I/O,
// its TABLE memory and its watchdog (docs/basic.md, "Time and motion"). Deterministic and host side; whoever
// owns the clock calls servo_tick() once per servo period, and a program (task.hpp) reads and commands it.
//
//   servo_tick():  moves waiting at the head of every axis they use start; every running move advances one
//                  servo period along its trapezoidal profile (SPEED, ACCEL, DECEL of its base axis); a move
//                  that reaches its end, or stops after CANCEL or RAPIDSTOP, ends and the next one starts
//
// Positions are kept in encoder edges (user units x UNITS) as a real controller keeps them; DPOS and MPOS are
// read in user units. A simulated axis follows its demand exactly: MPOS is DPOS to the nearest whole encoder
// edge (what an encoder counts) and FE is 0. DEFPOS and OFFPOS change a position at the next servo tick, during
// a move too (the move goes on for the rest of its distance).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace trionet::basic {

/// The axis parameters the simulator models, in the order of `axis_parameter_table`.
enum class axis_parameter : std::uint8_t {
  accel,
  atype,
  creep,
  d_gain,
  decel,
  dpos,
  endmove,
  fe,
  fe_limit,
  fs_limit,
  i_gain,
  idle,
  jogspeed,
  mpos,
  mspeed,
  mtype,
  ntype,
  offpos,
  ov_gain,
  p_gain,
  remain,
  rep_dist,
  rep_option,
  rs_limit,
  servo,
  speed,
  units,
  vff_gain,
  vp_speed,
};
inline constexpr std::size_t axis_parameter_count = 29;

struct axis_parameter_info {
  const char* name;
  bool read_only;        ///< the axis computes it: a program cannot assign it
  double default_value;  ///< the simulator's power-up value (read-only ones: not used)
};

const axis_parameter_info& info(axis_parameter p) noexcept;
/// The parameter named `upper_case_name`, or false.
bool find_axis_parameter(const std::string& upper_case_name, axis_parameter& out) noexcept;

/// MTYPE and NTYPE values, as the manual numbers them.
enum class move_type : std::uint8_t { idle = 0, move = 1, moveabs = 2, forward = 10, reverse = 11, datum = 12 };

const char* to_string(move_type type) noexcept;  ///< "MOVE", "MOVEABS", ...

struct machine_config {
  std::size_t axes = 8;           ///< AXIS(0) .. AXIS(axes - 1)
  std::size_t table_size = 16000;  ///< TABLE(0) .. TABLE(table_size - 1)
  std::size_t io_count = 32;       ///< IN(0) .. IN(io_count - 1); outputs OP(8) .. OP(io_count - 1)
  double servo_period_us = 1000;   ///< SERVO_PERIOD: the motion and TICKS clock (docs/protocol.md 4)
  double control = 206;            ///< what CONTROL reads
};

/// Something that happened to an axis or an output, for the trace.
struct machine_event {
  std::uint64_t tick;  ///< servo tick at which it happened
  std::string text;    ///< "axis 0: MOVE(100) starts at DPOS 0", ...
};

enum class motion_status : std::uint8_t {
  ok,
  busy,      ///< the axes' move buffers are full: try again later
  bad_axis,  ///< an axis number the controller does not have, or the same axis twice
};

class machine {
 public:
  explicit machine(const machine_config& config = {});

  // ---- the clock ----
  /// One servo period passes: the offsets DEFPOS and OFFPOS left are applied, then moves start, advance and
  /// end.
  void servo_tick();
  std::uint64_t ticks() const noexcept { return ticks_; }
  double servo_period_us() const noexcept { return config_.servo_period_us; }
  double control() const noexcept { return config_.control; }

  // ---- axes ----
  std::size_t axis_count() const noexcept { return axes_.size(); }
  double axis_value(std::size_t axis, axis_parameter p) const;
  enum class set_status : std::uint8_t { ok, read_only, out_of_range };
  /// Sets a writable parameter. A change of SPEED, ACCEL, DECEL or CREEP applies at once to the move the axis
  /// is the base of. UNITS must be above 0. OFFPOS shifts the position by `value` at the next servo tick (it
  /// reads the offset still to apply, 0 once applied).
  set_status set_axis_value(std::size_t axis, axis_parameter p, double value);
  /// MOVE (relative distances) or MOVEABS (end positions) on `axes`, one value each, in user units; the first
  /// axis's SPEED, ACCEL and DECEL shape the path. `busy` while any of the axes has a move running and one
  /// buffered.
  motion_status move(const std::vector<std::size_t>& axes, const std::vector<double>& values, move_type type);
  /// FORWARD (direction +1) or REVERSE (-1): at SPEED until CANCEL or RAPIDSTOP.
  motion_status forward(std::size_t axis, int direction);
  /// DATUM(mode) simplified: mode 0 does nothing (no motion errors to clear); 1..6 move to 0 at CREEP and
  /// define that as the datum.
  motion_status datum(std::size_t axis, int mode);
  /// DEFPOS: the axes' positions become `values` at the next servo tick, as the manual's controller does it
  /// (OFFPOS becomes each value less DPOS now); a running move goes on for the rest of its distance.
  motion_status defpos(const std::vector<std::size_t>& axes, const std::vector<double>& values);
  /// CANCEL: the running move decelerates at DECEL and ends (the buffered one then starts);
  /// CANCEL(1): the buffered move is dropped.
  void cancel(std::size_t axis, bool buffered);
  /// RAPIDSTOP: every axis's running move decelerates and ends; buffered moves are dropped.
  void rapidstop();
  bool idle(std::size_t axis) const { return axes_[axis].queue[0] < 0; }
  bool loaded(std::size_t axis) const { return axes_[axis].queue[1] < 0; }
  /// True while any move is running or waiting in a buffer, or an offset (DEFPOS, OFFPOS) waits for the next
  /// servo tick: while the positions may change.
  bool any_motion() const noexcept { return moves_in_use_ != 0 || offsets_pending_; }
  /// True for an axis a program has commanded or set up, or that is away from 0 (what a report shows).
  bool used(std::size_t axis) const { return axes_[axis].used; }

  // ---- digital I/O ----
  std::size_t io_count() const noexcept { return config_.io_count; }
  /// IN(n): the input as the operator's script set it, or the output driven on the same channel.
  bool input(std::size_t n) const { return inputs_[n] || outputs_[n]; }
  /// The input as the operator's script set it (without the output).
  bool input_signal(std::size_t n) const { return inputs_[n]; }
  void set_input(std::size_t n, bool on) { inputs_[n] = on; }
  bool output(std::size_t n) const { return outputs_[n]; }
  /// OP(n, state); false for a channel that is an input only (0..7) or beyond io_count.
  bool set_output(std::size_t n, bool on);

  // ---- TABLE ----
  std::size_t table_size() const noexcept { return table_.size(); }
  double table(std::size_t i) const { return table_[i]; }
  void set_table(std::size_t i, double value) { table_[i] = value; }

  // ---- WDOG ----
  bool wdog() const noexcept { return wdog_; }
  void set_wdog(bool on);

  /// Events since the last call, oldest first.
  std::vector<machine_event> take_events();

 private:
  struct axis_state {
    std::array<double, axis_parameter_count> parameters{};
    double position = 0;  // DPOS in edges
    double speed = 0;     // user units per second along the axis, for VP_SPEED
    int queue[2] = {-1, -1};  // running (or waiting to start) and buffered move, as indexes into moves_
    bool used = false;
  };
  // A trapezoidal profile along a path of `length` user units, from speed v0: ramp to vp at rate a1 (t1 s),
  // cruise (tc s, or for ever), decelerate at d2 to 0 (t2 s).
  struct profile {
    double v0 = 0, vp = 0, a1 = 0, t1 = 0, s1 = 0, tc = 0, sc = 0, d2 = 0, t2 = 0;
    bool endless = false;
    double distance(double t) const;
    double speed(double t) const;
    double duration() const { return t1 + tc + t2; }
  };
  struct move_state {
    move_type type = move_type::idle;
    bool in_use = false;
    bool running = false;
    bool loaded = false;    // in an axis's buffers: a move commanded waits in the process until the next tick
    bool stopping = false;  // CANCEL or RAPIDSTOP: decelerating to its end
    std::vector<std::size_t> axes;
    std::vector<double> values;     // as commanded (distances or end positions), user units
    std::vector<double> component;  // user units per unit of path, per axis
    std::vector<double> origin;     // each axis's position in edges when the move started (wraps included)
    double length = 0;              // of the path, user units (0 for an endless one)
    bool endless = false;
    double done = 0;     // path covered when the profile was (re)planned
    double elapsed = 0;  // seconds since then: ticks x the servo period (no sum of rounded steps)
    std::uint64_t ticks = 0;
    profile plan;
  };

  double units(std::size_t axis) const;
  double parameter(std::size_t axis, axis_parameter p) const {
    return axes_[axis].parameters[static_cast<std::size_t>(p)];
  }
  bool valid(const std::vector<std::size_t>& axes) const;
  int allocate_move();
  bool queue_move(int index);
  void start_ready_moves();
  void start(int index);
  void replan(move_state& m, bool stop);
  void advance(int index, double dt);
  void finish(int index, const char* how);
  void stop_at_limit(int index, std::size_t axis, double limit, const char* name);
  void wrap(std::size_t axis, move_state& m, std::size_t k);
  void apply_offsets();
  double covered(const move_state& m) const;
  double remain(std::size_t axis) const;
  void event(std::string text);
  std::string describe(const move_state& m) const;

  machine_config config_;
  std::uint64_t ticks_ = 0;
  std::vector<axis_state> axes_;
  std::vector<move_state> moves_;
  std::size_t moves_in_use_ = 0;
  bool offsets_pending_ = false;  // some axis's OFFPOS is not 0
  std::vector<bool> inputs_;
  std::vector<bool> outputs_;
  std::vector<double> table_;
  bool wdog_ = false;
  std::vector<machine_event> events_;
};

}  // namespace trionet::basic
