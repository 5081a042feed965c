#pragma once
// Progress on stderr for runs that take longer than about two seconds: the stage, the pass, the
// triangles and the worst AMIPS energy so far, and the time. On a terminal it is one line that
// updates in place (and is cleared at the end); otherwise plain lines, one per event.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "pipeline/pipeline.hpp"

namespace curvemesh::app {

class ProgressDisplay {
 public:
  // `input` names the run in each line.
  explicit ProgressDisplay(std::string input, double after_seconds = 2.0);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  // The pipeline's progress callback.
  void operator()(const pipeline::Progress& progress);

 private:
  void tick();               // the clock thread: redraws the line on a terminal
  std::string text() const;  // the current line (lock held)
  double elapsed() const;

  std::string input_;
  double after_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  std::condition_variable stop_signal_;
  bool stop_ = false, shown_ = false, printed_current_ = false;
  pipeline::Progress current_;
  std::thread clock_;
};

}  // namespace curvemesh::app
