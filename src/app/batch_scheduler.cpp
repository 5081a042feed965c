// The run of `curvemesh batch`: the loop that keeps N children going, and what follows when each
// one ends.
#include "app/batch_scheduler.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>
#include <set>
#include <system_error>
#include <utility>

#include "app/batch_error.hpp"
#include "app/commands.hpp"
#include "base/files.hpp"
#include "io/output_file.hpp"

namespace curvemesh::app::batch {

namespace {

// A drawing's mesh and statistics, gone (the first error, if any, in `ec`).
void remove_outputs(const Drawing& d, std::error_code& ec) {
  fs::remove(d.msh, ec);
  fs::remove(d.stats, ec);
}

// All of `text` in one write(2) when the kernel takes it so (it does for a regular file), so that a
// process killed at any moment leaves whole lines behind. Errors are ignored: the report is written
// again, whole, at the end.
void write_whole(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

std::string not_regular(mode_t mode) {
  if (S_ISLNK(mode)) return "it is a symbolic link, not followed";
  if (S_ISFIFO(mode)) return "it is a FIFO, not a regular file";
  if (S_ISDIR(mode)) return "it is a folder";
  return "it is not a regular file";
}

// The report as lines come, opened without following a link planted at its name and without
// waiting on a FIFO planted there (O_NONBLOCK), and truncated only once it is known to be a regular
// file: a report is never written through to another file, and never holds a run up.
int open_report(const fs::path& path) {
  const auto refuse = [&](const std::string& why) {
    return BatchError(kInvalidInput,
                      "curvemesh: " + path.string() + ": cannot write the report (" + why + ")");
  };
  const int fd =
      ::open(path.c_str(), O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    struct stat st {};
    // ELOOP and ENXIO say little: name what is there instead.
    if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) throw refuse(not_regular(st.st_mode));
    throw refuse(std::strerror(error));
  }
  struct stat st {};
  std::string why;
  if (::fstat(fd, &st) != 0)
    why = std::strerror(errno);
  else if (!S_ISREG(st.st_mode))
    why = not_regular(st.st_mode);
  else if (::ftruncate(fd, 0) != 0)
    why = std::strerror(errno);
  if (!why.empty()) {
    ::close(fd);
    throw refuse(why);
  }
  return fd;
}

}  // namespace

Batch::Batch(const Settings& settings, std::vector<Drawing> drawings, std::vector<std::string> forwarded,
             const BlockedSignals& signals)
    : settings_(settings),
      drawings_(std::move(drawings)),
      forwarded_(std::move(forwarded)),
      signals_(signals),
      lines_(drawings_.size()),
      progress_(drawings_.size(), ::isatty(STDERR_FILENO)) {
  for (const std::string& a : forwarded_) mesh_arguments_.push_back(a);
  setup_.mask = signals.old();
  setup_.address_space =
      settings.memory_limit_gb > 0 ? static_cast<rlim_t>(settings.memory_limit_gb * 1073741824.0) : 0;
}

Batch::~Batch() {
  if (report_fd_ >= 0) ::close(report_fd_);
}

int Batch::run(const fs::path& report_path) {
  report_path_ = report_path;
  std::error_code ec;
  if (report_path.has_parent_path()) fs::create_directories(report_path.parent_path(), ec);
  report_fd_ = open_report(report_path);
  remove_stale_temporaries();

  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < drawings_.size(); ++i) {
    const Drawing& d = drawings_[i];
    if (const auto stats = settings_.force ? std::optional<Json>() : finished_stats(d, mesh_arguments_))
      finish(i, skipped_line(d, *stats));
    else
      pending.push_back(i);
  }
  std::reverse(pending.begin(), pending.end());  // taken from the back, in sorted order

  while (!interrupted_ && (!pending.empty() || !running_.empty())) {
    while (running_.size() < settings_.jobs && !pending.empty()) {
      start_mesh(pending.back());
      pending.pop_back();
    }
    reap();
    if (interrupted_) break;
    enforce_time_limits();
    interrupted_ = wait_for_news();
    progress_.tick();
  }
  if (interrupted_) kill_all();
  progress_.end();
  write_sorted_report();
  return interrupted_;
}

