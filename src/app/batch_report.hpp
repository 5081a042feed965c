#pragma once
// The lines of a `curvemesh batch` report, one JSON object per drawing: its status and the figures
// read from the statistics `curvemesh mesh --stats` wrote. And the batch's record in those
// statistics, written once a mesh is certified, by which a later run skips a finished drawing.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/batch_inputs.hpp"
#include "app/batch_status.hpp"

namespace curvemesh::app::batch {

using Json = nlohmann::ordered_json;

// `j` as text for a file (one line when `indent` is -1). Never throws on text that is not UTF-8
// (a file name, a child's message: each bad byte becomes U+FFFD), and escapes DEL and the C1
// controls (U+0080..U+009F) as \u007f and \u0080.. as the C0 ones are, so that showing a report
// on a terminal (cat, tail -f) cannot drive it.
std::string json_text(const Json& j, int indent = -1);

// One report line, every key always present: figures a drawing does not have (no mesh, or no
// curved stage with --linear) are null.
Json report_line(const Drawing& d, Status status, double seconds, double peak_mb, const Json& stats,
                 const Json& check_invalid, const std::string& message);

// The statistics at `path` as an object; an empty one when there is none to read.
Json read_stats(const fs::path& path);

// The drawing file at `path` as a mesh of it is recorded: its absolute canonical path (made valid
// UTF-8), size and modification time in nanoseconds. Null when it cannot be looked at.
Json input_identity(const std::string& path);

// The batch's record of a certified mesh, to be stored in its statistics under "batch". `input` is
// the drawing's input_identity as it was when meshing started.
Json batch_record(double mesh_seconds, double mesh_peak_mb, double check_seconds, const Json& check_invalid,
                  const Json& mesh_arguments, const Json& input);

// The statistics of a finished drawing (see batch_report.cpp), or nothing when it must be redone.
std::optional<Json> finished_stats(const Drawing& d, const Json& mesh_arguments);

// The report line of a finished drawing, from its statistics.
Json skipped_line(const Drawing& d, const Json& stats);

}  // namespace curvemesh::app::batch
