// `trionet ring learn crc|layout` and `trionet genius learn crc` (learn_cli.cpp): the wire parameters from
// captures, written into a profile (docs/profile.md).
#pragma once

#include <cstdint>
#include <string_view>

#include "cli.hpp"

namespace trionet::cli {

int ring_learn_main(const words& args);
int genius_learn_main(const words& args);
extern const char* const ring_learn_usage;
extern const char* const genius_learn_usage;
const option_list& ring_learn_options();
const option_list& genius_learn_options();

/// A Genius token as an 11-bit word: "XX" data, "c:XX" control, "w:XXX" any word (genius_cli.cpp).
bool parse_genius_token(std::string_view text, std::uint16_t& word);

}  // namespace trionet::cli
