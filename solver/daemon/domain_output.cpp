#include "solver/daemon/domain_output.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "core/errors.h"
#include "core/log_escape.h"
#include "solver/run/domain_timing.h"

namespace crashlink::daemon {

namespace {

io::ResultWriterOptions writer_options(const std::string& domain) {
  io::ResultWriterOptions wo;
  wo.file_stem = domain;  // DIR/domains/<domain>.h5, what solver/gather reads back
  wo.history_flush_wall_s = 1.0;
  return wo;
}

}  // namespace

DomainOutput::DomainOutput(const std::string& out_dir, const std::string& domain,
                           const integration::Solver& solver)
    : domain_(domain),
      solver_(&solver),
      writer_((std::filesystem::path(out_dir) / "domains").string(), solver.model(),
              writer_options(domain)),
      recorder_(std::make_unique<run::DomainRecorder>(writer_, solver)),
      h5_path_(writer_.h5_path()) {}

void DomainOutput::follow(const integration::Solver& solver) {
  solver_ = &solver;
  recorder_ = std::make_unique<run::DomainRecorder>(writer_, solver);
  if (scheme_energy_) recorder_->set_scheme_energy(scheme_energy_);
  if (field_gate_) recorder_->set_field_gate(field_gate_);
}

void DomainOutput::set_scheme_energy(std::function<std::pair<double, double>(double)> share_J) {
  scheme_energy_ = std::move(share_J);
  recorder_->set_scheme_energy(scheme_energy_);
}

void DomainOutput::set_field_gate(std::function<bool()> settled) {
  field_gate_ = std::move(settled);
  recorder_->set_field_gate(field_gate_);
}

void DomainOutput::finish(double wall_s, double cpu_s, std::int64_t elements) {
  recorder_->finish();
  write_timing(wall_s, cpu_s, elements);
  writer_.close();
}

void DomainOutput::close_after_failure(double wall_s, double cpu_s,
                                       std::int64_t elements) noexcept {
  if (!writer_.is_open()) return;
  try {
    recorder_->flush();
    write_timing(wall_s, cpu_s, elements);
  } catch (const std::exception&) {
  }
  try {
    writer_.close();
  } catch (const std::exception&) {
  }
}

/// The domain's timing and the spot welds that let go in it (gathered into result.h5).
void DomainOutput::write_timing(double wall_s, double cpu_s, std::int64_t elements) {
  writer_.write_timing(wall_s, 0.0,
                       {run::domain_timing(*solver_, domain_, cpu_s, elements, setup_cpu_s_)});
  std::vector<io::SpotWeldFailure> welds;
  for (const auto& w : solver_->weld_failures())
    welds.push_back({w.name, w.time_s, w.normal_N, w.shear_N});
  writer_.write_spot_weld_failures(welds);
}

std::int64_t injected_fault_cycle(const std::string& domain) {
  const char* v = std::getenv("CRASHLINK_INJECT_INTERNAL_ERROR");
  if (v == nullptr) return -1;
  const std::string s(v);
  const auto colon = s.rfind(':');
  if (colon == std::string::npos || s.substr(0, colon) != domain) return -1;
  try {
    return std::stoll(s.substr(colon + 1));
  } catch (const std::exception&) {
    throw InputError(fmt::format("CRASHLINK_INJECT_INTERNAL_ERROR='{}': expected DOMAIN:CYCLE",
                                 core::log_escape(s)));
  }
}

}  // namespace crashlink::daemon
