// A Trio BASIC program compiled for the interpreter (task.hpp): statements with their jump targets resolved and
// expressions in reverse Polish form, made once by `compile` from the program text and read-only afterwards.
// The dialect and its decisions are in docs/basic.md; the words it knows in reserved_words.hpp.
//
//   text --compile--> program: statements[]      one per statement executed (IF, FOR, NEXT ... are statements;
//                               |                  a jump over an ELSE or ELSEIF part is added and not counted)
//                               +-> expressions[] -> code[]  (reverse Polish: push, push, operate)
//                               +-> arguments[] (MOVE, TABLE, BASE ... lists), jump_targets[] (ON ... GOTO)
//                               +-> print_items[], texts[], variable names, labels
//
// Untrusted text: at most `max_program_text` bytes, expressions and blocks nested at most `max_nesting` deep;
// anything else is a compile error with the line, the column and what was expected.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "basic/machine.hpp"

namespace trionet::basic {

inline constexpr std::size_t max_program_text = 1u << 20;
inline constexpr int max_nesting = 64;
inline constexpr std::size_t max_arguments = 32;  ///< in one MOVE(...), TABLE(...), BASE(...) or ON ... GOTO list

struct source_position {
  std::uint32_t line = 0;    ///< 1-based
  std::uint32_t column = 0;  ///< 1-based, in bytes
};

// ---- expressions ----

/// The system values an expression reads (expr_op::system).
enum class system_value : std::uint8_t {
  netstat,
  wdog,
  servo_period,
  control,
  motion_error,
  system_error,
  error_line,
  base_axis,
};

enum class expr_op : std::uint8_t {
  constant,     ///< push value
  variable,     ///< push variable `index`
  vr,           ///< replace the top (a VR number) by VR(top)
  table,        ///< replace the top (a TABLE index) by TABLE(top)
  axis,         ///< push axis parameter `index` of the base axis
  axis_of,      ///< replace the top (an axis number) by axis parameter `index` of that axis
  system,       ///< push system value `index`
  ticks,        ///< push TICKS
  key,          ///< replace the top (a channel) by KEY#top: TRUE (-1) or FALSE (0)
  in_all,       ///< push IN: inputs 0..23 as bits
  in_one,       ///< replace the top (an input) by IN(top): 1 or 0
  in_range,     ///< replace the top two (first, last) by IN(first,last) as bits
  read_op,      ///< replace the top (an output) by READ_OP(top): 1 or 0
  negate,
  logical_not,  ///< NOT: every bit of the integer part inverted
  absolute,
  integer_part,
  fraction,
  sign,
  square_root,
  sine,
  cosine,
  tangent,
  arc_sine,
  arc_cosine,
  arc_tangent,
  exponential,
  logarithm,
  add,
  subtract,
  multiply,
  divide,
  power,
  modulo,
  arc_tangent2,
  equal,
  not_equal,
  less,
  greater,
  less_equal,
  greater_equal,
  bit_and,
  bit_or,
  bit_xor,
};

struct expr_instr {
  expr_op op;
  std::uint32_t index;  ///< variable slot, axis parameter or system value
  double value;         ///< constant
};

/// What an expression reads that can change while a program waits (WAIT UNTIL).
enum expression_reads : std::uint8_t {
  reads_clock = 1,   ///< TICKS
  reads_axes = 2,    ///< axis parameters, IDLE, MTYPE ...
  reads_inputs = 4,  ///< IN
};

struct expression {
  std::uint32_t begin;  ///< [begin, end) in program::code
  std::uint32_t end;
  std::uint8_t reads;  ///< expression_reads bits
};

// ---- statements ----

enum class motion_command : std::uint8_t { move, moveabs, forward, reverse, cancel, rapidstop, datum, defpos };

enum class statement_kind : std::uint8_t {
  assign_variable,  ///< slot = expr[0]
  assign_vr,        ///< VR(expr[0]) = expr[1]
  assign_table,     ///< TABLE(expr[0]) = expr[1]
  assign_axis,      ///< axis parameter `slot` of AXIS(expr[1]) (none: the base axis) = expr[0]
  assign_netstat,   ///< NETSTAT = expr[0] (0 clears it)
  assign_wdog,      ///< WDOG = expr[0]
  assign_ticks,     ///< TICKS = expr[0]
  jump,             ///< GOTO, WEND, and the jump over an ELSE or ELSEIF part
  branch_unless,    ///< IF, ELSEIF, WHILE, UNTIL: go on if expr[0] is true, else jump to target
  gosub,
  return_from_gosub,
  on_jump,  ///< ON expr[0] GOTO (flag clear) / GOSUB (flag set) jump_targets[extra, extra+count)
  on_error,  ///< ON BASICERROR GOTO target
  for_start,  ///< slot = expr[0], hidden slots extra, extra+1 = expr[1], expr[2]; past the end: jump to target
  for_next,   ///< slot += step; still in range: jump to target (the first statement of the body)
  wait_until,
  wait_ms,      ///< WA(expr[0])
  wait_idle,    ///< WAIT IDLE (AXIS(expr[3]), none: the base axis)
  wait_loaded,  ///< WAIT LOADED (likewise)
  print,        ///< PRINT [#expr[0],] items [extra, extra+count); flag: ends with CR LF
  get,          ///< GET #expr[0], into slot (flag clear) or VR(expr[1]) (flag set)
  send,         ///< SEND(expr[0], expr[1], expr[2] [, expr[3]])
  output,       ///< OP(expr[0], expr[1]), or OP(expr[0]) as the bits of outputs 8.. (flag set)
  table_write,  ///< TABLE(expr[0], arguments[extra, extra+count) ...)
  base,         ///< BASE(arguments[extra, extra+count))
  motion,       ///< motion_command `slot` with arguments[extra, extra+count) on AXIS(expr[3]) or the base axes
  stop,         ///< STOP, HALT, or the end of the program
};

inline constexpr std::uint32_t no_expression = 0xFFFFFFFFu;

struct statement {
  statement_kind kind;
  bool counted = true;  ///< false for the jumps the compiler adds over ELSE and ELSEIF parts
  bool flag = false;
  std::uint32_t line = 0;
  std::uint32_t expr[4] = {no_expression, no_expression, no_expression, no_expression};
  std::uint32_t target = 0;
  std::uint32_t slot = 0;
  std::uint32_t extra = 0;
  std::uint32_t count = 0;
};

struct print_item {
  enum class kind : std::uint8_t { text, character, cursor, hex, number, formatted_number };
  kind what;
  char separator;        ///< after the item: ';', ',' or '\0' (none: the last item)
  std::uint32_t source;  ///< text: index in program::texts; otherwise an expression
  std::int16_t width;
  std::int16_t decimals;
};

struct program {
  std::string name;  ///< the file name given to `compile`, for messages
  std::vector<statement> statements;
  std::vector<expression> expressions;
  std::vector<expr_instr> code;
  std::vector<std::uint32_t> arguments;     ///< expression ids of argument lists
  std::vector<std::uint32_t> jump_targets;  ///< statement indexes of ON ... GOTO / GOSUB lists
  std::vector<print_item> print_items;
  std::vector<std::string> texts;
  std::vector<std::string> variable_names;  ///< slots 0..n-1 in lower case; FOR's hidden slots follow
  std::uint32_t slots = 0;                  ///< named variables + FOR's hidden end and step values
  std::uint32_t stack_depth = 1;            ///< the deepest expression's evaluation stack
  bool reads_clock = false;                 ///< some expression reads TICKS
};

// ---- compiling ----

enum class compile_status : std::uint8_t {
  ok,
  syntax_error,     ///< the text is not a statement of the dialect; the message says what was expected
  not_modelled,     ///< a Trio BASIC word the simulator does not model; the message names it
  unknown_label,    ///< GOTO or GOSUB to a label the program does not have
  duplicate_label,  ///< the same label twice
  unmatched_block,  ///< REPEAT/UNTIL, WHILE/WEND, FOR/NEXT, IF/ELSEIF/ELSE/ENDIF do not pair up
  too_large,        ///< text longer than max_program_text, or nested deeper than max_nesting
};

constexpr const char* to_string(compile_status status) noexcept {
  switch (status) {
    case compile_status::ok:
      return "ok";
    case compile_status::syntax_error:
      return "syntax_error";
    case compile_status::not_modelled:
      return "not_modelled";
    case compile_status::unknown_label:
      return "unknown_label";
    case compile_status::duplicate_label:
      return "duplicate_label";
    case compile_status::unmatched_block:
      return "unmatched_block";
    case compile_status::too_large:
      return "too_large";
  }
  return "unknown";
}

struct [[nodiscard]] compile_result {
  compile_status status = compile_status::ok;
  program compiled;     ///< when ok
  source_position at;   ///< when not ok: where
  std::string message;  ///< when not ok: what was found and what was expected; echoed text escaped and cut
  explicit operator bool() const noexcept { return status == compile_status::ok; }
  /// "NAME:LINE:COLUMN: message".
  std::string located_message() const;
};

/// Compiles program text as Trio writes it; `name` (usually the file name) is kept for messages.
compile_result compile(std::string_view name, std::string_view text);

}  // namespace trionet::basic
