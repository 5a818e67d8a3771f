// `trionet ring wire ENDPOINT ENDPOINT ...`: the ring's links between byte endpoints (ring_wire_cli.cpp).
#pragma once

#include "cli.hpp"

namespace trionet::cli {

/// `trionet ring wire`, an entry of the ring part's command table, and its help text.
int ring_wire_main(const words& args);
extern const char* const ring_wire_usage;

}  // namespace trionet::cli
