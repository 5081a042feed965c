// The child processes of `curvemesh batch`: fork and exec, limits, reading back what a child wrote,
// and classifying how it ended.
#include "app/batch_child.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sstream>

#include "app/batch_error.hpp"
#include "app/commands.hpp"

namespace curvemesh::app::batch {

namespace {

// A child's stdout or stderr: a temporary file with no name (nothing to clean up, and no pipe
// that a chatty child could fill while the parent is busy elsewhere).
File temporary_file() {
  File f(std::tmpfile(), &std::fclose);
  if (!f)
    throw BatchError(kInternal,
                     std::string("curvemesh: cannot create a temporary file (") + std::strerror(errno) + ")");
  ::fcntl(::fileno(f.get()), F_SETFD, FD_CLOEXEC);  // other children must not inherit it
  return f;
}

// The start of what a child wrote (a runaway warning stream is not worth reading whole).
std::string read_back(std::FILE* f, std::size_t limit = 1 << 16) {
  const int fd = ::fileno(f);
  std::string s(limit, '\0');
  std::size_t n = 0;
  if (::lseek(fd, 0, SEEK_SET) < 0) return {};
  while (n < limit) {
    const ssize_t r = ::read(fd, s.data() + n, limit - n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    n += static_cast<std::size_t>(r);
  }
  s.resize(n);
  return s;
}

// The first line that says what went wrong: warnings come before errors and are not the cause.
std::string first_error_line(const std::string& err) {
  std::istringstream s(err);
  std::string line;
  while (std::getline(s, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line.find("warning:") != std::string::npos) continue;
    return line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
  }
  return {};
}

std::string with_detail(std::string what, const std::string& err) {
  const std::string line = first_error_line(err);
  return line.empty() ? what : what + ": " + line;
}

std::string signal_name(int sig) {
  switch (sig) {
    case SIGKILL:
      return "SIGKILL";
    case SIGSEGV:
      return "SIGSEGV";
    case SIGABRT:
      return "SIGABRT";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGILL:
      return "SIGILL";
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "signal " + std::to_string(sig);
  }
}

}  // namespace

std::string path_argument(const std::string& path) {
  return path.starts_with('-') ? "./" + path : path;
}

Child start_child(const std::vector<std::string>& args, const ChildSetup& setup) {
  Child c;
  c.started = Clock::now();
  c.out = temporary_file();
  c.err = temporary_file();
  const int out_fd = ::fileno(c.out.get()), err_fd = ::fileno(c.err.get());
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  rlimit limit{};
  if (setup.address_space) {
    ::getrlimit(RLIMIT_AS, &limit);
    limit.rlim_cur = std::min(setup.address_space, limit.rlim_max);
  }
  // The child reports a failed exec through this pipe; a successful exec closes it (CLOEXEC).
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) {
    c.start_errno = errno;
    return c;
  }
  c.started = Clock::now();  // the clock starts here: the temporary files are not the drawing's time
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    c.start_errno = errno;
    ::close(report[0]);
    ::close(report[1]);
    return c;
  }
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec. A process group of its own, so that
    // the time limit kills whatever it started too, and the terminal's Ctrl-C reaches the batch
    // (which then kills its children) rather than each child separately.
    ::setpgid(0, 0);
    // A batch killed outright (SIGKILL: a scheduler after its grace time, the out-of-memory killer)
    // takes its children along rather than leaving them to write into OUTDIR unwatched.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    ::sigprocmask(SIG_SETMASK, &setup.mask, nullptr);
    const int null = ::open("/dev/null", O_RDONLY);
    if (null >= 0) ::dup2(null, 0);
    ::dup2(out_fd, 1);
    ::dup2(err_fd, 2);
    if (setup.address_space) ::setrlimit(RLIMIT_AS, &limit);
    // The very executable this batch runs, even if the file was replaced by a rebuild meanwhile.
    ::execv("/proc/self/exe", argv.data());
    const int e = errno;
    [[maybe_unused]] const ssize_t ignored = ::write(report[1], &e, sizeof e);
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // here too: kill(-pid) must work even before the child ran at all
  ::close(report[1]);
  int e = 0;
  ssize_t n;
  while ((n = ::read(report[0], &e, sizeof e)) < 0 && errno == EINTR) {
  }
  ::close(report[0]);
  if (n == static_cast<ssize_t>(sizeof e)) {
    ::waitpid(pid, nullptr, 0);
    c.start_errno = e;
    return c;
  }
  c.pid = pid;
  return c;
}

Outcome outcome_of(Child& c, int wait_status, double peak_mb) {
  Outcome o;
  o.wait_status = wait_status;
  o.start_errno = c.start_errno;
  o.timed_out = c.killed;
  o.seconds = std::chrono::duration<double>(Clock::now() - c.started).count();
  o.peak_mb = peak_mb;
  if (c.out) o.out = read_back(c.out.get());
  if (c.err) o.err = read_back(c.err.get());
  return o;
}

std::pair<Status, std::string> classify(const Outcome& o, const std::string& what, double timeout_s,
                                        double memory_limit_gb) {
  if (o.start_errno) {
    const std::string m = "cannot run curvemesh " + what + ": " + std::strerror(o.start_errno);
    // Under a tight address-space limit even exec can fail for want of memory.
    const bool memory = memory_limit_gb > 0 && (o.start_errno == ENOMEM || o.start_errno == E2BIG);
    return {memory ? Status::out_of_memory : Status::crash, m};
  }
  if (o.timed_out) {
    char m[96];
    std::snprintf(m, sizeof m, "no result within %g s (killed)", timeout_s);
    return {Status::timeout, what == "check" ? std::string(m) + " while certifying the mesh" : m};
  }
  // std::bad_alloc reaches main's catch-all and is reported as an internal error: it is memory.
  const bool bad_alloc = o.err.find("bad_alloc") != std::string::npos;
  char limit[64] = "";
  if (memory_limit_gb > 0) std::snprintf(limit, sizeof limit, " under --memory-limit %g GB", memory_limit_gb);
  if (WIFSIGNALED(o.wait_status)) {
    const int sig = WTERMSIG(o.wait_status);
    const std::string killed = "curvemesh " + what + " killed by " + signal_name(sig);
    if (bad_alloc) return {Status::out_of_memory, with_detail("out of memory" + std::string(limit), o.err)};
    // Not our SIGKILL (that is a time-out): the kernel's out-of-memory killer sends it.
    if (sig == SIGKILL) return {Status::out_of_memory, killed + " (not by the batch: out of memory)"};
    // Under an address-space limit, a failed allocation outside C++'s new (a thread's stack, the
    // C library) ends as a segmentation fault or an abort.
    if (memory_limit_gb > 0 && (sig == SIGSEGV || sig == SIGABRT))
      return {Status::out_of_memory, killed + limit + " (probably out of memory)"};
    return {Status::crash, with_detail(killed, o.err)};
  }
  const int code = WIFEXITED(o.wait_status) ? WEXITSTATUS(o.wait_status) : -1;
  if (code == kOk) return {Status::ok, ""};
  if (bad_alloc) return {Status::out_of_memory, with_detail("out of memory" + std::string(limit), o.err)};
  if (code == kInvalidInput) {
    const std::string line = first_error_line(o.err);  // it names the file, line and element
    return {Status::invalid_input, line.empty() ? "invalid input" : line};
  }
  return {Status::crash, with_detail("curvemesh " + what + " exited with " + std::to_string(code), o.err)};
}

}  // namespace curvemesh::app::batch
