#include "facecap/core/parallel.hpp"

#include "facecap/core/cpu_time.hpp"
#include "facecap/core/thread_name.hpp"

#include <pthread.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace facecap {

namespace {

thread_local bool t_inside_pool_job = false;
thread_local bool t_serial = false;  // SerialScope

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

// How long an idle worker keeps polling for the next job before it sleeps on
// the condition variable. The refinement's solver issues jobs of 30-100 us
// back to back; a condition-variable wake-up costs 10-20 us on a VM, as much
// as the work it would share, so workers spin through those gaps. Not much
// longer: a spinning worker takes CPU from the tracking stage running beside
// the refinement. `bench track --refine` on address_720p_a, 3 runs each:
// 20 / 50 / 200 us gave 17.7-18.1 / 19.5-22.6 / 16.4-19.0 fps.
constexpr auto kSpin = std::chrono::microseconds(50);
// Reading the clock costs more than a pause: read it every this many polls.
constexpr int kSpinsPerClockRead = 64;

// A fixed set of worker threads that share one job at a time. A job is a
// range cut into chunks. Its state is one 64-bit word, (generation << 32) |
// (chunk count << 16) | next chunk, so that a worker claims a chunk of the
// job it saw and never one of a later job. Workers and the calling thread take chunks; the caller
// waits until every chunk is done. Calls from inside a job, or while another
// thread's job runs, execute inline, so nesting and concurrent pipeline
// stages never block.
class ThreadPool {
 public:
  explicit ThreadPool(int workers) {
    for (int i = 0; i < workers; ++i)
      threads_.emplace_back([this] {
        name_this_thread("facecap-pool");
        worker_loop();
      });
  }
  ~ThreadPool() {
    {
      std::lock_guard lock(mutex_);
      stop_.store(true);
    }
    wake_.notify_all();
  }

  double cpu_ms() {
    double sum = 0;
    for (std::jthread& t : threads_) {
      clockid_t clock;
      if (pthread_getcpuclockid(t.native_handle(), &clock) == 0) sum += clock_ms(clock);
    }
    return sum;
  }

  bool try_run(int n, int chunks, const std::function<void(int, int)>& body) {
    std::unique_lock job_lock(job_mutex_, std::try_to_lock);
    if (!job_lock.owns_lock()) return false;
    body_ = &body;
    n_ = n;
    chunks_ = chunks;
    done_chunks_.store(0);
    ++generation_;
    state_.store((uint64_t(generation_) << 32) | (uint64_t(chunks) << 16));  // publishes body_, n_, chunks_
    if (sleepers_.load() > 0) {
      { std::lock_guard lock(mutex_); }  // a worker between its check and its wait has reached the wait
      wake_.notify_all();
    }
    run_chunks(generation_);
    // Wait for the chunks that workers took.
    const auto start = std::chrono::steady_clock::now();
    bool yielding = false;
    for (int spins = 1; done_chunks_.load(std::memory_order_acquire) < chunks; ++spins) {
      if (!yielding && spins % kSpinsPerClockRead == 0) yielding = std::chrono::steady_clock::now() - start > kSpin;
      if (yielding)
        std::this_thread::yield();
      else
        cpu_relax();
    }
    return true;
  }

 private:
  // Takes chunks of job `generation` until none is left.
  void run_chunks(uint32_t generation) {
    const bool was_inside = t_inside_pool_job;
    t_inside_pool_job = true;
    int done = 0;
    uint64_t s = state_.load(std::memory_order_acquire);
    while (uint32_t(s >> 32) == generation) {
      const uint32_t c = uint32_t(s) & 0xffff;
      if (c >= ((uint32_t(s) >> 16) & 0xffff)) break;
      if (!state_.compare_exchange_weak(s, s + 1, std::memory_order_acq_rel)) continue;
      // Chunk c is ours; the job cannot end before it is done, so body_,
      // n_ and chunks_ are still this job's.
      const int b = static_cast<int>(int64_t(n_) * c / chunks_);
      const int e = static_cast<int>(int64_t(n_) * (c + 1) / chunks_);
      (*body_)(b, e);
      ++done;
      s = state_.load(std::memory_order_acquire);
    }
    t_inside_pool_job = was_inside;
    if (done > 0) done_chunks_.fetch_add(done, std::memory_order_release);
  }

  void worker_loop() {
    uint32_t seen = 0;
    for (;;) {
      // Poll for a new job for a while, then sleep until one is published.
      const auto start = std::chrono::steady_clock::now();
      for (int spins = 1; uint32_t(state_.load() >> 32) == seen && !stop_.load(); ++spins) {
        if (spins % kSpinsPerClockRead == 0 && std::chrono::steady_clock::now() - start > kSpin) {
          std::unique_lock lock(mutex_);
          sleepers_.fetch_add(1);
          wake_.wait(lock, [&] { return stop_.load() || uint32_t(state_.load() >> 32) != seen; });
          sleepers_.fetch_sub(1);
          break;
        }
        cpu_relax();
      }
      if (stop_.load()) return;
      seen = uint32_t(state_.load() >> 32);
      run_chunks(seen);
    }
  }

  std::mutex job_mutex_;  // one job at a time
  std::mutex mutex_;      // for sleeping workers
  std::condition_variable wake_;
  std::atomic<uint64_t> state_{0};  // (generation << 32) | next chunk
  std::atomic<int> done_chunks_{0};
  std::atomic<int> sleepers_{0};
  std::atomic<bool> stop_{false};
  uint32_t generation_ = 0;  // written by the job's caller only
  const std::function<void(int, int)>* body_ = nullptr;
  int n_ = 0;
  int chunks_ = 0;
  std::vector<std::jthread> threads_;
};

std::atomic<bool> g_pool_made{false};

ThreadPool& pool() {
  static ThreadPool instance(worker_count() - 1);
  g_pool_made.store(true, std::memory_order_release);
  return instance;
}

}  // namespace

int worker_count() {
  static const int count = [] {
    if (const char* w = std::getenv("FACECAP_THREADS"); w != nullptr && std::atoi(w) > 0) return std::atoi(w);
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }();
  return count;
}

double pool_cpu_ms() { return g_pool_made.load(std::memory_order_acquire) ? pool().cpu_ms() : 0.0; }

SerialScope::SerialScope() : was_serial_(t_serial) { t_serial = true; }
SerialScope::~SerialScope() { t_serial = was_serial_; }

void parallel_for(int n, const std::function<void(int, int)>& body, int min_chunk) {
  if (n <= 0) return;
  const int workers = worker_count();
  const int chunks = std::min({workers * 4, std::max(1, n / std::max(1, min_chunk)), 0xffff});
  if (workers <= 1 || chunks <= 1 || t_inside_pool_job || t_serial || !pool().try_run(n, chunks, body)) {
    body(0, n);
  }
}

}  // namespace facecap
