#include "solver/run/run_single.h"

#include <cmath>
#include <vector>

#include "solver/core/errors.h"
#include "solver/integration/solver.h"
#include "solver/io/result_writer.h"
#include "solver/run/cpu_clock.h"
#include "solver/run/progress.h"

namespace crashlink::run {

namespace {

io::GlstatSample glstat(const integration::Solver& s) {
  const auto& e = s.energy();
  io::GlstatSample g;
  g.time_s = s.time_s();
  g.kinetic_energy_J = e.kinetic_J;
  g.internal_energy_J = e.internal_J;
  g.hourglass_energy_J = e.hourglass_J;
  g.contact_energy_J = e.contact_J;
  g.external_work_J = e.external_work_J;
  g.total_energy_J = e.total_J();
  g.energy_balance_error = e.balance_error();
  return g;
}

std::vector<io::ProbeSample> probes(const integration::Solver& s) {
  std::vector<io::ProbeSample> out;
  out.reserve(s.model().probes.size());
  for (const auto& p : s.model().probes) {
    const auto v = s.probe(p);
    io::ProbeSample ps;
    for (std::size_t d = 0; d < 3; ++d) {
      ps.displacement_m[d] = v.displacement_m[d];
      ps.velocity_m_s[d] = v.velocity_m_s[d];
      ps.acceleration_m_s2[d] = v.acceleration_m_s2[d];
    }
    out.push_back(ps);
  }
  return out;
}

std::vector<io::ContactSample> contact_samples(const integration::Solver& s) {
  std::vector<io::ContactSample> out(s.contact_steps().size());
  for (std::size_t k = 0; k < out.size(); ++k)
    for (std::size_t d = 0; d < 3; ++d) out[k].force_N[d] = s.contact_steps()[k].resultant_N[d];
  return out;
}

/// Element results of every part, kept between field states (no allocation per state).
struct FieldBuffers {
  std::vector<std::vector<double>> eps_p, von_mises, stress;
  std::vector<double> velocity;

  void write(io::ResultWriter& w, const integration::Solver& s) {
    const auto& m = s.model();
    eps_p.resize(m.parts.size());
    von_mises.resize(m.parts.size());
    stress.resize(m.parts.size());
    io::FieldState f;
    f.time_s = s.time_s();
    f.displacement_m = s.displacement();
    velocity.resize(3 * m.nodes.count());
    for (std::size_t i = 0; i < m.nodes.count(); ++i) {
      const Vec3 v = s.node_velocity(i);
      for (std::size_t d = 0; d < 3; ++d) velocity[3 * i + d] = v[d];
    }
    f.velocity_m_s = velocity;
    for (std::size_t p = 0; p < m.parts.size(); ++p) {
      const std::size_t ne = m.parts[p].element_count();
      eps_p[p].resize(ne);
      von_mises[p].resize(ne);
      stress[p].resize(6 * ne);
      s.element_output(p, {von_mises[p].data(), eps_p[p].data(), stress[p].data()});
      f.parts.push_back({eps_p[p], von_mises[p], stress[p]});
    }
    w.write_field_state(f);
  }
};

}  // namespace

double RunSummary::ns_per_element_cycle() const {
  if (elements <= 0 || cycles <= 0) return 0.0;
  return 1e9 * cpu_seconds / (static_cast<double>(elements) * static_cast<double>(cycles));
}

RunSummary run_single_domain(const model::Model& model, const RunOptions& options) {
  const double wall0 = wall_seconds();
  const double cpu0 = process_cpu_seconds();
  RunSummary sum;
  sum.domain = options.domain_name;
  sum.elements = static_cast<std::int64_t>(model.element_count());
  sum.end_time_s = model.controls.end_time_s;

  io::ResultWriter writer(options.out_dir, model);
  sum.result_h5 = writer.h5_path();
  sum.result_xdmf = writer.xdmf_path();
  integration::Solver solver(model, options.domain_name);
  FieldBuffers fields;
  Progress progress(stderr, model.controls.end_time_s, options.progress);
  const auto& c = model.controls;
  double next_history = 0.0;
  double next_field = 0.0;  // field states at 0, interval, 2 interval, ... and at the end
  double last_field_time = -1.0;
  auto write_fields = [&] {
    fields.write(writer, solver);
    last_field_time = solver.time_s();
  };
  try {
    solver.initialize();
    for (;;) {
      solver.begin_cycle();  // state at t^n complete; guard passed
      const double t = solver.time_s();
      if (t >= next_history) {
        writer.append_history(glstat(solver), probes(solver), contact_samples(solver));
        do next_history += c.history_interval_s;
        while (c.history_interval_s > 0.0 && next_history <= t);
      }
      if (t >= next_field) {
        write_fields();
        next_field =
            c.field_interval_s > 0.0 ? next_field + c.field_interval_s : c.end_time_s * 2.0;
        while (next_field <= t) next_field += c.field_interval_s;
      }
      if (solver.finished()) break;
      solver.end_cycle();
      progress.update(solver.time_s(), solver.cycle(), solver.dt_s());
    }
    if (last_field_time != solver.time_s()) write_fields();
  } catch (const NumericalError& e) {
    progress.finish();
    sum.failed = true;
    sum.failure = e.what();
    // The guard fired before the bad state was sampled: what is in the file is finite.
  }
  progress.finish();
  sum.cycles = solver.cycle();
  sum.dt_min_s = solver.dt_min_s();
  sum.energy = solver.energy();
  sum.cpu_seconds = process_cpu_seconds() - cpu0;
  sum.wall_seconds = wall_seconds() - wall0;
  writer.write_timing(
      sum.wall_seconds, 0.0,
      {{options.domain_name, sum.cpu_seconds, sum.cycles, sum.dt_min_s, sum.elements}});
  writer.close();
  return sum;
}

void print_summary(std::FILE* out, const RunSummary& s) {
  std::fprintf(out, "\n%-12s %10s %10s %12s %10s %14s\n", "domain", "elements", "cycles",
               "dt_min [s]", "CPU [s]", "ns/elem/cycle");
  std::fprintf(out, "%-12s %10lld %10lld %12.4e %10.3f %14.1f\n", s.domain.c_str(),
               static_cast<long long>(s.elements), static_cast<long long>(s.cycles), s.dt_min_s,
               s.cpu_seconds, s.ns_per_element_cycle());
  std::fprintf(out, "coordinator: none (one domain); wall %.3f s\n", s.wall_seconds);
  const auto& e = s.energy;
  std::fprintf(out,
               "energy [J]: initial %.6g  kinetic %.6g  internal %.6g  hourglass %.6g  "
               "external work %.6g  total %.6g\n",
               e.initial_total_J, e.kinetic_J, e.internal_J, e.hourglass_J, e.external_work_J,
               e.total_J());
  const double hg_share = e.internal_J != 0.0 ? 100.0 * e.hourglass_J / e.internal_J : 0.0;
  std::fprintf(
      out, "energy balance error %.4f %% of the largest energy; hourglass %.2f %% of internal\n",
      100.0 * e.balance_error(), hg_share);
  std::fprintf(out, "result: %s\n        %s\n", s.result_h5.c_str(), s.result_xdmf.c_str());
  if (s.failed) std::fprintf(out, "RUN FAILED: %s\n", s.failure.c_str());
}

}  // namespace crashlink::run
