#include "app/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "base/text.hpp"

namespace curvemesh::app {

ProgressDisplay::ProgressDisplay(std::string input, double after_seconds)
    : input_(base::printable(input)), after_(after_seconds), terminal_(::isatty(STDERR_FILENO) == 1) {
  clock_ = std::thread([this] { tick(); });
}

ProgressDisplay::~ProgressDisplay() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    if (terminal_ && shown_) std::cerr << "\r\33[K" << std::flush;  // the run's own output follows
  }
  stop_signal_.notify_all();
  clock_.join();
}

double ProgressDisplay::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string ProgressDisplay::text() const {
  char line[200];
  const pipeline::Progress& p = current_;
  int n = std::snprintf(line, sizeof line, "%s", pipeline::stage_name(p.stage));
  if (p.pass > 0) n += std::snprintf(line + n, sizeof line - n, " pass %d", p.pass);
  if (p.triangles > 0)
    n += std::snprintf(
        line + n, sizeof line - n,
        p.stage == pipeline::Stage::curve && p.pass > 0 ? ", %d above the stop energy" : ", %d triangles",
        p.triangles);
  if (p.max_amips > 0) n += std::snprintf(line + n, sizeof line - n, ", max AMIPS %.4g", p.max_amips);
  std::snprintf(line + n, sizeof line - n, " (%.0f s)", elapsed());
  return "curvemesh: " + input_ + ": " + line;
}

void ProgressDisplay::operator()(const pipeline::Progress& progress) {
  std::lock_guard lock(mutex_);
  current_ = progress;
  printed_current_ = false;
  if (elapsed() < after_) return;
  shown_ = true;
  printed_current_ = true;
  if (terminal_)
    std::cerr << "\r\33[K" << text() << std::flush;
  else
    std::cerr << text() << "\n";
}

void ProgressDisplay::tick() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    stop_signal_.wait_for(lock, std::chrono::milliseconds(500));
    if (stop_ || elapsed() < after_) continue;
    // A terminal's line shows the time going on; plain output says each event once, including
    // the one a long stage started with before the display began.
    if (terminal_) {
      shown_ = true;
      std::cerr << "\r\33[K" << text() << std::flush;
    } else if (!printed_current_) {
      shown_ = true;
      printed_current_ = true;
      std::cerr << text() << "\n";
    }
  }
}

}  // namespace curvemesh::app
