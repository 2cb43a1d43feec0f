#pragma once
// The contact forces of a result file as `crashlink report` plots them (tools/report.py
// contact_forces.png): each interface's resultant force on the slave side, every axis filtered by
// SAE J211/1 CFC 180 (signal/channel_filter.h: the class for structural forces) before the
// resultant is taken, in kN against ms.
#include <string>

#include "solver/io/result_reader.h"

namespace crashlink::apps {

/// Writes `path`: CSV with the header `contact,filter,time_ms,force_kN`, one row per sample of
/// each contact of `reader` (link order), `filter` "CFC 180". A contact with fewer than two
/// samples, or sampled too coarsely for the class (below about 763 Hz), is written unfiltered
/// with filter "none" and a note on stderr naming it and why. Names are quoted when they hold a
/// comma or a quote (RFC 4180). Throws InputError naming `who` when the file cannot be written.
void write_contact_force_csv(const std::string& path, const io::ResultReader& reader,
                             const char* who);

}  // namespace crashlink::apps
