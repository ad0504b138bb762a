// File > Open of an input that is not a .tsp file yet: its build into the cache folder, on the
// one background worker (tsp/core/background_worker.h), while the window keeps drawing the
// file it plays; its progress for the dialog; cancellation that leaves no file.
#pragma once
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include "jobs/play_input.h"
#include "tsp/core/background_worker.h"

namespace tspplayer {

/// One File > Open build. Made and read on the UI thread; progress() and cancel() may be called
/// from any thread.
class OpenJob {
 public:
  /// Starts building input with o (its field, "" for the input's own choice; the play command's
  /// input options) into cache_dir ("" for the default cache folder) on a worker thread.
  /// Throws std::system_error when no thread can start.
  OpenJob(std::string input, tspgl::PlayInputOptions o, std::string cache_dir);
  /// Cancels a running build and waits for it to stop (it leaves no file). Never throws.
  ~OpenJob();
  OpenJob(const OpenJob&) = delete;
  OpenJob& operator=(const OpenJob&) = delete;

  /// What the user asked to open.
  const std::string& input() const { return input_; }
  /// Asks the build to stop at its next progress report (no file is left). Thread-safe.
  void cancel() { worker_.request_stop(); }
  /// True once cancel() was called. Thread-safe.
  bool cancelled() const { return worker_.stop_requested(); }
  /// True once the build ended (built, failed or cancelled). Thread-safe.
  bool done() const { return done_; }

  /// The build's progress for the dialog.
  struct Progress {
    std::string phase, line;  ///< the build's phase, the last line it said
    std::int64_t done = 0, total = 0;
  };
  /// A snapshot of the progress. Thread-safe; never throws.
  Progress progress() const;
  /// Once done(): the .tsp file to play. Throws what the build threw (a tsp::Error naming the
  /// input and what was wrong; "cancelled" after cancel()).
  std::string result();

 private:
  std::string input_, field_;
  mutable std::mutex mu_;  // guards progress_ and result_
  Progress progress_;
  std::string result_;
  std::atomic<bool> done_{false};
  tsp::BackgroundWorker worker_;  // last: joined first, while the members above live
};

}  // namespace tspplayer
