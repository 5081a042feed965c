#pragma once
// The child processes of `curvemesh batch`: starting one (`curvemesh mesh` or `curvemesh check`,
// in a process group of its own, under an address-space limit, its output in temporary files),
// what it left behind once reaped, and what its end means for its drawing.
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/batch_status.hpp"

namespace curvemesh::app::batch {

using Clock = std::chrono::steady_clock;
using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

struct ChildSetup {
  sigset_t mask;         // the signal mask the children start with (the caller's original)
  rlim_t address_space;  // RLIMIT_AS for the child, 0 for none
};

struct Child {
  pid_t pid = -1;       // also its process group
  int start_errno = 0;  // fork or exec failed (pid stays -1)
  Clock::time_point started;
  bool killed = false;  // by us, for the time limit
  File out{nullptr, &std::fclose}, err{nullptr, &std::fclose};
};

// How a child ended.
struct Outcome {
  int wait_status = 0;
  int start_errno = 0;
  bool timed_out = false;
  double seconds = 0, peak_mb = 0;
  std::string out, err;
};

// `path` as a child's argument: a relative path that starts with '-' gets "./" before it. Paths
// come from folders and list files, and a file named "-o/x" or "--svg=y" must stay a file; the
// children also take their paths after "--", and this keeps that true of any parser.
std::string path_argument(const std::string& path);

// Runs this very executable with `args` (args[0] is the name it sees). Throws BatchError when no
// temporary file can be made for its output; a failed fork or exec is in the child's start_errno.
Child start_child(const std::vector<std::string>& args, const ChildSetup& setup);

// The outcome of a child reaped with `wait_status` (or that never started), with what it wrote.
Outcome outcome_of(Child& c, int wait_status, double peak_mb);

// What a child's end means for its drawing. `what` names the step ("mesh" or "check").
std::pair<Status, std::string> classify(const Outcome& o, const std::string& what, double timeout_s,
                                        double memory_limit_gb);

}  // namespace curvemesh::app::batch
