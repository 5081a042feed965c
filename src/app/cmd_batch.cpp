// `curvemesh batch`: many drawings, each meshed by a child process of its own (`curvemesh mesh`,
// then `curvemesh check` on the result), so that a crash, a hang or a runaway allocation costs
// that drawing only, never the run. Resumable (finished drawings are skipped), shardable over
// machines, with one JSON line per drawing in a report that `curvemesh report` summarizes.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/batch_child.hpp"
#include "app/batch_error.hpp"
#include "app/batch_inputs.hpp"
#include "app/batch_progress.hpp"
#include "app/batch_report.hpp"
#include "app/batch_status.hpp"
#include "app/commands.hpp"
#include "app/feature_options.hpp"
#include "features/options.hpp"
#include "io/output_file.hpp"
#include "optimize/optimize.hpp"
#include "triangulate/triangulate.hpp"

namespace curvemesh::app {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

// The mesh options a batch passes on to every `curvemesh mesh` child. They are registered with
// the same checks as `mesh` has, so a bad value is a usage error before any drawing runs, and
// then forwarded as the user wrote them (the child parses them again, the one source of truth).
struct MeshForwarding {
  bool linear = false;
  int msh_version = 41;
  features::Options features;
  optimize::Options optimize;
  triangulate::Options triangulate;
  std::vector<const CLI::Option*> options;  // forwarded when given on the command line
};

struct BatchArgs {
  std::vector<std::string> inputs;
  std::string output_dir, report, shard = "1/1";
  unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
  double timeout_s = 300, memory_limit_gb = 0;
  bool force = false;
  MeshForwarding mesh;
};

using batch::batch_record;
using batch::BatchError;
using batch::Child;
using batch::ChildSetup;
using batch::classify;
using batch::Drawing;
using batch::finished_stats;
using batch::Outcome;
using batch::outcome_of;
using batch::Progress;
using batch::read_stats;
using batch::report_line;
using batch::skipped_line;
using batch::start_child;
using batch::Status;
using batch::status_name;
using batch::succeeded;

// ---------------------------------------------------------------------------------------------
// The run

// Blocks the signals the batch waits for (children ending, Ctrl-C, kill) and restores the mask
// on the way out, so waiting is one sigtimedwait instead of a handler writing to a global.
class BlockedSignals {
 public:
  BlockedSignals() {
    sigemptyset(&set_);
    for (int s : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) sigaddset(&set_, s);
    ::sigprocmask(SIG_BLOCK, &set_, &old_);
  }
  ~BlockedSignals() { ::sigprocmask(SIG_SETMASK, &old_, nullptr); }
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;
  const sigset_t& set() const { return set_; }
  const sigset_t& old() const { return old_; }

 private:
  sigset_t set_, old_;
};

struct Job {
  std::size_t index = 0;  // into the shard's drawings
  bool checking = false;  // meshing first, then certifying
  Clock::time_point deadline;
  Child child;
  Outcome mesh;  // the mesh child's outcome, once checking
};

class Batch {
 public:
  Batch(const BatchArgs& args, std::vector<Drawing> drawings, std::vector<std::string> forwarded,
        const BlockedSignals& signals)
      : args_(args),
        drawings_(std::move(drawings)),
        forwarded_(std::move(forwarded)),
        signals_(signals),
        lines_(drawings_.size()),
        progress_(drawings_.size(), ::isatty(STDERR_FILENO)) {
    for (const std::string& a : forwarded_) mesh_arguments_.push_back(a);
    setup_.mask = signals.old();
    setup_.address_space =
        args.memory_limit_gb > 0 ? static_cast<rlim_t>(args.memory_limit_gb * 1073741824.0) : 0;
  }

  // Runs every drawing; returns the signal that interrupted the run, or 0.
  int run(const fs::path& report_path) {
    report_path_ = report_path;
    std::error_code ec;
    if (report_path.has_parent_path()) fs::create_directories(report_path.parent_path(), ec);
    report_.open(report_path, std::ios::trunc);
    if (!report_)
      throw BatchError(kInvalidInput, "curvemesh: " + report_path.string() + ": cannot write the report");

    std::vector<std::size_t> pending;
    for (std::size_t i = 0; i < drawings_.size(); ++i) {
      const Drawing& d = drawings_[i];
      if (const auto stats = args_.force ? std::optional<Json>() : finished_stats(d, mesh_arguments_))
        finish(i, skipped_line(d, *stats));
      else
        pending.push_back(i);
    }
    std::reverse(pending.begin(), pending.end());  // taken from the back, in sorted order

    int interrupted = 0;
    while (!interrupted && (!pending.empty() || !running_.empty())) {
      while (running_.size() < args_.jobs && !pending.empty()) {
        start_mesh(pending.back());
        pending.pop_back();
      }
      reap();
      enforce_time_limits();
      interrupted = wait_for_news();
      progress_.tick();
    }
    if (interrupted) kill_all();
    progress_.end();
    write_sorted_report();
    return interrupted;
  }

