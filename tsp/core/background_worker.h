// The one background thread of tsp/: a worker that runs submitted jobs one at a time, in the
// order submitted, each given a stop token; an exception a job throws is kept and rethrown on
// the owner's thread (wait(), rethrow_if_failed()); the destructor stops and joins the thread.
// The slab and brick prefetchers, the ordered collective writes and a partitioned build's
// receiving thread run on it (docs/architecture.md).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stop_token>

namespace tsp {

/// What a BackgroundWorker's destructor does with a thread still running a job.
enum class WorkerExit : std::uint8_t {
  join,    ///< requests stop, drops the pending jobs and waits for the running one to return
  abandon  ///< the same, but detaches the thread while a job runs (see ~BackgroundWorker)
};

/// One background thread running submitted jobs in order. The thread starts with the first job.
/// A job that throws makes the worker failed for good: its exception is kept (the first one),
/// the pending jobs are dropped, later submissions are ignored, and every wait() or
/// rethrow_if_failed() rethrows it. Every member is thread-safe (any thread may call it) unless
/// its comment says otherwise; the jobs run on the worker's thread only.
class BackgroundWorker {
 public:
  /// A job: long-running ones should return soon after the token's stop is requested (waits on
  /// a std::condition_variable_any can take the token to wake then).
  using Job = std::function<void(std::stop_token)>;
  /// Called once, on the worker's thread, right after a job threw: the worker is failed() by
  /// then, holds no lock, and wait() returns only after the hook did. Lets the owner wake its
  /// own waits that test failed(). Must not throw.
  using FailureHook = std::function<void()>;

  /// An idle worker; no thread until the first submit(). Never throws.
  explicit BackgroundWorker(FailureHook on_failure = {}, WorkerExit exit = WorkerExit::join);
  /// Requests stop and drops the pending jobs; then, with WorkerExit::join, waits for the
  /// running job to return; with WorkerExit::abandon, detaches the thread if a job runs: a job that
  /// may block forever (a receive from processes that failed) is left running, so whatever it
  /// references must outlive it or the process must end soon (tspplay-mpi: MPI_Abort). Never
  /// throws; a kept exception is dropped. Call it from the owner, never from a job.
  ~BackgroundWorker();
  BackgroundWorker(const BackgroundWorker&) = delete;
  BackgroundWorker& operator=(const BackgroundWorker&) = delete;

  /// Queues job after the ones submitted before; starts the thread on the first call. Ignored
  /// once failed() or stop_requested(). Throws std::system_error when no thread can start.
  void submit(Job job);
  /// Drops the queued jobs that have not started (the running one goes on); returns how many.
  /// Never throws.
  std::size_t cancel_pending();
  /// Drops the queued jobs and requests stop on every job's token: the running job should
  /// return soon, and no job runs afterwards. Never throws.
  void request_stop();
  /// True once request_stop() (or the destructor) ran. Never throws.
  bool stop_requested() const;
  /// The token every job gets: for waits outside the worker's thread that should end on stop
  /// too. Never throws.
  std::stop_token stop_token() const;
  /// True once a job threw. Never throws.
  bool failed() const;
  /// Blocks until no job is queued or running, then rethrows the kept exception, if any. Must
  /// not be called from a job (it would wait for itself).
  void wait();
  /// Rethrows the kept exception, if any, without waiting.
  void rethrow_if_failed() const;

 private:
  struct State;
  std::shared_ptr<State> state_;  // shared with the thread, which an abandoning worker detaches
  WorkerExit exit_;
};

}  // namespace tsp
