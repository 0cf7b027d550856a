#include "facecap/core/serial_worker.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

namespace facecap {

TEST(SerialWorker, RunsTasksInOrderOnOneOtherThread) {
  SerialWorker worker;
  std::vector<int> order;  // written by the worker alone
  std::vector<std::future<std::thread::id>> ids;
  for (int i = 0; i < 50; ++i) {
    ids.push_back(worker.submit([&order, i] {
      order.push_back(i);
      return std::this_thread::get_id();
    }));
  }
  std::vector<std::thread::id> ran_on;
  for (auto& id : ids) ran_on.push_back(id.get());
  EXPECT_NE(ran_on.front(), std::this_thread::get_id());
  for (const std::thread::id& id : ran_on) EXPECT_EQ(id, ran_on.front());
  ASSERT_EQ(order.size(), 50u);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(order[i], i);
}

TEST(SerialWorker, ATasksExceptionComesThroughItsFuture) {
  SerialWorker worker;
  auto failing = worker.submit([]() -> int { throw std::runtime_error("no fit"); });
  auto fine = worker.submit([] { return 7; });
  EXPECT_THROW(failing.get(), std::runtime_error);
  EXPECT_EQ(fine.get(), 7);
}

TEST(SerialWorker, WhatWasGivenRunsBeforeItEnds) {
  std::atomic<int> done = 0;
  {
    SerialWorker worker;
    for (int i = 0; i < 20; ++i) {
      worker.submit([&done] {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        ++done;
      });
    }
  }
  EXPECT_EQ(done.load(), 20);
  for (int i = 0; i < 200; ++i) SerialWorker idle;  // started and ended at once, never stuck
}

}  // namespace facecap
