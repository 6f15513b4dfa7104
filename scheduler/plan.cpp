#include "scheduler/plan.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>

namespace raceway::scheduler {

namespace {

int piece_of(const TaskCatalogue& cat, int t) {
  return cat.parent.empty() ? t : cat.parent[static_cast<std::size_t>(t)];
}

/// A level-1 unit: a rolling element's tasks, or one border piece's.
struct Unit {
  std::vector<int> tasks;
  double cost = 0;
  std::set<int> bodies;
};

std::vector<Unit> make_units(std::span<const double> cost, const TaskCatalogue& cat) {
  std::vector<Unit> units;
  std::map<int, std::size_t> of_group, of_border_piece;
  for (int t = 0; t < cat.task_count; ++t) {
    const int g = cat.group[static_cast<std::size_t>(t)];
    // A border piece (one segment, perhaps cut into sub-tasks) is a unit; a rolling element's
    // pieces together are one.
    auto& index = g == border_group ? of_border_piece : of_group;
    auto [it, fresh] = index.try_emplace(g == border_group ? piece_of(cat, t) : g, units.size());
    if (fresh) units.emplace_back();
    const std::size_t u = it->second;
    units[u].tasks.push_back(t);
    units[u].cost += cost[static_cast<std::size_t>(t)];
    if (!cat.bodies.empty())
      for (int b : cat.bodies[static_cast<std::size_t>(t)])
        if (b >= 0) units[u].bodies.insert(b);
  }
  return units;
}

std::vector<double> rank_loads(std::span<const int> owner, std::span<const double> cost, std::size_t ranks) {
  std::vector<double> load(ranks, 0.0);
  for (std::size_t t = 0; t < owner.size(); ++t) load[static_cast<std::size_t>(owner[t])] += cost[t];
  return load;
}

/// Greedy LPT: units by decreasing cost, each to the rank whose weighted finish time is smallest.
std::vector<int> lpt(const std::vector<Unit>& units, std::span<const double> capacity) {
  std::vector<std::size_t> order(units.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return units[a].cost > units[b].cost; });
  std::vector<double> load(capacity.size(), 0.0);
  std::vector<int> unit_rank(units.size(), 0);
  for (std::size_t u : order) {
    std::size_t best = 0;
    double best_finish = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < capacity.size(); ++r) {
      if (capacity[r] <= 0) continue;
      const double finish = (load[r] + units[u].cost) / capacity[r];
      if (finish < best_finish) best_finish = finish, best = r;
    }
    load[best] += units[u].cost;
    unit_rank[u] = static_cast<int>(best);
  }
  return unit_rank;
}

