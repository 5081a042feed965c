#pragma once
// Diffusion curves (Orzan et al. 2008; paper §5.1, Fig. 12): every curve carries a colour on
// each side; the mesh of the drawing's box is cut open along the curves, each side of a cut
// holds its colour, and the picture is the harmonic interpolant of those colours:
//
//   Δc = 0 in the box minus the curves, per channel (red, green, blue),
//   c = the side's colour on each side of every curve, ∂c/∂n = 0 on the box's border,
//
// solved with P2 elements on the curved (cubic) map or on the straight map of the same mesh.
//
// Sides. SVG's y axis points down, so "left" is meant as on screen: walking along a curve the
// way its parameter grows (the way its path is drawn), the left side is on the walker's left
// hand; a curve drawn rightwards has its left side above it on screen. The reader has already
// exchanged the two colours of elements drawn through a mirroring transform, and the pipeline
// has given each curve its two colours (MeshedDrawing::colours).
//
// Which lines are cut: every primary and every secondary line that lies on an input curve.
// Secondary lines are curve pieces too (too short or too bent to be reproduced by curved edges,
// kept within ε by straight ones): leaving them uncut would let the colours of the two sides
// leak through every sharp bend of a curve.
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "fem/domain.hpp"
#include "fem/drawing.hpp"
#include "fem/output.hpp"
#include "fem/space.hpp"

namespace curvemesh::fem {

// One side of a cut: triangle t's local edge e (Gmsh order: 0→1, 1→2, 2→0) held at `colour`.
struct ColouredEdge {
  int triangle = -1, edge = -1;
  Rgb colour{};
};

struct DiffusionMesh {
  CutMesh cut;                      // the drawing's cubic mesh cut open; same triangles, same order
  std::vector<ColouredEdge> sides;  // two per cut line inside the box, one on the box's border
  int cut_lines = 0;                // lines of the drawing's mesh that were cut
};

// Cuts the drawing's mesh open along its primary and secondary lines that lie on a soup curve
// and gives each side the colour of the curve on that side. `colours` is indexed by soup curve
// (std::invalid_argument when a line's curve is beyond it).
DiffusionMesh cut_along_curves(const MeshedDrawing& drawing, const std::vector<SideColours>& colours);

struct DiffuseOptions {
  // The colour of the parts of the box that no cut reaches (a component of the cut mesh with no
  // coloured edge, where the solution is any constant).
  Rgb background = {1, 1, 1};
};

struct DiffusionResult {
  std::array<Eigen::VectorXd, 3> channel;  // red, green, blue, one value per unknown of the space
  int unknowns = 0;                        // of the space
  int fixed = 0;                           // held by the colours of the sides
  int background_components = 0;           // components with no coloured edge, set to the background
  double assembly_seconds = 0, solve_seconds = 0;

  // The colour at reference point ξ of triangle t.
  Rgb at(const Space& space, int t, const Vec2& xi) const;
};

// Solves the Laplace equation per channel on `geometry` (a cut mesh, cubic or straight) with
// `space`, the unknowns on the given edges held at their colours (an unknown on several edges,
// such as a cut's loose end, at the mean of theirs). One CHOLMOD factorization serves the three
// channels.
DiffusionResult diffuse(const Geometry& geometry, const Space& space, const std::vector<ColouredEdge>& sides,
                        const DiffuseOptions& options = {});

}  // namespace curvemesh::fem
