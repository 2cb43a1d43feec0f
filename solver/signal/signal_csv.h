#pragma once
// A 1-D acceleration history in CSV, the input of `crashlink hic FILE.csv` (docs/design.md §4):
//
//   time_s,accel_g          <- header, exactly these two names (spaces around them allowed)
//   0.0000,0.0
//   0.0001,1.25
//   ...
//
// One sample per line: time [s], acceleration [g] as given (see solver/signal/hic.h for the sign
// convention). Blank lines and lines starting with '#' are skipped; a UTF-8 byte-order mark and
// CRLF line ends are accepted.
#include <string>
#include <vector>

namespace crashlink::signal {

struct CsvSignal {
  std::vector<double> time_s;   ///< [n], strictly increasing
  std::vector<double> accel_g;  ///< [n]
};

/// Reads and checks the file; throws InputError ("file:line: what; fix") on a missing file, a
/// wrong header, a malformed or non-finite number, fewer than 2 samples, or time not increasing.
CsvSignal read_signal_csv(const std::string& path);

}  // namespace crashlink::signal
