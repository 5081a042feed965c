#pragma once
// The run of `curvemesh batch`: the drawings of one shard, N children at a time, each meshed and
// then certified within its time limit, finished ones skipped, every drawing's line written to the
// report as it ends and the whole report sorted at the end. Stopped from outside (SIGINT, SIGTERM,
// SIGHUP), it kills its children, leaves their drawings unfinished and keeps the report of the rest.
#include <signal.h>
#include <sys/resource.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "app/batch_child.hpp"
#include "app/batch_inputs.hpp"
#include "app/batch_progress.hpp"
#include "app/batch_report.hpp"

namespace curvemesh::app::batch {

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

// How the drawings run: --jobs, --timeout, --memory-limit (0 for none) and --force.
struct Settings {
  unsigned jobs = 1;
  double timeout_s = 300, memory_limit_gb = 0;
  bool force = false;
  int threads = 1;  // --threads of every child, meshing and checking
};

class Batch {
 public:
  // `forwarded` are the mesh options passed on to every `curvemesh mesh`.
  Batch(const Settings& settings, std::vector<Drawing> drawings, std::vector<std::string> forwarded,
        const BlockedSignals& signals);

  // Runs every drawing; returns the signal that interrupted the run, or 0. Throws BatchError when
  // the report cannot be written.
  int run(const fs::path& report_path);
  ~Batch();
  Batch(const Batch&) = delete;
  Batch& operator=(const Batch&) = delete;

  const Progress& progress() const { return progress_; }

 private:
  struct Job {
    std::size_t index = 0;  // into the shard's drawings
    bool checking = false;  // meshing first, then certifying
    Clock::time_point deadline;
    Child child;
    Outcome mesh;  // the mesh child's outcome, once checking
    Json input;    // the drawing file as meshing started (input_identity)
  };

  void remove_stale_temporaries() const;
  void start_mesh(std::size_t i);
  void reap();
  int interruption_of(const Outcome& o) const;
  void after_mesh(Job job, const Outcome& o);
  void after_check(Job job, const Outcome& o);
  void enforce_time_limits();
  int wait_for_news();
  void kill_all();
  void finish(std::size_t i, Json line);
  void write_sorted_report();

  Settings settings_;
  std::vector<Drawing> drawings_;
  std::vector<std::string> forwarded_;
  Json mesh_arguments_ = Json::array();
  const BlockedSignals& signals_;
  ChildSetup setup_{};
  std::vector<std::optional<Json>> lines_;
  std::vector<Job> running_;
  Progress progress_;
  fs::path report_path_;
  int report_fd_ = -1;   // the report as lines come, one write(2) each
  int interrupted_ = 0;  // the signal that stops the run
};

}  // namespace curvemesh::app::batch