  const Progress& progress() const { return progress_; }

 private:
  void start_mesh(std::size_t i) {
    const Drawing& d = drawings_[i];
    // Redoing a drawing starts from nothing: a failure must not leave an earlier run's mesh behind
    // to be taken for this run's.
    std::error_code ec;
    fs::remove(d.msh, ec);
    fs::remove(d.stats, ec);
    if (d.msh.has_parent_path()) fs::create_directories(d.msh.parent_path(), ec);
    if (ec) {
      finish(i, report_line(d, Status::crash, 0, 0, Json::object(), nullptr,
                            "cannot create " + d.msh.parent_path().string() + ": " + ec.message()));
      return;
    }
    std::vector<std::string> argv = {"curvemesh",    "mesh",    d.path,          "-o",
                                     d.msh.string(), "--stats", d.stats.string()};
    argv.insert(argv.end(), forwarded_.begin(), forwarded_.end());
    Job job;
    job.index = i;
    job.child = start_child(argv, setup_);
    job.deadline = job.child.started + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(args_.timeout_s));
    if (job.child.pid < 0) {
      const Outcome o = outcome_of(job.child, 0, 0);
      const auto [status, message] = classify(o, "mesh", args_.timeout_s, args_.memory_limit_gb);
      finish(i, report_line(d, status, 0, 0, Json::object(), nullptr, message));
      return;
    }
    running_.push_back(std::move(job));
  }

  // Collects every child that has ended, with its peak resident memory from the kernel.
  void reap() {
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
      if (job.checking)
        after_check(std::move(job), o);
      else
        after_mesh(std::move(job), o);
    }
  }

  void after_mesh(Job job, const Outcome& o) {
    const Drawing& d = drawings_[job.index];
    const auto [status, message] = classify(o, "mesh", args_.timeout_s, args_.memory_limit_gb);
    if (status != Status::ok) {
      finish(job.index, report_line(d, status, o.seconds, o.peak_mb, Json::object(), nullptr, message));
      return;
    }
    // Certified by `check` in a child too: an uncertifiable mesh may be expensive or crash the
    // checker, and the time limit covers both steps.
    job.mesh = o;
    job.checking = true;
    job.child = start_child({"curvemesh", "check", d.msh.string(), "--json"}, setup_);
    if (job.child.pid < 0) {
      after_check(std::move(job), outcome_of(job.child, 0, 0));
      return;
    }
    running_.push_back(std::move(job));
  }

  void after_check(Job job, const Outcome& o) {
    const Drawing& d = drawings_[job.index];
    Json stats = read_stats(d.stats);
    Json verdict = Json::parse(o.out, nullptr, false);
    const Json check_invalid =
        verdict.is_object() && verdict.contains("invalid") ? verdict["invalid"] : Json();
    auto [status, message] = classify(o, "check", args_.timeout_s, args_.memory_limit_gb);
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
      stats["batch"] =
          batch_record(job.mesh.seconds, job.mesh.peak_mb, o.seconds, check_invalid, mesh_arguments_);
      try {
        io::write_file_atomically(d.stats.string(), stats.dump(1) + "\n");
      } catch (const io::OutputError& e) {
        status = Status::crash;
        message = e.what();
      }
    }
    if (status != Status::ok) {
      // Only certified meshes stay in OUTDIR (as `mesh` writes nothing when it fails), and a
      // resumed run must redo this drawing rather than skip it.
      std::error_code ec;
      fs::remove(d.msh, ec);
      fs::remove(d.stats, ec);
    }
    finish(job.index,
           report_line(d, status, job.mesh.seconds, job.mesh.peak_mb, stats, check_invalid, message));
  }

  void enforce_time_limits() {
    const auto now = Clock::now();
    for (Job& j : running_)
      if (!j.child.killed && now >= j.deadline) {
        ::kill(-j.child.pid, SIGKILL);  // the whole group; the child is reaped as usual
        j.child.killed = true;
      }
  }

  // Sleeps until a child ends, the next deadline passes or 100 ms go by; returns the number of an
  // interrupting signal (Ctrl-C, SIGTERM, SIGHUP), or 0.
  int wait_for_news() {
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

  void kill_all() {
    for (Job& j : running_) ::kill(-j.child.pid, SIGKILL);
    for (Job& j : running_) {
      ::waitpid(j.child.pid, nullptr, 0);
      std::error_code ec;
      fs::remove(drawings_[j.index].msh, ec);
      fs::remove(drawings_[j.index].stats, ec);
    }
    running_.clear();
  }

  void finish(std::size_t i, Json line) {
    // Written as they come, so a run that dies still leaves a report; sorted at the end.
    report_ << line.dump() << "\n" << std::flush;
    progress_.finished(line);
    lines_[i] = std::move(line);
  }

  void write_sorted_report() {
    report_.close();
    std::string text;
    for (const auto& line : lines_)
      if (line) text += line->dump() + "\n";
    try {
      io::write_file_atomically(report_path_.string(), text);
    } catch (const io::OutputError& e) {
      throw BatchError(kInvalidInput, std::string("curvemesh: ") + e.what());
    }
  }

  const BatchArgs& args_;
  std::vector<Drawing> drawings_;
  std::vector<std::string> forwarded_;
  Json mesh_arguments_ = Json::array();
  const BlockedSignals& signals_;
  ChildSetup setup_{};
  std::vector<std::optional<Json>> lines_;
  std::vector<Job> running_;
  Progress progress_;
  fs::path report_path_;
  std::ofstream report_;
};

