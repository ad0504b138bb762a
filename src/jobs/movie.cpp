#include "jobs/movie.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "tsp/core/error.h"
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

// Starts args[0] with args; stdin_fd ≥ 0 becomes its standard input. Throws tsp::IoError.
pid_t spawn(std::vector<std::string> args, int stdin_fd, int close_fd) {
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
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw tsp::IoError(args[0] + ": cannot start the movie encoder");
  return pid;
}

// Waits for pid; returns its exit status (−1 when it did not exit normally). Throws tsp::IoError.
int wait_for(pid_t pid, const std::string& what) {
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

bool encode_movie(const std::vector<fs::path>& frames, const fs::path& out, int fps) {
  const auto found = find_on_path("ffmpeg");
  if (!found) return false;
  const fs::path ffmpeg = *found;
  if (frames.empty()) throw tsp::IoError(out.string() + ": no frames to encode");
  tsp::TempOutput tmp(out.string());
  // The frames under consecutive names (strided steps, any file names): symbolic links in a
  // private folder beside the movie, removed however this ends.
  std::string pattern = (fs::path(tmp.dir()) / ".frames.XXXXXX").string();
  if (!mkdtemp(pattern.data()))
    throw tsp::IoError(out.string() + ": cannot make a temporary folder for the frames");
  const fs::path links = pattern;
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{links};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.png", i);
    std::error_code ec;
    fs::create_symlink(fs::absolute(frames[i]), links / name, ec);
    if (ec) throw tsp::IoError(out.string() + ": cannot link frame " + frames[i].string());
  }
  std::vector<std::string> args = {ffmpeg.string(), "-nostdin", "-loglevel", "error", "-y",
                                   "-framerate", std::to_string(fps), "-start_number", "0", "-i",
                                   (links / "frame_%05d.png").string()};
  add_output(args, out, tmp.tmp());
  const int status = wait_for(spawn(args, -1, -1), ffmpeg.string());
  if (status != 0)
    throw tsp::IoError(out.string() + ": ffmpeg failed to encode " +
                       std::to_string(frames.size()) + " frames from " +
                       frames.front().parent_path().string() + " (exit status " +
                       std::to_string(status) + ")");
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
  std::vector<std::string> args = {ffmpeg.string(), "-loglevel", "error", "-y", "-f", "rawvideo",
                                   "-pix_fmt", "rgba", "-s",
                                   std::to_string(width) + "x" + std::to_string(height),
                                   "-framerate", std::to_string(fps), "-i", "-"};
  add_output(args, out, tmp_->tmp());
  try {
    pid_ = spawn(args, fds[0], fds[1]);
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
  if (status != 0 || frames_ == 0)
    throw tsp::IoError(out_.string() + ": ffmpeg failed to encode " + std::to_string(frames_) +
                       " frames (exit status " + std::to_string(status) + ")");
  tmp_->commit();
}

}  // namespace tspgl
