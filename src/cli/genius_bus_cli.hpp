// `trionet genius simulate` and `trionet genius plan` (genius_bus_cli.cpp): a bus of device nodes, and SBAs
// without collision risk (docs/genius.md).
#pragma once

#include "cli.hpp"

namespace trionet::cli {

int genius_simulate_main(const words& args);
int genius_plan_main(const words& args);
extern const char* const genius_simulate_usage;
extern const char* const genius_plan_usage;
const option_list& genius_simulate_option_list();
const option_list& genius_plan_option_list();

}  // namespace trionet::cli
