#include "app/messages.hpp"

#include <sys/resource.h>

#include <cstdio>
#include <iostream>

#include "base/text.hpp"

namespace curvemesh::app {

void say(const std::string& message) {
  std::cerr << "curvemesh: " << base::printable(message) << "\n";
}

std::string out_of_memory_message() {
  // "bad_alloc" is what `curvemesh batch` looks for in a child's messages.
  std::string m = "out of memory (std::bad_alloc)";
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    char gb[64];
    std::snprintf(gb, sizeof gb, " under an address-space limit of %.3g GB (--memory-limit)",
                  double(limit.rlim_cur) / 1073741824.0);
    m += gb;
  }
  return m + "; nothing written. --max-curves, --max-elements and --max-triangles refuse such drawings sooner";
}

void warn(const std::string& input, const std::string& message) {
  say(input + ": warning: " + message);
}

}  // namespace curvemesh::app
