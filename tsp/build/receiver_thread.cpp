#include "tsp/build/receiver_thread.h"

#include <utility>

namespace tsp::detail {

ReceiverThread::ReceiverThread(std::int64_t count, std::function<void(std::int64_t)> receive) {
  if (count <= 0) return;
  thread_ = std::thread([this, count, receive = std::move(receive)] {
    try {
      for (std::int64_t k = 0; k < count; ++k) receive(k);
    } catch (...) {
      error_ = std::current_exception();
    }
  });
}

ReceiverThread::~ReceiverThread() {
  if (thread_.joinable()) thread_.detach();
}

void ReceiverThread::finish() {
  if (thread_.joinable()) thread_.join();
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace tsp::detail
