// The background stages' thread: tasks in order on one thread, a bounded
// queue, and the first error kept and passed on.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

#include "background_worker.hpp"

using touchcloud::BackgroundWorker;

TEST(BackgroundWorker, RunsTasksInOrderOnOneThreadOfItsOwn) {
  BackgroundWorker worker;
  std::vector<int> order;
  std::vector<std::thread::id> threads;
  for (int i = 0; i < 100; ++i)
    worker.submit([&, i](std::exception_ptr) {
      order.push_back(i);
      threads.push_back(std::this_thread::get_id());
    });
  worker.wait_idle();
  ASSERT_EQ(order.size(), 100u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(order[static_cast<std::size_t>(i)], i);
  for (const auto& id : threads) EXPECT_EQ(id, threads.front());
  EXPECT_NE(threads.front(), std::this_thread::get_id());
  EXPECT_EQ(worker.error(), nullptr);
}

TEST(BackgroundWorker, SubmitWaitsWhileTheQueueIsFull) {
  BackgroundWorker worker(2);
  std::promise<void> release;
  const std::shared_future<void> released = release.get_future().share();
  std::atomic<int> ran{0};
  worker.submit([&](std::exception_ptr) { released.wait(); ++ran; });  // holds the thread
  worker.submit([&](std::exception_ptr) { ++ran; });
  worker.submit([&](std::exception_ptr) { ++ran; });
  // The second and third fill the queue once the first has started; a
  // fourth finds room only when the first ends.
  auto fourth = std::async(std::launch::async, [&] { worker.submit([&](std::exception_ptr) { ++ran; }); });
  EXPECT_EQ(fourth.wait_for(std::chrono::milliseconds(100)), std::future_status::timeout);
  EXPECT_EQ(ran, 0);
  release.set_value();
  fourth.get();
  worker.wait_idle();
  EXPECT_EQ(ran, 4);
}

TEST(BackgroundWorker, KeepsTheFirstErrorAndPassesItOn) {
  BackgroundWorker worker;
  std::vector<bool> saw_error;
  worker.submit([](std::exception_ptr) { throw std::runtime_error("first"); });
  worker.submit([](std::exception_ptr) { throw std::runtime_error("second"); });
  worker.submit([&](std::exception_ptr earlier) { saw_error.push_back(earlier != nullptr); });
  worker.wait_idle();
  EXPECT_EQ(saw_error, (std::vector<bool>{true}));
  ASSERT_NE(worker.error(), nullptr);
  try {
    std::rethrow_exception(worker.error());
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "first");
  }
}
