#include "solver/run/output_thread.hpp"

#include "io/h5/thread_core.hpp"

#include <algorithm>
#include <chrono>

namespace raceway::run {

OutputThread::OutputThread(std::size_t state_size, Work work, std::size_t capacity, std::size_t batch)
    : work_(std::move(work)),
      ring_(std::max<std::size_t>(capacity, 1)),
      batch_(std::clamp<std::size_t>(batch, 1, ring_.size())) {
  for (Slot& s : ring_) s.z.resize(state_size);
  thread_ = std::thread([this] { loop(); });
}

OutputThread::~OutputThread() {
  stop_.store(true);
  wake();
  thread_.join();
}

std::string OutputThread::bind_to_core(int core) { return h5::bind_thread_to_core(thread_, core); }

void OutputThread::wake() {
  signal_.fetch_add(1);
  signal_.notify_one();
}

void OutputThread::submit(double t, long sample, const std::vector<double>& z, const std::vector<double>& rows) {
  if (failed_.load(std::memory_order_acquire)) std::rethrow_exception(error_);
  const std::uint64_t q = queued_.load(std::memory_order_relaxed);
  for (std::uint64_t w = worked_.load(); q - w >= ring_.size(); w = worked_.load()) {
    wake();  // full: the output thread may be waiting for a batch
    worked_.wait(w);
  }
  Slot& slot = ring_[q % ring_.size()];
  slot.t = t, slot.sample = sample;
  std::copy(z.begin(), z.end(), slot.z.begin());
  slot.rows.assign(rows.begin(), rows.end());  // allocates only the first time round the ring
  queued_.store(q + 1, std::memory_order_release);
  if ((q + 1) % batch_ == 0) wake();
}

void OutputThread::drain(bool rethrow) {
  const std::uint64_t q = queued_.load(std::memory_order_relaxed);
  if (worked_.load() != q) wake();
  for (std::uint64_t w = worked_.load(); w != q; w = worked_.load()) worked_.wait(w);
  if (rethrow && failed_.load(std::memory_order_acquire)) std::rethrow_exception(error_);
}

void OutputThread::loop() {
  for (;;) {
    const std::uint32_t signal = signal_.load();  // before looking at the queue: a later wake() is seen
    const std::uint64_t q = queued_.load(std::memory_order_acquire);
    std::uint64_t w = worked_.load(std::memory_order_relaxed);
    if (w == q) {
      if (stop_.load()) return;
      signal_.wait(signal);
      continue;
    }
    for (; w != q; ++w) {
      const Slot& slot = ring_[w % ring_.size()];
      if (!failed_.load(std::memory_order_relaxed)) {
        const auto start = std::chrono::steady_clock::now();
        try {
          work_(slot.t, slot.sample, slot.z, slot.rows);
        } catch (...) {
          error_ = std::current_exception();
          failed_.store(true, std::memory_order_release);
        }
        busy_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
      worked_.store(w + 1, std::memory_order_release);
      worked_.notify_one();
    }
  }
}

}  // namespace raceway::run
