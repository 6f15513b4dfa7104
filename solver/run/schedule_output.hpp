// The scheduler's history in the output file: group /scheduler (docs/output_layout.md). Written
// once at the end of a run (also a failed one); differs between rank counts and runs by design,
// so the bitwise-identity tests leave it out.
#pragma once

#include <limits>

#include "io/h5/h5_series.hpp"
#include "scheduler/schedule_log.hpp"

namespace raceway::run {

/// Bytes of /scheduler's attributes and object headers, apart from its arrays: what
/// estimate_output reserves for it in every run.
inline constexpr double kScheduleLogFixedBytes = 16e3;

/// The bytes of /scheduler's arrays for `log` (task arrays, plans, imbalance samples), uncompressed.
double schedule_log_array_bytes(const scheduler::ScheduleLog& log);

/// Writes /scheduler within `budget_bytes` for its arrays (what [output] max_size leaves after the
/// series and the fixed parts): past it, every other imbalance sample is left out (and
/// sample_every doubled) until they fit, then the plans beyond the first and last ones, then the
/// per-task arrays; what was left out is said in the attribute `left_out_for_max_size`.
void write_schedule_log(h5::H5SeriesWriter& file, const scheduler::ScheduleLog& log,
                        double budget_bytes = std::numeric_limits<double>::infinity());

}  // namespace raceway::run
