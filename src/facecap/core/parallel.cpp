#include "facecap/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace facecap {

namespace {

thread_local bool t_inside_pool_job = false;

// A fixed set of worker threads that share one job at a time. A job is a
// range cut into chunks; workers and the calling thread take chunks from an
// atomic counter. Calls from inside a job, or while another thread's job
// runs, execute inline, so nesting and concurrent pipeline stages never block.
class ThreadPool {
 public:
  explicit ThreadPool(int workers) {
    for (int i = 0; i < workers; ++i) threads_.emplace_back([this] { worker_loop(); });
  }
  ~ThreadPool() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
  }

  bool try_run(int n, int chunks, const std::function<void(int, int)>& body) {
    std::unique_lock job_lock(job_mutex_, std::try_to_lock);
    if (!job_lock.owns_lock()) return false;
    {
      std::lock_guard lock(mutex_);
      body_ = &body;
      n_ = n;
      chunks_ = chunks;
      next_chunk_.store(0);
      done_chunks_ = 0;
      ++generation_;
    }
    wake_.notify_all();
    run_chunks();
    std::unique_lock lock(mutex_);
    finished_.wait(lock, [this] { return done_chunks_ == chunks_ && active_workers_ == 0; });
    body_ = nullptr;
    return true;
  }

 private:
  void run_chunks() {
    const bool was_inside = t_inside_pool_job;
    t_inside_pool_job = true;
    int done = 0;
    for (int c = next_chunk_.fetch_add(1); c < chunks_; c = next_chunk_.fetch_add(1)) {
      const int b = static_cast<int>(int64_t(n_) * c / chunks_);
      const int e = static_cast<int>(int64_t(n_) * (c + 1) / chunks_);
      (*body_)(b, e);
      ++done;
    }
    t_inside_pool_job = was_inside;
    if (done > 0) {
      std::lock_guard lock(mutex_);
      done_chunks_ += done;
    }
  }

  void worker_loop() {
    uint64_t seen = 0;
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      if (body_ == nullptr) continue;
      // A worker joins only while the job is live; the caller waits for all
      // joined workers to leave before it ends the job, so none straddles two.
      ++active_workers_;
      lock.unlock();
      run_chunks();
      lock.lock();
      --active_workers_;
      if (active_workers_ == 0) finished_.notify_all();
    }
  }

  std::mutex job_mutex_;  // one job at a time
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable finished_;
  const std::function<void(int, int)>* body_ = nullptr;
  int n_ = 0;
  int chunks_ = 0;
  std::atomic<int> next_chunk_{0};
  int done_chunks_ = 0;
  int active_workers_ = 0;
  uint64_t generation_ = 0;
  bool stop_ = false;
  std::vector<std::jthread> threads_;
};

ThreadPool& pool() {
  static ThreadPool instance(worker_count() - 1);
  return instance;
}

}  // namespace

int worker_count() {
  static const int count = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return count;
}

void parallel_for(int n, const std::function<void(int, int)>& body, int min_chunk) {
  if (n <= 0) return;
  const int workers = worker_count();
  const int chunks = std::min(workers * 4, std::max(1, n / std::max(1, min_chunk)));
  if (workers <= 1 || chunks <= 1 || t_inside_pool_job || !pool().try_run(n, chunks, body)) {
    body(0, n);
  }
}

}  // namespace facecap
