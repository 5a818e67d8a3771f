// `trionet genius ...` (placeholder until the genius part lands).
#include "cli.hpp"

int trionet::cli::genius_main(const std::vector<std::string>& /*args*/) {
  return fail("the genius commands are not built yet");
}
