#include "basic/machine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "basic/number_format.hpp"

namespace trionet::basic {
namespace {

constexpr axis_parameter_info parameter_table[axis_parameter_count] = {
    {"ACCEL", false, 1000},
    {"ATYPE", false, 0},
    {"CREEP", false, 200},
    {"D_GAIN", false, 0},
    {"DECEL", false, 1000},
    {"DPOS", true, 0},
    {"ENDMOVE", true, 0},
    {"FE", true, 0},
    {"FE_LIMIT", false, 2000},
    {"FS_LIMIT", false, 200000000},
    {"I_GAIN", false, 0},
    {"IDLE", true, 0},
    {"JOGSPEED", false, 200},
    {"MPOS", true, 0},
    {"MSPEED", true, 0},
    {"MTYPE", true, 0},
    {"NTYPE", true, 0},
    {"OFFPOS", false, 0},
    {"OV_GAIN", false, 0},
    {"P_GAIN", false, 1},
    {"REMAIN", true, 0},
    {"REP_DIST", false, 200000000},
    {"REP_OPTION", false, 0},
    {"RS_LIMIT", false, -200000000},
    {"SERVO", false, 0},
    {"SPEED", false, 1000},
    {"UNITS", false, 1},
    {"VFF_GAIN", false, 0},
    {"VP_SPEED", true, 0},
};

constexpr double forever = std::numeric_limits<double>::infinity();

std::string axes_text(const std::vector<std::size_t>& axes) {
  std::string out = axes.size() == 1 ? "axis " : "axes ";
  for (std::size_t i = 0; i < axes.size(); ++i) out += (i ? "," : "") + std::to_string(axes[i]);
  return out;
}

}  // namespace

const axis_parameter_info& info(axis_parameter p) noexcept {
  return parameter_table[static_cast<std::size_t>(p)];
}

bool find_axis_parameter(const std::string& upper_case_name, axis_parameter& out) noexcept {
  for (std::size_t i = 0; i < axis_parameter_count; ++i) {
    if (upper_case_name == parameter_table[i].name) {
      out = static_cast<axis_parameter>(i);
      return true;
    }
  }
  return false;
}

const char* to_string(move_type type) noexcept {
  switch (type) {
    case move_type::idle:
      return "idle";
    case move_type::move:
      return "MOVE";
    case move_type::moveabs:
      return "MOVEABS";
    case move_type::forward:
      return "FORWARD";
    case move_type::reverse:
      return "REVERSE";
    case move_type::datum:
      return "DATUM";
  }
  return "?";
}

// ---- the profile ----

double machine::profile::distance(double t) const {
  if (t <= t1) return v0 * t + 0.5 * a1 * t * t;
  const double cruising = t - t1;
  if (endless || cruising <= tc) return s1 + vp * cruising;
  const double braking = std::min(cruising - tc, t2);
  return s1 + sc + vp * braking - 0.5 * d2 * braking * braking;
}

double machine::profile::speed(double t) const {
  if (t <= t1) return v0 + a1 * t;
  const double cruising = t - t1;
  if (endless || cruising <= tc) return vp;
  const double braking = std::min(cruising - tc, t2);
  return std::max(0.0, vp - d2 * braking);
}

namespace {

// From speed v0 >= 0 over `remaining` user units (endless: no end), at most vmax, speeding up at `accel` and
// slowing down at `decel` (a rate of 0 or less changes speed at once). A path too short to stop on at `decel`
// is stopped on harder, so that no move runs past its end.
template <class Profile>
Profile plan_profile(double v0, double vmax, double accel, double decel, double remaining, bool endless) {
  Profile p;
  p.v0 = v0;
  p.endless = endless;
  if (!(vmax > 0)) vmax = 0;
  const bool instant_up = !(accel > 0);
  const bool instant_down = !(decel > 0);
  const auto ramp = [&](double from, double to) {  // phase 1: from -> to
    if (to >= from) {
      p.a1 = instant_up ? 0 : accel;
      p.t1 = instant_up ? 0 : (to - from) / accel;
    } else {
      p.a1 = instant_down ? 0 : -decel;
      p.t1 = instant_down ? 0 : (from - to) / decel;
    }
    p.s1 = p.t1 * (from + to) / 2;
    if (p.t1 == 0) p.a1 = 0;
    p.vp = to;
  };
  const auto brake = [&](double from) {  // phase 3: from -> 0 at decel
    p.d2 = instant_down ? 0 : decel;
    p.t2 = instant_down ? 0 : from / decel;
  };
  if (endless) {
    ramp(v0, vmax);
    return p;
  }
  const double stopping = instant_down ? 0 : v0 * v0 / (2 * decel);
  if (stopping >= remaining) {  // decelerate to the end
    p.vp = v0;
    if (v0 > 0 && remaining > 0) {
      p.t2 = 2 * remaining / v0;
      p.d2 = v0 / p.t2;
    }
    return p;
  }
  if (vmax == 0) {  // SPEED 0: slow down and stay short of the end
    ramp(v0, 0);
    p.endless = true;
    return p;
  }
  double peak = vmax;
  if (v0 <= vmax) {
    const double up = instant_up ? 0 : 1 / (2 * accel);
    const double down = instant_down ? 0 : 1 / (2 * decel);
    if (up + down > 0) peak = std::min(vmax, std::sqrt((remaining + v0 * v0 * up) / (up + down)));
  }
  ramp(v0, peak);
  brake(peak);
  const double braking_distance = p.t2 * peak / 2;
  p.sc = std::max(0.0, remaining - p.s1 - braking_distance);
  p.tc = peak > 0 ? p.sc / peak : 0;
  return p;
}

}  // namespace

// ---- the machine ----

machine::machine(const machine_config& config)
    : config_(config),
      axes_(config.axes),
      inputs_(config.io_count, false),
      outputs_(config.io_count, false),
      table_(config.table_size, 0.0) {
  if (!(config_.servo_period_us > 0)) config_.servo_period_us = 1000;
  for (axis_state& a : axes_) {
    for (std::size_t i = 0; i < axis_parameter_count; ++i) a.parameters[i] = parameter_table[i].default_value;
  }
  moves_.resize(2 * axes_.size());
}

double machine::units(std::size_t axis) const {
  return parameter(axis, axis_parameter::units);
}

void machine::event(std::string text) {
  events_.push_back({ticks_, std::move(text)});
}

std::vector<machine_event> machine::take_events() {
  std::vector<machine_event> out;
  out.swap(events_);
  return out;
}

std::string machine::describe(const move_state& m) const {
  std::string out = std::string(to_string(m.type));
  if (m.type == move_type::forward || m.type == move_type::reverse) return out;
  out += '(';
  for (std::size_t i = 0; i < m.values.size(); ++i) out += (i ? "," : "") + format_value(m.values[i]);
  return out + ')';
}

void machine::set_wdog(bool on) {
  if (on == wdog_) return;
  wdog_ = on;
  event(on ? "WDOG ON" : "WDOG OFF");
}

bool machine::set_output(std::size_t n, bool on) {
  if (n < 8 || n >= outputs_.size()) return false;
  if (outputs_[n] != on) {
    outputs_[n] = on;
    event("OP(" + std::to_string(n) + (on ? ",ON)" : ",OFF)"));
  }
  return true;
}

double machine::covered(const move_state& m) const {
  if (!m.running) return 0;
  const double s = m.done + m.plan.distance(m.elapsed);
  return m.endless ? s : std::min(s, m.length);
}

double machine::remain(std::size_t axis) const {
  const int index = axes_[axis].queue[0];
  if (index < 0) return 0;
  const move_state& m = moves_[static_cast<std::size_t>(index)];
  if (!m.running || m.endless) return 0;
  const auto k = static_cast<std::size_t>(std::find(m.axes.begin(), m.axes.end(), axis) - m.axes.begin());
  return std::fabs(m.component[k]) * (m.length - covered(m));
}

double machine::axis_value(std::size_t axis, axis_parameter p) const {
  const axis_state& a = axes_[axis];
  switch (p) {
    case axis_parameter::dpos:
      return a.position / units(axis);
    case axis_parameter::mpos:  // an encoder counts whole edges
      return std::round(a.position) / units(axis);
    case axis_parameter::endmove: {
      if (a.queue[0] < 0) return a.position / units(axis);
      const move_state& m = moves_[static_cast<std::size_t>(a.queue[0])];
      if (!m.running || m.endless) return a.position / units(axis);
      const auto k = static_cast<std::size_t>(std::find(m.axes.begin(), m.axes.end(), axis) - m.axes.begin());
      return m.origin[k] / units(axis) + m.component[k] * m.length;
    }
    case axis_parameter::fe:
      return 0;
    case axis_parameter::idle:
      return a.queue[0] < 0 ? -1.0 : 0.0;
    case axis_parameter::mtype: {
      if (a.queue[0] < 0) return 0;
      const move_state& m = moves_[static_cast<std::size_t>(a.queue[0])];
      return m.running ? static_cast<double>(m.type) : 0.0;
    }
    case axis_parameter::ntype: {
      // The manual's PMOVE: a move command waits in the process's move buffer until the next servo tick loads
      // it into the axis's next-move buffer; NTYPE shows it from then on, until it starts.
      for (const int index : {a.queue[1], a.queue[0]}) {
        if (index < 0) continue;
        const move_state& m = moves_[static_cast<std::size_t>(index)];
        if (m.loaded && !m.running) return static_cast<double>(m.type);
      }
      return 0;
    }
    case axis_parameter::remain:
      return remain(axis);
    case axis_parameter::mspeed:
    case axis_parameter::vp_speed:
      return a.speed;
    default:
      return a.parameters[static_cast<std::size_t>(p)];
  }
}

machine::set_status machine::set_axis_value(std::size_t axis, axis_parameter p, double value) {
  if (info(p).read_only) return set_status::read_only;
  if (p == axis_parameter::units && !(value > 0)) return set_status::out_of_range;
  axis_state& a = axes_[axis];
  a.parameters[static_cast<std::size_t>(p)] = value;
  a.used = true;
  if (p == axis_parameter::offpos && value != 0) offsets_pending_ = true;
  if (p == axis_parameter::speed || p == axis_parameter::accel || p == axis_parameter::decel ||
      p == axis_parameter::creep) {
    const int index = a.queue[0];
    if (index >= 0) {
      move_state& m = moves_[static_cast<std::size_t>(index)];
      if (m.running && m.axes.front() == axis) replan(m, m.stopping);
    }
  }
  return set_status::ok;
}

bool machine::valid(const std::vector<std::size_t>& axes) const {
  if (axes.empty()) return false;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (axes[i] >= axes_.size()) return false;
    for (std::size_t j = 0; j < i; ++j) {
      if (axes[i] == axes[j]) return false;
    }
  }
  return true;
}

