// Every word Trio BASIC reserves, as the Motion Coordinator technical reference of the fibre-ring era
// (MC206/MC224) lists them: commands, functions, operators, constants, system, process and axis parameters.
// Each is either modelled by the simulator or refused at compile time with a message that names it; a reserved
// word is never a user variable or a label (docs/basic.md, "The words of Trio BASIC").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace trionet::basic {

/// Which part of the manual's command chapter a word belongs to.
enum class word_kind : std::uint8_t {
  motion_command,     ///< MOVE, BASE, DATUM ... (Motion and Axis Commands)
  io_command,         ///< PRINT, GET, IN, OP, SEND ... (Input / Output Commands)
  program_structure,  ///< IF, FOR, GOSUB, WA, WAIT ... (Program Loops and Structures)
  system_command,     ///< RUN, STOP, GLOBAL, CONSTANT ... (System Parameters and Commands)
  system_parameter,   ///< NETSTAT, WDOG, SERVO_PERIOD ...
  process_parameter,  ///< TICKS, PROCNUMBER ... (one per running program)
  mathematical,       ///< ABS, SIN, AND, MOD ... (Mathematical Operations and Commands)
  constant,           ///< TRUE, FALSE, ON, OFF, PI
  axis_parameter,     ///< SPEED, MPOS, UNITS ...
};

/// "system parameter", "motion command" ... as a message says it.
const char* to_string(word_kind kind) noexcept;

struct reserved_word {
  const char* name;  ///< upper case, as the manual writes it
  word_kind kind;
  bool modelled;     ///< false: a program that uses it is refused at compile time
  const char* hint;  ///< for a refused word: what to use instead, or nullptr
};

/// The whole table, sorted by name.
const reserved_word* reserved_words_begin() noexcept;
const reserved_word* reserved_words_end() noexcept;
std::size_t reserved_word_count() noexcept;

/// The entry for `upper_case_name`, or nullptr when Trio BASIC does not reserve it.
const reserved_word* find_reserved_word(std::string_view upper_case_name) noexcept;

/// "`WDOG` is a Trio BASIC system parameter that the simulator does not model" (with the hint, if any).
std::string refusal_message(const reserved_word& word);

}  // namespace trionet::basic
