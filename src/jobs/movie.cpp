#include "jobs/movie.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/core/temp_output.h"

extern char** environ;

namespace tspgl {

namespace fs = std::filesystem;

namespace {

// ffmpeg's output options for out's kind, then the output file. Even sizes: H.264 in yuv420p
// needs them; the temporary name has no usable extension, hence -f.
void add_output(std::vector<std::string>& args, const fs::path& out, const std::string& tmp) {
  if (out.extension() == ".gif") {
    args.insert(args.end(), {"-f", "gif"});
  } else {
    args.insert(args.end(), {"-vf", "scale=trunc(iw/2)*2:trunc(ih/2)*2", "-pix_fmt", "yuv420p",
                             "-movflags", "+faststart", "-f", "mp4"});
  }
  args.push_back(tmp);
}

/// Most characters of ffmpeg's error output quoted in a message.
constexpr std::size_t kMaxQuotedError = 200;

// An anonymous file for ffmpeg's standard error (never blocks ffmpeg, whatever it writes).
int error_file(const fs::path& out) {
  const int fd = memfd_create("ffmpeg-errors", MFD_CLOEXEC);
  if (fd < 0) throw tsp::IoError(out.string() + ": cannot capture the movie encoder's errors");
  return fd;
}

// The first line of what ffmpeg wrote to fd (at most kMaxQuotedError characters); "" for none.
std::string first_error(int fd) {
  char buf[kMaxQuotedError + 1];
  const ssize_t n = pread(fd, buf, kMaxQuotedError, 0);
  if (n <= 0) return "";
  std::string text(buf, std::size_t(n));
  const std::size_t start = text.find_first_not_of(" \r\n");
  if (start == std::string::npos) return "";
  text = text.substr(start);
  return text.substr(0, text.find_first_of("\r\n"));
}

// Throws tsp::Interrupted after SIGINT/SIGTERM, tsp::IoError when ffmpeg failed: exit status ≠
// 0, an error it reported on errors_fd (at -loglevel error it reports only errors, and some, such
// as a full disk, with exit status 0) or an empty output file.
void check_encoder(int status, int errors_fd, const std::string& tmp, const std::string& what) {
  tsp::throw_if_interrupted();
  const std::string error = first_error(errors_fd);
  struct stat st {};
  const bool empty = ::stat(tmp.c_str(), &st) != 0 || st.st_size == 0;
  if (status == 0 && error.empty() && !empty) return;
  throw tsp::IoError(what + " (ffmpeg exit status " + std::to_string(status) +
                     (error.empty() ? (empty ? ", no output" : "") : ": " + error) +
                     "); the existing movie, if any, is left as it was");
}

// Starts args[0] with args; stdin_fd ≥ 0 becomes its standard input, errors_fd its standard
// error. Throws tsp::IoError.
pid_t spawn(std::vector<std::string> args, int stdin_fd, int close_fd, int errors_fd) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdin_fd >= 0) {
    posix_spawn_file_actions_adddup2(&actions, stdin_fd, STDIN_FILENO);
    posix_spawn_file_actions_addclose(&actions, stdin_fd);
  }
  if (close_fd >= 0) posix_spawn_file_actions_addclose(&actions, close_fd);
  if (errors_fd >= 0) posix_spawn_file_actions_adddup2(&actions, errors_fd, STDERR_FILENO);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw tsp::IoError(args[0] + ": cannot start the movie encoder");
  return pid;
}

// Waits for pid; returns its exit status (−1 when it did not exit normally). SIGINT/SIGTERM stop
// it meanwhile. Throws tsp::IoError.
int wait_for(pid_t pid, const std::string& what) {
  const tsp::StopChildOnInterrupt stop(pid);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw tsp::IoError(what + ": lost the movie encoder");
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path require_ffmpeg(const fs::path& out) {
  const auto ffmpeg = find_on_path("ffmpeg");
  if (!ffmpeg)
    throw tsp::IoError(out.string() + ": ffmpeg is not on PATH (apt-get install ffmpeg; "
                                      "scripts/install-deps.sh installs it)");
  return *ffmpeg;
}

}  // namespace

std::optional<fs::path> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::string dirs = path;
  std::size_t p = 0;
  while (p <= dirs.size()) {
    std::size_t c = dirs.find(':', p);
    if (c == std::string::npos) c = dirs.size();
    const fs::path candidate = fs::path(c > p ? dirs.substr(p, c - p) : ".") / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
    p = c + 1;
  }
  return std::nullopt;
}

void check_movie_name(const fs::path& out, const std::string& what) {
  const std::string ext = out.extension().string();
  if (ext != ".mp4" && ext != ".gif")
    throw tsp::UsageError(what + " " + out.string() + ": expected a .mp4 or .gif file name");
}

