#pragma once
// The method's parameters on the command line, registered in one place for every command that
// meshes: the feature options (§4) for `features`, `solve` and `diffuse`, and the whole set for
// `mesh` and `batch`. Checked again, all together, by pipeline::Parameters::validate.
#include <vector>

#include "io/msh_writer.hpp"
#include "pipeline/parameters.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace curvemesh::app {

// The options of curvemesh::parameter_options() (the one definition of each, with its help and
// range), registered to set `parameters`.

// The groups "features" and "limits": --mu, --epsilon, -l/--edge-length, --min-edge-length,
// --min-angle, --junction-angle, --no-features, --eps-m; --max-input-mb, --max-elements,
// --max-curves, --max-triangles, --threads.
void add_feature_options(CLI::App& cmd, pipeline::Parameters& parameters);

// The group "run": --regions, --domain, --stop-after (`mesh` alone).
void add_run_options(CLI::App& cmd, pipeline::Parameters& parameters);

// --regions and --domain, what `batch` passes on of the group "run" (not --stop-after: a batch
// certifies finished meshes). Returns the options it registered.
std::vector<const CLI::Option*> add_batch_run_options(CLI::App& cmd, pipeline::Parameters& parameters);
// --threads alone (for `check`, which takes no other parameter).
void add_threads_option(CLI::App& cmd, pipeline::Parameters& parameters);

// --memory-limit GB: the process's address space (setrlimit RLIMIT_AS), as batch sets its
// children's; 0 (the default) leaves it as it is.
void add_memory_limit_option(CLI::App& cmd, double& gigabytes);
// Applies it; a run that reaches it ends with exit 1 ("out of memory", main.cpp).
void limit_memory(double gigabytes);

// The group "mesh" (--order, --linear, --max-iterations, --stop-amips, --box-margin,
// --curved-stop-amips, --max-curved-passes), --msh-version, --msh-boundary-only and the feature
// options. Returns the options it registered, in order (what `batch` passes on to its children).
std::vector<const CLI::Option*> add_mesh_options(CLI::App& cmd, pipeline::Parameters& parameters,
                                                 io::MshOptions& msh);

// Whether the parameters are consistent; if not, says why on stderr.
bool parameters_valid(const pipeline::Parameters& parameters);

}  // namespace curvemesh::app