int machine::allocate_move() {
  for (std::size_t i = 0; i < moves_.size(); ++i) {
    if (!moves_[i].in_use) {
      moves_[i] = move_state{};
      moves_[i].in_use = true;
      ++moves_in_use_;
      return static_cast<int>(i);
    }
  }
  return -1;  // cannot happen: at most two moves per axis are in use
}

bool machine::queue_move(int index) {
  move_state& m = moves_[static_cast<std::size_t>(index)];
  for (std::size_t axis : m.axes) {
    axis_state& a = axes_[axis];
    (a.queue[0] < 0 ? a.queue[0] : a.queue[1]) = index;
    a.used = true;
  }
  return true;
}

motion_status machine::move(const std::vector<std::size_t>& axes, const std::vector<double>& values, move_type type) {
  if (!valid(axes) || axes.size() != values.size()) return motion_status::bad_axis;
  // One move runs (MTYPE) and one waits (NTYPE): a move not started yet holds the waiting place, so a second
  // move command waits for the first to start at the next servo tick.
  for (std::size_t axis : axes) {
    const axis_state& a = axes_[axis];
    if (a.queue[1] >= 0 || (a.queue[0] >= 0 && !moves_[static_cast<std::size_t>(a.queue[0])].running)) {
      return motion_status::busy;
    }
  }
  const int index = allocate_move();
  if (index < 0) return motion_status::busy;
  move_state& m = moves_[static_cast<std::size_t>(index)];
  m.type = type;
  m.axes = axes;
  m.values = values;
  queue_move(index);
  return motion_status::ok;
}