void encode_movie_into(const std::vector<fs::path>& frames, tsp::TempOutput& tmp,
                       const fs::path& out, int fps) {
  const fs::path ffmpeg = require_ffmpeg(out);
  if (frames.empty()) throw tsp::IoError(out.string() + ": no frames to encode");
  // The frames under consecutive names (strided steps, any file names): symbolic links in a
  // private folder beside the movie, removed however this ends.
  std::string pattern = (fs::path(tmp.dir()) / ".frames.XXXXXX").string();
  if (!mkdtemp(pattern.data()))
    throw tsp::IoError(out.string() + ": cannot make a temporary folder for the frames");
  const fs::path links = pattern;
  struct Cleanup {
    fs::path p;
    int fd = -1;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
      if (fd >= 0) close(fd);
    }
  } cleanup{links};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.png", i);
    std::error_code ec;
    fs::create_symlink(fs::absolute(frames[i]), links / name, ec);
    if (ec) throw tsp::IoError(out.string() + ": cannot link frame " + frames[i].string());
  }
  std::vector<std::string> args = {ffmpeg.string(), "-nostdin", "-xerror", "-loglevel", "error",
                                   "-y", "-framerate", std::to_string(fps), "-start_number", "0",
                                   "-i", (links / "frame_%05d.png").string()};
  add_output(args, out, tmp.tmp());
  cleanup.fd = error_file(out);
  const int status = wait_for(spawn(args, -1, -1, cleanup.fd), ffmpeg.string());
  check_encoder(status, cleanup.fd, tmp.tmp(),
                out.string() + ": ffmpeg failed to encode " + std::to_string(frames.size()) +
                    " frames");
}

bool encode_movie(const std::vector<fs::path>& frames, const fs::path& out, int fps) {
  if (!find_on_path("ffmpeg")) return false;
  tsp::TempOutput tmp(out.string());
  encode_movie_into(frames, tmp, out, fps);
  tmp.commit();
  return true;
}

MovieWriter::MovieWriter(const fs::path& out, int width, int height, int fps)
    : out_(out), width_(width), height_(height) {
  check_movie_name(out, "movie");
  if (width < 1 || height < 1 || fps < 1)
    throw tsp::UsageError(out.string() + ": a movie needs a positive frame size and rate");
  const fs::path ffmpeg = require_ffmpeg(out);
  tmp_ = std::make_unique<tsp::TempOutput>(out.string());
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0)
    throw tsp::IoError(out.string() + ": cannot open a pipe to the movie encoder");
  std::vector<std::string> args = {ffmpeg.string(), "-xerror", "-loglevel", "error", "-y",
                                   "-f", "rawvideo",
                                   "-pix_fmt", "rgba", "-s",
                                   std::to_string(width) + "x" + std::to_string(height),
                                   "-framerate", std::to_string(fps), "-i", "-"};
  add_output(args, out, tmp_->tmp());
  try {
    errors_ = error_file(out);
    pid_ = spawn(args, fds[0], fds[1], errors_);
  } catch (...) {
    close(fds[0]);
    close(fds[1]);
    throw;
  }
  close(fds[0]);
  pipe_ = fds[1];
}

MovieWriter::~MovieWriter() {
  if (pipe_ >= 0) close(pipe_);
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  if (errors_ >= 0) close(errors_);
  // tmp_ removes the unfinished output.
}

void MovieWriter::write(const tsp::Image& frame, int repeat) {
  if (frame.width != width_ || frame.height != height_)
    throw tsp::UsageError(out_.string() + ": frame of " + std::to_string(frame.width) + "x" +
                          std::to_string(frame.height) + ", the movie is " +
                          std::to_string(width_) + "x" + std::to_string(height_));
  if (pipe_ < 0) throw tsp::IoError(out_.string() + ": the movie is already finished");
  // A reader that died raises SIGPIPE on this thread: blocked here, write returns EPIPE instead,
  // and the pending signal is taken before unblocking.
  sigset_t pipe_set, old;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old);
  bool failed = false;
  for (int k = 0; k < repeat && !failed; ++k) {
    const std::uint8_t* p = frame.rgba.data();
    std::size_t left = frame.rgba.size();
    while (left > 0) {
      const ssize_t n = ::write(pipe_, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        failed = true;
        break;
      }
      p += n;
      left -= std::size_t(n);
    }
    if (!failed) ++frames_;
  }
  if (failed) {
    const timespec zero{0, 0};
    sigtimedwait(&pipe_set, nullptr, &zero);
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  if (failed) {
    close(pipe_);
    pipe_ = -1;
    const int status = wait_for(pid_, out_.string());
    pid_ = -1;
    throw tsp::IoError(out_.string() + ": ffmpeg stopped reading frames (exit status " +
                       std::to_string(status) + ")");
  }
}

void MovieWriter::finish() {
  if (pipe_ < 0) throw tsp::IoError(out_.string() + ": the movie is already finished");
  close(pipe_);
  pipe_ = -1;
  const int status = wait_for(pid_, out_.string());
  pid_ = -1;
  if (frames_ == 0) throw tsp::IoError(out_.string() + ": no frames to encode");
  check_encoder(status, errors_, tmp_->tmp(),
                out_.string() + ": ffmpeg failed to encode " + std::to_string(frames_) + " frames");
  tmp_->commit();
}

}  // namespace tspgl
