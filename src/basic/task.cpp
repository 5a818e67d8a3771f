#include "basic/task.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "basic/number_format.hpp"

namespace trionet::basic {
namespace {

constexpr double true_value = -1.0;  // TRUE in Trio BASIC; FALSE is 0
constexpr std::size_t in_bits = 24;  // IN without a channel, and IN(first,last) at most: inputs 0..23

double truth(bool b) {
  return b ? true_value : 0.0;
}

// A channel, address, VR number or character: the value truncated toward zero, if it fits an int.
bool to_int(double v, int& out) {
  if (!(v > -2147483649.0 && v < 2147483648.0)) return false;
  out = static_cast<int>(v);
  return true;
}

// The integer part for AND, OR, XOR, NOT and MOD (saturating; NaN is 0).
// The whole numbers a bitwise operation, MOD or OP(bits) takes: those a double holds exactly, -2^53..2^53.
constexpr double whole_limit = 9007199254740992.0;

bool whole(double v) { return std::fabs(v) <= whole_limit; }

// A value beyond whole_limit as an error message shows it: 6 significant digits (1e+300, not 301 digits).
std::string large_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// The integer part toward zero of a value within whole_limit (callers check it first).
std::int64_t integer_of(double v) { return static_cast<std::int64_t>(v); }

bool same_bits(double a, double b) {
  std::uint64_t x = 0;
  std::uint64_t y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

std::string text_of(double v) {
  return format_value(v);
}

const char* function_name(expr_op op) {
  switch (op) {
    case expr_op::square_root:
      return "SQR";
    case expr_op::arc_sine:
      return "ASIN";
    case expr_op::arc_cosine:
      return "ACOS";
    case expr_op::logarithm:
      return "LN";
    case expr_op::exponential:
      return "EXP";
    case expr_op::tangent:
      return "TAN";
    case expr_op::power:
      return "^";
    default:
      return "the calculation";
  }
}

}  // namespace

task::task(const program& code, controller& io, const task_config& config)
    : code_(&code),
      io_(&io),
      config_(config),
      vars_(code.slots, 0.0),
      stack_(static_cast<std::size_t>(code.stack_depth) + 1, 0.0),
      ticks_base_(io.hardware().ticks()) {
  // A FOR loop's step reads "not running" (NaN) until its FOR runs and after the loop ends: a NEXT reached by a
  // jump into the loop's body is an error, not a pass with bounds left by another time.
  for (const statement& s : code.statements) {
    if (s.kind == statement_kind::for_start) vars_[s.extra + 1] = std::numeric_limits<double>::quiet_NaN();
  }
}

std::uint32_t task::line() const noexcept {
  if (state_ == task_state::ended || state_ == task_state::failed) return line_;
  if (pc_ < code_->statements.size()) return code_->statements[pc_].line;
  return line_;
}

std::uint8_t task::waiting_reads() const noexcept {
  if (wait_ != wait_reason::wait_until || pc_ >= code_->statements.size()) return 0;
  return code_->expressions[code_->statements[pc_].expr[0]].reads;
}

const double* task::find_variable(std::string_view name) const {
  for (std::size_t i = 0; i < code_->variable_names.size(); ++i) {
    const std::string& known = code_->variable_names[i];
    if (known.size() != name.size()) continue;
    bool same = true;
    for (std::size_t k = 0; k < name.size() && same; ++k) {
      const char c = name[k];
      same = known[k] == ((c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c);
    }
    if (same) return &vars_[i];
  }
  return nullptr;
}

void task::world_changed() noexcept {
  idle_ = false;
  snapshot_valid_ = false;
  steps_ = 0;
  power_ = 1;
}

// After a taken jump: has the task come back to a state it was in, with nothing changed in between? The states
// after jumps follow each other deterministically while nothing changes, so Brent's method finds any such loop:
// keep a snapshot, replaced after 1, 2, 4, 8 ... jumps, and compare every new state with it.
void task::jumped() {
  if (effects_ != watched_effects_) {
    watched_effects_ = effects_;
    world_changed();
  }
  if (idle_) return;
  if (snapshot_valid_ && snapshot_pc_ == pc_ && snapshot_gosub_ == gosub_) {
    idle_ = true;
    return;
  }
  if (++steps_ >= power_) {
    snapshot_pc_ = pc_;
    snapshot_gosub_ = gosub_;
    snapshot_valid_ = true;
    power_ *= 2;
    steps_ = 0;
  }
}

// A runtime error: the task stops, unless ON BASICERROR GOTO named a label, where it goes on.
bool task::fail(const std::string& message) {
  error_ = message;
  wait_ = wait_reason::none;
  pending_ = false;
  ++effects_;
  if (error_handler_ != no_expression) {
    error_line_ = line_;
    ++handled_errors_;
    pc_ = error_handler_;
    state_ = task_state::running;
    return false;
  }
  state_ = task_state::failed;
  return false;
}

void task::end_here(std::uint32_t line) noexcept {
  state_ = task_state::ended;
  wait_ = wait_reason::none;
  line_ = line;
  pending_ = false;
  ++effects_;
}

bool task::store(double& slot, double value) noexcept {
  if (same_bits(slot, value)) return false;
  slot = value;
  ++effects_;
  return true;
}

bool task::vr_address(double value, std::size_t& index) {
  const std::size_t count = io_->vr_count();
  if (!(value >= 0) || value >= static_cast<double>(count)) {
    return fail("VR(" + text_of(value) + "): bad address (this controller has VR(0) to VR(" +
                std::to_string(count == 0 ? 0 : count - 1) + "))");
  }
  index = static_cast<std::size_t>(value);
  return true;
}

bool task::table_address(double value, std::size_t& index) {
  const std::size_t count = io_->hardware().table_size();
  if (!(value >= 0) || value >= static_cast<double>(count)) {
    return fail("TABLE(" + text_of(value) + "): bad address (this controller has TABLE(0) to TABLE(" +
                std::to_string(count == 0 ? 0 : count - 1) + "))");
  }
  index = static_cast<std::size_t>(value);
  return true;
}

bool task::axis_number(double value, std::size_t& axis) {
  const std::size_t count = io_->hardware().axis_count();
  if (!(value >= 0) || value >= static_cast<double>(count)) {
    return fail("AXIS(" + text_of(value) + "): this controller has axes 0 to " + std::to_string(count - 1));
  }
  axis = static_cast<std::size_t>(value);
  return true;
}

bool task::io_number(double value, std::size_t& n, bool output) {
  const std::size_t count = io_->hardware().io_count();
  const double first = output ? 8 : 0;
  if (!(value >= first) || value >= static_cast<double>(count)) {
    return fail(std::string(output ? "OP(" : "IN(") + text_of(value) + "): this controller has " +
                (output ? "outputs 8 to " : "inputs 0 to ") + std::to_string(count - 1));
  }
  n = static_cast<std::size_t>(value);
  return true;
}

double task::system(system_value which) const {
  machine& hw = io_->hardware();
  switch (which) {
    case system_value::netstat:
      return static_cast<double>(io_->netstat());
    case system_value::wdog:
      return hw.wdog() ? 1.0 : 0.0;
    case system_value::servo_period:
      return hw.servo_period_us();
    case system_value::control:
      return hw.control();
    case system_value::motion_error:
    case system_value::system_error:
      return 0;  // a simulated axis never loses its position, and nothing else goes wrong in the hardware
    case system_value::error_line:
      return error_line_;
    case system_value::base_axis:
      return base_axis();
  }
  return 0;
}

bool task::eval(std::uint32_t id, double& out) {
  const expression e = code_->expressions[id];
  const expr_instr* ip = code_->code.data() + e.begin;
  const expr_instr* const end = code_->code.data() + e.end;
  double* sp = stack_.data();
  machine& hw = io_->hardware();
  // A bitwise operation or MOD on a value beyond the whole numbers a double holds is refused, not clamped.
  const auto beyond_whole = [&](const char* op, double v) {
    return fail(std::string(op) + " of " + large_text(v) + ": outside the whole numbers it takes (-2^53..2^53)");
  };
  for (; ip != end; ++ip) {
    switch (ip->op) {
      case expr_op::constant:
        *sp++ = ip->value;
        break;
      case expr_op::variable:
        *sp++ = vars_[ip->index];
        break;
      case expr_op::vr: {
        std::size_t index = 0;
        if (!vr_address(sp[-1], index)) return false;
        sp[-1] = io_->vr(index);
        break;
      }
      case expr_op::table: {
        std::size_t index = 0;
        if (!table_address(sp[-1], index)) return false;
        sp[-1] = hw.table(index);
        break;
      }
      case expr_op::axis:
        *sp++ = hw.axis_value(base_.front(), static_cast<axis_parameter>(ip->index));
        break;
      case expr_op::axis_of: {
        std::size_t axis = 0;
        if (!axis_number(sp[-1], axis)) return false;
        sp[-1] = hw.axis_value(axis, static_cast<axis_parameter>(ip->index));
        break;
      }
      case expr_op::system:
        *sp++ = system(static_cast<system_value>(ip->index));
        break;
      case expr_op::ticks:
        *sp++ = ticks_value_ - static_cast<double>(hw.ticks() - ticks_base_);
        break;
      case expr_op::key: {
        int channel = 0;
        const key_result k = to_int(sp[-1], channel) ? io_->key(channel) : key_result{io_status::bad_channel, false};
        if (!k) return fail("KEY#" + text_of(sp[-1]) + ": bad channel (KEY# reads channel 3 or 4)");
        sp[-1] = truth(k.waiting);
        break;
      }
      case expr_op::in_all: {
        double bits = 0;
        for (std::size_t i = std::min(in_bits, hw.io_count()); i-- > 0;) bits = bits * 2 + (hw.input(i) ? 1 : 0);
        *sp++ = bits;
        break;
      }
      case expr_op::in_one: {
        std::size_t n = 0;
        if (!io_number(sp[-1], n, false)) return false;
        sp[-1] = hw.input(n) ? 1.0 : 0.0;
        break;
      }
      case expr_op::in_range: {
        std::size_t first = 0;
        std::size_t last = 0;
        if (!io_number(sp[-2], first, false) || !io_number(sp[-1], last, false)) return false;
        if (last < first || last - first >= in_bits)
          return fail("IN(" + text_of(sp[-2]) + "," + text_of(sp[-1]) + "): at most 24 inputs, first to last");
        double bits = 0;
        for (std::size_t i = last + 1; i-- > first;) bits = bits * 2 + (hw.input(i) ? 1 : 0);
        sp[-2] = bits;
        --sp;
        break;
      }
      case expr_op::read_op: {
        std::size_t n = 0;
        if (!io_number(sp[-1], n, true)) return false;
        sp[-1] = hw.output(n) ? 1.0 : 0.0;
        break;
      }
      case expr_op::negate:
        sp[-1] = -sp[-1];
        break;
      case expr_op::logical_not:
        if (!whole(sp[-1])) return beyond_whole("NOT", sp[-1]);
        sp[-1] = static_cast<double>(~integer_of(sp[-1]));
        break;
      case expr_op::absolute:
        sp[-1] = std::fabs(sp[-1]);
        break;
      case expr_op::integer_part:
        sp[-1] = std::trunc(sp[-1]);
        break;
      case expr_op::fraction:
        sp[-1] = sp[-1] - std::trunc(sp[-1]);
        break;
      case expr_op::sign:
        sp[-1] = sp[-1] > 0 ? 1.0 : (sp[-1] < 0 ? -1.0 : 0.0);
        break;
      case expr_op::square_root:
        if (sp[-1] < 0) return fail("SQR(" + text_of(sp[-1]) + "): the square root of a negative number");
        sp[-1] = std::sqrt(sp[-1]);
        break;
      case expr_op::sine:
        sp[-1] = std::sin(sp[-1]);
        break;
      case expr_op::cosine:
        sp[-1] = std::cos(sp[-1]);
        break;
      case expr_op::tangent:
        sp[-1] = std::tan(sp[-1]);
        break;
      case expr_op::arc_sine:
      case expr_op::arc_cosine:
        if (!(sp[-1] >= -1 && sp[-1] <= 1))
          return fail(std::string(function_name(ip->op)) + "(" + text_of(sp[-1]) + "): the value must be -1 to 1");
        sp[-1] = ip->op == expr_op::arc_sine ? std::asin(sp[-1]) : std::acos(sp[-1]);
        break;
      case expr_op::arc_tangent:
        sp[-1] = std::atan(sp[-1]);
        break;
      case expr_op::exponential:
        sp[-1] = std::exp(sp[-1]);
        break;
      case expr_op::logarithm:
        if (!(sp[-1] > 0)) return fail("LN(" + text_of(sp[-1]) + "): the logarithm of a number 0 or below");
        sp[-1] = std::log(sp[-1]);
        break;
      case expr_op::add:
        sp[-2] = sp[-2] + sp[-1];
        --sp;
        break;
      case expr_op::subtract:
        sp[-2] = sp[-2] - sp[-1];
        --sp;
        break;
      case expr_op::multiply:
        sp[-2] = sp[-2] * sp[-1];
        --sp;
        break;
      case expr_op::divide:
        if (sp[-1] == 0) return fail("division by zero");
        sp[-2] = sp[-2] / sp[-1];
        --sp;
        break;
      case expr_op::power: {
        const double r = std::pow(sp[-2], sp[-1]);
        if (std::isnan(r) || (sp[-2] == 0 && sp[-1] < 0)) {
          return fail(text_of(sp[-2]) + "^" + text_of(sp[-1]) + ": no real result");
        }
        sp[-2] = r;
        --sp;
        break;
      }
      case expr_op::arc_tangent2:
        sp[-2] = std::atan2(sp[-2], sp[-1]);
        --sp;
        break;
      case expr_op::modulo: {
        if (!whole(sp[-2]) || !whole(sp[-1])) return beyond_whole("MOD", whole(sp[-2]) ? sp[-1] : sp[-2]);
        const std::int64_t a = integer_of(sp[-2]);
        const std::int64_t b = integer_of(sp[-1]);
        if (b == 0) return fail("MOD by zero");
        sp[-2] = b == -1 ? 0.0 : static_cast<double>(a % b);
        --sp;
        break;
      }
      case expr_op::equal:
        sp[-2] = truth(sp[-2] == sp[-1]);
        --sp;
        break;
      case expr_op::not_equal:
        sp[-2] = truth(sp[-2] != sp[-1]);
        --sp;
        break;
      case expr_op::less:
        sp[-2] = truth(sp[-2] < sp[-1]);
        --sp;
        break;
      case expr_op::greater:
        sp[-2] = truth(sp[-2] > sp[-1]);
        --sp;
        break;
      case expr_op::less_equal:
        sp[-2] = truth(sp[-2] <= sp[-1]);
        --sp;
        break;
      case expr_op::greater_equal:
        sp[-2] = truth(sp[-2] >= sp[-1]);
        --sp;
        break;
      case expr_op::bit_and:
        if (!whole(sp[-2]) || !whole(sp[-1])) return beyond_whole("AND", whole(sp[-2]) ? sp[-1] : sp[-2]);
        sp[-2] = static_cast<double>(integer_of(sp[-2]) & integer_of(sp[-1]));
        --sp;
        break;
      case expr_op::bit_or:
        if (!whole(sp[-2]) || !whole(sp[-1])) return beyond_whole("OR", whole(sp[-2]) ? sp[-1] : sp[-2]);
        sp[-2] = static_cast<double>(integer_of(sp[-2]) | integer_of(sp[-1]));
        --sp;
        break;
      case expr_op::bit_xor:
        if (!whole(sp[-2]) || !whole(sp[-1])) return beyond_whole("XOR", whole(sp[-2]) ? sp[-1] : sp[-2]);
        sp[-2] = static_cast<double>(integer_of(sp[-2]) ^ integer_of(sp[-1]));
        --sp;
        break;
    }
  }
  out = sp[-1];
  if (!std::isfinite(out)) return fail("a value out of range (the calculation overflows)");
  return true;
}

// The axes a motion command with `count` values moves: the base axes (BASE, or AXIS(n) for this command
// alone), followed by every other axis in order, the first `count` of them.
std::vector<std::size_t> task::base_group(std::size_t count, std::uint32_t axis_expression, bool& ok) {
  ok = false;
  std::vector<std::size_t> order;
  const std::size_t axes = io_->hardware().axis_count();
  if (axis_expression != no_expression) {
    double v = 0;
    std::size_t axis = 0;
    if (!eval(axis_expression, v) || !axis_number(v, axis)) return {};
    order.push_back(axis);
  } else {
    order = base_;
  }
  const std::vector<std::size_t> named = order;
  for (std::size_t a = 0; a < axes && order.size() < count; ++a) {
    if (std::find(order.begin(), order.end(), a) == order.end()) order.push_back(a);
  }
  if (count > order.size()) {
    fail(std::to_string(count) + " values for " + std::to_string(axes) + " axes");
    return {};
  }
  // The axes after those BASE (or AXIS) named: the manual pages at hand do not say whether they start from
  // axis 0 (BASE(2): 2, 0, 1, ...) or follow the last one named (2, 3, 4, ...). Where the two readings give
  // other axes, the command is refused rather than moving axes the controller might not.
  std::vector<std::size_t> following = named;
  for (std::size_t step = 1; step <= axes && following.size() < count; ++step) {
    const std::size_t a = (named.back() + step) % axes;
    if (std::find(following.begin(), following.end(), a) == following.end()) following.push_back(a);
  }
  if (!std::equal(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), following.begin())) {
    std::string given;
    for (std::size_t a : named) given += (given.empty() ? "" : ",") + std::to_string(a);
    fail(std::to_string(count) + " values for the " + std::to_string(named.size()) + (named.size() == 1 ? " axis" : " axes") + " named (" + given +
         "): which axes follow them is not modelled; name every axis the command moves (BASE(" + given + ",...))");
    return {};
  }
  order.resize(count);
  ok = true;
  return order;
}

bool task::motion(const statement& s) {
  machine& hw = io_->hardware();
  const auto command = static_cast<motion_command>(s.slot);
  if (!pending_) {
    motion_args_.assign(s.count, 0.0);
    for (std::uint32_t i = 0; i < s.count; ++i) {
      if (!eval(code_->arguments[s.extra + i], motion_args_[i])) return false;
    }
    const bool group = command == motion_command::move || command == motion_command::moveabs ||
                       command == motion_command::defpos;
    bool ok = true;
    if (command != motion_command::rapidstop) motion_axes_ = base_group(group ? s.count : 1, s.expr[3], ok);
    if (!ok) return false;
    pending_ = true;
  }
  motion_status status = motion_status::ok;
  switch (command) {
    case motion_command::move:
    case motion_command::moveabs:
      status = hw.move(motion_axes_, motion_args_, command == motion_command::move ? move_type::move : move_type::moveabs);
      break;
    case motion_command::defpos:
      status = hw.defpos(motion_axes_, motion_args_);
      break;
    case motion_command::forward:
    case motion_command::reverse:
      status = hw.forward(motion_axes_.front(), command == motion_command::forward ? 1 : -1);
      break;
    case motion_command::cancel: {
      const double mode = motion_args_.empty() ? 0 : motion_args_.front();
      if (mode != 0 && mode != 1) return fail("CANCEL(" + text_of(mode) + "): the mode is 0 (the running move) or 1 (the buffered one)");
      hw.cancel(motion_axes_.front(), mode == 1);
      break;
    }
    case motion_command::rapidstop:
      hw.rapidstop();
      break;
    case motion_command::datum: {
      const double mode = motion_args_.front();
      if (!(mode >= 0 && mode <= 6) || mode != std::trunc(mode))
        return fail("DATUM(" + text_of(mode) + "): the mode is 0 to 6");
      status = hw.datum(motion_axes_.front(), static_cast<int>(mode));
      break;
    }
  }
  if (status == motion_status::busy) {
    state_ = task_state::waiting;
    wait_ = wait_reason::motion;
    return false;
  }
  if (status == motion_status::bad_axis) return fail("the same axis twice in one move");
  pending_ = false;
  ++effects_;
  return true;
}

bool task::waits_for_motion() {
  state_ = task_state::waiting;
  wait_ = wait_reason::motion;
  return true;
}

std::uint32_t task::run(std::uint32_t budget) {
  if (state_ == task_state::ended || state_ == task_state::failed) return 0;
  state_ = task_state::running;
  wait_ = wait_reason::none;
  machine& hw = io_->hardware();
  const statement* const all = code_->statements.data();
  const auto size = static_cast<std::uint32_t>(code_->statements.size());
  std::uint32_t done = 0;
  while (done < budget) {
    if (pc_ >= size) {
      end_here(line_);
      break;
    }
    const statement& s = all[pc_];
    line_ = s.line;
    double v = 0;
    switch (s.kind) {
      case statement_kind::assign_variable:
        if (!eval(s.expr[0], v)) goto out;
        store(vars_[s.slot], v);
        ++pc_;
        break;
      case statement_kind::assign_vr: {
        std::size_t index = 0;
        double value = 0;
        if (!eval(s.expr[0], v) || !vr_address(v, index) || !eval(s.expr[1], value)) goto out;
        if (!same_bits(io_->vr(index), value)) {
          io_->set_vr(index, value);
          ++effects_;
        }
        ++pc_;
        break;
      }
      case statement_kind::assign_table: {
        std::size_t index = 0;
        double value = 0;
        if (!eval(s.expr[0], v) || !table_address(v, index) || !eval(s.expr[1], value)) goto out;
        if (!same_bits(hw.table(index), value)) {
          hw.set_table(index, value);
          ++effects_;
        }
        ++pc_;
        break;
      }
      case statement_kind::table_write: {
        std::size_t first = 0;
        if (!eval(code_->arguments[s.extra], v) || !table_address(v, first)) goto out;
        for (std::uint32_t i = 1; i < s.count; ++i) {
          std::size_t index = 0;
          double value = 0;
          if (!table_address(static_cast<double>(first + i - 1), index) ||
              !eval(code_->arguments[s.extra + i], value)) {
            goto out;
          }
          if (!same_bits(hw.table(index), value)) {
            hw.set_table(index, value);
            ++effects_;
          }
        }
        ++pc_;
        break;
      }
      case statement_kind::assign_axis: {
        std::size_t axis = base_.front();
        double a = 0;
        if (s.expr[1] != no_expression && (!eval(s.expr[1], a) || !axis_number(a, axis))) goto out;
        if (!eval(s.expr[0], v)) goto out;
        const auto p = static_cast<axis_parameter>(s.slot);
        if (!same_bits(hw.axis_value(axis, p), v)) {
          if (hw.set_axis_value(axis, p, v) != machine::set_status::ok) {
            fail(std::string(info(p).name) + "=" + text_of(v) + ": out of range (UNITS must be above 0)");
            goto out;
          }
          ++effects_;
        }
        ++pc_;
        break;
      }
      case statement_kind::assign_netstat:
        if (!eval(s.expr[0], v)) goto out;
        if (v != 0) {
          fail("NETSTAT can only be cleared: NETSTAT=0");
          goto out;
        }
        if (io_->netstat() != 0) {
          io_->clear_netstat();
          ++effects_;
        }
        ++pc_;
        break;
      case statement_kind::assign_wdog:
        if (!eval(s.expr[0], v)) goto out;
        if (hw.wdog() != (v != 0)) {
          hw.set_wdog(v != 0);
          ++effects_;
        }
        ++pc_;
        break;
      case statement_kind::assign_ticks:
        if (!eval(s.expr[0], v)) goto out;
        ticks_value_ = v;
        ticks_base_ = hw.ticks();
        ++effects_;
        ++pc_;
        break;
      case statement_kind::jump:
        pc_ = s.target;
        jumped();
        break;
      case statement_kind::branch_unless:
        if (!eval(s.expr[0], v)) goto out;
        if (v != 0) {
          ++pc_;
        } else {
          pc_ = s.target;
          jumped();
        }
        break;
      case statement_kind::gosub:
        if (gosub_.size() >= config_.max_gosub_depth) {
          fail("GOSUB nested more than " + std::to_string(config_.max_gosub_depth) + " deep");
          goto out;
        }
        gosub_.push_back(pc_ + 1);
        pc_ = s.target;
        jumped();
        break;
      case statement_kind::return_from_gosub:
        if (gosub_.empty()) {
          fail("RETURN without GOSUB");
          goto out;
        }
        pc_ = gosub_.back();
        gosub_.pop_back();
        jumped();
        break;
      case statement_kind::on_jump: {
        if (!eval(s.expr[0], v)) goto out;
        const double k = std::trunc(v);
        if (!(k >= 1 && k <= static_cast<double>(s.count))) {  // out of range: on to the next statement
          ++pc_;
          break;
        }
        if (s.flag) {
          if (gosub_.size() >= config_.max_gosub_depth) {
            fail("GOSUB nested more than " + std::to_string(config_.max_gosub_depth) + " deep");
            goto out;
          }
          gosub_.push_back(pc_ + 1);
        }
        pc_ = code_->jump_targets[s.extra + static_cast<std::uint32_t>(k) - 1];
        jumped();
        break;
      }
      case statement_kind::on_error:
        error_handler_ = s.target;
        ++pc_;
        break;
      case statement_kind::for_start: {
        double last = 0;
        double step = 1;
        if (!eval(s.expr[0], v) || !eval(s.expr[1], last)) goto out;
        if (s.expr[2] != no_expression && !eval(s.expr[2], step)) goto out;
        store(vars_[s.slot], v);
        store(vars_[s.extra], last);
        store(vars_[s.extra + 1], step);
        if (step >= 0 ? v <= last : v >= last) {
          ++pc_;
        } else {
          vars_[s.extra + 1] = std::numeric_limits<double>::quiet_NaN();  // the loop is not running
          pc_ = s.target;
          jumped();
        }
        break;
      }
      case statement_kind::for_next: {
        const double last = vars_[s.extra];
        const double step = vars_[s.extra + 1];
        if (std::isnan(step)) {
          fail("NEXT " + code_->variable_names[s.slot] + " without its FOR running (a jump into the loop)");
          goto out;
        }
        double& variable = vars_[s.slot];
        store(variable, variable + step);
        if (step >= 0 ? variable <= last : variable >= last) {
          pc_ = s.target;
          jumped();
        } else {
          vars_[s.extra + 1] = std::numeric_limits<double>::quiet_NaN();  // the loop has ended
          ++pc_;
        }
        break;
      }
      case statement_kind::wait_until:
        if (!eval(s.expr[0], v)) goto out;
        if (v == 0) {
          state_ = task_state::waiting;
          wait_ = wait_reason::wait_until;
          goto out;
        }
        ++pc_;
        break;
      case statement_kind::wait_ms:
        if (!pending_) {
          if (!eval(s.expr[0], v)) goto out;
          if (!(v >= 0)) {
            fail("WA(" + text_of(v) + "): the time must be 0 ms or more");
            goto out;
          }
          // Servo ticks, as the controller counts them: WA(t) resumes at the t-th tick (at the default period)
          // after the one it started in.
          const double ticks = std::ceil(v * 1000.0 / hw.servo_period_us() - 1e-9);
          wake_at_ = hw.ticks() + (ticks >= 1e18 ? static_cast<std::uint64_t>(1e18) : static_cast<std::uint64_t>(ticks));
          pending_ = true;
        }
        if (hw.ticks() < wake_at_) {
          state_ = task_state::waiting;
          wait_ = wait_reason::wa;
          goto out;
        }
        pending_ = false;
        ++pc_;
        break;
      case statement_kind::wait_idle:
      case statement_kind::wait_loaded: {
        std::size_t axis = base_.front();
        if (s.expr[3] != no_expression && (!eval(s.expr[3], v) || !axis_number(v, axis))) goto out;
        const bool ready = s.kind == statement_kind::wait_idle ? hw.idle(axis) : hw.loaded(axis);
        if (!ready) {
          waits_for_motion();
          goto out;
        }
        ++pc_;
        break;
      }
      case statement_kind::output: {
        if (!eval(s.expr[0], v)) goto out;
        if (s.flag) {  // OP(bits): outputs 8 up, one bit each
          if (!whole(v)) {
            fail("OP(" + large_text(v) + "): outside the whole numbers it takes (-2^53..2^53)");
            goto out;
          }
          const std::int64_t bits = integer_of(v);
          for (std::size_t n = 8; n < hw.io_count() && n < 8 + in_bits; ++n) {
            const bool on = ((bits >> (n - 8)) & 1) != 0;
            if (hw.output(n) != on) {
              (void)hw.set_output(n, on);
              ++effects_;
            }
          }
        } else {
          std::size_t n = 0;
          double state = 0;
          if (!io_number(v, n, true) || !eval(s.expr[1], state)) goto out;
          if (hw.output(n) != (state != 0)) {
            (void)hw.set_output(n, state != 0);
            ++effects_;
          }
        }
        ++pc_;
        break;
      }
      case statement_kind::base: {
        std::vector<std::size_t> axes;
        for (std::uint32_t i = 0; i < s.count; ++i) {
          std::size_t axis = 0;
          if (!eval(code_->arguments[s.extra + i], v) || !axis_number(v, axis)) goto out;
          if (std::find(axes.begin(), axes.end(), axis) != axes.end()) {
            fail("BASE names axis " + std::to_string(axis) + " twice");
            goto out;
          }
          axes.push_back(axis);
        }
        if (axes != base_) {
          base_ = std::move(axes);
          ++effects_;
        }
        ++pc_;
        break;
      }
      case statement_kind::motion:
        if (!motion(s)) goto out;
        ++pc_;
        break;
      case statement_kind::print:
        if (!print(s)) goto out;
        ++pc_;
        break;
      case statement_kind::get:
        if (!get(s)) goto out;
        ++pc_;
        break;
      case statement_kind::send:
        if (!send(s)) goto out;
        ++pc_;
        break;
      case statement_kind::stop:
        ++done;
        end_here(s.line);
        goto out;
    }
    done += s.counted ? 1u : 0u;
  }
out:
  statements_ += done;
  return done;
}

bool task::build_print_text(const statement& s) {
  text_.clear();
  for (std::uint32_t i = 0; i < s.count; ++i) {
    const print_item& item = code_->print_items[s.extra + i];
    double v = 0;
    int c = 0;
    switch (item.what) {
      case print_item::kind::text:
        text_ += code_->texts[item.source];
        break;
      case print_item::kind::character:
        if (!eval(item.source, v)) return false;
        if (!to_int(v, c) || c < 0 || c > 255) return fail("CHR(" + text_of(v) + "): a character is 0..255");
        text_ += static_cast<char>(c);
        break;
      case print_item::kind::cursor:
        if (!eval(item.source, v)) return false;
        if (!to_int(v, c) || c < 0 || c > 255) return fail("CURSOR(" + text_of(v) + "): a position is 0..255");
        text_ += '\x1b';
        text_ += 'H';
        text_ += static_cast<char>(c);
        break;
      case print_item::kind::hex: {
        if (!eval(item.source, v)) return false;
        const double whole = std::trunc(v);
        if (!(whole >= 0 && whole < 4294967296.0))
          return fail("HEX(" + text_of(v) + "): HEX prints whole numbers 0 to $FFFFFFFF");
        char digits[16];
        std::snprintf(digits, sizeof digits, "%llX", static_cast<unsigned long long>(whole));
        text_ += digits;
        break;
      }
      case print_item::kind::number:
        if (!eval(item.source, v)) return false;
        append_print_number(text_, v);
        break;
      case print_item::kind::formatted_number:
        if (!eval(item.source, v)) return false;
        append_print_number(text_, v, item.width, item.decimals);
        break;
    }
    if (item.separator == ',') text_ += '\t';
  }
  if (s.flag) text_ += "\r\n";
  return true;
}

bool task::print(const statement& s) {
  if (!pending_) {
    int channel = 0;
    if (s.expr[0] != no_expression) {
      double c = 0;
      if (!eval(s.expr[0], c)) return false;
      if (!to_int(c, channel)) return fail("PRINT #" + text_of(c) + ": bad channel");
    }
    if (!build_print_text(s)) return false;
    channel_ = channel;
    text_sent_ = 0;
    pending_ = true;
  }
  while (text_sent_ < text_.size()) {
    const std::string_view rest = std::string_view(text_).substr(text_sent_);
    const print_result r = io_->print(channel_, rest);
    const auto where = [&] { return "PRINT #" + std::to_string(channel_); };
    switch (r.status) {
      case io_status::ok:
        break;
      case io_status::busy:
        state_ = task_state::waiting;
        wait_ = wait_reason::print;
        return false;
      case io_status::bad_address:
        return fail(where() + ": bad address (the network's BASIC addresses are 10..24)");
      case io_status::character_out_of_range:
        return fail(where() + ": a character above 127 (the ring carries 0..127)");
      default:
        return fail(where() + ": bad channel (#0 is the terminal, #1 and #2 the serial ports, #5 to #7 Motion "
                              "Perfect's channels, #10 to #24 the network)");
    }
    if (r.queued == 0) {
      state_ = task_state::waiting;
      wait_ = wait_reason::print;
      return false;
    }
    text_sent_ += r.queued < rest.size() ? r.queued : rest.size();
    ++effects_;
  }
  pending_ = false;
  return true;
}

bool task::send(const statement& s) {
  if (!pending_) {
    for (int i = 0; i < 4; ++i) {
      send_args_[i] = 0;
      if (s.expr[i] != no_expression && !eval(s.expr[i], send_args_[i])) return false;
    }
    pending_ = true;
  }
  int n = 0;
  int type = 0;
  int data1 = 0;
  const auto n_text = [&] { return text_of(send_args_[0]); };
  if (!to_int(send_args_[0], n)) return fail("SEND(" + n_text() + ",...): bad address (BASIC addresses are 10..24)");
  if (!to_int(send_args_[1], type) || (type != 1 && type != 2)) {
    return fail("SEND(" + n_text() + "," + text_of(send_args_[1]) +
                ",...): bad type (1 = direct variable transfer, 2 = keypad offset)");
  }
  const auto head = [&] {
    return "SEND(" + n_text() + "," + std::to_string(type) + "," + text_of(send_args_[2]);
  };
  if (type == 1 && s.expr[3] == no_expression) return fail(head() + "): a direct variable transfer needs a value");
  const bool data1_fits = to_int(send_args_[2], data1);
  io_status status = io_status::ok;
  if (type == 1) {
    status = data1_fits ? io_->send_variable(n, data1, send_args_[3]) : io_status::vr_out_of_range;
  } else {
    status = data1_fits ? io_->send_keypad_offset(n, data1) : io_status::offset_out_of_range;
  }
  switch (status) {
    case io_status::ok:
      pending_ = false;
      ++effects_;
      return true;
    case io_status::busy:
      state_ = task_state::waiting;
      wait_ = wait_reason::send;
      return false;
    case io_status::bad_address:
      return fail(head() + ",...): bad address (BASIC addresses are 10..24)");
    case io_status::vr_out_of_range:
      return fail(head() + ",...): VR number out of range (0..16383)");
    case io_status::value_out_of_range:
      return fail(head() + "," + text_of(send_args_[3]) + "): value out of range for the network");
    case io_status::offset_out_of_range:
      return fail(head() + "): keypad offset out of range (BASIC addresses 10..24)");
    default:
      return fail(head() + ",...): " + to_string(status));
  }
}

bool task::get(const statement& s) {
  double c = 0;
  int channel = 0;
  if (!eval(s.expr[0], c)) return false;
  if (!to_int(c, channel)) return fail("GET #" + text_of(c) + ": bad channel (GET # reads channel 3 or 4)");
  std::size_t index = 0;
  if (s.flag) {
    double v = 0;
    if (!eval(s.expr[1], v) || !vr_address(v, index)) return false;
  }
  const get_result r = io_->get(channel);
  if (r.status == io_status::busy) {
    state_ = task_state::waiting;
    wait_ = wait_reason::get;
    return false;
  }
  if (!r) return fail("GET #" + std::to_string(channel) + ": bad channel (GET # reads channel 3 or 4)");
  ++effects_;
  if (s.flag) {
    io_->set_vr(index, r.value);
  } else {
    vars_[s.slot] = r.value;
  }
  return true;
}

}  // namespace trionet::basic
