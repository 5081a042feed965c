#include "io/svg_writer.hpp"

#include <algorithm>
#include <charconv>

namespace curvemesh::io {

SvgWriter::SvgWriter(const geometry::Box2& extent) {
  geometry::Box2 box = extent;
  if (box.empty()) box.add(geometry::Vec2(0, 0)), box.add(geometry::Vec2(1, 1));
  double margin = 0.02 * box.diagonal();
  if (!(margin > 0)) margin = 1.0;
  dot_radius_ = 0.003 * (box.diagonal() + margin);
  out_ = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"";
  number(box.min.x() - margin);
  out_ += ' ';
  number(box.min.y() - margin);
  out_ += ' ';
  number(box.width() + 2 * margin);
  out_ += ' ';
  number(box.height() + 2 * margin);
  out_ += "\" width=\"1000\" height=\"";
  const double aspect = (box.height() + 2 * margin) / (box.width() + 2 * margin);
  number(std::max(1.0, std::min(100000.0, 1000.0 * aspect)));
  out_ += "\">\n<g fill=\"none\" stroke-width=\"";
  number(box.diagonal() > 0 ? box.diagonal() / 1000 : 0.001);
  out_ += "\" stroke-linecap=\"round\">\n";
}

void SvgWriter::number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out_.append(buf, r.ptr);
}

void SvgWriter::path_start(std::string_view colour) {
  out_ += "<path stroke=\"";
  out_ += colour;
  out_ += "\" d=\"M";
}

void SvgWriter::cubic(const geometry::CubicBezier& c, std::string_view colour) {
  piece({3, {c.p[0], c.p[1], c.p[2], c.p[3]}}, colour);
}

void SvgWriter::command(const BezierPiece& c) {
  out_ += c.degree == 1 ? " L" : c.degree == 2 ? " Q" : " C";
  for (int i = 1; i <= c.degree; ++i) {
    out_ += ' ';
    number(c.p[i].x());
    out_ += ' ';
    number(c.p[i].y());
  }
}

void SvgWriter::piece(const BezierPiece& c, std::string_view colour) {
  path_start(colour);
  out_ += ' ';
  number(c.p[0].x());
  out_ += ' ';
  number(c.p[0].y());
  command(c);
  out_ += "\"/>\n";
}

void SvgWriter::segment(const geometry::Vec2& a, const geometry::Vec2& b, std::string_view colour) {
  path_start(colour);
  out_ += ' ';
  number(a.x());
  out_ += ' ';
  number(a.y());
  out_ += " L ";
  number(b.x());
  out_ += ' ';
  number(b.y());
  out_ += "\"/>\n";
}

void SvgWriter::dot(const geometry::Vec2& p, std::string_view colour) {
  out_ += "<circle stroke=\"none\" fill=\"";
  out_ += colour;
  out_ += "\" cx=\"";
  number(p.x());
  out_ += "\" cy=\"";
  number(p.y());
  out_ += "\" r=\"";
  number(dot_radius_);
  out_ += "\"/>\n";
}

void SvgWriter::filled(const std::vector<BezierPiece>& boundary, std::string_view fill) {
  if (boundary.empty()) return;
  out_ += "<path stroke=\"none\" fill=\"";
  out_ += fill;
  out_ += "\" d=\"M ";
  number(boundary[0].p[0].x());
  out_ += ' ';
  number(boundary[0].p[0].y());
  for (const BezierPiece& c : boundary) command(c);
  out_ += " Z\"/>\n";
}

std::string SvgWriter::finish() {
  out_ += "</g>\n</svg>\n";
  return std::move(out_);
}

}  // namespace curvemesh::io
