#include "common/worker_pool.h"

#include <algorithm>

namespace aerobox {
namespace {

// [iterations] a thread spins, about 50 us, before it sleeps on a condition variable
constexpr int kSpins = 20000;

void Relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

}  // namespace

WorkerPool::WorkerPool(int threads) {
  for (int i = 1; i < std::max(1, threads); ++i) workers_.emplace_back([this, i] { Work(i); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_.store(true);
  }
  start_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void WorkerPool::RunBlock(int block) {
  const int blocks = threads();
  const int begin = static_cast<int>(static_cast<long>(n_) * block / blocks);
  const int end = static_cast<int>(static_cast<long>(n_) * (block + 1) / blocks);
  if (begin >= end) return;
  try {
    (*fn_)(begin, end);
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = std::current_exception();
  }
}

void WorkerPool::Work(int index) {
  long seen = 0;
  for (;;) {
    for (int spin = 0; spin < kSpins && generation_.load() == seen && !stopping_.load(); ++spin) {
      Relax();
    }
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stopping_.load() || generation_.load() != seen; });
      if (stopping_.load()) return;
      seen = generation_.load();
    }
    RunBlock(index);
    if (pending_.fetch_sub(1) == 1) {
      std::lock_guard<std::mutex> lock(mutex_);  // the caller waits under it: no lost wake-up
      done_.notify_one();
    }
  }
}

void WorkerPool::For(int n, const std::function<void(int begin, int end)>& fn) {
  if (n <= 0) return;
  if (workers_.empty() || n == 1) {
    fn(0, n);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    n_ = n;
    fn_ = &fn;
    error_ = nullptr;
    pending_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  start_.notify_all();
  RunBlock(0);
  for (int spin = 0; spin < kSpins && pending_.load() != 0; ++spin) Relax();
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return pending_.load() == 0; });
  if (error_) std::rethrow_exception(error_);
}

}  // namespace aerobox
