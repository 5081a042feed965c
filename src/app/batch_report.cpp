// The report lines of `curvemesh batch` and the record in the statistics that skipping relies on.
#include "app/batch_report.hpp"

#include <sys/stat.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <system_error>

#include "base/text.hpp"

namespace curvemesh::app::batch {

namespace {

Json figure(const Json& j, const char* section, const char* key) {
  if (j.contains(section) && j[section].is_object() && j[section].contains(key)) return j[section][key];
  return nullptr;
}

// Rounded to 1/per_unit, as the nearest double (what a reader expects to see printed).
double rounded(double x, double per_unit) {
  return std::round(x * per_unit) / per_unit;
}

}  // namespace

std::string json_text(const Json& j, int indent) {
  const std::string raw = j.dump(indent, ' ', false, Json::error_handler_t::replace);
  std::string text;
  text.reserve(raw.size());
  // Outside strings the text is plain ASCII, and 0xC2 only ever leads a two-byte sequence: these
  // bytes are characters of some string, escaped where they stand.
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const auto c = static_cast<unsigned char>(raw[i]);
    const auto next = i + 1 < raw.size() ? static_cast<unsigned char>(raw[i + 1]) : 0u;
    if (c == 0x7f || (c == 0xc2 && next >= 0x80 && next <= 0x9f)) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c == 0x7f ? 0x7fu : next);
      text += escaped;
      if (c == 0xc2) ++i;
    } else {
      text += raw[i];
    }
  }
  return text;
}

Json report_line(const Drawing& d, Status status, double seconds, double peak_mb, const Json& stats,
                 const Json& check_invalid, const std::string& message) {
  const bool curved = stats.contains("curve");
  const bool meshed = status == Status::ok || status == Status::skipped || status == Status::invalid_output;
  Json line;
  line["path"] = d.path;
  line["status"] = status_name(status);
  line["seconds"] = rounded(seconds, 1000);
  line["peak_mb"] = rounded(peak_mb, 10);
  line["triangles"] = meshed ? figure(stats, "mesh", "triangles") : Json();
  line["curved_triangles"] = meshed && curved ? figure(stats, "curve", "curved_triangles") : Json();
  line["min_angle_deg"] = meshed ? figure(stats, "mesh", "min_angle_deg") : Json();
  // The curved triangles' own energy when curved: that is the mesh written.
  line["max_amips"] =
      meshed ? (curved ? figure(stats, "curve", "max_amips") : figure(stats, "mesh", "max_amips")) : Json();
  line["fitted_edges"] = meshed && curved ? figure(stats, "curve", "fitted_edges") : Json();
  line["straight_primary_edges"] = meshed && curved ? figure(stats, "curve", "straight_primary_edges") : Json();
  line["max_distance_rel"] = meshed && curved ? figure(stats, "curve", "max_distance_rel") : Json();
  line["mean_fit_distance_rel"] = meshed && curved ? figure(stats, "curve", "mean_fit_distance_rel") : Json();
  line["check_invalid"] = check_invalid;
  line["message"] = message;
  line["output"] = succeeded(status) ? d.msh.string() : "";
  return line;
}

Json read_stats(const fs::path& path) {
  std::ifstream in(path);
  Json stats = Json::parse(in, nullptr, false);
  if (stats.is_discarded() || !stats.is_object()) return Json::object();
  return stats;
}

Json input_identity(const std::string& path) {
  struct stat st {};
  std::error_code ec;
  const fs::path canonical = fs::canonical(path, ec);
  if (ec || ::stat(canonical.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return nullptr;
  Json identity;
  identity["path"] = base::repair_utf8(canonical.string());
  identity["size"] = static_cast<std::uint64_t>(st.st_size);
  identity["mtime_ns"] = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  return identity;
}

Json batch_record(double mesh_seconds, double mesh_peak_mb, double check_seconds, const Json& check_invalid,
                  const Json& mesh_arguments, const Json& input) {
  Json record;
  record["seconds"] = rounded(mesh_seconds, 1000);
  record["peak_mb"] = rounded(mesh_peak_mb, 10);
  record["check_seconds"] = rounded(check_seconds, 1000);
  record["check_invalid"] = check_invalid;
  record["mesh_arguments"] = mesh_arguments;
  record["input"] = input;
  return record;
}

// A drawing is finished when its mesh and statistics exist, are newer than the drawing, and the
// statistics carry the batch's record for the same mesh options and the same drawing file. The
// record is written only after `check` certified the mesh, so a run killed between meshing and
// certifying is redone, and so is a drawing meshed with other options (a linear mesh must not stand
// in for a curved one). The file is compared by path, size and time, not by time alone: outputs
// are named after the drawing's file name, so another a.svg (from another folder, or copied over
// with its old time kept) meets the same a.msh and must not be taken for the one meshed.
std::optional<Json> finished_stats(const Drawing& d, const Json& mesh_arguments) {
  std::error_code ec;
  const auto input_time = fs::last_write_time(d.path, ec);
  if (ec) return std::nullopt;
  for (const fs::path& p : {d.msh, d.stats}) {
    const auto t = fs::last_write_time(p, ec);
    if (ec || !(t > input_time)) return std::nullopt;
  }
  Json stats = read_stats(d.stats);
  if (!stats.contains("batch")) return std::nullopt;
  const Json& record = stats["batch"];
  if (!record.is_object() || record.value("mesh_arguments", Json()) != mesh_arguments) return std::nullopt;
  const Json input = input_identity(d.path);
  if (input.is_null() || record.value("input", Json()) != input) return std::nullopt;
  return stats;
}

Json skipped_line(const Drawing& d, const Json& stats) {
  const Json& r = stats["batch"];
  return report_line(d, Status::skipped, r.value("seconds", 0.0), r.value("peak_mb", 0.0), stats,
                     r.value("check_invalid", Json()), "");
}

}  // namespace curvemesh::app::batch
