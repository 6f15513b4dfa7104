#include "solver/run/output_thread.hpp"

#include <algorithm>
#include <chrono>

namespace raceway::solver {

OutputThread::OutputThread(std::size_t state_size, Work work, std::size_t capacity, std::size_t batch)
    : work_(std::move(work)), ring_(std::max<std::size_t>(capacity, 1)), batch_(std::clamp<std::size_t>(batch, 1, ring_.size())) {
  for (Slot& s : ring_) s.z.resize(state_size);
  thread_ = std::thread([this] { loop(); });
}

OutputThread::~OutputThread() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  queued_.notify_one();
  thread_.join();
}

void OutputThread::submit(double t, long sample, const std::vector<double>& z) {
  std::unique_lock lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  worked_.wait(lock, [&] { return count_ < ring_.size(); });
  // The slot after the queued ones is this thread's alone until count_ takes it in: the worker
  // only reads the `count_` slots from head_.
  Slot& slot = ring_[(head_ + count_) % ring_.size()];
  lock.unlock();
  slot.t = t, slot.sample = sample;
  std::copy(z.begin(), z.end(), slot.z.begin());
  lock.lock();
  if (++count_ >= batch_) queued_.notify_one();
}

void OutputThread::drain(bool rethrow) {
  std::unique_lock lock(mutex_);
  urgent_ = true;
  queued_.notify_one();
  worked_.wait(lock, [&] { return count_ == 0; });
  urgent_ = false;
  if (rethrow && error_) std::rethrow_exception(error_);
}

double OutputThread::busy_seconds() const {
  const std::lock_guard lock(mutex_);
  return busy_;
}

void OutputThread::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    queued_.wait(lock, [&] { return count_ >= batch_ || stop_ || (urgent_ && count_ > 0); });
    if (count_ == 0) return;  // stopping, nothing left
    while (count_ > 0) {
      const Slot& slot = ring_[head_];
      const bool failed = error_ != nullptr;
      lock.unlock();
      std::exception_ptr error;
      const auto start = std::chrono::steady_clock::now();
      if (!failed) try {
          work_(slot.t, slot.sample, slot.z);
        } catch (...) {
          error = std::current_exception();
        }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      lock.lock();
      busy_ += seconds;
      if (error) error_ = error;
      head_ = (head_ + 1) % ring_.size();
      --count_;
      worked_.notify_one();
    }
  }
}

}  // namespace raceway::solver
