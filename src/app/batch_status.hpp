#pragma once
// What became of one drawing in `curvemesh batch`: the statuses its report lines carry, which
// `curvemesh report` reads back. One list for both commands.
#include <array>
#include <cstddef>
#include <string_view>

namespace curvemesh::app::batch {

// In the order `curvemesh report` lists them: the successes first, then the failures.
enum class Status { ok, skipped, invalid_input, timeout, out_of_memory, crash, invalid_output };

// Each status's name in the report, in the order of Status.
inline constexpr std::array<const char*, 7> kStatusNames = {
    "ok", "skipped", "invalid-input", "timeout", "out-of-memory", "crash", "invalid-output"};
static_assert(kStatusNames.size() == static_cast<std::size_t>(Status::invalid_output) + 1);

inline const char* status_name(Status s) {
  return kStatusNames[static_cast<std::size_t>(s)];
}

// A drawing succeeded when it has a certified mesh: made by this run (ok) or by an earlier one
// (skipped).
inline bool succeeded(Status s) {
  return s == Status::ok || s == Status::skipped;
}
inline bool succeeded(std::string_view status) {
  return status == status_name(Status::ok) || status == status_name(Status::skipped);
}

}  // namespace curvemesh::app::batch
