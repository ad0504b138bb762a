#include "tsp/core/background_worker.h"

#include <atomic>
#include <cassert>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

namespace tsp {

// Everything the thread touches: shared, so that an abandoned thread never outlives it.
struct BackgroundWorker::State {
  std::mutex mutex;
  std::condition_variable cv;  // a job queued, stop, or the worker became idle
  std::deque<Job> jobs;        // queued, not started
  bool running = false;        // a job is running
  bool quit = false;           // the owner is gone: the thread ends once the queue is empty
  std::exception_ptr error;    // the first job's exception
  std::atomic<bool> failed{false};
  std::stop_source stop;
  FailureHook on_failure;
  std::thread thread;
  std::thread::id thread_id;   // the worker's thread, for asserts

  void run();
};

namespace detail {

// Runs job, returning the exception it threw (null when none).
std::exception_ptr run_job(const BackgroundWorker::Job& job, std::stop_token token) {
  try {
    job(std::move(token));
  } catch (...) {
    return std::current_exception();
  }
  return nullptr;
}

}  // namespace detail

void BackgroundWorker::State::run() {
  std::unique_lock lock(mutex);
  for (;;) {
    cv.wait(lock, [&] { return quit || !jobs.empty(); });
    if (jobs.empty()) return;  // quit with nothing left
    Job job = std::move(jobs.front());
    jobs.pop_front();
    running = true;
    lock.unlock();
    std::exception_ptr e = detail::run_job(job, stop.get_token());
    job = nullptr;  // its captures go before the owner may see the worker idle
    lock.lock();
    if (e) {
      if (!error) error = std::move(e);
      jobs.clear();
      failed.store(true);
      // Still running: wait() returns only after the hook ran.
      if (FailureHook hook = std::exchange(on_failure, nullptr)) {
        lock.unlock();
        hook();
        lock.lock();
      }
    }
    running = false;
    cv.notify_all();
  }
}

BackgroundWorker::BackgroundWorker(FailureHook on_failure, WorkerExit exit)
    : state_(std::make_shared<State>()), exit_(exit) {
  state_->on_failure = std::move(on_failure);
}

BackgroundWorker::~BackgroundWorker() {
  request_stop();
  bool busy = false;
  {
    std::lock_guard lock(state_->mutex);
    state_->quit = true;  // with the queue empty: no job starts any more
    busy = state_->running;
  }
  state_->cv.notify_all();
  if (!state_->thread.joinable()) return;
  assert(std::this_thread::get_id() != state_->thread.get_id() && "destroyed from its own job");
  // An idle thread ends at once, so it is joined even when abandoning.
  if (exit_ == WorkerExit::join || !busy)
    state_->thread.join();
  else
    state_->thread.detach();
}

void BackgroundWorker::submit(Job job) {
  std::lock_guard lock(state_->mutex);
  if (state_->failed.load() || state_->stop.stop_requested()) return;
  if (!state_->thread.joinable()) {
    state_->thread = std::thread([s = state_] { s->run(); });
    state_->thread_id = state_->thread.get_id();
  }
  state_->jobs.push_back(std::move(job));
  state_->cv.notify_all();
}

std::size_t BackgroundWorker::cancel_pending() {
  std::lock_guard lock(state_->mutex);
  const std::size_t n = state_->jobs.size();
  state_->jobs.clear();
  state_->cv.notify_all();  // wait() may be done now
  return n;
}

void BackgroundWorker::request_stop() {
  {
    std::lock_guard lock(state_->mutex);
    state_->jobs.clear();
    state_->cv.notify_all();
  }
  // Outside the lock: stop callbacks (waits on the token) run here and may take other locks.
  state_->stop.request_stop();
}

bool BackgroundWorker::stop_requested() const { return state_->stop.stop_requested(); }

std::stop_token BackgroundWorker::stop_token() const { return state_->stop.get_token(); }

bool BackgroundWorker::failed() const { return state_->failed.load(); }

void BackgroundWorker::wait() {
  std::unique_lock lock(state_->mutex);
  assert(std::this_thread::get_id() != state_->thread_id && "wait() from a job");
  state_->cv.wait(lock, [&] { return state_->jobs.empty() && !state_->running; });
  if (state_->error) std::rethrow_exception(state_->error);
}

void BackgroundWorker::rethrow_if_failed() const {
  std::lock_guard lock(state_->mutex);
  if (state_->error) std::rethrow_exception(state_->error);
}

}  // namespace tsp
