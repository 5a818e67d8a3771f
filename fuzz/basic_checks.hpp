// What the two BASIC harnesses share (basic_program.cpp: any text; basic_grammar.cpp: programs built from the
// grammar): a controller whose answers come from the input, the checks that a compiled program is well formed,
// and a bounded run that checks the task's invariants turn by turn.
//
//   - compile never fails silently: an error has a status, a message, a line within the text and a column >= 1,
//     and no program; compiling the same text again gives the same result;
//   - a compiled program is well formed: every expression id, code range, jump target, variable slot, axis
//     parameter, argument list, print item and text index is in range; every expression leaves exactly one
//     value on the stack and never needs more than `stack_depth`;
//   - running it (300 turns, 0..3 servo ticks between turns) on a controller with 64 VRs: a turn runs at most
//     its budget, statements() adds the turns up, effects() only grows; waiting <=> a wait reason; failed =>
//     an error message; an ended or failed task stays so and runs nothing more; line() is within the text;
//     the axes' positions stay finite.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "basic/controller.hpp"
#include "basic/machine.hpp"
#include "basic/program.hpp"
#include "basic/task.hpp"
#include "fuzz_check.hpp"

namespace trionet_fuzz {

namespace basic = trionet::basic;

class basic_controller final : public basic::controller {
 public:
  explicit basic_controller(split_source& choices) : choices_(choices), machine_(machine_config()) {}

  basic::print_result print(int channel, std::string_view text) override {
    const bool terminal = channel == 0 || channel == 1 || channel == 2 || (channel >= 5 && channel <= 7);
    if (!terminal && (channel < 10 || channel > 24)) return {basic::io_status::bad_channel, 0};
    for (char c : text) {
      if (!terminal && static_cast<unsigned char>(c) > 127) return {basic::io_status::character_out_of_range, 0};
    }
    const std::size_t room = choices_.next() % 40;
    return {basic::io_status::ok, text.size() < room ? text.size() : room};
  }
  basic::io_status send_variable(int address, int vr, double) override {
    if (address < 10 || address > 24) return basic::io_status::bad_address;
    if (vr < 0 || vr > 16383) return basic::io_status::vr_out_of_range;
    return choices_.next() % 4 == 0 ? basic::io_status::busy : basic::io_status::ok;
  }
  basic::io_status send_keypad_offset(int address, int offset) override {
    if (address < 10 || address > 24) return basic::io_status::bad_address;
    if (offset < 10 || offset > 24) return basic::io_status::offset_out_of_range;
    return choices_.next() % 4 == 0 ? basic::io_status::busy : basic::io_status::ok;
  }
  basic::key_result key(int channel) override {
    if (channel != 3 && channel != 4) return {basic::io_status::bad_channel, false};
    return {basic::io_status::ok, choices_.next() % 2 == 0};
  }
  basic::get_result get(int channel) override {
    if (channel != 3 && channel != 4) return {basic::io_status::bad_channel, 0};
    const std::uint32_t c = choices_.next();
    if (c % 3 == 0) return {basic::io_status::busy, 0};
    return {basic::io_status::ok, static_cast<std::uint8_t>(c >> 8)};
  }
  std::uint32_t netstat() override { return netstat_; }
  void clear_netstat() override { netstat_ = 0; }
  std::size_t vr_count() const override { return 64; }
  double vr(std::size_t index) const override {
    FUZZ_CHECK(index < 64);
    return vrs_[index];
  }
  void set_vr(std::size_t index, double value) override {
    FUZZ_CHECK(index < 64);
    vrs_[index] = value;
  }
  basic::machine& hardware() override { return machine_; }

  void new_turn() {
    netstat_ |= choices_.next() % 32 == 0 ? 8u : 0u;
    const std::uint32_t c = choices_.next();
    if (c % 8 == 0) machine_.set_input((c >> 8) % machine_.io_count(), (c >> 16) % 2 == 0);
  }

