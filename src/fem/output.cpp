#include "fem/output.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <tuple>

namespace curvemesh::fem {

double value_at(const Space& space, const Eigen::VectorXd& u, int t, const Vec2& xi, int components, int component) {
  const Eigen::VectorXd phi = space.basis().values(xi);
  const auto d = space.dofs(t);
  double v = 0;
  for (int i = 0; i < space.local_size(); ++i) v += u[std::size_t(d[i]) * components + component] * phi(i);
  return v;
}

std::vector<double> values_at_nodes(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u,
                                    int components) {
  const io::HighOrderMesh& mesh = geometry.mesh();
  std::vector<double> out(mesh.nodes.size() * components, 0.0);
  const std::vector<Vec2> ref = reference_nodes(mesh.order);
  std::vector<Eigen::VectorXd> phi;
  for (const Vec2& xi : ref) phi.push_back(space.basis().values(xi));
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    const auto d = space.dofs(t);
    for (std::size_t k = 0; k < ref.size(); ++k)
      for (int c = 0; c < components; ++c) {
        double v = 0;
        for (int i = 0; i < space.local_size(); ++i) v += u[std::size_t(d[i]) * components + c] * phi[k](i);
        out[std::size_t(tri[k]) * components + c] = v;
      }
  }
  return out;
}

Image rasterize(const Geometry& geometry, const geometry::Box2& view, int width,
                const std::function<Rgb(int t, const Vec2& xi)>& colour, Rgb background) {
  Image img;
  const Vec2 size = view.max - view.min;
  std::tie(img.width, img.height) = picture_size(view, width);
  if (std::int64_t(img.width) * img.height > kMaxPicturePixels)
    throw std::length_error("a picture of more than " + std::to_string(kMaxPicturePixels) + " pixels");
  const double pixel = size.x() / img.width;
  img.rgb.assign(std::size_t(img.width) * img.height * 3, 0);
  std::vector<char> done(std::size_t(img.width) * img.height, 0);
  auto put = [&](int px, int py, const Rgb& c) {
    for (int k = 0; k < 3; ++k)
      img.rgb[(std::size_t(py) * img.width + px) * 3 + k] =
          static_cast<std::uint8_t>(std::lround(255 * std::clamp(c[k], 0.0, 1.0)));
  };
  const io::HighOrderMesh& mesh = geometry.mesh();
  const double tol = 1e-9;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    // The triangle's nodes' box, grown by a quarter: a curved edge bulges less than that beyond
    // its nodes in a valid triangle.
    Vec2 lo = mesh.nodes[mesh.triangle(t)[0]], hi = lo;
    for (int i : mesh.triangle(t)) lo = lo.cwiseMin(mesh.nodes[i]), hi = hi.cwiseMax(mesh.nodes[i]);
    // Beyond a straight side by more than twice its inner nodes' distance from it, a point is
    // outside the curved triangle (a cubic edge through nodes d off its chord strays at most
    // about 1.3 d): such pixels skip the inverse map.
    const auto tri = mesh.triangle(t);
    std::array<double, 3> margin{0, 0, 0};
    const int per_edge = mesh.order - 1;
    for (int e = 0; e < 3 && per_edge > 0; ++e) {
      const Vec2 a = mesh.nodes[tri[e]], b = mesh.nodes[tri[(e + 1) % 3]];
      const Vec2 n = Vec2(b.y() - a.y(), a.x() - b.x()).normalized();
      for (int k = 0; k < per_edge; ++k)
        margin[e] = std::max(margin[e], 2 * std::abs(n.dot(mesh.nodes[tri[3 + per_edge * e + k]] - a)));
    }
    auto far_outside = [&](const Vec2& x) {
      // Counter-clockwise corners: the inside is to the left of each side.
      for (int e = 0; e < 3; ++e) {
        const Vec2 a = mesh.nodes[tri[e]], b = mesh.nodes[tri[(e + 1) % 3]];
        const Vec2 d = b - a;
        const double left = (d.x() * (x.y() - a.y()) - d.y() * (x.x() - a.x())) / d.norm();
        if (left < -margin[e] - 1e-9 * d.norm()) return true;
      }
      return false;
    };
    const Vec2 grow = (hi - lo) * (mesh.order > 1 ? 0.25 : 0.0);
    lo -= grow, hi += grow;
    const int x0 = std::max(0, static_cast<int>(std::floor((lo.x() - view.min.x()) / pixel - 0.5)));
    const int x1 = std::min(img.width - 1, static_cast<int>(std::ceil((hi.x() - view.min.x()) / pixel - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor((lo.y() - view.min.y()) / pixel - 0.5)));
    const int y1 = std::min(img.height - 1, static_cast<int>(std::ceil((hi.y() - view.min.y()) / pixel - 0.5)));
    for (int py = y0; py <= y1; ++py)
      for (int px = x0; px <= x1; ++px) {
        if (done[std::size_t(py) * img.width + px]) continue;
        const Vec2 x(view.min.x() + (px + 0.5) * pixel, view.min.y() + (py + 0.5) * pixel);
        if (far_outside(x)) continue;
        Vec2 xi;
        if (!geometry.inverse(t, x, xi)) continue;
        if (xi.x() < -tol || xi.y() < -tol || xi.x() + xi.y() > 1 + tol) continue;
        put(px, py, colour(t, xi));
        done[std::size_t(py) * img.width + px] = 1;
      }
  }
  for (int py = 0; py < img.height; ++py)
    for (int px = 0; px < img.width; ++px)
      if (!done[std::size_t(py) * img.width + px]) put(px, py, background);
  return img;
}

