// `curvemesh report`: what batches did, from their JSON Lines reports (several shards at once):
// success rate, counts by status, time and memory distributions, the slowest drawings and the
// failures grouped by cause; with --html, one self-contained page with histograms of time and
// peak memory (like the paper's Fig. 11) and the same tables.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/batch_status.hpp"
#include "app/commands.hpp"
#include "app/messages.hpp"
#include "app/outputs.hpp"
#include "base/text.hpp"

namespace curvemesh::app {

namespace {

using Json = nlohmann::json;

struct ReportArgs {
  std::vector<std::string> inputs;
  std::string html;
};

using batch::succeeded;

struct Entry {
  std::string path, status, message;
  double seconds = 0, peak_mb = 0;
  Json triangles;  // null when there is no mesh
};

struct Distribution {
  std::size_t n = 0;
  double median = 0, p90 = 0, p99 = 0, max = 0;
};

// Quantiles by linear interpolation between order statistics (the median of an even count is
// the mean of the middle two, as usual).
Distribution distribution(std::vector<double> v) {
  Distribution d;
  d.n = v.size();
  if (v.empty()) return d;
  std::sort(v.begin(), v.end());
  const auto q = [&](double p) {
    const double at = p * static_cast<double>(v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(std::floor(at));
    const std::size_t j = std::min(i + 1, v.size() - 1);
    return v[i] + (at - static_cast<double>(i)) * (v[j] - v[i]);
  };
  d.median = q(0.5);
  d.p90 = q(0.9);
  d.p99 = q(0.99);
  d.max = v.back();
  return d;
}

struct Cause {
  std::string status, text;
  std::vector<const Entry*> drawings;
};

struct Summary {
  std::vector<Entry> entries;  // one per path, sorted by path
  std::size_t duplicates = 0, cut_short = 0, succeeded = 0;
  std::vector<std::pair<std::string, std::size_t>> counts;  // by status, in batch::Status's order
  Distribution time, memory;                                // over the drawings that have a mesh
  std::vector<const Entry*> slowest;
  std::vector<Cause> causes;  // most drawings first
};

class ReportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every line of every report; a drawing listed twice (a re-run's report beside the first one's)
// counts once, by its later line. A last line that ends without a newline and is not JSON was being
// written when its batch was killed (its node failed, say): it is left out and counted in `cut_short`,
// and that drawing is missing, as if it had not run. Any other line that is not a report line is an
// error.
// A report of a whole collection is a few MB; far beyond, the file is not one.
constexpr std::uint64_t kMaxReportBytes = std::uint64_t(1) << 30;

std::vector<Entry> read_reports(const std::vector<std::string>& files, std::size_t& duplicates,
                                std::size_t& cut_short) {
  std::map<std::string, Entry> by_path;
  duplicates = 0;
  cut_short = 0;
  for (const std::string& file : files) {
    std::string content;
    try {
      content = base::read_input_file(file, kMaxReportBytes, "");
    } catch (const base::InputFileError& e) {
      throw ReportError(e.what());
    }
    std::size_t start = 0;
    for (int number = 1; start < content.size(); ++number) {
      const std::size_t end = content.find('\n', start);
      const bool terminated = end != std::string::npos;
      const std::string text = content.substr(start, terminated ? end - start : std::string::npos);
      start = terminated ? end + 1 : content.size();
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::string where = file + ":" + std::to_string(number) + ": ";
      const Json line = Json::parse(text, nullptr, false);
      if (!terminated && (line.is_discarded() || !line.is_object())) {
        say("warning: " + where + "the last line is cut short (its batch was killed while writing it); left out");
        ++cut_short;
        continue;
      }
      if (line.is_discarded() || !line.is_object()) throw ReportError(where + "not a JSON object");
      for (const char* key : {"path", "status"})
        if (!line.contains(key) || !line[key].is_string())
          throw ReportError(where + "'" + key + "' is not a string");
      for (const char* key : {"seconds", "peak_mb"})
        if (!line.contains(key) || !line[key].is_number())
          throw ReportError(where + "'" + key + "' is not a number");
      Entry e;
      e.path = line["path"];
      e.status = line["status"];
      e.seconds = line["seconds"];
      e.peak_mb = line["peak_mb"];
      e.message =
          line.contains("message") && line["message"].is_string() ? line["message"].get<std::string>() : "";
      e.triangles = line.contains("triangles") ? line["triangles"] : Json();
      duplicates += by_path.count(e.path);
      by_path[e.path] = std::move(e);
    }
  }
  std::vector<Entry> out;
  for (auto& [path, e] : by_path) out.push_back(std::move(e));
  return out;
}

// A failure's cause: its message without what differs between drawings that failed the same way
// (the drawing's own path, line numbers and counts).
std::string cause_of(const Entry& e) {
  std::string m = e.message;
  for (std::size_t at = 0; !e.path.empty() && (at = m.find(e.path, at)) != std::string::npos; at += 4)
    m.replace(at, e.path.size(), "FILE");
  m = std::regex_replace(m, std::regex("[0-9]+(\\.[0-9]+)?"), "N");
  return m.empty() ? "(no message)" : m;
}

Summary summarize(const std::vector<std::string>& files) {
  Summary s;
  s.entries = read_reports(files, s.duplicates, s.cut_short);
  std::map<std::string, std::size_t> counts;
  std::vector<double> times, memory;
  for (const Entry& e : s.entries) {
    ++counts[e.status];
    if (succeeded(e.status)) {
      ++s.succeeded;
      times.push_back(e.seconds);
      memory.push_back(e.peak_mb);
    }
  }
  // The statuses `curvemesh batch` writes, in the order they are listed; others sort after them.
  for (const char* status : batch::kStatusNames)
    if (counts.count(status)) s.counts.emplace_back(status, counts[status]);
  for (const auto& [status, n] : counts)
    if (std::find(s.counts.begin(), s.counts.end(), std::make_pair(status, n)) == s.counts.end())
      s.counts.emplace_back(status, n);
  s.time = distribution(times);
  s.memory = distribution(memory);

  for (const Entry& e : s.entries) s.slowest.push_back(&e);
  std::stable_sort(s.slowest.begin(), s.slowest.end(),
                   [](const Entry* a, const Entry* b) { return a->seconds > b->seconds; });
  if (s.slowest.size() > 10) s.slowest.resize(10);

  std::map<std::pair<std::string, std::string>, std::vector<const Entry*>> causes;
  for (const Entry& e : s.entries)
    if (!succeeded(e.status)) causes[{e.status, cause_of(e)}].push_back(&e);
  for (auto& [key, drawings] : causes) s.causes.push_back({key.first, key.second, std::move(drawings)});
  std::stable_sort(s.causes.begin(), s.causes.end(),
                   [](const Cause& a, const Cause& b) { return a.drawings.size() > b.drawings.size(); });
  return s;
}

std::string fixed(double x, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, x);
  return b;
}

std::string percent(std::size_t part, std::size_t whole) {
  return whole ? fixed(100.0 * static_cast<double>(part) / static_cast<double>(whole), 1) + " %" : "-";
}

std::string distribution_text(const Distribution& d, int digits) {
  if (d.n == 0) return "-";
  return "median " + fixed(d.median, digits) + ", p90 " + fixed(d.p90, digits) + ", p99 " +
         fixed(d.p99, digits) + ", max " + fixed(d.max, digits);
}

void print_text(const Summary& s, std::size_t files, std::ostream& out) {
  const std::size_t n = s.entries.size();
  out << "drawings: " << n << " (from " << files << (files == 1 ? " report" : " reports");
  if (s.duplicates) out << "; " << s.duplicates << " listed again, the later line counts";
  if (s.cut_short)
    out << "; " << s.cut_short << (s.cut_short == 1 ? " last line" : " last lines")
        << " cut short by a killed batch, left out";
  out << ")\n";
  out << "success rate: " << s.succeeded << " of " << n << " (" << percent(s.succeeded, n)
      << ") ok or skipped\n";
  out << "by status:";
  for (const auto& [status, count] : s.counts)
    out << " " << status << " " << count << (&status == &s.counts.back().first ? "" : ",");
  out << "\n";
  out << "time (s, " << s.time.n << " meshed): " << distribution_text(s.time, 3) << "\n";
  out << "peak memory (MB, " << s.memory.n << " meshed): " << distribution_text(s.memory, 1) << "\n";
  if (!s.slowest.empty()) {
    out << "slowest:\n";
    for (const Entry* e : s.slowest) {
      char b[96];
      std::snprintf(b, sizeof b, "  %9.3f s %8.1f MB  %-14s ", e->seconds, e->peak_mb, e->status.c_str());
      out << b << base::printable(e->path) << "\n";
    }
  }
  if (!s.causes.empty()) {
    out << "failures by cause:\n";
    for (const Cause& c : s.causes) {
      out << "  " << base::printable(c.status) << ", " << c.drawings.size()
          << (c.drawings.size() == 1 ? " drawing: " : " drawings: ") << base::printable(c.text) << "\n";
      const std::size_t shown = std::min<std::size_t>(c.drawings.size(), 10);
      for (std::size_t i = 0; i < shown; ++i) out << "    " << base::printable(c.drawings[i]->path) << "\n";
      if (shown < c.drawings.size()) out << "    ... and " << c.drawings.size() - shown << " more\n";
    }
  }
}

// ---------------------------------------------------------------------------------------------
// HTML: one file, no network: inline style, inline SVG, no scripts, no fonts.

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  return out;
}

// 1, 2 or 5 times a power of ten, at least x.
double nice_step(double x) {
  if (x <= 0) return 1;
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= x * (1 - 1e-12)) return m * p;
  return 10 * p;
}

