// trionet_concurrency_stress: the two sides of a node run in two threads with no lock and no interrupt
// masking (tests/support/concurrency_stress.hpp). scripts/concurrency-test builds it with ThreadSanitizer.
//
//   trionet_concurrency_stress [--steps N] [--seed S] [--node all|NODE[,NODE...]] [--link uart|dma]
#include "stress/command_line.hpp"

int main(int argc, char** argv) {
  return trionet::stress::command_line("trionet_concurrency_stress", argc, argv);
}
