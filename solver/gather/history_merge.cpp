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

/// The summed glstat columns (energy_balance_error excluded: recomputed). The scheme's energy
/// shares (lts, the last column) are held, not interpolated: each domain's row of a history
/// instant holds its share at the same coarse instant (the last at or before the history
/// instant), and that row is the last at or before the grid's row of that instant (the grid is the
/// domain with the fewest rows, whose row comes at its first instant past the history instant,
/// after every finer domain's). Their sum is the energy; NaN stays NaN.
constexpr double io::GlstatSample::*kSummed[] = {
    &io::GlstatSample::kinetic_energy_J,   &io::GlstatSample::internal_energy_J,
    &io::GlstatSample::hourglass_energy_J, &io::GlstatSample::contact_energy_J,
    &io::GlstatSample::external_work_J,    &io::GlstatSample::total_energy_J,
    &io::GlstatSample::coupling_work_J,    &io::GlstatSample::scheme_energy_J};

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
    for (const auto column : kSummed) row.*column = 0.0;  // (scheme_energy_J starts as NaN)
    for (std::size_t s = 0; s < series.size(); ++s) {
      if (series[s].empty()) continue;
      const Bracket b = bracket(times[s], t);
      for (std::size_t c = 0; c + 1 < kWidth; ++c)
        row.*kSummed[c] += interpolate(values[s], kWidth, c, b);
      // held: the last row at or before t, to the rounding of the domains' summed steps
      const auto& ts = times[s];
      const auto after = std::upper_bound(ts.begin(), ts.end(), end_with_margin(t));
      const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - ts.begin() - 1, 0));
      row.*kSummed[kWidth - 1] += values[s][kWidth * i + kWidth - 1];
    }
    out.rows.push_back(row);
  }
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
