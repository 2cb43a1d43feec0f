// crashlink-solver (apps/solver_program.h).
#include "apps/solver_program.h"

int main(int argc, char** argv) {
  return crashlink::apps::solver_program(argc, argv);
}
