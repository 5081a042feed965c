// Progress of `curvemesh batch` on stderr, and the summary a run ends with.
#include "app/batch_progress.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "base/text.hpp"

namespace curvemesh::app::batch {

std::string clock_text(double s) {
  char b[32];
  const long t = std::lround(s);
  if (t >= 3600)
    std::snprintf(b, sizeof b, "%ldh%02ldm", t / 3600, t / 60 % 60);
  else if (t >= 60)
    std::snprintf(b, sizeof b, "%ldm%02lds", t / 60, t % 60);
  else
    std::snprintf(b, sizeof b, "%.1fs", s);
  return b;
}

Progress::Progress(std::size_t total, bool terminal)
    : total_(total), terminal_(terminal), start_(Clock::now()) {}

void Progress::finished(const Json& line) {
  const std::string status = line["status"];
  // Paths and messages come from file names and children's output: shown, never obeyed.
  const std::string path = base::printable(line["path"].get<std::string>());
  ++done_;
  ++counts_[status];
  if (succeeded(status))
    ++ok_;
  else
    ++failed_;
  if (status != status_name(Status::skipped)) ++ran_;
  if (!terminal_) {
    char head[96];
    std::snprintf(head, sizeof head, "[%zu/%zu] %-14s %8.2f s %7.0f MB  ", done_, total_, status.c_str(),
                  line["seconds"].get<double>(), line["peak_mb"].get<double>());
    const std::string message = base::printable(line["message"].get<std::string>());
    std::cerr << head << path << (message.empty() ? "" : "  " + message) << "\n";
    return;
  }
  // On a terminal the failures stay readable above the progress line.
  if (!succeeded(status))
    std::cerr << "\r\33[K" << status << ": " << path << "  "
              << base::printable(line["message"].get<std::string>()) << "\n";
  draw();
}

void Progress::tick() {
  if (terminal_ && Clock::now() - drawn_ > std::chrono::milliseconds(200)) draw();
}

void Progress::end() {
  if (terminal_) std::cerr << "\n";
}

double Progress::elapsed() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void Progress::draw() {
  drawn_ = Clock::now();
  const double t = elapsed();
  const std::string eta = done_ == total_ ? "0s" : ran_ ? clock_text(t / ran_ * (total_ - done_)) : "?";
  std::cerr << "\r\33[K[" << done_ << "/" << total_ << "] ok " << ok_ << "  failed " << failed_
            << "  elapsed " << clock_text(t) << "  ETA " << eta << std::flush;
}

std::string Progress::summary(const std::string& shard, std::size_t all, const std::string& report) const {
  const auto count = [&](Status s) {
    const auto it = counts_.find(status_name(s));
    return it == counts_.end() ? 0 : it->second;
  };
  std::ostringstream summary;
  summary << "curvemesh batch: " << done_;
  if (done_ < total_) summary << " of " << total_;
  summary << " drawings";
  if (!shard.empty()) summary << " (shard " << shard << " of " << all << ")";
  summary << ": ok " << count(Status::ok) << ", skipped " << count(Status::skipped) << ", failed " << failed_;
  std::string sep = " (";
  for (const auto& [s, n] : counts_)
    if (!succeeded(s)) {
      summary << sep << s << " " << n;
      sep = ", ";
    }
  if (sep == ", ") summary << ")";
  summary << "; " << clock_text(elapsed()) << "; report " << base::printable(report);
  return summary.str();
}

}  // namespace curvemesh::app::batch
