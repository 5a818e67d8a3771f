// Fuzz harness: the BASIC compiler and interpreter (src/basic/) on arbitrary program text.
//
// The whole input is the program text. Choices for the controller (how much room PRINT # and SEND find, which
// characters GET # receives, NETSTAT) and the run (statements per turn, clock steps) come from a generator
// seeded with the input's hash. Invariants:
//   - compile never fails silently: an error has a status, a message, a line within the text and a column >= 1,
//     and no program; compiling the same text again gives the same result;
//   - a compiled program is well formed: every expression id, code range, jump target, variable slot, axis
//     parameter, print item and text index is in range; every expression leaves exactly one value on the
//     stack and never needs more than `stack_depth`;
//   - running it on a controller with 64 VRs: a turn runs at most its budget, statements() adds the turns up,
//     effects() only grows; waiting <=> a wait reason; failed <=> an error message; an ended or failed task
//     stays so and runs nothing more; line() is within the text.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

#include "basic/controller.hpp"
#include "basic/program.hpp"
#include "basic/task.hpp"
#include "fuzz_check.hpp"

namespace {

namespace basic = trionet::basic;

class fuzz_controller final : public basic::controller {
 public:
  explicit fuzz_controller(trionet_fuzz::split_source& choices) : choices_(choices) {}

  basic::print_result print(int channel, std::string_view text) override {
    if (channel != 0 && (channel < 10 || channel > 24)) return {basic::io_status::bad_channel, 0};
    for (char c : text) {
      if (channel != 0 && static_cast<unsigned char>(c) > 127) return {basic::io_status::character_out_of_range, 0};
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
  double parameter(std::size_t index) const override {
    FUZZ_CHECK(index < basic::axis_parameter_count);
    return parameters_[index];
  }
  void set_parameter(std::size_t index, double value) override {
    FUZZ_CHECK(index < basic::axis_parameter_count);
    parameters_[index] = value;
  }

  void new_turn() { netstat_ |= choices_.next() % 32 == 0 ? 8u : 0u; }

 private:
  trionet_fuzz::split_source& choices_;
  std::uint32_t netstat_ = 0;
  double vrs_[64] = {};
  double parameters_[basic::axis_parameter_count] = {};
};

bool valid_expression(const basic::program& p, std::uint32_t id) {
  return id < p.expressions.size();
}

// Each expression: its code in range, one value left, never deeper than stack_depth.
void check_expressions(const basic::program& p) {
  for (const basic::expression& e : p.expressions) {
    FUZZ_CHECK(e.begin < e.end && e.end <= p.code.size());
    std::int64_t depth = 0;
    for (std::uint32_t i = e.begin; i < e.end; ++i) {
      const basic::expr_instr& in = p.code[i];
      switch (in.op) {
        case basic::expr_op::constant:
        case basic::expr_op::netstat:
          ++depth;
          break;
        case basic::expr_op::variable:
          FUZZ_CHECK(in.index < p.variable_names.size());
          ++depth;
          break;
        case basic::expr_op::parameter:
          FUZZ_CHECK(in.index < basic::axis_parameter_count);
          ++depth;
          break;
        case basic::expr_op::vr:
        case basic::expr_op::key:
        case basic::expr_op::negate:
        case basic::expr_op::logical_not:
        case basic::expr_op::absolute:
        case basic::expr_op::integer_part:
          FUZZ_CHECK(depth >= 1);
          break;
        default:
          FUZZ_CHECK(depth >= 2);
          --depth;
          break;
      }
      FUZZ_CHECK(depth <= static_cast<std::int64_t>(p.stack_depth));
    }
    FUZZ_CHECK(depth == 1);
  }
}

void check_statements(const basic::program& p) {
  const auto size = p.statements.size();
  for (const basic::statement& s : p.statements) {
    for (std::uint32_t e : s.expr) FUZZ_CHECK(e == basic::no_expression || valid_expression(p, e));
    FUZZ_CHECK(s.line >= 1);
    switch (s.kind) {
      case basic::statement_kind::assign_variable:
        FUZZ_CHECK(s.slot < p.variable_names.size() && valid_expression(p, s.expr[0]));
        break;
      case basic::statement_kind::assign_parameter:
        FUZZ_CHECK(s.slot < basic::axis_parameter_count && valid_expression(p, s.expr[0]));
        break;
      case basic::statement_kind::assign_vr:
        FUZZ_CHECK(valid_expression(p, s.expr[0]) && valid_expression(p, s.expr[1]));
        break;
      case basic::statement_kind::jump:
      case basic::statement_kind::gosub:
        FUZZ_CHECK(s.target <= size);
        break;
      case basic::statement_kind::branch_unless:
        FUZZ_CHECK(s.target <= size && valid_expression(p, s.expr[0]));
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
      default:
        break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
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
    return 0;
  }
  const basic::program& p = r.compiled;
  FUZZ_CHECK(p.variable_names.size() <= p.slots);
  check_expressions(p);
  check_statements(p);

  trionet_fuzz::split_source choices(trionet_fuzz::hash(data, size));
  fuzz_controller io(choices);
  basic::task task(p, io);
  std::uint64_t now = 0;
  std::uint64_t statements = 0;
  std::uint64_t effects = 0;
  for (int turn = 0; turn < 300; ++turn) {
    io.new_turn();
    const std::uint32_t budget = 1 + choices.next() % 64;
    const basic::task_state before = task.state();
    const std::uint32_t ran = task.run(now, budget);
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
    FUZZ_CHECK((state == basic::task_state::failed) == !task.error().empty());
    FUZZ_CHECK(task.line() <= lines);
    now += 1 + choices.next() % 3;
  }
  return 0;
}
