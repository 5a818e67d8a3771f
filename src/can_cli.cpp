// `trionet can ...` (placeholder until the can part lands).
#include "cli.hpp"

int trionet::cli::can_main(const std::vector<std::string>& /*args*/) {
  return fail("the can commands are not built yet");
}
