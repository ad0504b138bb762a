// The one background worker: jobs run in order on one thread, pending jobs can be cancelled,
// stop reaches the running job's token, a job's exception comes back on the owner's thread, and
// the destructor joins (or, abandoning, detaches a busy thread).
#include "tsp/core/background_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <future>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "tsp/core/error.h"

namespace {

using tsp::BackgroundWorker;
using tsp::WorkerExit;

constexpr int kJobs = 200;

// A gate a job waits at until the test opens it (or the job's stop is requested).
class Gate {
 public:
  void open() {
    {
      std::lock_guard lock(mutex_);
      open_ = true;
    }
    cv_.notify_all();
  }
  void wait(const std::stop_token& stop) {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, stop, [&] { return open_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable_any cv_;
  bool open_ = false;
};

TEST(BackgroundWorker, RunsJobsInOrderOnOneThread) {
  BackgroundWorker worker;
  std::vector<int> order;  // written by the worker's thread only
  std::set<std::thread::id> threads;
  for (int i = 0; i < kJobs; ++i)
    worker.submit([&, i](std::stop_token) {
      order.push_back(i);
      threads.insert(std::this_thread::get_id());
    });
  worker.wait();
  ASSERT_EQ(int(order.size()), kJobs);
  for (int i = 0; i < kJobs; ++i) EXPECT_EQ(order[std::size_t(i)], i);
  ASSERT_EQ(threads.size(), 1u);
  EXPECT_NE(*threads.begin(), std::this_thread::get_id());
  EXPECT_FALSE(worker.failed());
  EXPECT_NO_THROW(worker.rethrow_if_failed());
}

TEST(BackgroundWorker, WaitOnAnIdleWorkerReturnsAtOnce) {
  BackgroundWorker worker;
  EXPECT_NO_THROW(worker.wait());
}

TEST(BackgroundWorker, CancelPendingDropsTheQueuedJobsButNotTheRunningOne) {
  BackgroundWorker worker;
  Gate gate;
  std::promise<void> started;
  std::atomic<int> ran{0};
  worker.submit([&](std::stop_token stop) {
    started.set_value();
    gate.wait(stop);
    ++ran;
  });
  for (int i = 0; i < 5; ++i) worker.submit([&](std::stop_token) { ran += 100; });
  started.get_future().wait();
  EXPECT_EQ(worker.cancel_pending(), 5u);
  gate.open();
  worker.wait();
  EXPECT_EQ(ran.load(), 1);
  // The worker goes on taking jobs.
  worker.submit([&](std::stop_token) { ran += 10; });
  worker.wait();
  EXPECT_EQ(ran.load(), 11);
}

TEST(BackgroundWorker, RequestStopReachesTheRunningJobAndRunsNothingMore) {
  BackgroundWorker worker;
  std::promise<void> started;
  std::atomic<bool> saw_stop{false};
  std::atomic<int> later{0};
  worker.submit([&](std::stop_token stop) {
    started.set_value();
    Gate never;
    never.wait(stop);  // returns only on stop
    saw_stop = stop.stop_requested();
  });
  worker.submit([&](std::stop_token) { ++later; });
  started.get_future().wait();
  EXPECT_FALSE(worker.stop_requested());
  worker.request_stop();
  EXPECT_TRUE(worker.stop_requested());
  EXPECT_TRUE(worker.stop_token().stop_requested());
  worker.wait();
  EXPECT_TRUE(saw_stop.load());
  worker.submit([&](std::stop_token) { ++later; });  // ignored after stop
  worker.wait();
  EXPECT_EQ(later.load(), 0);
}

TEST(BackgroundWorker, AJobsExceptionComesBackOnTheOwnersThreadWithItsType) {
  std::atomic<int> hooks{0};
  BackgroundWorker worker([&] { ++hooks; });
  std::atomic<int> ran{0};
  worker.submit([&](std::stop_token) { ++ran; });
  worker.submit([](std::stop_token) { throw tsp::IoError("disk gone"); });
  worker.submit([&](std::stop_token) { ++ran; });  // dropped: the worker failed before it
  EXPECT_THROW(worker.wait(), tsp::IoError);
  EXPECT_TRUE(worker.failed());
  EXPECT_EQ(ran.load(), 1);
  EXPECT_EQ(hooks.load(), 1);
  // The exception is kept: every later wait or check rethrows it, and nothing more runs.
  EXPECT_THROW(worker.rethrow_if_failed(), tsp::IoError);
  worker.submit([&](std::stop_token) { ++ran; });
  EXPECT_THROW(worker.wait(), tsp::IoError);
  EXPECT_EQ(ran.load(), 1);
  try {
    worker.wait();
  } catch (const tsp::IoError& e) {
    EXPECT_STREQ(e.what(), "disk gone");
  }
}

TEST(BackgroundWorker, TheFailureHookWakesAnOwnersWait) {
  std::mutex mutex;
  std::condition_variable cv;
  BackgroundWorker worker([&] {
    std::lock_guard lock(mutex);
    cv.notify_all();
  });
  worker.submit([](std::stop_token) { throw std::runtime_error("late"); });
  {
    std::unique_lock lock(mutex);
    cv.wait(lock, [&] { return worker.failed(); });
  }
  EXPECT_THROW(worker.rethrow_if_failed(), std::runtime_error);
}

TEST(BackgroundWorker, DestructorStopsAndJoinsTheRunningJob) {
  std::atomic<bool> returned{false};
  std::promise<void> started;
  {
    BackgroundWorker worker;
    worker.submit([&](std::stop_token stop) {
      started.set_value();
      Gate never;
      never.wait(stop);
      returned = true;
    });
    worker.submit([&](std::stop_token) { FAIL() << "a pending job ran after destruction began"; });
    started.get_future().wait();
  }
  EXPECT_TRUE(returned.load());  // joined: the job had returned before the destructor did
}

TEST(BackgroundWorker, DestructorDropsAKeptException) {
  {
    BackgroundWorker worker;
    worker.submit([](std::stop_token) { throw std::runtime_error("never waited for"); });
    while (!worker.failed()) std::this_thread::yield();
  }
  SUCCEED();
}

TEST(BackgroundWorker, AnAbandoningWorkerDetachesABusyThreadAndJoinsAnIdleOne) {
  // Busy: the job ignores its token and blocks until the test lets it go, after the destructor.
  auto gate = std::make_shared<Gate>();
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> finished = done->get_future();
  std::promise<void> started;
  {
    BackgroundWorker worker({}, WorkerExit::abandon);
    worker.submit([gate, done, &started](std::stop_token) {
      started.set_value();
      gate->wait(std::stop_token{});  // no stop: only open() ends it
      done->set_value();
    });
    started.get_future().wait();
  }  // returns although the job still runs
  EXPECT_EQ(finished.wait_for(std::chrono::milliseconds(0)), std::future_status::timeout);
  gate->open();
  finished.wait();
  // Idle: nothing to abandon.
  std::atomic<int> ran{0};
  {
    BackgroundWorker worker({}, WorkerExit::abandon);
    worker.submit([&](std::stop_token) { ++ran; });
    worker.wait();
  }
  EXPECT_EQ(ran.load(), 1);
}

}  // namespace