/// METIS k-way on the level-1 graph; empty when METIS cannot be used or fails.
std::vector<int> metis_kway(const std::vector<Unit>& units, std::span<const double> capacity) {
  // METIS needs every part to have positive target weight: map parts to ranks with capacity > 0.
  std::vector<int> part_rank;
  for (std::size_t r = 0; r < capacity.size(); ++r)
    if (capacity[r] > 0) part_rank.push_back(static_cast<int>(r));
  const auto nparts = static_cast<idx_t>(part_rank.size());
  const auto nvtxs = static_cast<idx_t>(units.size());
  if (nparts < 2 || nvtxs <= nparts) return {};
  const double max_cost = std::max_element(units.begin(), units.end(), [](auto& a, auto& b) { return a.cost < b.cost; })->cost;
  if (!(max_cost > 0)) return {};
  std::vector<idx_t> xadj{0}, adjncy, adjwgt, vwgt;
  for (std::size_t u = 0; u < units.size(); ++u) {
    // Integer vertex weights (idx_t is 32-bit): costs scaled so the heaviest unit weighs 10^6.
    vwgt.push_back(std::max<idx_t>(1, static_cast<idx_t>(std::lround(units[u].cost / max_cost * 1e6))));
    for (std::size_t v = 0; v < units.size(); ++v) {
      if (u == v) continue;
      idx_t shared = 0;
      for (int b : units[u].bodies) shared += static_cast<idx_t>(units[v].bodies.count(b));
      if (shared > 0) adjncy.push_back(static_cast<idx_t>(v)), adjwgt.push_back(shared);
    }
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
  }
  double cap_sum = 0;
  for (int r : part_rank) cap_sum += capacity[static_cast<std::size_t>(r)];
  std::vector<real_t> tpwgts;
  for (int r : part_rank) tpwgts.push_back(static_cast<real_t>(capacity[static_cast<std::size_t>(r)] / cap_sum));
  idx_t ncon = 1, objval = 0, np = nparts, nv = nvtxs;
  real_t ubvec = 1.03f;  // 3 % load tolerance, METIS's default for k-way
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = 1;  // reproducible plans for the same costs
  std::vector<idx_t> part(units.size(), 0);
  const int status = METIS_PartGraphKway(&nv, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr,
                                         adjncy.empty() ? nullptr : adjwgt.data(), &np, tpwgts.data(), &ubvec, options,
                                         &objval, part.data());
  // METIS signals its own internal errors by raising SIGTERM in the calling thread, where raceway
  // blocks it (solver/run/stop_signals.hpp), so such an error may come back as METIS_OK: a part
  // out of range is taken as a failure too (the caller plans without METIS).
  if (status != METIS_OK || std::any_of(part.begin(), part.end(), [&](idx_t p) { return p < 0 || p >= np; })) return {};
  std::vector<int> unit_rank(units.size());
  for (std::size_t u = 0; u < units.size(); ++u) unit_rank[u] = part_rank[static_cast<std::size_t>(part[u])];
  return unit_rank;
}

std::vector<int> owners_of(const std::vector<Unit>& units, const std::vector<int>& unit_rank, int task_count) {
  std::vector<int> owner(static_cast<std::size_t>(task_count), 0);
  for (std::size_t u = 0; u < units.size(); ++u)
    for (int t : units[u].tasks) owner[static_cast<std::size_t>(t)] = unit_rank[u];
  return owner;
}

/// What level 2 can move off a rank: a piece's tasks there, or one task of a heavy piece.
struct Move {
  std::vector<int> tasks;
  double cost = 0;
};

/// The moves off rank `from` within group g, in task order: light pieces whole, heavy ones by task.
std::vector<Move> moves_of_group(const std::vector<int>& owner, std::span<const double> cost, const TaskCatalogue& cat,
                                 int from, int g, double heavy) {
  std::vector<Move> moves;
  std::map<int, std::size_t> of_piece;
  for (int t = 0; t < cat.task_count; ++t) {
    const auto ti = static_cast<std::size_t>(t);
    if (owner[ti] != from || cat.group[ti] != g) continue;
    auto [it, fresh] = of_piece.try_emplace(piece_of(cat, t), moves.size());
    if (fresh) moves.emplace_back();
    moves[it->second].tasks.push_back(t);
    moves[it->second].cost += cost[ti];
  }
  std::vector<Move> out;
  for (auto& m : moves) {
    if (m.cost > heavy && m.tasks.size() > 1)
      for (int t : m.tasks) out.push_back({{t}, cost[static_cast<std::size_t>(t)]});
    else
      out.push_back(std::move(m));
  }
  return out;
}

/// Everything level 2 can move off rank `from` (moves_of_group over its groups, in group order).
std::vector<Move> moves_of_rank(const std::vector<int>& owner, std::span<const double> cost, const TaskCatalogue& cat,
                                int from, double heavy) {
  std::set<int> groups;
  for (int t = 0; t < cat.task_count; ++t)
    if (owner[static_cast<std::size_t>(t)] == from) groups.insert(cat.group[static_cast<std::size_t>(t)]);
  std::vector<Move> out;
  for (const int g : groups)
    for (Move& m : moves_of_group(owner, cost, cat, from, g, heavy)) out.push_back(std::move(m));
  return out;
}