// A process killed between writing a file and renaming it into place (by the time limit, by a
// scheduler, by its node going down) leaves a temporary beside it (base::is_temporary_of: the
// NAME.tmp.PID of earlier versions too). Nothing reads those, but a half-written mesh can be large,
// so the ones of this run's drawings and of its report go before it starts. Other files are left
// alone: shards sharing OUTDIR remove their own.
void Batch::remove_stale_temporaries() const {
  std::map<fs::path, std::set<std::string>> ours;  // folder -> the names whose temporaries are ours
  for (const Drawing& d : drawings_)
    for (const fs::path& p : {d.msh, d.stats}) ours[p.parent_path()].insert(p.filename().string());
  ours[report_path_.parent_path()].insert(report_path_.filename().string());
  for (const auto& [folder, names] : ours) {
    std::error_code ec;
    for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end; !ec && it != end;
         it.increment(ec)) {
      // The name before the last ".tmp." is the only one the file can be a temporary of (the
      // random part has no dot): one look-up per file, however many drawings share the folder.
      const std::string file = it->path().filename().string();
      const auto at = file.rfind(".tmp.");
      if (at == std::string::npos) continue;
      const auto name = names.find(file.substr(0, at));
      std::error_code ignored;
      if (name != names.end() && base::is_temporary_of(file, *name)) fs::remove(it->path(), ignored);
    }
  }
}

void Batch::start_mesh(std::size_t i) {
  const Drawing& d = drawings_[i];
  // Redoing a drawing starts from nothing: a failure must not leave an earlier run's mesh behind
  // to be taken for this run's.
  std::error_code ec;
  remove_outputs(d, ec);
  if (d.msh.has_parent_path()) fs::create_directories(d.msh.parent_path(), ec);
  if (ec) {
    finish(i, report_line(d, Status::crash, 0, 0, Json::object(), nullptr,
                          "cannot create " + d.msh.parent_path().string() + ": " + ec.message()));
    return;
  }
  // The drawing last, after "--": whatever its name, it is read as the input, never as an option.
  std::vector<std::string> argv = {
      "curvemesh", "mesh", "-o", path_argument(d.msh.string()), "--stats", path_argument(d.stats.string()),
      "-q"};
  argv.insert(argv.end(), forwarded_.begin(), forwarded_.end());
  argv.insert(argv.end(), {"--threads", std::to_string(settings_.threads), "--", path_argument(d.path)});
  Job job;
  job.index = i;
  // Taken before the child reads the drawing: one changed while it was meshed is redone next time.
  job.input = input_identity(d.path);
  job.child = start_child(argv, setup_);
  job.deadline = job.child.started + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(settings_.timeout_s));
  if (job.child.pid < 0) {
    const Outcome o = outcome_of(job.child, 0, 0);
    const auto [status, message] = classify(o, "mesh", settings_.timeout_s, settings_.memory_limit_gb);
    finish(i, report_line(d, status, 0, 0, Json::object(), nullptr, message));
    return;
  }
  running_.push_back(std::move(job));
}

// Collects every child that has ended, with its peak resident memory from the kernel.
void Batch::reap() {
  int status = 0;
  rusage usage{};
  pid_t pid;
  while ((pid = ::wait4(-1, &status, WNOHANG, &usage)) > 0) {
    const auto it =
        std::find_if(running_.begin(), running_.end(), [&](const Job& j) { return j.child.pid == pid; });
    if (it == running_.end()) continue;
    Job job = std::move(*it);
    running_.erase(it);
    const double peak_mb = usage.ru_maxrss / 1024.0;  // kilobytes on Linux
    const Outcome o = outcome_of(job.child, status, peak_mb);
    if (const int sig = interruption_of(o)) {
      // Not the drawing's failure: it is left unfinished (no line, no outputs), to be redone.
      std::error_code ec;
      remove_outputs(drawings_[job.index], ec);
      interrupted_ = sig;
    } else if (job.checking)
      after_check(std::move(job), o);
    else
      after_mesh(std::move(job), o);
  }
}

void Batch::after_mesh(Job job, const Outcome& o) {
  const Drawing& d = drawings_[job.index];
  const auto [status, message] = classify(o, "mesh", settings_.timeout_s, settings_.memory_limit_gb);
  if (status != Status::ok) {
    finish(job.index, report_line(d, status, o.seconds, o.peak_mb, Json::object(), nullptr, message));
    return;
  }
  // Certified by `check` in a child too: an uncertifiable mesh may be expensive or crash the
  // checker, and the time limit covers both steps.
  job.mesh = o;
  job.checking = true;
  job.child = start_child({"curvemesh", "check", "--json", "--threads", std::to_string(settings_.threads), "--",
                           path_argument(d.msh.string())},
                          setup_);
  if (job.child.pid < 0) {
    after_check(std::move(job), outcome_of(job.child, 0, 0));
    return;
  }
  running_.push_back(std::move(job));
}

