#pragma once
// What every command does with its files: checks, before anything is read or written, that no
// output is an input or named twice; then writes its outputs together or not at all.
#include <functional>
#include <vector>

#include "base/files.hpp"

namespace curvemesh::app {

// False, after saying why on stderr, when an output is the same file as an input (same device and
// inode, through any link or spelling) or two outputs name one file: the run must stop with exit 2.
// Paths left empty are options not given.
bool outputs_distinct(const std::vector<base::NamedPath>& inputs, const std::vector<base::NamedPath>& outputs);

// Runs `add` on a set of outputs and commits them: every file written, or none (base::OutputFiles).
// Returns 0, or exit code 1 after saying on stderr what could not be written.
int write_together(const std::function<void(base::OutputFiles&)>& add);

}  // namespace curvemesh::app
