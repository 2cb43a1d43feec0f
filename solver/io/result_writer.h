#pragma once
// The result writer: DIR/result.h5 (layout: docs/result-format.md, contract: docs/design.md §4) and
// DIR/result.xdmf for ParaView. Plain data in, no solver internals. SI units; every dataset
// carries a "units" attribute. What a run that dies leaves behind: ResultWriter and
// docs/result-format.md "Robustness". Arrays: n = model node count, ne = element count of a part.
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/model/model.h"

namespace crashlink::io {

/// One glstat row: global energies of the whole model at time_s.
struct GlstatSample {
  double time_s = 0.0;
  double kinetic_energy_J = 0.0;
  double internal_energy_J = 0.0;  ///< stress work incl. bulk viscosity
  double hourglass_energy_J = 0.0;
  double contact_energy_J = 0.0;
  double external_work_J = 0.0;  ///< work of loads, prescribed motion, gravity
  double total_energy_J = 0.0;
  /// relative: (total - initial - external - coupling) / reference [-]
  double energy_balance_error = 0.0;
  /// Work done on the domain(s) by the coupling between domains (link and drift forces; the
  /// `layer` scheme's layer force on J and the ghost motion): energy.h coupling_work_J. 0 in a
  /// single-domain run; summed over the domains it is the energy the coupling put in (> 0) or
  /// took out.
  double coupling_work_J = 0.0;
  /// The coupling scheme's conserved discrete energy, this domain's share at the coarse instant
  /// scheme_energy_time_s, the last at or before the row's history instant (`lts`:
  /// cosim::LtsEnergy E^{k-1/2}, docs/multirate.md "lts"); summed over the domains' rows of the
  /// same coarse instant it is the energy (a share alone is not one). NaN where there is none
  /// (mono, layer, paper; before lts's third coarse instant).
  double scheme_energy_J = std::numeric_limits<double>::quiet_NaN();
  double scheme_energy_time_s = std::numeric_limits<double>::quiet_NaN();  ///< its instant [s]
};

/// One probe row (node or rigid-body centre of mass), global frame.
struct ProbeSample {
  double displacement_m[3] = {0.0, 0.0, 0.0};
  double velocity_m_s[3] = {0.0, 0.0, 0.0};
  double acceleration_m_s2[3] = {0.0, 0.0, 0.0};
};

/// One contact row: resultant force on the slave side of an interface, global frame, and the
/// interface's contact energy (contact::ContactStep::energy_J: minus the work of its forces since
/// the start; below zero the contact has created energy).
struct ContactSample {
  double force_N[3] = {0.0, 0.0, 0.0};
  double energy_J = 0.0;
};

/// Element results of one part; an empty span means "not available" (not written).
struct PartFieldState {
  std::span<const double> eps_p;         ///< [ne] effective plastic strain [-]
  std::span<const double> von_mises_Pa;  ///< [ne]
  std::span<const double> stress_Pa;     ///< [6ne] Voigt xx,yy,zz,xy,yz,zx, element e at 6e
};

/// One field state. `parts` is empty (no element results) or one entry per model.parts, in order.
struct FieldState {
  double time_s = 0.0;
  std::span<const double> displacement_m;  ///< [3n] interleaved xyz, node i at 3i..3i+2; required
  std::span<const double> velocity_m_s;    ///< [3n] as displacement_m; empty: not written
  std::vector<PartFieldState> parts;
};

/// Cost of one domain (daemon) over the run.
struct DomainTiming {
  std::string name;
  double cpu_seconds = 0.0;
  std::int64_t cycles = 0;
  double dt_min_s = 0.0;
  std::int64_t elements = 0;
  std::int64_t threads = 1;  ///< the solver's threads (cpu_seconds is theirs summed)
  /// Cost figures of the scale benchmark (bench/bench_scale.py; 0 in files written before):
  double contact_seconds = 0.0;          ///< CPU time in contact search and forces [s]
  std::int64_t contact_node_cycles = 0;  ///< slave nodes tested, summed over the evaluations
  std::int64_t peak_rss_bytes = 0;       ///< the process's peak resident memory, VmHWM [B]
  /// CPU before the first cycle [s] (of cpu_seconds): reading, cutting, masses, the first step
  double setup_cpu_seconds = 0.0;
  /// The element kernels' CPU [s] and the element-cycles they computed, per kind, over the
  /// cycles the solver samples (integration::Solver::kernel_cost: one in 16), and how many
  std::int64_t kernel_sampled_cycles = 0;
  double hex_kernel_seconds = 0.0;
  std::int64_t hex_element_cycles = 0;
  double shell_kernel_seconds = 0.0;
  std::int64_t shell_element_cycles = 0;
  /// The global step's refreshes after set-up, CPU [s] (every one; 0 without it)
  double global_step_seconds = 0.0;
};

/// A spot weld that let go (integration::WeldFailure): /events/spot_weld_failures/<k> with the
/// attributes name, time [s], tension [N], shear [N], in the order they failed.
struct SpotWeldFailure {
  std::string name;
  double time_s = 0.0;
  double tension_N = 0.0, shear_N = 0.0;
};

struct ResultWriterOptions {
  std::size_t history_flush_samples = 1000;  ///< flush history after this many buffered samples
  double history_flush_wall_s = 5.0;         ///< ... or when this much wall time has passed
  std::size_t history_chunk_rows = 1024;     ///< HDF5 chunk length of the history datasets
  /// The files are DIR/<file_stem>.h5 and DIR/<file_stem>.xdmf: "result" for a run's result, the
  /// domain name for a daemon's DIR/domains/<domain>.h5 (solver/gather reads those back).
  std::string file_stem = "result";
};

/// The HDF5 link name of a user name (part, probe, contact, domain, interface): '/' would nest
/// groups, so it becomes '_'; "", "." and ".." become "<fallback>_<index>".
std::string result_link_name(const std::string& name, const char* fallback, std::size_t index);

/// Not thread-safe (nor is the serial HDF5 library): one thread owns the writer.
/// Robustness: history is buffered and written by flush_history(), which runs automatically every
/// ResultWriterOptions::history_flush_samples samples or history_flush_wall_s wall seconds and is
/// followed by H5Fflush, so a run that dies leaves a readable file with every sample up to the last
/// flush. Field states and timing are flushed as they are written, and result.xdmf is rewritten
/// (atomically) after each field state. The destructor closes everything, also during stack
/// unwinding, and never throws. HDF5 failures throw ResultFileError (solver/io/hdf5_handles.h)
/// naming the file, the object and the call.
class ResultWriter {
 public:
  /// Creates `dir` if needed, DIR/result.h5 (truncated) with /mesh, empty /history datasets and
  /// /states, and a mesh-only DIR/result.xdmf (names: ResultWriterOptions::file_stem). Throws
  /// ResultFileError, or ModelError if the model's arrays are inconsistent (x0 not 3n, connectivity
  /// not a multiple of the element's node count, duplicate part or probe names).
  ResultWriter(const std::string& dir, const model::Model& model, ResultWriterOptions options = {});
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;
  ~ResultWriter();  ///< close(); never throws (a failure is printed to stderr)