motion_status machine::forward(std::size_t axis, int direction) {
  return move({axis}, {static_cast<double>(direction)}, direction > 0 ? move_type::forward : move_type::reverse);
}

motion_status machine::datum(std::size_t axis, int mode) {
  if (axis >= axes_.size()) return motion_status::bad_axis;
  if (mode == 0) return motion_status::ok;
  return move({axis}, {0.0}, move_type::datum);
}

motion_status machine::defpos(const std::vector<std::size_t>& axes, const std::vector<double>& values) {
  if (!valid(axes) || axes.size() != values.size()) return motion_status::bad_axis;
  // The manual's controller turns DEFPOS into OFFPOS, applied at the next servo tick.
  for (std::size_t i = 0; i < axes.size(); ++i) {
    axis_state& a = axes_[axes[i]];
    a.parameters[static_cast<std::size_t>(axis_parameter::offpos)] = values[i] - a.position / units(axes[i]);
    a.used = true;
  }
  offsets_pending_ = true;
  std::string text = axes_text(axes) + ": DEFPOS(";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? "," : "") + format_value(values[i]);
  event(text + ")");
  return motion_status::ok;
}

// OFFPOS: each axis's position (and the origin of the move it runs, so that the move goes on for the rest of its
// distance) shifts by the offset left, which then reads 0.
void machine::apply_offsets() {
  offsets_pending_ = false;
  for (std::size_t axis = 0; axis < axes_.size(); ++axis) {
    axis_state& a = axes_[axis];
    double& offset = a.parameters[static_cast<std::size_t>(axis_parameter::offpos)];
    if (offset == 0) continue;
    const double shift = offset * units(axis);
    offset = 0;
    a.position += shift;
    const int index = a.queue[0];
    if (index < 0) continue;
    move_state& m = moves_[static_cast<std::size_t>(index)];
    if (!m.running) continue;
    const auto k = static_cast<std::size_t>(std::find(m.axes.begin(), m.axes.end(), axis) - m.axes.begin());
    m.origin[k] += shift;
  }
}

