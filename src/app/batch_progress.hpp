#pragma once
// Progress of `curvemesh batch` on stderr, from the report lines as they come: one line rewritten
// in place on a terminal, one line per drawing otherwise (a log file should not fill with carriage
// returns); and the summary a run ends with.
#include <chrono>
#include <cstddef>
#include <map>
#include <string>

#include "app/batch_report.hpp"

namespace curvemesh::app::batch {

// A duration for people: 12.3s, 4m05s, 2h07m.
std::string clock_text(double s);

class Progress {
 public:
  Progress(std::size_t total, bool terminal);

  // A drawing's report line is written.
  void finished(const Json& line);
  // Redraws the progress line now and then, so that the clock moves.
  void tick();
  void end();

  double elapsed() const;
  // Drawings finished that are neither ok nor skipped.
  std::size_t failed() const { return failed_; }

  // The line a run ends with. `shard` is --shard as given, empty when the run is not sharded;
  // `all` counts the drawings of every shard.
  std::string summary(const std::string& shard, std::size_t all, const std::string& report) const;

 private:
  using Clock = std::chrono::steady_clock;

  void draw();

  std::size_t total_, done_ = 0, ok_ = 0, failed_ = 0, ran_ = 0;
  std::map<std::string, std::size_t> counts_;  // by status
  bool terminal_;
  Clock::time_point start_, drawn_;
};

}  // namespace curvemesh::app::batch
