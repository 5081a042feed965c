#pragma once
// Writing outputs all or nothing (base/files.hpp), under the names the writers of this layer use.
#include "base/files.hpp"

namespace curvemesh::io {

using base::OutputError;
using base::OutputFiles;
using base::write_file_atomically;

}  // namespace curvemesh::io