struct Histogram {
  std::string title, x_label;
  std::vector<std::size_t> ok, failed;                // per bin
  std::vector<std::pair<double, std::string>> ticks;  // position in bins (0 = left edge), label
};

// Time in bins of a quarter decade: times of a corpus spread over orders of magnitude.
Histogram time_histogram(const std::vector<Entry>& entries) {
  Histogram h{"Time per drawing", "seconds (log scale)", {}, {}, {}};
  const double floor_s = 1e-3;  // below a millisecond is all the same here
  double lo = INFINITY, hi = -INFINITY;
  for (const Entry& e : entries) {
    const double x = std::log10(std::max(e.seconds, floor_s));
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const int first = static_cast<int>(std::floor(lo * 4)),
            last = std::max(static_cast<int>(std::ceil(hi * 4)), first + 1);
  const std::size_t bins = static_cast<std::size_t>(last - first);
  h.ok.assign(bins, 0);
  h.failed.assign(bins, 0);
  for (const Entry& e : entries) {
    const double x = std::log10(std::max(e.seconds, floor_s)) * 4 - first;
    const std::size_t b = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, std::floor(x))));
    (succeeded(e.status) ? h.ok : h.failed)[b]++;
  }
  for (int k = (first + 3) / 4 - 1; k * 4 <= last; ++k)
    if (k * 4 >= first) {
      char label[32];
      std::snprintf(label, sizeof label, "%g s", std::pow(10.0, k));
      h.ticks.emplace_back(k * 4 - first, label);
    }
  return h;
}

