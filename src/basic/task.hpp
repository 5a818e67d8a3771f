// A running BASIC program: the interpreter. One `task` runs one compiled program (program.hpp) against one
// controller (controller.hpp), a budget of statements at a time, on a clock the caller supplies:
//
//   for each byte-time:  the servo ticks due -> task.run(statements_per_byte_time) -> ring.step()
//
// A statement that cannot complete yet (PRINT #n or SEND without room, GET #n with nothing received, WAIT UNTIL
// with a false condition, WA before its time, a move with the axes' buffers full, WAIT IDLE while the axis
// moves) ends the task's turn and is tried again at its next turn; the rest of the ring goes on. WA and TICKS
// count the controller's servo ticks (machine.hpp). A runtime error stops the task with its line and a message
// (or goes to its ON BASICERROR label); the controller and every other task go on. Deterministic: the same
// program, controller behaviour and clock give the same run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "basic/controller.hpp"
#include "basic/program.hpp"

namespace trionet::basic {

enum class task_state : std::uint8_t {
  running,  ///< has statements left to run
  waiting,  ///< a statement waits (see wait_reason) and is tried again at the next turn
  ended,    ///< ran off its end or reached STOP
  failed,   ///< stopped by a runtime error (error(), line())
};

constexpr const char* to_string(task_state state) noexcept {
  switch (state) {
    case task_state::running:
      return "running";
    case task_state::waiting:
      return "waiting";
    case task_state::ended:
      return "ended";
    case task_state::failed:
      return "failed";
  }
  return "unknown";
}

/// What a waiting task waits for.
enum class wait_reason : std::uint8_t {
  none,
  print,       ///< room in the transmit queue for the rest of a PRINT #n
  send,        ///< room in the transmit queue for a SEND
  get,         ///< a character for GET #n
  wait_until,  ///< WAIT UNTIL's condition
  wa,          ///< WA's time
  motion,      ///< room in the axes' move buffers, or the axes to stop (WAIT IDLE, WAIT LOADED, DEFPOS)
};

constexpr const char* to_string(wait_reason reason) noexcept {
  switch (reason) {
    case wait_reason::none:
      return "none";
    case wait_reason::print:
      return "print";
    case wait_reason::send:
      return "send";
    case wait_reason::get:
      return "get";
    case wait_reason::wait_until:
      return "wait_until";
    case wait_reason::wa:
      return "wa";
    case wait_reason::motion:
      return "motion";
  }
  return "unknown";
}

struct task_config {
  /// GOSUB nesting beyond this stops the task with an error.
  std::size_t max_gosub_depth = 64;
};

class task {
 public:
  /// `code` and `io` must outlive the task.
  task(const program& code, controller& io, const task_config& config = {});

  /// Runs statements until `budget` statements have run, one waits, or the program ends or fails. Returns the
  /// number of statements run.
  std::uint32_t run(std::uint32_t budget);

  task_state state() const noexcept { return state_; }
  wait_reason waiting_for() const noexcept { return wait_; }
  /// What the condition of the WAIT UNTIL the task waits in reads (expression_reads bits; 0 otherwise).
  std::uint8_t waiting_reads() const noexcept;
  /// The line of the statement that runs next or waits; once ended or failed, of the last one run.
  std::uint32_t line() const noexcept;
  /// The runtime error that stopped the task, or the last one its ON BASICERROR label took ("" if none).
  const std::string& error() const noexcept { return error_; }
  /// Runtime errors the ON BASICERROR label took so far.
  std::uint64_t handled_errors() const noexcept { return handled_errors_; }
  const program& code() const noexcept { return *code_; }

  /// Statements run so far.
  std::uint64_t statements() const noexcept { return statements_; }
  /// Changes the task has made so far: values stored that differ from the old ones (variables, VRs, axis
  /// parameters), characters queued or read, NETSTAT cleared, the task ending or failing.
  std::uint64_t effects() const noexcept { return effects_; }
  /// True when the task is running round a loop that changes nothing (the same statement with the same GOSUB
  /// returns came round again with no effect in between): while nothing outside changes (world_changed()),
  /// it will loop like this for ever.
  bool idle() const noexcept { return idle_ && effects_ == watched_effects_; }
  /// Tells the task that something it may read changed outside it (a character or VR arrived, NETSTAT...):
  /// the loop it was idling in may now go somewhere else.
  void world_changed() noexcept;

  /// Named variables, in order of first appearance in the program text, names in lower case.
  std::size_t variable_count() const noexcept { return code_->variable_names.size(); }
  const std::string& variable_name(std::size_t i) const { return code_->variable_names[i]; }
  double variable(std::size_t i) const { return vars_[i]; }
  /// The variable `name` (any case), or nullptr if the program has none of that name.
  const double* find_variable(std::string_view name) const;

 private:
  bool eval(std::uint32_t expression, double& out);
  bool store(double& slot, double value) noexcept;
  bool fail(const std::string& message);
  void jumped();
  bool vr_address(double value, std::size_t& index);
  bool table_address(double value, std::size_t& index);
  bool axis_number(double value, std::size_t& axis);
  bool io_number(double value, std::size_t& n, bool output);
  double system(system_value which) const;
  double base_axis() const { return static_cast<double>(base_.front()); }
  std::vector<std::size_t> base_group(std::size_t count, std::uint32_t axis_expression, bool& ok);
  bool build_print_text(const statement& s);
  bool print(const statement& s);
  bool send(const statement& s);
  bool get(const statement& s);
  bool motion(const statement& s);
  bool waits_for_motion();
  void end_here(std::uint32_t line) noexcept;

  const program* code_;
  controller* io_;
  task_config config_;
  std::vector<double> vars_;
  std::vector<double> stack_;
  std::vector<std::uint32_t> gosub_;
  std::uint32_t pc_ = 0;
  std::uint32_t line_ = 0;
  task_state state_ = task_state::running;
  wait_reason wait_ = wait_reason::none;
  std::string error_;
  std::uint64_t statements_ = 0;
  std::uint64_t effects_ = 0;

  // A statement that waits keeps what it evaluated.
  bool pending_ = false;
  std::string text_;
  std::size_t text_sent_ = 0;
  int channel_ = 0;
  double send_args_[4] = {};
  std::uint64_t wake_at_ = 0;

  // Per process, as on the controller: the base axes, TICKS, the ON BASICERROR label and ERROR_LINE.
  std::vector<std::size_t> base_{0};
  double ticks_value_ = 0;
  std::uint64_t ticks_base_ = 0;
  std::uint32_t error_handler_ = no_expression;
  double error_line_ = 0;
  std::uint64_t handled_errors_ = 0;
  std::vector<double> motion_args_;
  std::vector<std::size_t> motion_axes_;

  // Idle-loop detection (Brent's cycle finding over the states after taken jumps).
  bool idle_ = false;
  bool snapshot_valid_ = false;
  std::uint32_t snapshot_pc_ = 0;
  std::vector<std::uint32_t> snapshot_gosub_;
  std::uint64_t steps_ = 0;
  std::uint64_t power_ = 1;
  std::uint64_t watched_effects_ = 0;
};

}  // namespace trionet::basic
