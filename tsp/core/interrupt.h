// Ending a command cleanly on SIGINT/SIGTERM: the first signal only sets a flag (and stops a
// child process such as ffmpeg); the command's loops and every output's commit check it and throw
// Interrupted, so the stack unwinds, temporaries are removed and old outputs stay as they were. A
// second signal ends the process at once (its temporaries are swept by the next run).
#pragma once
#include <sys/types.h>

#include "tsp/core/error.h"

namespace tsp {

/// Thrown by throw_if_interrupted() once SIGINT or SIGTERM arrived; main maps it to exit 1.
class Interrupted : public Error {
 public:
  using Error::Error;
};

/// Installs the SIGINT/SIGTERM handlers for its lifetime (nested scopes share the outermost's
/// handlers). Construct on the main thread only; not thread-safe.
class InterruptScope {
 public:
  /// Installs the handlers unless an outer scope did. Never throws.
  InterruptScope();
  /// Restores the previous handlers (outermost scope only). Never throws.
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

/// True once SIGINT or SIGTERM arrived under an InterruptScope. Never throws; thread-safe.
bool interrupted();

/// Throws Interrupted ("interrupted by SIGINT; ...") when interrupted(). Thread-safe.
void throw_if_interrupted();

/// While it lives, a SIGINT/SIGTERM also sends SIGTERM to child pid (an encoder the command waits
/// for), so the wait ends. One at a time; never throws; construct on the main thread.
class StopChildOnInterrupt {
 public:
  /// Registers pid (sent SIGTERM at once if the interruption already came).
  explicit StopChildOnInterrupt(pid_t pid);
  /// Unregisters it.
  ~StopChildOnInterrupt();
  StopChildOnInterrupt(const StopChildOnInterrupt&) = delete;
  StopChildOnInterrupt& operator=(const StopChildOnInterrupt&) = delete;
};

namespace detail {
/// Marks the process as interrupted as the handler would (tests of the commit path). Thread-safe.
void simulate_interrupt(int signal_number);
/// Clears the flag again (tests only). Thread-safe.
void clear_interrupt();
}  // namespace detail

}  // namespace tsp
