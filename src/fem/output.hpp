#pragma once
// Looking at solutions: a field's values at the mesh nodes (for VTU point data), pictures of a
// field over the drawing's box (each pixel centre located in its triangle through the inverse
// of the triangle's map, so curved triangles are drawn curved), and PNG files (libpng).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "fem/space.hpp"
#include "geometry/bezier.hpp"

namespace curvemesh::fem {

// u (unknowns of `space`) evaluated at every node of the geometry's mesh; nodes in no triangle
// get 0. With several components, `u` holds component c of unknown i at i * components + c.
std::vector<double> values_at_nodes(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u,
                                    int components = 1);

// The value of u (one component) in triangle t at reference point ξ.
double value_at(const Space& space, const Eigen::VectorXd& u, int t, const Vec2& xi, int components = 1,
                int component = 0);

using Rgb = std::array<double, 3>;  // each in [0, 1]

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // 3 bytes per pixel, rows from the top
};

// The picture of `view` (the drawing's user space, y down as in SVG) at `width` pixels across:
// every pixel whose centre lies in a triangle takes colour(t, ξ); the others `background`.
Image rasterize(const Geometry& geometry, const geometry::Box2& view, int width,
                const std::function<Rgb(int t, const Vec2& xi)>& colour, Rgb background = {1, 1, 1});

// A perceptually ordered colour map (dark blue → green → yellow) for s in [0, 1].
Rgb colour_map(double s);

// A height field over the mesh as a 3D surface: each triangle of order k split into k² flat
// ones over its nodes; vertices (x, −y, z[node]) so that the drawing reads the right way up.
// Wavefront OBJ or ASCII PLY text.
std::string surface_obj(const io::HighOrderMesh& mesh, const std::vector<double>& z);
std::string surface_ply(const io::HighOrderMesh& mesh, const std::vector<double>& z);

// Throws io::OutputError when the file cannot be written.
void write_png(const Image& image, const std::string& path);

}  // namespace curvemesh::fem