void Batch::after_check(Job job, const Outcome& o) {
  const Drawing& d = drawings_[job.index];
  Json stats = read_stats(d.stats);
  Json verdict = Json::parse(o.out, nullptr, false);
  const Json check_invalid = verdict.is_object() && verdict.contains("invalid") ? verdict["invalid"] : Json();
  auto [status, message] = classify(o, "check", settings_.timeout_s, settings_.memory_limit_gb);
  if (status == Status::ok && !(check_invalid.is_number() && check_invalid.get<long>() == 0)) {
    status = Status::invalid_output;
    message = "curvemesh check printed no verdict";
  } else if (status == Status::invalid_input || status == Status::crash) {
    // `check` refused the mesh (exit 1) or could not read it: either way it is not certified.
    status = Status::invalid_output;
    message = check_invalid.is_number() && check_invalid.get<long>() > 0
                  ? "curvemesh check: " + check_invalid.dump() + " invalid elements"
                  : "curvemesh check: " + message;
  }
  if (status == Status::ok) {
    stats["batch"] = batch_record(job.mesh.seconds, job.mesh.peak_mb, o.seconds, check_invalid,
                                  mesh_arguments_, job.input);
    try {
      io::write_file_atomically(d.stats.string(), json_text(stats, 1) + "\n");
    } catch (const io::OutputError& e) {
      status = Status::crash;
      message = e.what();
    }
  }
  if (status != Status::ok) {
    // Only certified meshes stay in OUTDIR (as `mesh` writes nothing when it fails), and a
    // resumed run must redo this drawing rather than skip it.
    std::error_code ec;
    remove_outputs(d, ec);
  }
  finish(job.index,
         report_line(d, status, job.mesh.seconds, job.mesh.peak_mb, stats, check_invalid, message));
}

// A child killed by SIGTERM, SIGINT or SIGHUP was stopped from outside. When the batch gets one of
// them too, within a second, the whole run is being stopped (a scheduler such as Slurm signals
// every process of a job, in no set order; so does a shutdown): the drawing is unfinished, not
// failed. Returns that signal; 0 when the child alone was stopped (then it is a crash, as before).
int Batch::interruption_of(const Outcome& o) const {
  if (o.start_errno || o.timed_out || !WIFSIGNALED(o.wait_status)) return 0;
  const int sig = WTERMSIG(o.wait_status);
  if (sig != SIGTERM && sig != SIGINT && sig != SIGHUP) return 0;
  if (interrupted_) return interrupted_;
  sigset_t stops;
  sigemptyset(&stops);
  for (int s : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&stops, s);
  const timespec one_second{1, 0};
  siginfo_t info;
  const int got = ::sigtimedwait(&stops, &info, &one_second);
  return got > 0 ? got : 0;
}

void Batch::enforce_time_limits() {
  const auto now = Clock::now();
  for (Job& j : running_)
    if (!j.child.killed && now >= j.deadline) {
      ::kill(-j.child.pid, SIGKILL);  // the whole group; the child is reaped as usual
      j.child.killed = true;
    }
}

// Sleeps until a child ends, the next deadline passes or 100 ms go by; returns the number of an
// interrupting signal (Ctrl-C, SIGTERM, SIGHUP), or 0.
int Batch::wait_for_news() {
  if (running_.empty()) return 0;
  auto wake = Clock::now() + std::chrono::milliseconds(100);
  for (const Job& j : running_)
    if (!j.child.killed) wake = std::min(wake, j.deadline);
  const auto ns = std::max<long long>(
      0, std::chrono::duration_cast<std::chrono::nanoseconds>(wake - Clock::now()).count());
  const timespec timeout{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
  siginfo_t info;
  const int sig = ::sigtimedwait(&signals_.set(), &info, &timeout);
  return sig > 0 && sig != SIGCHLD ? sig : 0;
}

void Batch::kill_all() {
  for (Job& j : running_) ::kill(-j.child.pid, SIGKILL);
  for (Job& j : running_) {
    ::waitpid(j.child.pid, nullptr, 0);
    std::error_code ec;
    remove_outputs(drawings_[j.index], ec);
  }
  running_.clear();
}

void Batch::finish(std::size_t i, Json line) {
  // Written as they come, each line in one write, so a run that dies, even by SIGKILL, still leaves
  // a report of whole lines; sorted at the end.
  write_whole(report_fd_, json_text(line) + "\n");
  progress_.finished(line);
  lines_[i] = std::move(line);
}

void Batch::write_sorted_report() {
  ::close(report_fd_);
  report_fd_ = -1;
  std::string text;
  for (const auto& line : lines_)
    if (line) text += json_text(*line) + "\n";
  try {
    io::write_file_atomically(report_path_.string(), text);
  } catch (const io::OutputError& e) {
    throw BatchError(kInvalidInput, std::string("curvemesh: ") + e.what());
  }
}

}  // namespace curvemesh::app::batch
