// A Trio BASIC program compiled for the interpreter (task.hpp): statements with their jump targets resolved and
// expressions in reverse Polish form, made once by `compile` from the program text and read-only afterwards.
// The dialect and its decisions are in docs/basic.md.
//
//   text --compile--> program: statements[]      one per statement executed (IF, FOR, NEXT ... are statements;
//                               |                  a jump over an ELSE part is added and not counted)
//                               +-> expressions[] -> code[]  (reverse Polish: push, push, operate)
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

namespace trionet::basic {

inline constexpr std::size_t max_program_text = 1u << 20;
inline constexpr int max_nesting = 64;

/// The axis parameters a program may assign and read, held by its controller as named values (no motion).
inline constexpr const char* axis_parameter_names[] = {
    "ACCEL", "CREEP",  "DECEL",    "DPOS",   "D_GAIN", "FE_LIMIT", "FS_LIMIT", "I_GAIN", "JOGSPEED",
    "MPOS",  "P_GAIN", "REP_DIST", "RS_LIMIT", "SERVO", "SPEED",   "UNITS",    "VFF_GAIN"};
inline constexpr std::size_t axis_parameter_count = sizeof axis_parameter_names / sizeof axis_parameter_names[0];

struct source_position {
  std::uint32_t line = 0;    ///< 1-based
  std::uint32_t column = 0;  ///< 1-based, in bytes
};

// ---- expressions ----

enum class expr_op : std::uint8_t {
  constant,   ///< push value
  variable,   ///< push variable `index`
  vr,         ///< replace the top (a VR number) by VR(top)
  parameter,  ///< push axis parameter `index`
  key,        ///< replace the top (a channel) by KEY#top: TRUE (-1) or FALSE (0)
  netstat,    ///< push NETSTAT
  negate,
  logical_not,  ///< NOT: every bit of the integer part inverted
  absolute,
  integer_part,
  add,
  subtract,
  multiply,
  divide,
  modulo,
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
  std::uint32_t index;  ///< variable slot or axis parameter
  double value;         ///< constant
};

struct expression {
  std::uint32_t begin;  ///< [begin, end) in program::code
  std::uint32_t end;
};

// ---- statements ----

enum class statement_kind : std::uint8_t {
  assign_variable,   ///< slot = expr[0]
  assign_vr,         ///< VR(expr[0]) = expr[1]
  assign_parameter,  ///< parameter slot = expr[0]
  assign_netstat,    ///< NETSTAT = expr[0] (0 clears it)
  jump,              ///< GOTO, WEND, and the jump over an ELSE part
  branch_unless,     ///< IF, WHILE, UNTIL: go on if expr[0] is true, else jump to target
  gosub,
  return_from_gosub,
  for_start,  ///< slot = expr[0], hidden slots extra, extra+1 = expr[1], expr[2]; past the end: jump to target
  for_next,   ///< slot += step; still in range: jump to target (the first statement of the body)
  wait_until,
  wait_ms,  ///< WA(expr[0])
  print,    ///< PRINT [#expr[0],] items [extra, extra+count); flag: ends with CR LF
  get,      ///< GET #expr[0], into slot (flag clear) or VR(expr[1]) (flag set)
  send,     ///< SEND(expr[0], expr[1], expr[2] [, expr[3]])
  stop,
};

inline constexpr std::uint32_t no_expression = 0xFFFFFFFFu;

struct statement {
  statement_kind kind;
  bool counted = true;  ///< false for the jump the compiler adds over an ELSE part
  bool flag = false;
  std::uint32_t line = 0;
  std::uint32_t expr[4] = {no_expression, no_expression, no_expression, no_expression};
  std::uint32_t target = 0;
  std::uint32_t slot = 0;
  std::uint32_t extra = 0;
  std::uint32_t count = 0;
};

struct print_item {
  enum class kind : std::uint8_t { text, character, cursor, number, formatted_number };
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
  std::vector<print_item> print_items;
  std::vector<std::string> texts;
  std::vector<std::string> variable_names;  ///< slots 0..n-1 in lower case; FOR's hidden slots follow
  std::uint32_t slots = 0;                  ///< named variables + FOR's hidden end and step values
  std::uint32_t stack_depth = 1;            ///< the deepest expression's evaluation stack
};

// ---- compiling ----

enum class compile_status : std::uint8_t {
  ok,
  syntax_error,     ///< the text is not a statement of the dialect; the message says what was expected
  unknown_label,    ///< GOTO or GOSUB to a label the program does not have
  duplicate_label,  ///< the same label twice
  unmatched_block,  ///< REPEAT/UNTIL, WHILE/WEND, FOR/NEXT, IF/ELSE/ENDIF do not pair up
  too_large,        ///< text longer than max_program_text, or nested deeper than max_nesting
};

constexpr const char* to_string(compile_status status) noexcept {
  switch (status) {
    case compile_status::ok:
      return "ok";
    case compile_status::syntax_error:
      return "syntax_error";
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
  program compiled;    ///< when ok
  source_position at;  ///< when not ok: where
  std::string message;  ///< when not ok: what was expected, and what was found
  explicit operator bool() const noexcept { return status == compile_status::ok; }
  /// "NAME:LINE:COLUMN: message".
  std::string located_message() const;
};

/// Compiles program text as Trio writes it; `name` (usually the file name) is kept for messages.
compile_result compile(std::string_view name, std::string_view text);

}  // namespace trionet::basic