 private:
  static basic::machine_config machine_config() {
    basic::machine_config config;
    config.axes = 4;
    config.table_size = 256;
    return config;
  }
  split_source& choices_;
  std::uint32_t netstat_ = 0;
  double vrs_[64] = {};
  basic::machine machine_;
};

inline bool valid_expression(const basic::program& p, std::uint32_t id) {
  return id < p.expressions.size();
}

// What each operation does to the depth of the evaluation stack: +1 pushes, 0 replaces the top, -1 takes two
// and leaves one. Written here again on purpose (not shared with the compiler), so that the two can disagree.
inline int stack_effect(basic::expr_op op) {
  using basic::expr_op;
  switch (op) {
    case expr_op::constant:
    case expr_op::variable:
    case expr_op::axis:
    case expr_op::system:
    case expr_op::ticks:
    case expr_op::in_all:
      return 1;
    case expr_op::vr:
    case expr_op::table:
    case expr_op::axis_of:
    case expr_op::key:
    case expr_op::in_one:
    case expr_op::read_op:
    case expr_op::negate:
    case expr_op::logical_not:
    case expr_op::absolute:
    case expr_op::integer_part:
    case expr_op::fraction:
    case expr_op::sign:
    case expr_op::square_root:
    case expr_op::sine:
    case expr_op::cosine:
    case expr_op::tangent:
    case expr_op::arc_sine:
    case expr_op::arc_cosine:
    case expr_op::arc_tangent:
    case expr_op::exponential:
    case expr_op::logarithm:
      return 0;
    default:
      return -1;
  }
}

// Each expression: its code in range, one value left, never deeper than stack_depth.
inline void check_expressions(const basic::program& p) {
  for (const basic::expression& e : p.expressions) {
    FUZZ_CHECK(e.begin < e.end && e.end <= p.code.size());
    std::int64_t depth = 0;
    for (std::uint32_t i = e.begin; i < e.end; ++i) {
      const basic::expr_instr& in = p.code[i];
      const int effect = stack_effect(in.op);
      FUZZ_CHECK(depth >= (effect == 1 ? 0 : effect == 0 ? 1 : 2));
      if (in.op == basic::expr_op::variable) FUZZ_CHECK(in.index < p.variable_names.size());
      if (in.op == basic::expr_op::axis || in.op == basic::expr_op::axis_of)
        FUZZ_CHECK(in.index < basic::axis_parameter_count);
      depth += effect;
      FUZZ_CHECK(depth <= static_cast<std::int64_t>(p.stack_depth));
    }
    FUZZ_CHECK(depth == 1);
  }
}

inline void check_arguments(const basic::program& p, const basic::statement& s) {
  FUZZ_CHECK(s.extra + s.count <= p.arguments.size());
  FUZZ_CHECK(s.count <= basic::max_arguments);
  for (std::uint32_t i = s.extra; i < s.extra + s.count; ++i) FUZZ_CHECK(valid_expression(p, p.arguments[i]));
}

inline void check_statements(const basic::program& p) {
  const auto size = p.statements.size();
  for (const basic::statement& s : p.statements) {
    for (std::uint32_t e : s.expr) FUZZ_CHECK(e == basic::no_expression || valid_expression(p, e));
    FUZZ_CHECK(s.line >= 1);
    switch (s.kind) {
      case basic::statement_kind::assign_variable:
        FUZZ_CHECK(s.slot < p.variable_names.size() && valid_expression(p, s.expr[0]));
        break;
      case basic::statement_kind::assign_axis:
        FUZZ_CHECK(s.slot < basic::axis_parameter_count && valid_expression(p, s.expr[0]));
        FUZZ_CHECK(!basic::info(static_cast<basic::axis_parameter>(s.slot)).read_only);
        break;
      case basic::statement_kind::assign_vr:
      case basic::statement_kind::assign_table:
        FUZZ_CHECK(valid_expression(p, s.expr[0]) && valid_expression(p, s.expr[1]));
        break;
      case basic::statement_kind::jump:
      case basic::statement_kind::gosub:
      case basic::statement_kind::on_error:
        FUZZ_CHECK(s.target <= size);
        break;
      case basic::statement_kind::branch_unless:
        FUZZ_CHECK(s.target <= size && valid_expression(p, s.expr[0]));
        break;
      case basic::statement_kind::on_jump:
        FUZZ_CHECK(valid_expression(p, s.expr[0]) && s.count >= 1 && s.extra + s.count <= p.jump_targets.size());
        for (std::uint32_t i = s.extra; i < s.extra + s.count; ++i) FUZZ_CHECK(p.jump_targets[i] <= size);
        break;
      case basic::statement_kind::for_start:
      case basic::statement_kind::for_next:
        FUZZ_CHECK(s.target <= size && s.slot < p.variable_names.size());
        FUZZ_CHECK(s.extra >= p.variable_names.size() && s.extra + 1 < p.slots);
        break;
      case basic::statement_kind::print:
        FUZZ_CHECK(s.extra + s.count <= p.print_items.size());
        for (std::uint32_t i = s.extra; i < s.extra + s.count; ++i) {
          const basic::print_item& item = p.print_items[i];
          if (item.what == basic::print_item::kind::text) {
            FUZZ_CHECK(item.source < p.texts.size());
          } else {
            FUZZ_CHECK(valid_expression(p, item.source));
          }
          FUZZ_CHECK(item.width >= 0 && item.width <= 99 && item.decimals >= 0 && item.decimals <= 15);
        }
        break;
      case basic::statement_kind::get:
        FUZZ_CHECK(valid_expression(p, s.expr[0]));
        FUZZ_CHECK(s.flag ? valid_expression(p, s.expr[1]) : s.slot < p.variable_names.size());
        break;
      case basic::statement_kind::send:
        FUZZ_CHECK(valid_expression(p, s.expr[0]) && valid_expression(p, s.expr[1]) &&
                   valid_expression(p, s.expr[2]));
        break;
      case basic::statement_kind::table_write:
        check_arguments(p, s);
        FUZZ_CHECK(s.count >= 2);
        break;
      case basic::statement_kind::base:
        check_arguments(p, s);
        FUZZ_CHECK(s.count >= 1);
        break;
      case basic::statement_kind::motion:
        check_arguments(p, s);
        FUZZ_CHECK(s.slot <= static_cast<std::uint32_t>(basic::motion_command::defpos));
        break;
      case basic::statement_kind::output:
        FUZZ_CHECK(valid_expression(p, s.expr[0]) && (s.flag || valid_expression(p, s.expr[1])));
        break;
      default:
        break;
    }
  }
}

/// Compiles `text` and, if it compiles, runs it for a bounded number of turns with every check above.
inline void compile_and_run(std::string_view text, std::uint32_t seed) {
  std::size_t lines = 1;
  for (char c : text) lines += c == '\n' || c == '\r' ? 1 : 0;  // an upper bound (CR LF counts twice)

  basic::compile_result r = basic::compile("fuzz.bas", text);
  const basic::compile_result again = basic::compile("fuzz.bas", text);
  FUZZ_CHECK(r.status == again.status && r.message == again.message &&
             r.compiled.statements.size() == again.compiled.statements.size() &&
             r.compiled.code.size() == again.compiled.code.size());
  if (!r) {
    FUZZ_CHECK(!r.message.empty());
    FUZZ_CHECK(r.at.line >= 1 && r.at.line <= lines && r.at.column >= 1);
    FUZZ_CHECK(r.compiled.statements.empty());
    for (char c : r.message) FUZZ_CHECK(static_cast<unsigned char>(c) >= 32 && static_cast<unsigned char>(c) < 127);
    return;
  }
  const basic::program& p = r.compiled;
  FUZZ_CHECK(p.variable_names.size() <= p.slots);
  check_expressions(p);
  check_statements(p);

  split_source choices(seed);
  basic_controller io(choices);
  basic::task task(p, io);
  std::uint64_t statements = 0;
  std::uint64_t effects = 0;
  for (int turn = 0; turn < 300; ++turn) {
    io.new_turn();
    const std::uint32_t budget = 1 + choices.next() % 64;
    const basic::task_state before = task.state();
    const std::uint32_t ran = task.run(budget);
    FUZZ_CHECK(ran <= budget);
    statements += ran;
    FUZZ_CHECK(task.statements() == statements);
    FUZZ_CHECK(task.effects() >= effects);
    effects = task.effects();
    const basic::task_state state = task.state();
    if (before == basic::task_state::ended || before == basic::task_state::failed) {
      FUZZ_CHECK(ran == 0 && state == before);
    }
    FUZZ_CHECK((state == basic::task_state::waiting) == (task.waiting_for() != basic::wait_reason::none));
    FUZZ_CHECK(state != basic::task_state::failed || !task.error().empty());
    FUZZ_CHECK(state == basic::task_state::failed || task.handled_errors() != 0 || task.error().empty());
    FUZZ_CHECK(task.line() <= lines);
    const std::uint32_t ticks = choices.next() % 4;
    for (std::uint32_t k = 0; k < ticks; ++k) io.hardware().servo_tick();
    for (std::size_t axis = 0; axis < io.hardware().axis_count(); ++axis) {
      FUZZ_CHECK(std::isfinite(io.hardware().axis_value(axis, basic::axis_parameter::dpos)));
    }
    (void)io.hardware().take_events();
  }
}

}  // namespace trionet_fuzz