Histogram memory_histogram(const std::vector<Entry>& entries) {
  Histogram h{"Peak memory per drawing", "MB", {}, {}, {}};
  double hi = 0;
  for (const Entry& e : entries) hi = std::max(hi, e.peak_mb);
  const double step = nice_step(std::max(hi, 1.0) / 20);
  const std::size_t bins = std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(hi / step)) + 1);
  h.ok.assign(bins, 0);
  h.failed.assign(bins, 0);
  for (const Entry& e : entries) {
    const std::size_t b = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, e.peak_mb / step)));
    (succeeded(e.status) ? h.ok : h.failed)[b]++;
  }
  const std::size_t every = std::max<std::size_t>(1, (bins + 5) / 6);
  for (std::size_t b = 0; b <= bins; b += every) {
    char label[32];
    std::snprintf(label, sizeof label, "%g", static_cast<double>(b) * step);
    h.ticks.emplace_back(static_cast<double>(b), label);
  }
  return h;
}

std::string histogram_svg(const Histogram& h) {
  const double width = 640, height = 240, left = 48, right = 16, top = 28, bottom = 44;
  const double plot_w = width - left - right, plot_h = height - top - bottom;
  std::size_t most = 1;
  for (std::size_t b = 0; b < h.ok.size(); ++b) most = std::max(most, h.ok[b] + h.failed[b]);
  const double y_step = std::max(1.0, nice_step(static_cast<double>(most) / 4));  // whole drawings
  const double y_max = std::ceil(static_cast<double>(most) / y_step) * y_step;
  const double bin_w = plot_w / static_cast<double>(h.ok.size());
  const auto y = [&](double count) { return top + plot_h * (1 - count / y_max); };
  std::ostringstream s;
  s << "<svg width=\"" << width << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " " << height
    << "\" role=\"img\" aria-label=\"" << escape(h.title) << "\">\n";
  s << "<text x=\"" << left << "\" y=\"16\" class=\"title\">" << escape(h.title) << "</text>\n";
  for (double c = 0; c <= y_max + 1e-9; c += y_step) {
    s << "<line x1=\"" << left << "\" x2=\"" << left + plot_w << "\" y1=\"" << y(c) << "\" y2=\"" << y(c)
      << "\" class=\"grid\"/>";
    s << "<text x=\"" << left - 6 << "\" y=\"" << y(c) + 4 << "\" text-anchor=\"end\">" << c << "</text>\n";
  }
  for (std::size_t b = 0; b < h.ok.size(); ++b) {
    const double x = left + bin_w * static_cast<double>(b);
    const double ok = static_cast<double>(h.ok[b]), all = ok + static_cast<double>(h.failed[b]);
    if (h.ok[b])
      s << "<rect x=\"" << x + 0.5 << "\" y=\"" << y(ok) << "\" width=\"" << std::max(bin_w - 1, 0.5)
        << "\" height=\"" << y(0) - y(ok) << "\" class=\"ok\"><title>" << h.ok[b]
        << " meshed</title></rect>\n";
    if (h.failed[b])
      s << "<rect x=\"" << x + 0.5 << "\" y=\"" << y(all) << "\" width=\"" << std::max(bin_w - 1, 0.5)
        << "\" height=\"" << y(ok) - y(all) << "\" class=\"failed\"><title>" << h.failed[b]
        << " failed</title></rect>\n";
  }
  s << "<line x1=\"" << left << "\" x2=\"" << left + plot_w << "\" y1=\"" << y(0) << "\" y2=\"" << y(0)
    << "\" class=\"axis\"/>\n";
  for (const auto& [at, label] : h.ticks) {
    const double x = left + bin_w * at;
    s << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << y(0) << "\" y2=\"" << y(0) + 5
      << "\" class=\"axis\"/>";
    s << "<text x=\"" << x << "\" y=\"" << y(0) + 18 << "\" text-anchor=\"middle\">" << escape(label)
      << "</text>\n";
  }
  s << "<text x=\"" << left + plot_w / 2 << "\" y=\"" << height - 6 << "\" text-anchor=\"middle\">"
    << escape(h.x_label) << "</text>\n";
  s << "<rect x=\"" << width - right - 150 << "\" y=\"8\" width=\"10\" height=\"10\" class=\"ok\"/><text x=\""
    << width - right - 136 << "\" y=\"17\">meshed</text>";
  s << "<rect x=\"" << width - right - 80
    << "\" y=\"8\" width=\"10\" height=\"10\" class=\"failed\"/><text x=\"" << width - right - 66
    << "\" y=\"17\">failed</text>\n";
  s << "</svg>\n";
  return s.str();
}