/// When no single move off the most loaded rank `hi` lowers it (every piece it could give is
/// larger than the gap to the least loaded rank): the exchange of one of its moves with a cheaper
/// one of another rank that lowers the larger of the two ranks' weighted times the most. False
/// when no exchange lowers it.
bool exchange_off(std::vector<int>& owner, std::vector<double>& load, std::span<const double> cost,
                  const TaskCatalogue& cat, std::span<const double> capacity, std::size_t hi, double heavy_share) {
  const double hi_norm = load[hi] / capacity[hi];
  const std::vector<Move> mine = moves_of_rank(owner, cost, cat, static_cast<int>(hi), heavy_share * capacity[hi]);
  double best_norm = hi_norm;
  const Move *give = nullptr, *take = nullptr;
  std::size_t with = hi;
  std::vector<std::vector<Move>> theirs(capacity.size());
  for (std::size_t r = 0; r < capacity.size(); ++r) {
    if (r == hi || capacity[r] <= 0) continue;
    theirs[r] = moves_of_rank(owner, cost, cat, static_cast<int>(r), heavy_share * capacity[r]);
    for (const Move& a : mine)
      for (const Move& b : theirs[r]) {
        const double d = a.cost - b.cost;
        if (!(d > 0)) continue;
        const double worst = std::max((load[hi] - d) / capacity[hi], (load[r] + d) / capacity[r]);
        if (worst < best_norm) best_norm = worst, give = &a, take = &b, with = r;
      }
  }
  if (give == nullptr) return false;
  for (int t : give->tasks) owner[static_cast<std::size_t>(t)] = static_cast<int>(with);
  for (int t : take->tasks) owner[static_cast<std::size_t>(t)] = static_cast<int>(hi);
  load[hi] -= give->cost - take->cost;
  load[with] += give->cost - take->cost;
  return true;
}

/// Level 2: moves pieces (or tasks of heavy pieces) off the most loaded rank, heaviest rolling
/// element first; when no move helps, exchanges one for a cheaper one of another rank.
void split_heaviest(std::vector<int>& owner, std::span<const double> cost, const TaskCatalogue& cat,
                    std::span<const double> capacity, const PlanOptions& options) {
  const std::size_t ranks = capacity.size();
  std::vector<double> load = rank_loads(owner, cost, ranks);
  double total = 0, cap_sum = 0;
  for (std::size_t r = 0; r < ranks; ++r) total += load[r], cap_sum += capacity[r];
  const double mean = total / cap_sum;
  for (int iteration = 0; iteration < cat.task_count; ++iteration) {
    std::size_t hi = 0, lo = 0;
    double hi_norm = -1, lo_norm = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < ranks; ++r) {
      if (capacity[r] <= 0) continue;
      const double n = load[r] / capacity[r];
      if (n > hi_norm) hi_norm = n, hi = r;
      if (n < lo_norm) lo_norm = n, lo = r;
    }
    if (hi == lo || hi_norm <= mean * (1 + options.level2_tolerance)) return;
    // Amount x that equalises hi and lo: (load_hi - x)/cap_hi = (load_lo + x)/cap_lo.
    const double x = (load[hi] * capacity[lo] - load[lo] * capacity[hi]) / (capacity[hi] + capacity[lo]);
    // Group costs on hi, to try the heaviest rolling element's tasks first.
    std::map<int, double> group_cost;
    for (int t = 0; t < cat.task_count; ++t)
      if (owner[static_cast<std::size_t>(t)] == static_cast<int>(hi))
        group_cost[cat.group[static_cast<std::size_t>(t)]] += cost[static_cast<std::size_t>(t)];
    std::vector<std::pair<double, int>> groups;
    for (auto [g, c] : group_cost) groups.emplace_back(c, g);
    std::sort(groups.rbegin(), groups.rend());
    Move best;
    for (auto [gc, g] : groups) {
      double best_distance = std::numeric_limits<double>::infinity();
      for (Move& m : moves_of_group(owner, cost, cat, static_cast<int>(hi), g, options.split_share * mean * capacity[hi])) {
        const double c = m.cost;
        // The move must lower the larger of the two ranks' weighted times.
        if (!(c > 0) || std::max((load[hi] - c) / capacity[hi], (load[lo] + c) / capacity[lo]) >= hi_norm) continue;
        const double d = std::abs(c - x);
        if (d < best_distance) best_distance = d, best = std::move(m);
      }
      if (!best.tasks.empty()) break;
    }
    if (best.tasks.empty()) {
      if (exchange_off(owner, load, cost, cat, capacity, hi, options.split_share * mean)) continue;
      return;
    }
    for (int t : best.tasks) owner[static_cast<std::size_t>(t)] = static_cast<int>(lo);
    load[hi] -= best.cost;
    load[lo] += best.cost;
  }
}

}  // namespace

