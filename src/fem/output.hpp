#pragma once
// Looking at solutions: a field's values at the mesh nodes (for VTU point data), pictures of a
// field over the drawing's box (each pixel centre located in its triangle through the inverse
// of the triangle's map, so curved triangles are drawn curved), and PNG files (libpng).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
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

// The most pixels a picture may have (8192 x 8192): its memory, 4 bytes a pixel, stays at 256 MB.
inline constexpr std::int64_t kMaxPicturePixels = std::int64_t(1) << 26;

// The width and height of the picture of `view` at `width` pixels across (the height as the
// drawing's aspect gives it, at most kMaxPicturePixels).
std::pair<int, int> picture_size(const geometry::Box2& view, int width);

// The picture of `view` (the drawing's user space, y down as in SVG) at `width` pixels across:
// every pixel whose centre lies in a triangle takes colour(t, ξ); the others `background`.
// Throws std::length_error above kMaxPicturePixels (callers check picture_size first).
Image rasterize(const Geometry& geometry, const geometry::Box2& view, int width,
                const std::function<Rgb(int t, const Vec2& xi)>& colour, Rgb background = {1, 1, 1});

// A perceptually ordered colour map (dark blue → green → yellow) for s in [0, 1].
Rgb colour_map(double s);

// A height field over the mesh as a 3D surface: each triangle of order k split into k² flat
// ones over its nodes; vertices (x, −y, z[node]) so that the drawing reads the right way up.
// Wavefront OBJ or ASCII PLY text.
std::string surface_obj(const io::HighOrderMesh& mesh, const std::vector<double>& z);
std::string surface_ply(const io::HighOrderMesh& mesh, const std::vector<double>& z);

// The picture as a PNG file's bytes. Throws std::runtime_error when libpng fails.
std::string png_bytes(const Image& image);

}  // namespace curvemesh::fem
