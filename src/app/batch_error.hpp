#pragma once
// What fails `curvemesh batch` as a whole rather than one drawing (an input that is not there, a
// report that cannot be written), with the exit code the command returns.
#include <stdexcept>
#include <string>

namespace curvemesh::app::batch {

class BatchError : public std::runtime_error {
 public:
  BatchError(int code, const std::string& message) : std::runtime_error(message), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

}  // namespace curvemesh::app::batch