void machine::cancel(std::size_t axis, bool buffered) {
  if (axis >= axes_.size()) return;
  axis_state& a = axes_[axis];
  const int index = buffered ? a.queue[1] : a.queue[0];
  if (index < 0) return;
  move_state& m = moves_[static_cast<std::size_t>(index)];
  if (!buffered && m.running) {
    if (!m.stopping) {
      replan(m, true);
      event(axes_text(m.axes) + ": " + describe(m) + " cancelled, decelerating");
    }
    return;
  }
  // Not started yet: it goes from every axis's buffer.
  for (std::size_t other : m.axes) {
    axis_state& o = axes_[other];
    if (o.queue[1] == index) o.queue[1] = -1;
    if (o.queue[0] == index) {
      o.queue[0] = o.queue[1];
      o.queue[1] = -1;
    }
  }
  event(axes_text(m.axes) + ": " + describe(m) + " cancelled before it started");
  m.in_use = false;
  --moves_in_use_;
}

void machine::rapidstop() {
  for (std::size_t axis = 0; axis < axes_.size(); ++axis) {
    cancel(axis, true);
    cancel(axis, false);
  }
}

void machine::replan(move_state& m, bool stop) {
  const bool datum_move = m.type == move_type::datum;
  const std::size_t base = m.axes.front();
  const double vmax = parameter(base, datum_move ? axis_parameter::creep : axis_parameter::speed);
  const double accel = parameter(base, axis_parameter::accel);
  const double decel = parameter(base, axis_parameter::decel);
  const double v = m.running ? m.plan.speed(m.elapsed) : 0;
  m.done = covered(m);
  m.elapsed = 0;
  m.ticks = 0;
  if (stop) {
    double stopping = decel > 0 ? v * v / (2 * decel) : 0;
    if (!m.endless) stopping = std::min(stopping, m.length - m.done);
    m.length = m.done + stopping;
    m.endless = false;
    m.stopping = true;
    m.plan = plan_profile<profile>(v, vmax, accel, decel, stopping, false);
    return;
  }
  m.plan = plan_profile<profile>(v, vmax, accel, decel, m.endless ? forever : m.length - m.done, m.endless);
}

void machine::start(int index) {
  move_state& m = moves_[static_cast<std::size_t>(index)];
  const std::size_t n = m.axes.size();
  m.component.assign(n, 0.0);
  m.origin.resize(n);
  std::vector<double> distance(n, 0.0);
  std::string at;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t axis = m.axes[k];
    m.origin[k] = axes_[axis].position;
    const double dpos = axes_[axis].position / units(axis);
    at += (k ? ", " : "") + format_value(dpos);
    switch (m.type) {
      case move_type::move:
        distance[k] = m.values[k];
        break;
      case move_type::moveabs:
        distance[k] = m.values[k] - dpos;
        break;
      case move_type::datum:
        distance[k] = -dpos;
        break;
      case move_type::forward:
      case move_type::reverse:
        distance[k] = m.values[k];
        break;
      case move_type::idle:
        break;
    }
  }
  m.endless = m.type == move_type::forward || m.type == move_type::reverse;
  // The path's length, scaled by the largest distance so that no square overflows (MOVE(1e155) is a long move,
  // not one of infinite length in no direction).
  double largest = 0;
  for (double d : distance) largest = std::max(largest, std::fabs(d));
  double length = 0;
  if (largest > 0 && std::isfinite(largest)) {
    for (double d : distance) length += (d / largest) * (d / largest);
    length = largest * std::sqrt(length);
  }
  if (length > 0) {
    for (std::size_t k = 0; k < n; ++k) m.component[k] = distance[k] / length;
  }
  m.length = m.endless ? 0 : length;
  m.done = 0;
  m.elapsed = 0;
  m.ticks = 0;
  m.running = false;  // replan() reads the speed of a running move: this one starts from rest
  replan(m, false);
  m.running = true;
  event(axes_text(m.axes) + ": " + describe(m) + " starts at DPOS " + at);
}