Rgb colour_map(double s) {
  // Piecewise-linear through samples of a viridis-like ramp.
  static constexpr Rgb stops[] = {{0.267, 0.005, 0.329}, {0.230, 0.322, 0.546}, {0.128, 0.567, 0.551},
                                  {0.369, 0.789, 0.383}, {0.993, 0.906, 0.144}};
  if (!std::isfinite(s)) s = 0;
  s = std::clamp(s, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(s));
  const double f = s - i;
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = (1 - f) * stops[i][k] + f * stops[i + 1][k];
  return c;
}

namespace {

// The flat triangles of the surface, as node triples (counter-clockwise after y → −y).
std::vector<std::array<int, 3>> flat_triangles(const io::HighOrderMesh& mesh) {
  const int k = mesh.order;
  // Node of the lattice point (i, j) (ξ = i/k, η = j/k) in Gmsh's order.
  auto local = [k](int i, int j) {
    if (j == 0) return i == 0 ? 0 : i == k ? 1 : 2 + i;                 // edge 0→1
    if (i + j == k) return j == k ? 2 : 3 + (k - 1) + (j - 1);           // edge 1→2
    if (i == 0) return 3 + 2 * (k - 1) + (k - 1 - j);                     // edge 2→0
    return 3 * k;                                                         // the centre (k = 3)
  };
  std::vector<std::array<int, 3>> out;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int j = 0; j < k; ++j)
      for (int i = 0; i + j < k; ++i) {
        // Reversed (a, c, b): the y flip mirrors the plane.
        out.push_back({tri[local(i, j)], tri[local(i, j + 1)], tri[local(i + 1, j)]});
        if (i + j + 1 < k) out.push_back({tri[local(i + 1, j)], tri[local(i, j + 1)], tri[local(i + 1, j + 1)]});
      }
  }
  return out;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

std::string surface_obj(const io::HighOrderMesh& mesh, const std::vector<double>& z) {
  std::string s = "# curvemesh surface: x, -y, height\n";
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    s += "v " + num(mesh.nodes[i].x()) + " " + num(-mesh.nodes[i].y()) + " " + num(z[i]) + "\n";
  for (const auto& f : flat_triangles(mesh))
    s += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " + std::to_string(f[2] + 1) + "\n";
  return s;
}

std::string surface_ply(const io::HighOrderMesh& mesh, const std::vector<double>& z) {
  const auto faces = flat_triangles(mesh);
  std::string s = "ply\nformat ascii 1.0\ncomment curvemesh surface: x, -y, height\nelement vertex " +
                  std::to_string(mesh.nodes.size()) + "\nproperty double x\nproperty double y\nproperty double z\n" +
                  "element face " + std::to_string(faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    s += num(mesh.nodes[i].x()) + " " + num(-mesh.nodes[i].y()) + " " + num(z[i]) + "\n";
  for (const auto& f : faces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  return s;
}

namespace {

// libpng's sink: the bytes appended to the string it was given.
void append_png(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}

}  // namespace

std::string png_bytes(const Image& image) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng failed to start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng failed to encode the picture");
  }
  png_set_write_fn(png, &out, &append_png, nullptr);
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<png_bytep>(image.rgb.data() + std::size_t(y) * image.width * 3));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

std::pair<int, int> picture_size(const geometry::Box2& view, int width) {
  const geometry::Vec2 size = view.max - view.min;
  const int w = std::max(1, width);
  const double pixel = size.x() / w;
  const double h = size.y() / pixel;
  if (!(h < double(kMaxPicturePixels))) return {w, static_cast<int>(kMaxPicturePixels)};  // NaN too
  return {w, std::max(1, static_cast<int>(std::lround(h)))};
}

}  // namespace curvemesh::fem
