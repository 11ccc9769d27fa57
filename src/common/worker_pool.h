// A fixed set of threads that run one loop's blocks together: For(n, fn) splits [0, n) into
// contiguous blocks, one per thread (the caller's thread takes the first), and returns when all
// are done. For stepping many independent worlds at once: each index must touch only its own
// data, so the result does not depend on the number of threads. A loop that calls For again and
// again (a batch of worlds stepped from Python) finds its threads awake: they spin for a moment
// after each call before they sleep.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace aerobox {

class WorkerPool {
 public:
  // `threads` in all, the caller's included (at least 1).
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }
  // fn(begin, end) on the blocks of [0, n); an exception thrown in any block is rethrown here
  // (the first one) once every block has ended.
  void For(int n, const std::function<void(int begin, int end)>& fn);

 private:
  void Work(int index);
  void RunBlock(int block);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_;
  std::condition_variable done_;
  std::atomic<long> generation_{0};  // one per For call
  std::atomic<int> pending_{0};      // workers still running the current call's blocks
  std::atomic<bool> stopping_{false};
  int n_ = 0;
  const std::function<void(int, int)>* fn_ = nullptr;
  std::exception_ptr error_;
};

}  // namespace aerobox