void machine::start_ready_moves() {
  for (std::size_t i = 0; i < moves_.size(); ++i) {
    move_state& m = moves_[i];
    if (!m.in_use || m.running) continue;
    const bool at_head = std::all_of(m.axes.begin(), m.axes.end(),
                                     [&](std::size_t axis) { return axes_[axis].queue[0] == static_cast<int>(i); });
    if (at_head) start(static_cast<int>(i));
  }
}

// Bit 0 of a parameter's integer part. A program may set any value: NaN, infinities and magnitudes of 2^53 or
// more (all even) have it clear, and nothing is converted that does not fit a long long.
static bool odd(double v) {
  if (!(std::fabs(v) < 9007199254740992.0)) return false;
  return (static_cast<long long>(v) & 1) != 0;
}

void machine::wrap(std::size_t axis, move_state& m, std::size_t k) {
  axis_state& a = axes_[axis];
  const double rep = parameter(axis, axis_parameter::rep_dist) * units(axis);
  if (!(rep > 0)) return;
  double shift = 0;
  if (odd(parameter(axis, axis_parameter::rep_option))) {
    if (a.position >= rep || a.position < 0) shift = std::floor(a.position / rep) * rep;
  } else if (a.position > rep || a.position < -rep) {
    shift = std::floor((a.position + rep) / (2 * rep)) * 2 * rep;
  }
  if (shift == 0) return;
  a.position -= shift;
  m.origin[k] -= shift;
}

void machine::finish(int index, const char* how) {
  move_state& m = moves_[static_cast<std::size_t>(index)];
  std::string at;
  for (std::size_t k = 0; k < m.axes.size(); ++k) {
    axis_state& a = axes_[m.axes[k]];
    a.speed = 0;
    if (a.queue[0] == index) {
      a.queue[0] = a.queue[1];
      a.queue[1] = -1;
    }
    at += (k ? ", " : "") + format_value(a.position / units(m.axes[k]));
  }
  if (m.type == move_type::datum && std::string(how) == "ends") {
    for (std::size_t axis : m.axes) axes_[axis].position = 0;
  }
  event(axes_text(m.axes) + ": " + describe(m) + " " + how + " at DPOS " + at);
  m.in_use = false;
  --moves_in_use_;
}

void machine::stop_at_limit(int index, std::size_t axis, double limit, const char* name) {
  axes_[axis].position = limit * units(axis);
  event("axis " + std::to_string(axis) + ": stopped at " + name + " " + format_value(limit));
  finish(index, "stopped");
}

void machine::advance(int index, double dt) {
  move_state& m = moves_[static_cast<std::size_t>(index)];
  m.elapsed = static_cast<double>(++m.ticks) * dt;
  // A tolerance far below one servo period, so that a move of exactly N periods ends at the Nth tick.
  const bool finished = !m.endless && !m.plan.endless && m.elapsed >= m.plan.duration() - 1e-9;
  const double s = finished ? m.length : covered(m);
  const double v = finished ? 0 : m.plan.speed(m.elapsed);
  for (std::size_t k = 0; k < m.axes.size(); ++k) {
    const std::size_t axis = m.axes[k];
    axis_state& a = axes_[axis];
    const double u = units(axis);
    a.position = m.origin[k] + m.component[k] * s * u;
    a.speed = std::fabs(m.component[k]) * v;
    const double p = a.position / u;
    const double forward_limit = parameter(axis, axis_parameter::fs_limit);
    const double reverse_limit = parameter(axis, axis_parameter::rs_limit);
    if (m.component[k] > 0 && p > forward_limit) return stop_at_limit(index, axis, forward_limit, "FS_LIMIT");
    if (m.component[k] < 0 && p < reverse_limit) return stop_at_limit(index, axis, reverse_limit, "RS_LIMIT");
    wrap(axis, m, k);
  }
  if (finished) finish(index, m.stopping ? "stopped" : "ends");
}

void machine::servo_tick() {
  ++ticks_;
  if (offsets_pending_) apply_offsets();
  if (moves_in_use_ == 0) return;
  for (move_state& m : moves_) m.loaded = m.in_use;  // moves commanded since the last tick reach the axes
  start_ready_moves();
  const double dt = config_.servo_period_us * 1e-6;
  for (std::size_t i = 0; i < moves_.size(); ++i) {
    if (moves_[i].in_use && moves_[i].running) advance(static_cast<int>(i), dt);
  }
  // A buffered move takes over in the tick its predecessor ended (MTYPE becomes it, NTYPE 0); it moves from
  // the next tick on.
  start_ready_moves();
}

}  // namespace trionet::basic
