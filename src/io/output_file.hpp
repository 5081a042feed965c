#pragma once
// Writing outputs all-or-nothing: a failed run leaves no partial file behind.
#include <stdexcept>
#include <string>
#include <string_view>

namespace curvemesh::io {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `content` to a temporary file beside `path` and renames it over `path`.
// Throws OutputError naming the path when that fails.
void write_file_atomically(const std::string& path, std::string_view content);

}  // namespace curvemesh::io
