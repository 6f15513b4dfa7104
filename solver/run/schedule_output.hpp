// The scheduler's history in the output file: group /scheduler (docs/output_layout.md). Written
// once at the end of a run (also a failed one); differs between rank counts and runs by design,
// so the bitwise-identity tests leave it out.
#pragma once

#include "io/h5/h5_series.hpp"
#include "scheduler/schedule_log.hpp"

namespace raceway::solver {

void write_schedule_log(io::H5SeriesWriter& file, const scheduler::ScheduleLog& log);

}  // namespace raceway::solver
