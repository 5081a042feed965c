// `curvemesh batch`: many drawings, each meshed by a child process of its own (`curvemesh mesh`,
// then `curvemesh check` on the result), so that a crash, a hang or a runaway allocation costs
// that drawing only, never the run. Resumable (finished drawings are skipped), shardable over
// machines, with one JSON line per drawing in a report that `curvemesh report` summarizes.
// This file holds the command line; the batch_*.hpp files hold the rest: the inputs and shards,
// the child processes, the report lines, the progress display and the scheduler.
#include <signal.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "app/batch_error.hpp"
#include "app/batch_inputs.hpp"
#include "app/batch_scheduler.hpp"
#include "app/commands.hpp"
#include "app/mesh_options.hpp"
#include "base/text.hpp"

namespace curvemesh::app {

namespace {

namespace fs = std::filesystem;

// The mesh options a batch passes on to every `curvemesh mesh` child. They are registered with
// the same checks as `mesh` has, so a bad value is a usage error before any drawing runs, and
// then forwarded as the user wrote them (the child parses them again, the one source of truth).
struct MeshForwarding {
  pipeline::Parameters parameters;
  io::MshOptions msh;
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

// The mesh options as the user gave them, to pass on to each child: a flag (--linear,
// --no-features) by its name, an option with its last value.
std::vector<std::string> forwarded_arguments(const MeshForwarding& m) {
  std::vector<std::string> out;
  for (const CLI::Option* o : m.options) {
    if (o->count() == 0 || o->get_name() == "--threads") continue;  // child_threads passes it on
    if (o->get_expected_min() == 0) {
      out.push_back(o->get_name());
    } else if (!o->results().empty()) {
      out.push_back(o->get_name());
      out.push_back(o->results().back());
    }
  }
  return out;
}

// The threads each child may use: --threads as given, else the hardware threads shared by the
// jobs (at least one each), so that J children of T threads each do not oversubscribe the machine.
int child_threads(const BatchArgs& args) {
  for (const CLI::Option* o : args.mesh.options)
    if (o->get_name() == "--threads" && o->count() > 0) return args.mesh.parameters.threads;
  return static_cast<int>(std::max(1u, std::max(1u, std::thread::hardware_concurrency()) / args.jobs));
}

int run_batch(const BatchArgs& args) {
  if (!parameters_valid(args.mesh.parameters)) return kUsage;
  const auto shard = batch::parse_shard(args.shard);
  if (!shard) {
    std::cerr << "curvemesh: --shard wants K/N with 1 <= K <= N, not '" << base::printable(args.shard)
              << "'\n";
    return kUsage;
  }
  try {
    batch::Inputs inputs = batch::expand_inputs(args.inputs);
    const fs::path output_dir = fs::path(args.output_dir);
    batch::assign_outputs(inputs.drawings, output_dir);
    const std::size_t total = inputs.drawings.size();
    std::vector<batch::Drawing> mine = batch::shard_of(inputs.drawings, *shard);
    if (total == 0) std::cerr << "curvemesh: warning: no drawings in the inputs\n";
    const fs::path report_path =
        args.report.empty() ? batch::default_report_path(output_dir, *shard) : fs::path(args.report);
    // Before anything is written: `--report a.svg` must not empty the drawing it is about to mesh.
    if (const std::string clash = batch::output_clash(inputs, mine, report_path); !clash.empty())
      throw batch::BatchError(kUsage, "curvemesh: " + clash);

    std::error_code ec;
    fs::create_directories(output_dir, ec);
    if (ec)
      throw batch::BatchError(kInvalidInput,
                              "curvemesh: " + output_dir.string() + ": cannot create (" + ec.message() + ")");

    const batch::BlockedSignals signals;
    batch::Batch batch_run({args.jobs, args.timeout_s, args.memory_limit_gb, args.force, child_threads(args)},
                           std::move(mine),
                           forwarded_arguments(args.mesh), signals);
    const int interrupted = batch_run.run(report_path);

    const batch::Progress& progress = batch_run.progress();
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
  } catch (const batch::BatchError& e) {
    std::cerr << base::printable(e.what()) << "\n";  // it may name a file: shown, never obeyed
    return e.code();
  }
}

}  // namespace

Runner add_batch_command(CLI::App& app) {
  auto args = std::make_shared<BatchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "Mesh many drawings, each in a process of its own, resumable, with a JSON Lines report\n"
      "Mesh many drawings, each in a child process of its own (`curvemesh mesh`, then `curvemesh check "
      "--json` on the result), N at a time, so that a crash, a hang or running out of memory costs that "
      "drawing only. Outputs mirror the inputs under OUTDIR (X.msh and the statistics X.json). Finished "
      "drawings are skipped when run again. Writes one JSON line per drawing, in sorted order, to the "
      "report (summarize it with `curvemesh report`); progress goes to stderr. Stopped by SIGINT, SIGTERM "
      "or SIGHUP (Ctrl-C, a scheduler's time limit or cancel), it kills its children, keeps the report "
      "of the drawings that finished and ends by that signal; run it again to finish. Exit 0 when every "
      "drawing is ok or skipped, 1 when any failed, 2 on a usage error.");
  cmd->add_option("inputs", args->inputs,
                  "drawings to mesh: SVG (.svg, .svgz) or .poly files, folders (every *.svg and *.svgz below them, outputs mirroring "
                  "their folders), or list files (any other file: one path per line, '#' starts a comment, "
                  "relative paths are relative to the list's folder). The list is sorted by path and each "
                  "file is meshed once")
      ->required();
  cmd->add_option("-o,--output-dir", args->output_dir,
                  "folder for the meshes and their statistics: a folder input's drawings keep their path "
                  "below that folder, files keep their name; names that would collide get a suffix hashed "
                  "from the drawing's path")
      ->required();
  cmd->add_option("-j,--jobs", args->jobs,
                  "drawings meshed at the same time (default: the hardware threads); each may use the hardware "
                  "threads divided by the jobs (at least one) unless --threads says how many, so that the "
                  "children share the machine without oversubscribing it")
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
      "curved_triangles, min_angle_deg, max_amips, fitted_edges, straight_primary_edges (primary edges "
      "left straight, off their curve), max_distance_rel, "
      "mean_fit_distance_rel, check_invalid, message, output (default: OUTDIR/report.jsonl, "
      "OUTDIR/report-K-of-N.jsonl with --shard). It must be a regular file or nothing yet: a link or "
      "a FIFO found there is refused, not followed; and no output may be an input (a usage error)");
  cmd->add_flag("--force", args->force,
                "mesh every drawing again; without it a drawing whose mesh and statistics are newer than "
                "the drawing, certified and made with the same mesh options from the same file (path, size "
                "and modification time), is skipped (status skipped, its figures read back from the "
                "statistics)");
  cmd->add_option("--shard", args->shard,
                  "K/N: mesh only the drawings whose index i in the sorted list has i % N == K-1 (K from 1), "
                  "to split a corpus over N runs whose reports add up to the whole")
      ->capture_default_str();
  args->mesh.options = add_batch_run_options(*cmd, args->mesh.parameters);
  for (const CLI::Option* o : add_mesh_options(*cmd, args->mesh.parameters, args->mesh.msh))
    args->mesh.options.push_back(o);
  cmd->footer(
      "The options from --regions on are passed on to each `curvemesh mesh` as given; see "
      "`curvemesh mesh --help`.");
  return [args] { return run_batch(*args); };
}

}  // namespace curvemesh::app
