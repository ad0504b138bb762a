// tsp/build: the thread on which a process of a partitioned build takes what the others send.
#pragma once
#include <cstdint>
#include <exception>
#include <functional>
#include <thread>

namespace tsp::detail {

/// Runs receive(k) for k = 0 … count − 1 on a thread of its own while the caller works; an
/// exception it throws comes back from finish(). Destroyed without finish() (the caller failed),
/// it abandons the thread, which may wait on processes that will never send: the caller ends
/// the job (tspplay-mpi: MPI_Abort). One owner thread calls finish().
class ReceiverThread {
 public:
  /// Starts the thread; none when count is 0. Never throws but std::system_error.
  ReceiverThread(std::int64_t count, std::function<void(std::int64_t)> receive);
  ~ReceiverThread();
  ReceiverThread(const ReceiverThread&) = delete;
  ReceiverThread& operator=(const ReceiverThread&) = delete;
  /// Waits for the count receives; rethrows the first exception one of them threw.
  void finish();

 private:
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace tsp::detail
