#include "mpi/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <sstream>

#include "jobs/movie.h"
#include "tsp/core/error.h"

extern char** environ;

namespace tspmpi {
namespace fs = std::filesystem;

fs::path serial_tspplay() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path beside = ec ? fs::path() : self.parent_path() / "tspplay";
  if (!beside.empty() && ::access(beside.c_str(), X_OK) == 0) return beside;
  if (auto on_path = tspgl::find_on_path("tspplay")) return *on_path;
  throw tsp::IoError("tspplay-mpi render runs the serial tspplay on every rank, and there is none "
                     "beside " + (self.empty() ? std::string("this executable") : self.string()) +
                     " (" + beside.string() + ") or on PATH");
}

namespace {

// Reads both pipes (either may be -1) until they close; a child writing much to one while we
// wait on the other cannot block.
void drain(int err_fd, int out_fd, std::string& err, std::string& out) {
  pollfd fds[2] = {{err_fd, POLLIN, 0}, {out_fd, POLLIN, 0}};
  std::string* into[2] = {&err, &out};
  char buf[65536];
  for (;;) {
    int open = 0;
    for (const pollfd& p : fds) open += p.fd >= 0;
    if (open == 0) return;
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      const ssize_t n = ::read(fds[i].fd, buf, sizeof buf);
      if (n > 0) {
        into[i]->append(buf, std::size_t(n));
      } else if (n == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
      }
    }
  }
}

}  // namespace

ChildResult run_child(const fs::path& program, const std::vector<std::string>& args,
                      const std::vector<std::string>& env, bool keep_out) {
  // Everything exec needs is made before fork: the child only redirects and execs.
  std::vector<std::string> argv_s{program.string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_s;
  for (char** e = environ; *e; ++e) {
    const std::string v = *e;
    bool replaced = false;
    for (const std::string& n : env)
      replaced |= v.compare(0, n.find('=') + 1, n, 0, n.find('=') + 1) == 0;
    if (!replaced) env_s.push_back(v);
  }
  env_s.insert(env_s.end(), env.begin(), env.end());
  std::vector<char*> envp;
  for (std::string& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);

  int err_pipe[2] = {-1, -1}, out_pipe[2] = {-1, -1};
  if (::pipe2(err_pipe, O_CLOEXEC) != 0 || (keep_out && ::pipe2(out_pipe, O_CLOEXEC) != 0))
    throw tsp::IoError(program.string() + ": cannot make a pipe (" + std::strerror(errno) + ")");
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int e = errno;
    for (int fd : {err_pipe[0], err_pipe[1], out_pipe[0], out_pipe[1]})
      if (fd >= 0) ::close(fd);
    throw tsp::IoError(program.string() + ": cannot start (" + std::strerror(e) + ")");
  }
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);  // the rank died before the line above
    const int null_fd = ::open("/dev/null", O_RDWR);
    ::dup2(null_fd, 0);
    ::dup2(keep_out ? out_pipe[1] : null_fd, 1);
    ::dup2(err_pipe[1], 2);
    ::execve(argv[0], argv.data(), envp.data());
    const char* m = "cannot run the serial tspplay\n";
    (void)!::write(2, m, std::strlen(m));
    ::_exit(127);
  }
  ::close(err_pipe[1]);
  if (keep_out) ::close(out_pipe[1]);
  ChildResult r;
  drain(err_pipe[0], keep_out ? out_pipe[0] : -1, r.err, r.out);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

std::vector<std::string> child_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  const std::string prefix = "tspplay: ";
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t cr = line.rfind('\r');  // a progress bar's last state
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (line.rfind(prefix, 0) == 0) line = line.substr(prefix.size());
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

}  // namespace tspmpi
