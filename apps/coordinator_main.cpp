// crashlink-coordinator (apps/coordinator_program.h).
#include "apps/coordinator_program.h"

int main(int argc, char** argv) {
  return crashlink::apps::coordinator_program(argc, argv);
}