  /// Buffers one history row; `probes` has one sample per model.probes, `contacts` one per
  /// model.contacts (/history/contacts/<name>/{time, force, energy}) and `walls` one per
  /// model.rigid_walls (/history/rigid_walls/<name>/{time, force, work}: the wall's force on the
  /// nodes it stops and its work on them, in the sample's energy_J), same order.
  /// May flush (see ResultWriterOptions).
  void append_history(const GlstatSample& g, const std::vector<ProbeSample>& probes,
                      const std::vector<ContactSample>& contacts = {},
                      const std::vector<ContactSample>& walls = {});
  /// Writes the buffered history rows and H5Fflush-es the file.
  void flush_history();

  // Whole-column history appends, for a writer that holds the histories already (the gather of a
  // coupled run, solver/gather/gather_results.h): glstat rows, and each probe and contact with its
  // own sample times (the rows of the domain that holds it). Each call first writes the rows
  // append_history() buffered, then appends directly (no buffering) and H5Fflush-es. Mixing them
  // with append_history() is allowed but the caller then owns the "same length k" of the layout.
  // `time_s` and `rows` have the same length; throws ResultFileError otherwise or for an index
  // outside model.probes / model.contacts.
  void append_glstat_rows(std::span<const GlstatSample> rows);
  void append_probe_rows(std::size_t probe, std::span<const double> time_s,
                         std::span<const ProbeSample> rows);
  void append_contact_rows(std::size_t contact, std::span<const double> time_s,
                           std::span<const ContactSample> rows);
  /// Rigid wall `wall` (model.rigid_walls): force and work (energy_J) rows.
  void append_wall_rows(std::size_t wall, std::span<const double> time_s,
                        std::span<const ContactSample> rows);

  /// Writes /states/<k> (k = 0, 1, ...), flushes, and rewrites result.xdmf.
  void write_field_state(const FieldState& s);
  /// Writes (or replaces) /timing; flushes.
  void write_timing(double wall_seconds, double coordinator_cpu_seconds,
                    const std::vector<DomainTiming>& domains);
  /// flush_history() (buffers written, H5Fflush).
  void flush();
  /// /events/spot_weld_failures (nothing without failures: older files keep their layout).
  void write_spot_weld_failures(const std::vector<SpotWeldFailure>& failures);
  /// Flushes, writes result.xdmf and closes result.h5. Idempotent; after it every other call
  /// throws ResultFileError. If a step fails the file is still closed and the first error thrown.
  void close();

  bool is_open() const { return impl_ != nullptr; }
  const std::string& h5_path() const { return h5_path_; }
  const std::string& xdmf_path() const { return xdmf_path_; }
  std::size_t state_count() const { return state_count_; }            ///< field states written
  std::size_t history_rows_written() const { return history_rows_; }  ///< rows on disk (flushed)

 private:
  void append_item_rows(bool wall, std::size_t item, std::span<const double> time_s,
                        std::span<const ContactSample> rows);
  struct Impl;
  std::string h5_path_;
  std::string xdmf_path_;
  std::size_t state_count_ = 0;
  std::size_t history_rows_ = 0;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crashlink::io
