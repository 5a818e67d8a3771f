// `trionet ring wire ENDPOINT ENDPOINT ...`: the ring's links between byte endpoints (ring_wire_cli.cpp).
#pragma once

#include "cli.hpp"

namespace trionet::cli {

/// `trionet ring wire`, an entry of the ring part's command table, its help text and option table.
int ring_wire_main(const words& args);
extern const char* const ring_wire_usage;
const option_list& ring_wire_options();

}  // namespace trionet::cli