std::string html_page(const Summary& s, const std::vector<std::string>& files) {
  const std::size_t n = s.entries.size();
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       "<title>curvemesh batch report</title>\n<style>\n"
       "body { font-family: sans-serif; margin: 2em; color: #222; max-width: 60em; }\n"
       "table { border-collapse: collapse; margin: 0.5em 0 1.5em; }\n"
       "th, td { padding: 0.2em 0.8em; border-bottom: 1px solid #ddd; text-align: left; vertical-align: top; "
       "}\n"
       "td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }\n"
       "svg { display: block; margin: 1em 0; font-size: 11px; }\n"
       "svg .title { font-size: 13px; font-weight: bold; }\n"
       "svg .ok { fill: #4a7ab5; } svg .failed { fill: #c8553d; }\n"
       "svg .grid { stroke: #e4e4e4; } svg .axis { stroke: #444; }\n"
       "code { font-size: 0.95em; }\n"
       "</style>\n</head>\n<body>\n";
  h << "<h1>curvemesh batch report</h1>\n<p>" << n << " drawings from";
  for (const std::string& f : files) h << " <code>" << escape(f) << "</code>";
  h << ". Success rate: <strong>" << s.succeeded << " of " << n << " (" << percent(s.succeeded, n)
    << ")</strong> meshed and certified (ok or skipped).";
  if (s.duplicates) h << " " << s.duplicates << " drawings were listed again; the later line counts.";
  if (s.cut_short)
    h << " " << s.cut_short << (s.cut_short == 1 ? " report ends" : " reports end")
      << " in a line cut short by a killed batch; left out.";
  h << "</p>\n";

  h << "<h2>By status</h2>\n<table>\n<tr><th>status</th><th class=\"n\">drawings</th><th "
       "class=\"n\">share</th></tr>\n";
  for (const auto& [status, count] : s.counts)
    h << "<tr><td>" << escape(status) << "</td><td class=\"n\">" << count << "</td><td class=\"n\">"
      << percent(count, n) << "</td></tr>\n";
  h << "</table>\n";

  h << "<h2>Time and memory</h2>\n<p>Over the " << s.time.n
    << " drawings with a certified mesh.</p>\n<table>\n"
       "<tr><th></th><th class=\"n\">median</th><th class=\"n\">p90</th><th class=\"n\">p99</th><th "
       "class=\"n\">max</th></tr>\n";
  const auto row = [&](const char* name, const Distribution& d, int digits) {
    h << "<tr><td>" << name << "</td>";
    for (double x : {d.median, d.p90, d.p99, d.max})
      h << "<td class=\"n\">" << (d.n ? fixed(x, digits) : "-") << "</td>";
    h << "</tr>\n";
  };
  row("seconds", s.time, 3);
  row("peak memory (MB)", s.memory, 1);
  h << "</table>\n";
  if (n) h << histogram_svg(time_histogram(s.entries)) << histogram_svg(memory_histogram(s.entries));

  h << "<h2>Slowest drawings</h2>\n<table>\n<tr><th>drawing</th><th>status</th><th class=\"n\">seconds</th>"
       "<th class=\"n\">peak MB</th><th class=\"n\">triangles</th></tr>\n";
  for (const Entry* e : s.slowest)
    h << "<tr><td><code>" << escape(e->path) << "</code></td><td>" << escape(e->status)
      << "</td><td class=\"n\">" << fixed(e->seconds, 3) << "</td><td class=\"n\">" << fixed(e->peak_mb, 1)
      << "</td><td class=\"n\">" << (e->triangles.is_number() ? e->triangles.dump() : "") << "</td></tr>\n";
  h << "</table>\n";

  h << "<h2>Failures by cause</h2>\n";
  if (s.causes.empty()) h << "<p>None.</p>\n";
  for (const Cause& c : s.causes) {
    h << "<h3>" << escape(c.status) << ", " << c.drawings.size()
      << (c.drawings.size() == 1 ? " drawing" : " drawings") << ": <code>" << escape(c.text)
      << "</code></h3>\n<table>\n"
      << "<tr><th>drawing</th><th class=\"n\">seconds</th><th>message</th></tr>\n";
    for (const Entry* e : c.drawings)
      h << "<tr><td><code>" << escape(e->path) << "</code></td><td class=\"n\">" << fixed(e->seconds, 3)
        << "</td><td>" << escape(e->message) << "</td></tr>\n";
    h << "</table>\n";
  }
  h << "</body>\n</html>\n";
  return h.str();
}