// The mesh options as the user gave them, to pass on to each child.
std::vector<std::string> forwarded_arguments(const MeshForwarding& m) {
  std::vector<std::string> out;
  if (m.linear) out.push_back("--linear");
  for (const CLI::Option* o : m.options)
    if (o->count() > 0 && !o->results().empty()) {
      out.push_back(o->get_name());
      out.push_back(o->results().back());
    }
  return out;
}

int run_batch(const BatchArgs& args) {
  if (!feature_options_valid(args.mesh.features)) return kUsage;
  const auto shard = batch::parse_shard(args.shard);
  if (!shard) {
    std::cerr << "curvemesh: --shard wants K/N with 1 <= K <= N, not '" << args.shard << "'\n";
    return kUsage;
  }
  try {
    std::vector<Drawing> all = batch::expand_inputs(args.inputs);
    const fs::path output_dir = fs::path(args.output_dir);
    batch::assign_outputs(all, output_dir);
    const std::size_t total = all.size();
    std::vector<Drawing> mine = batch::shard_of(std::move(all), *shard);
    if (total == 0) std::cerr << "curvemesh: warning: no drawings in the inputs\n";

    std::error_code ec;
    fs::create_directories(output_dir, ec);
    if (ec)
      throw BatchError(kInvalidInput,
                       "curvemesh: " + output_dir.string() + ": cannot create (" + ec.message() + ")");
    const fs::path report_path =
        args.report.empty() ? batch::default_report_path(output_dir, *shard) : fs::path(args.report);

    const BlockedSignals signals;
    Batch batch(args, std::move(mine), forwarded_arguments(args.mesh), signals);
    const int interrupted = batch.run(report_path);

    const Progress& progress = batch.progress();
    std::cerr << progress.summary(shard->n > 1 ? args.shard : "", total, report_path.string()) << "\n";
    if (interrupted) {
      std::cerr << "curvemesh: interrupted; the report lists the drawings that finished\n";
      // Die of the same signal, as a shell expects of an interrupted program.
      ::signal(interrupted, SIG_DFL);
      sigset_t one;
      sigemptyset(&one);
      sigaddset(&one, interrupted);
      ::sigprocmask(SIG_UNBLOCK, &one, nullptr);
      ::raise(interrupted);
      return kInvalidInput;
    }
    return progress.failed() ? kInvalidInput : kOk;
  } catch (const BatchError& e) {
    std::cerr << e.what() << "\n";
    return e.code();
  }
}

