// What the MPI executor writes into its ScheduleLog (scheduler/schedule_log.hpp), and the plan lines
// it logs. Pure (no MPI).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "scheduler/cost_model.hpp"
#include "scheduler/executor.hpp"
#include "scheduler/schedule_log.hpp"

namespace raceway::scheduler {

/// The catalogue's sizes, groups and pieces (what the replay model needs of the tasks).
void log_catalogue(ScheduleLog& log, const TaskCatalogue& catalogue);
/// One evaluation of `phase`: sums per phase and rank, the measured costs, and every sample_every-th
/// evaluation a sample. Past 2^17 samples every other one is dropped and sampling halves: bounded
/// memory over long runs (10^7 evaluations).
void log_evaluation(ScheduleLog& log, long evaluation, int phase, double time, const EvaluationBalance& balance,
                    std::span<const double> busy, double wall, int plan_version, const std::vector<double>& measured_cost);
/// Adds a plan event; returns the lines to log: the first 20 plans and then every 100th (a long
/// adaptive run makes thousands; all are kept in the log).
std::vector<std::string> log_plan(ScheduleLog& log, const PlanEvent& event);
/// "scheduler: rhs plan v3 before evaluation 120 (imbalance, greedy LPT): predicted imbalance ..."
std::string plan_event_line(const PlanEvent& event);

}  // namespace raceway::scheduler
