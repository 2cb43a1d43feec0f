// crashlink-solver-hold: crashlink-solver with the test scheme "hold" registered first
// (tests/support/hold_scheme.h; run by tests/integration/hold_scheme_test.cpp).
#include "apps/solver_program.h"
#include "tests/support/hold_scheme.h"

int main(int argc, char** argv) {
  crashlink::test_schemes::register_hold();
  return crashlink::apps::solver_program(argc, argv);
}
