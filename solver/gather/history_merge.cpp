// Interpolation and summed glstat of the gather (history_merge.h).
#include "solver/gather/history_merge.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace crashlink::gather {

Bracket bracket(std::span<const double> times, double t) {
  if (times.empty() || t <= times.front()) return {0, 0.0};
  if (t >= times.back()) return {times.size() - 1, 0.0};
  // First sample >= t; times.front() < t < times.back(), so 0 < j < size.
  const auto j =
      static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), t) - times.begin());
  if (times[j] == t) return {j, 0.0};
  const double span = times[j] - times[j - 1];
  return {j - 1, span > 0.0 ? (t - times[j - 1]) / span : 0.0};
}

double interpolate(std::span<const double> y, std::size_t width, std::size_t c, const Bracket& b) {
  const double a = y[width * b.i + c];
  if (b.w == 0.0) return a;
  return a + b.w * (y[width * (b.i + 1) + c] - a);
}

double end_with_margin(double t_end) {
  return t_end + 1e-12 * std::abs(t_end);
}

namespace {

/// The summed glstat columns (energy_balance_error excluded: recomputed; the scheme's energy
/// apart: merge_scheme_energy).
constexpr double io::GlstatSample::*kSummed[] = {
    &io::GlstatSample::kinetic_energy_J,   &io::GlstatSample::internal_energy_J,
    &io::GlstatSample::hourglass_energy_J, &io::GlstatSample::contact_energy_J,
    &io::GlstatSample::external_work_J,    &io::GlstatSample::total_energy_J,
    &io::GlstatSample::coupling_work_J};

/// The scheme's energy (lts) of the merged rows, which are the grid domain's rows in order: each
/// row's coarse instant K is the grid row's scheme_energy_time_s, and its energy the sum of every
/// domain's share at K, from the domain's row that holds K (not interpolated: the shares are of
/// instants, not of the rows' times). NaN where some domain has no row of K or there is no K.
void merge_scheme_energy(const std::vector<std::vector<io::GlstatSample>>& series, std::size_t grid,
                         std::vector<io::GlstatSample>& rows) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::size_t> cursor(series.size(), 0);  // keys never decrease: one pass each
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double key = series[grid][r].scheme_energy_time_s;
    rows[r].scheme_energy_time_s = key;
    rows[r].scheme_energy_J = std::isfinite(key) ? 0.0 : nan;
    if (!std::isfinite(key)) continue;
    for (std::size_t s = 0; s < series.size(); ++s) {
      const auto& d = series[s];
      if (d.empty()) continue;
      auto& c = cursor[s];
      while (c < d.size() && !(d[c].scheme_energy_time_s >= key)) ++c;  // (NaN keys skipped)
      rows[r].scheme_energy_J +=
          c < d.size() && d[c].scheme_energy_time_s == key ? d[c].scheme_energy_J : nan;
    }
  }
}

}  // namespace

GlstatMerge merge_glstat(const std::vector<std::vector<io::GlstatSample>>& series) {
  GlstatMerge out;
  bool any = false;
  out.end_time_s = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < series.size(); ++s) {
    if (series[s].empty()) continue;
    out.end_time_s = std::min(out.end_time_s, series[s].back().time_s);
    if (!any || series[s].size() < series[out.grid].size()) out.grid = s;
    any = true;
  }
  if (!any) {
    out.end_time_s = 0.0;
    return out;
  }
  const double last = end_with_margin(out.end_time_s);
  std::vector<std::vector<double>> times(series.size()), values(series.size());
  constexpr std::size_t kWidth = std::size(kSummed);
  for (std::size_t s = 0; s < series.size(); ++s) {
    for (const io::GlstatSample& g : series[s]) {
      times[s].push_back(g.time_s);
      for (const auto column : kSummed) values[s].push_back(g.*column);
    }
  }
  for (const double t : times[out.grid]) {
    if (t > last) break;
    io::GlstatSample row;
    row.time_s = t;
    for (std::size_t s = 0; s < series.size(); ++s) {
      if (series[s].empty()) continue;
      const Bracket b = bracket(times[s], t);
      for (std::size_t c = 0; c < kWidth; ++c)
        row.*kSummed[c] += interpolate(values[s], kWidth, c, b);
    }
    out.rows.push_back(row);
  }
  merge_scheme_energy(series, out.grid, out.rows);
  recompute_balance_error(out.rows);
  return out;
}

namespace {

/// E0 of the balance: total - external work - coupling work of the first row.
double initial_energy_J(const io::GlstatSample& first) {
  return first.total_energy_J - first.external_work_J - first.coupling_work_J;
}

/// The reference after row g: the largest energy seen so far (energy.h update_reference).
double updated_reference_J(double reference, const io::GlstatSample& g, double e0) {
  return std::max({reference, std::abs(g.kinetic_energy_J), std::abs(g.internal_energy_J),
                   std::abs(e0 + g.external_work_J), std::abs(g.external_work_J)});
}

}  // namespace

void recompute_balance_error(std::vector<io::GlstatSample>& rows) {
  if (rows.empty()) return;
  // Balance of energy.h: total - E0 - external work - coupling work (the coupling's work is
  // energy put in or taken out by the scheme, not integration error; it has its own column).
  const double e0 = initial_energy_J(rows.front());
  double reference = 0.0;
  for (io::GlstatSample& g : rows) {
    reference = updated_reference_J(reference, g, e0);
    const double balance = g.total_energy_J - e0 - g.external_work_J - g.coupling_work_J;
    g.energy_balance_error = reference > 0.0 ? balance / reference : 0.0;
  }
}

double balance_reference_J(const std::vector<io::GlstatSample>& rows) {
  if (rows.empty()) return 0.0;
  const double e0 = initial_energy_J(rows.front());
  double reference = 0.0;
  for (const io::GlstatSample& g : rows) reference = updated_reference_J(reference, g, e0);
  return reference;
}

}  // namespace crashlink::gather