// The `mesh` options worth setting for a corpus, with the checks and defaults `mesh` has.
void add_forwarded_mesh_options(CLI::App& cmd, MeshForwarding& m) {
  cmd.add_flag("--linear", m.linear,
               "mesh: make linear meshes (straight 3-node triangles) instead of curved ones");
  const std::size_t first = cmd.get_options().size();
  cmd.add_option("--msh-version", m.msh_version, "mesh: Gmsh file format, 4.1 or 2.2")
      ->capture_default_str()
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, int>{{"4.1", 41}, {"41", 41}, {"2.2", 22}, {"22", 22}}));
  add_feature_options(cmd, m.features);
  cmd.add_option("--max-iterations", m.optimize.max_iterations, "mesh: optimization passes at most")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("--stop-amips", m.optimize.stop_max_amips,
                 "mesh: optimization stops once every triangle's AMIPS energy is at most this")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 1e9));
  cmd.add_option("--box-margin", m.triangulate.box_margin_rel,
                 "mesh: the meshed box extends the drawing's bounding box by this, relative to d")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 10.0));
  const auto all = cmd.get_options();
  m.options.assign(all.begin() + static_cast<std::ptrdiff_t>(first), all.end());
}

}  // namespace

Runner add_batch_command(CLI::App& app) {
  auto args = std::make_shared<BatchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "Mesh many drawings, each in a child process of its own (`curvemesh mesh`, then `curvemesh check "
      "--json` on the result), N at a time, so that a crash, a hang or running out of memory costs that "
      "drawing only. Outputs mirror the inputs under OUTDIR (X.msh and the statistics X.json). Finished "
      "drawings are skipped when run again. Writes one JSON line per drawing, in sorted order, to the "
      "report (summarize it with `curvemesh report`); progress goes to stderr. Exit 0 when every "
      "drawing is ok or skipped, 1 when any failed, 2 on a usage error.");
  cmd->add_option("inputs", args->inputs,
                  "drawings to mesh: SVG or .poly files, folders (every *.svg below them, outputs mirroring "
                  "their folders), or list files (any other file: one path per line, '#' starts a comment, "
                  "relative paths are relative to the list's folder). The list is sorted by path and each "
                  "file is meshed once")
      ->required();
  cmd->add_option("-o,--output-dir", args->output_dir,
                  "folder for the meshes and their statistics: a folder input's drawings keep their path "
                  "below that folder, files keep their name; names that would collide get a suffix hashed "
                  "from the drawing's path")
      ->required();
  cmd->add_option("-j,--jobs", args->jobs, "drawings meshed at the same time (default: the hardware threads)")
      ->capture_default_str()
      ->check(CLI::Range(1u, 4096u));
  cmd->add_option("--timeout", args->timeout_s,
                  "seconds per drawing, meshing and certifying together; then its process group is killed "
                  "(status timeout)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--memory-limit", args->memory_limit_gb,
                  "address space per child in GB (2^30 bytes; setrlimit RLIMIT_AS); a child that runs out "
                  "has status out-of-memory (default: no limit)")
      ->check(CLI::PositiveNumber);
  cmd->add_option(
      "--report", args->report,
      "the JSON Lines report: one object per drawing with path, status (ok, invalid-input, timeout, "
      "out-of-memory, crash, invalid-output, skipped), seconds, peak_mb, triangles, "
      "curved_triangles, min_angle_deg, max_amips, fitted_edges, max_distance_rel, "
      "mean_fit_distance_rel, check_invalid, message, output (default: OUTDIR/report.jsonl, "
      "OUTDIR/report-K-of-N.jsonl with --shard)");
  cmd->add_flag("--force", args->force,
                "mesh every drawing again; without it a drawing whose mesh and statistics are newer than "
                "the drawing, certified and made with the same mesh options, is skipped (status skipped, "
                "its figures read back from the statistics)");
  cmd->add_option("--shard", args->shard,
                  "K/N: mesh only the drawings whose index i in the sorted list has i % N == K-1 (K from 1), "
                  "to split a corpus over N runs whose reports add up to the whole")
      ->capture_default_str();
  add_forwarded_mesh_options(*cmd, args->mesh);
  cmd->footer(
      "The options from --linear on are passed on to each `curvemesh mesh` as given; see "
      "`curvemesh mesh --help`.");
  return [args] { return run_batch(*args); };
}

}  // namespace curvemesh::app