double predicted_imbalance(std::span<const int> owner, std::span<const double> cost, std::span<const double> capacity) {
  const std::vector<double> load = rank_loads(owner, cost, capacity.size());
  double total = 0, cap_sum = 0, worst = 0;
  for (std::size_t r = 0; r < capacity.size(); ++r) {
    total += load[r];
    if (capacity[r] <= 0) continue;
    cap_sum += capacity[r];
    worst = std::max(worst, load[r] / capacity[r]);
  }
  return total > 0 ? worst / (total / cap_sum) : 1.0;
}

double imbalance_with_tail_filling(std::span<const double> fixed_load, double total, std::span<const double> capacity) {
  double cap_sum = 0, worst = 0;
  for (std::size_t r = 0; r < capacity.size(); ++r) {
    if (capacity[r] <= 0) continue;
    cap_sum += capacity[r];
    worst = std::max(worst, fixed_load[r] / capacity[r]);
  }
  if (total <= 0 || cap_sum <= 0) return 1.0;
  const double mean = total / cap_sum;  // every rank done at once: the tail filled the gaps
  return std::max(worst, mean) / mean;
}

double predicted_imbalance_with_tail(std::span<const int> owner, std::span<const double> cost,
                                     std::span<const double> capacity, double share) {
  if (share <= 0) return predicted_imbalance(owner, cost, capacity);
  std::vector<int> fixed(owner.begin(), owner.end());
  mark_tail(fixed, cost, share);
  std::vector<double> load(capacity.size(), 0.0);
  double total = 0;
  for (std::size_t t = 0; t < fixed.size(); ++t) {
    total += cost[t];
    if (fixed[t] >= 0) load[static_cast<std::size_t>(fixed[t])] += cost[t];
  }
  return imbalance_with_tail_filling(load, total, capacity);
}

int count_split_groups(std::span<const int> owner, std::span<const int> group) {
  std::map<int, std::set<int>> ranks_of;
  for (std::size_t t = 0; t < owner.size(); ++t)
    if (group[t] != border_group) ranks_of[group[t]].insert(owner[t]);
  int n = 0;
  for (const auto& [g, r] : ranks_of) n += r.size() > 1 ? 1 : 0;
  return n;
}

int count_split_parents(std::span<const int> owner, std::span<const int> parent) {
  if (parent.size() != owner.size()) return 0;
  std::map<int, std::set<int>> ranks_of;
  for (std::size_t t = 0; t < owner.size(); ++t) ranks_of[parent[t]].insert(owner[t]);
  int n = 0;
  for (const auto& [p, r] : ranks_of) n += r.size() > 1 ? 1 : 0;
  return n;
}

