// Mono on 1 thread and on N threads in one process, the two solvers stepping the same scene in
// alternating blocks of K cycles (docs/threads.md "Measured"). Both run the same cycles to the
// same bits, so each pair of blocks compares like with like, and the host's slow drift (runs of
// the same command vary by up to 30 % on a shared VM) falls out of the per-pair ratios:
//   bench_threads_interleaved [--scene FILE] [--threads N] [--blocks B] [--cycles K]
//                             [--warmup W]
// defaults: scenarios/head_impact.yaml, 2, 40, 250, 2000 (W may be 0). Prints per pair the wall
// and CPU per cycle of each side, then the medians of the per-pair ratios, speed-up (wall 1 /
// wall N) and CPU per cycle (N / 1), and the same two from the totals. The N-thread team sleeps
// through the 1-thread blocks: its first loops after one pay a wake-up, and a worker's last spin
// (at most 100 us per block) counts in the 1-thread block's process CPU; with K = 500 both are
// far below the spread. The scene's end time is lifted so that no block runs out of cycles. Exit 1
// if the two sides' time and energies differ at the end (they must agree to the bit), 2 on a bad
// argument.
#include <fmt/format.h>

#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/cpu_clock.h"
#include "core/median.h"
#include "solver/integration/solver.h"
#include "solver/io/scenario_reader.h"

using namespace crashlink;

namespace {

struct Side {
  std::unique_ptr<model::Model> model;
  std::unique_ptr<integration::Solver> solver;
};

Side make_side(const std::string& scene, int threads) {
  Side s;
  s.model = std::make_unique<model::Model>(io::read_scenario(scene));
  s.model->domains.clear();
  s.model->controls.end_time_s = 1.0;  // never finished inside the benchmark
  s.solver = std::make_unique<integration::Solver>(*s.model, "mono");
  s.solver->set_threads(threads);
  s.solver->initialize();
  return s;
}

struct Block {
  double wall_s = 0, cpu_s = 0;
};

Block run_block(integration::Solver& solver, int cycles) {
  const double w0 = core::wall_seconds(), c0 = core::process_cpu_seconds();
  for (int i = 0; i < cycles; ++i) {
    solver.begin_cycle();
    solver.end_cycle();
  }
  return {core::wall_seconds() - w0, core::process_cpu_seconds() - c0};
}

int usage(std::string_view why) {
  fmt::print(stderr,
             "bench_threads_interleaved: {}\nusage: bench_threads_interleaved [--scene FILE] "
             "[--threads N] [--blocks B] [--cycles K] [--warmup W]\n",
             why);
  return 2;
}

}  // namespace

int main(int argc, char** argv) try {
  std::string scene = std::string(CRASHLINK_SCENARIO_DIR) + "/head_impact.yaml";
  int threads = 2, blocks = 40, cycles = 250, warmup = 2000;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    int* target = a == "--threads"  ? &threads
                  : a == "--blocks" ? &blocks
                  : a == "--cycles" ? &cycles
                  : a == "--warmup" ? &warmup
                                    : nullptr;
    if (a != "--scene" && !target) return usage(fmt::format("unknown option {}", a));
    if (i + 1 >= argc) return usage(fmt::format("{} needs a value", a));
    const std::string v = argv[++i];
    if (!target) {
      scene = v;
      continue;
    }
    char* end = nullptr;
    const long n = std::strtol(v.c_str(), &end, 10);
    const long low = target == &warmup ? 0 : 1;
    if (v.empty() || *end != '\0' || n < low || n > 1000000)
      return usage(fmt::format("{} {}: a whole number from {} to 10^6 is needed", a, v, low));
    *target = static_cast<int>(n);
  }
  Side one = make_side(scene, 1), many = make_side(scene, threads);
  run_block(*one.solver, warmup);
  run_block(*many.solver, warmup);
  fmt::print("{}: 1 thread against {} threads, {} pairs of {} cycles after {} warm-up cycles\n",
             scene, threads, blocks, cycles, warmup);
  fmt::print("{:>5} {:>14} {:>14} {:>14} {:>14} {:>9} {:>9}\n", "pair", "wall 1 [us]",
             fmt::format("wall {} [us]", threads), "CPU 1 [us]",
             fmt::format("CPU {} [us]", threads), "speed-up", "CPU N/1");
  std::vector<double> speed_up, cpu_ratio, w1s, wns, c1s, cns;
  for (int b = 0; b < blocks; ++b) {
    // Alternate which side goes first, so that neither always follows the other's cache state.
    Block b1, bn;
    if (b % 2 == 0) {
      b1 = run_block(*one.solver, cycles);
      bn = run_block(*many.solver, cycles);
    } else {
      bn = run_block(*many.solver, cycles);
      b1 = run_block(*one.solver, cycles);
    }
    const double k = 1e6 / cycles;
    w1s.push_back(k * b1.wall_s);
    wns.push_back(k * bn.wall_s);
    c1s.push_back(k * b1.cpu_s);
    cns.push_back(k * bn.cpu_s);
    speed_up.push_back(b1.wall_s / bn.wall_s);
    cpu_ratio.push_back(bn.cpu_s / b1.cpu_s);
    fmt::print("{:>5} {:>14.1f} {:>14.1f} {:>14.1f} {:>14.1f} {:>9.3f} {:>9.3f}\n", b + 1,
               w1s.back(), wns.back(), c1s.back(), cns.back(), speed_up.back(), cpu_ratio.back());
  }
  // The two sides must have run the same cycles to the same bits (docs/threads.md): else the
  // comparison is not like with like, and the threads have a bug.
  const auto& e1 = one.solver->energy();
  const auto& en = many.solver->energy();
  if (one.solver->time_s() != many.solver->time_s() || e1.kinetic_J != en.kinetic_J ||
      e1.internal_J != en.internal_J || e1.hourglass_J != en.hourglass_J ||
      e1.contact_J != en.contact_J || e1.external_work_J != en.external_work_J ||
      e1.reference_J != en.reference_J) {
    fmt::print(stderr,
               "bench_threads_interleaved: the sides differ after the same cycles: t {} against "
               "{} s, kinetic {} against {} J, internal {} against {} J, hourglass {} against {} "
               "J, contact {} against {} J, external work {} against {} J\n",
               one.solver->time_s(), many.solver->time_s(), e1.kinetic_J, en.kinetic_J,
               e1.internal_J, en.internal_J, e1.hourglass_J, en.hourglass_J, e1.contact_J,
               en.contact_J, e1.external_work_J, en.external_work_J);
    return 1;
  }
  fmt::print(
      "medians per cycle: wall 1 thread {:.1f} us, {} threads {:.1f} us; CPU {:.1f} against "
      "{:.1f} us\n",
      core::median(w1s), threads, core::median(wns), core::median(c1s), core::median(cns));
  fmt::print(
      "median of the pairs' ratios: speed-up {:.3f}, CPU per cycle {} threads / 1 = {:.3f}\n",
      core::median(speed_up), threads, core::median(cpu_ratio));
  double w1 = 0, wn = 0, c1 = 0, cn = 0;
  for (std::size_t b = 0; b < w1s.size(); ++b) {
    w1 += w1s[b];
    wn += wns[b];
    c1 += c1s[b];
    cn += cns[b];
  }
  fmt::print("from the totals: speed-up {:.3f}, CPU per cycle {} threads / 1 = {:.3f}\n", w1 / wn,
             threads, cn / c1);
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "bench_threads_interleaved: {}\n", e.what());
  return 1;
}