int run_report(const ReportArgs& args) {
  std::vector<base::NamedPath> inputs;
  for (const std::string& input : args.inputs) inputs.push_back({"input", input});
  if (!outputs_distinct(inputs, {{"--html", args.html}})) return kUsage;
  Summary s;
  try {
    s = summarize(args.inputs);
  } catch (const ReportError& e) {
    say(e.what());
    return kInvalidInput;
  }
  print_text(s, args.inputs.size(), std::cout);
  if (args.html.empty()) return kOk;
  return write_together([&](base::OutputFiles& out) { out.add(args.html, html_page(s, args.inputs)); });
}

}  // namespace

Runner add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Summarize batch reports: success rate, time, memory, failures by cause\n"
      "Summarize the JSON Lines reports of `curvemesh batch` (several at once, e.g. one per shard): "
      "success rate (ok or skipped), drawings by status, median, p90, p99 and max of time and peak "
      "memory over the meshed drawings, the 10 slowest drawings, and the failures grouped by cause "
      "(status and message, with the drawing's path and numbers taken out). A drawing listed in more "
      "than one line counts once, by its last line. A report's last line that was cut short (its batch "
      "was killed while writing it) is left out with a warning; any other line that is not a report "
      "line is an error (exit 1).");
  cmd->add_option("reports", args->inputs, "report files (.jsonl) written by `curvemesh batch --report`")
      ->required();
  cmd->add_option("--html", args->html,
                  "also write the summary as one self-contained HTML page (no network, scripts or fonts): "
                  "the tables and inline-SVG histograms of time (log-scale bins) and peak memory, meshed "
                  "and failed drawings stacked");
  return [args] { return run_report(*args); };
}

}  // namespace curvemesh::app
