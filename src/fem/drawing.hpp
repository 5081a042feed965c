#pragma once
// The drawing a problem is solved on: a finished curved mesh and what the problems need to know
// of the drawing (pipeline/meshed_drawing.hpp). The pipeline makes it; fem only reads it.
#include "pipeline/meshed_drawing.hpp"

namespace curvemesh::fem {

using pipeline::MeshedDrawing;
using pipeline::SideColours;

}  // namespace curvemesh::fem
