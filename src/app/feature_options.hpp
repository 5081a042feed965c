#pragma once
// The feature-processing options, shared by every subcommand that runs that stage.
#include "features/options.hpp"

namespace CLI {
class App;
}

namespace curvemesh::app {

void add_feature_options(CLI::App& cmd, features::Options& options);

// ε below μ cannot be honoured: resampling already puts secondary chords up to μ from their
// curves. Returns false (after saying why) when the options are inconsistent.
bool feature_options_valid(const features::Options& options);

}  // namespace curvemesh::app
