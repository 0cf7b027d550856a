#pragma once
// One thread that runs the tasks given to it, one after another, for as long
// as it lives: a stage that hands each frame's work to another core (the
// pipelined capture's fit) without starting a thread a frame. A new thread's
// stack is mapped afresh each time (glibc returns a finished thread's stack
// pages to the kernel), which on the 2-core VM cost about 50 page faults a
// frame.
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>

#include "facecap/core/thread_name.hpp"

namespace facecap {

class SerialWorker {
 public:
  // `name`: the thread's (thread_name.hpp).
  explicit SerialWorker(const char* name = "facecap-worker")
      : thread_([this, name](std::stop_token stop) {
          name_this_thread(name);
          run(stop);
        }) {}
  // Runs what was given before it ends.
  ~SerialWorker() {
    {
      const std::lock_guard lock(mutex_);  // not between the worker's look at the queue and its wait
      thread_.request_stop();
    }
    ready_.notify_all();
  }
  SerialWorker(const SerialWorker&) = delete;
  SerialWorker& operator=(const SerialWorker&) = delete;

  // Runs `task` on the worker's thread after those given before it; its
  // result (or exception) comes through the future.
  template <typename Task>
  auto submit(Task task) -> std::future<std::invoke_result_t<Task&>> {
    using Result = std::invoke_result_t<Task&>;
    auto packaged = std::make_shared<std::packaged_task<Result()>>(std::move(task));
    std::future<Result> result = packaged->get_future();
    {
      const std::lock_guard lock(mutex_);
      tasks_.emplace_back([packaged] { (*packaged)(); });
    }
    ready_.notify_one();
    return result;
  }

 private:
  void run(const std::stop_token& stop) {
    while (true) {
      std::function<void()> task;
      {
        std::unique_lock lock(mutex_);
        ready_.wait(lock, [&] { return stop.stop_requested() || !tasks_.empty(); });
        if (tasks_.empty()) return;  // stopping, with nothing left to run
        task = std::move(tasks_.front());
        tasks_.pop_front();
      }
      task();
    }
  }

  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> tasks_;
  std::jthread thread_;  // last: started once the rest exists, joined before it goes
};

}  // namespace facecap
