#include "scheduler/tail_claims.hpp"

#include <atomic>

#include "scheduler/plan.hpp"

namespace raceway::scheduler {

namespace {

static_assert(std::atomic_ref<std::int64_t>::is_always_lock_free, "the claim words must be lock-free");

// A part's claim word: the front index in the low 32 bits, the back (one past the last) above.
constexpr std::int64_t pack(std::int64_t front, std::int64_t back) { return back << 32 | front; }
constexpr std::int64_t front_of(std::int64_t w) { return w & 0xffffffff; }
constexpr std::int64_t back_of(std::int64_t w) { return w >> 32; }

/// Takes one position of a part, from the front or the back; -1 when the part is empty.
std::int64_t take(std::int64_t& w_ref, bool from_front) {
  std::atomic_ref<std::int64_t> w(w_ref);
  std::int64_t now = w.load(std::memory_order_acquire);
  for (;;) {
    const std::int64_t f = front_of(now), b = back_of(now);
    if (f >= b) return -1;
    if (w.compare_exchange_weak(now, from_front ? pack(f + 1, b) : pack(f, b - 1), std::memory_order_acq_rel))
      return from_front ? f : b - 1;
  }
}

}  // namespace

void encode_tail(std::vector<int>& owner, std::span<const double> cost, double share, int ranks) {
  const std::vector<int> plan = owner;
  const std::vector<int> tail = mark_tail(owner, cost, share);  // largest first
  std::vector<int> count(static_cast<std::size_t>(ranks), 0);
  for (const int t : tail) {
    const int r = plan[static_cast<std::size_t>(t)];
    owner[static_cast<std::size_t>(t)] = shared_task - (count[static_cast<std::size_t>(r)]++ * ranks + r);
  }
}

TailParts decode_tail(std::span<const int> owner, int ranks) {
  std::vector<std::vector<int>> part(static_cast<std::size_t>(ranks));
  for (std::size_t t = 0; t < owner.size(); ++t) {
    if (owner[t] >= 0) continue;
    const int code = shared_task - owner[t];
    auto& p = part[static_cast<std::size_t>(code % ranks)];
    const auto at = static_cast<std::size_t>(code / ranks);
    if (p.size() <= at) p.resize(at + 1, -1);
    p[at] = static_cast<int>(t);
  }
  TailParts parts;
  parts.start.assign(1, 0);
  for (const auto& p : part) {
    parts.tasks.insert(parts.tasks.end(), p.begin(), p.end());
    parts.start.push_back(static_cast<int>(parts.tasks.size()));
  }
  return parts;
}

void TailClaims::reset(const TailParts& parts) {
  for (std::size_t r = 0; r + 1 < parts.start.size(); ++r)
    std::atomic_ref<std::int64_t>(word(static_cast<int>(r))).store(pack(parts.start[r], parts.start[r + 1]),
                                                                    std::memory_order_release);
}

std::int64_t TailClaims::claim(int rank) {
  if (const std::int64_t own = take(word(rank), true); own >= 0) return own;
  for (;;) {
    int victim = 0;
    std::int64_t most = 0;
    for (int r = 0; r < ranks_; ++r) {
      const std::int64_t w = std::atomic_ref<std::int64_t>(word(r)).load(std::memory_order_acquire);
      if (back_of(w) - front_of(w) > most) most = back_of(w) - front_of(w), victim = r;
    }
    if (most == 0) return -1;
    if (const std::int64_t stolen = take(word(victim), false); stolen >= 0) return stolen;
  }
}

}  // namespace raceway::scheduler