Plan make_plan(std::span<const double> cost, const TaskCatalogue& cat, std::span<const double> capacity,
               const PlanOptions& options) {
  if (cost.size() != static_cast<std::size_t>(cat.task_count) || cat.group.size() != cost.size() ||
      (!cat.parent.empty() && cat.parent.size() != cost.size()))
    throw std::invalid_argument("make_plan: one cost and one group (and parent, if any) per task are needed");
  double cap_sum = 0;
  for (double c : capacity) cap_sum += std::max(c, 0.0);
  if (!(cap_sum > 0)) throw std::invalid_argument("make_plan: no rank has a positive capacity");
  Plan plan;
  std::size_t active = 0;
  for (double c : capacity) active += c > 0 ? 1 : 0;
  const std::vector<Unit> units = make_units(cost, cat);
  if (active == 1) {
    const auto r = static_cast<int>(std::find_if(capacity.begin(), capacity.end(), [](double c) { return c > 0; }) -
                                    capacity.begin());
    plan.owner.assign(cost.size(), r);
    plan.method = PlanMethod::single_rank;
    return plan;
  }
  std::vector<int> owner = owners_of(units, lpt(units, capacity), cat.task_count);
  plan.method = PlanMethod::greedy_lpt;
  split_heaviest(owner, cost, cat, capacity, options);
  double best = predicted_imbalance(owner, cost, capacity);
  if (options.try_metis) {
    const std::vector<int> by_metis = metis_kway(units, capacity);
    if (!by_metis.empty()) {
      std::vector<int> metis_owner = owners_of(units, by_metis, cat.task_count);
      split_heaviest(metis_owner, cost, cat, capacity, options);
      const double m = predicted_imbalance(metis_owner, cost, capacity);
      if (m <= best) best = m, owner = std::move(metis_owner), plan.method = PlanMethod::metis_kway;
    }
  }
  plan.owner = std::move(owner);
  plan.predicted_imbalance = best;
  plan.split_groups = count_split_groups(plan.owner, cat.group);
  plan.split_parents = count_split_parents(plan.owner, cat.parent);
  return plan;
}

std::vector<int> mark_tail(std::vector<int>& owner, std::span<const double> cost, double share, double tail_floor) {
  std::vector<int> tail;
  if (share <= 0 || owner.empty()) return tail;
  const int ranks = *std::max_element(owner.begin(), owner.end()) + 1;
  // Claiming a task costs an atomic add on a cache line all ranks share (0.1-0.2 us): a task far
  // cheaper than the largest moves too little work per claim, and stays in its rank's fixed list.
  const double floor = share < 1 ? tail_floor * *std::max_element(cost.begin(), cost.end()) : 0.0;
  for (int r = 0; r < ranks; ++r) {
    std::vector<int> mine;
    double load = 0;
    for (std::size_t t = 0; t < owner.size(); ++t) {
      if (owner[t] != r) continue;
      load += cost[t];
      if (cost[t] >= floor) mine.push_back(static_cast<int>(t));
    }
    // Cheapest first; among equal costs the later task first (deterministic).
    std::stable_sort(mine.begin(), mine.end(), [&](int a, int b) {
      return cost[static_cast<std::size_t>(a)] < cost[static_cast<std::size_t>(b)] ||
             (cost[static_cast<std::size_t>(a)] == cost[static_cast<std::size_t>(b)] && a > b);
    });
    double taken = 0;
    for (const int t : mine) {
      const double c = cost[static_cast<std::size_t>(t)];
      if (share < 1 && taken + c > share * load) break;
      taken += c;
      tail.push_back(t);
    }
  }
  for (const int t : tail) owner[static_cast<std::size_t>(t)] = shared_task;
  std::stable_sort(tail.begin(), tail.end(), [&](int a, int b) {
    return cost[static_cast<std::size_t>(a)] > cost[static_cast<std::size_t>(b)] ||
           (cost[static_cast<std::size_t>(a)] == cost[static_cast<std::size_t>(b)] && a < b);
  });
  return tail;
}

}  // namespace raceway::scheduler
