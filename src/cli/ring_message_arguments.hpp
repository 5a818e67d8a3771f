// The arguments that describe one ring message, as `trionet ring encode` and `trionet ring send` take them:
//   print --to N TEXT | var --to N --vr V --value X | offset --to N --offset M | mode --to N --mode 0|127
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "cli.hpp"

namespace trionet::cli {

/// The options of every message kind (for a command's option table).
const option_list& ring_message_options();

/// The frame that `kind` and the parsed `args` describe (the options of another kind are refused; a print
/// takes exactly one positional, TEXT). False with `error` saying what is wrong.
bool ring_message_frame(const std::string& kind, const arguments& args, std::vector<std::uint8_t>& frame,
                        std::string& error);

}  // namespace trionet::cli
