// `trionet ring simulate ...` (the simulator lands with the ring nodes).
#include "cli.hpp"
#include "ring_cli.hpp"

int trionet::cli::ring_simulate_main(const std::vector<std::string>& /*args*/) {
  return fail("ring simulate: the ring simulator is not built yet");
}
