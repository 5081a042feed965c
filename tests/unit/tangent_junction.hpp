// A drawing with a junction whose chords and tangents disagree: two arcs of 60° leave (0, 0) at
// a small angle from each other and turn apart (one clockwise, one counter-clockwise), inside a
// frame ten times their size. Their first pieces' chords open wider than the angle between
// their tangents, which is the angle curved edges leave (0, 0) at.
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/vec2.hpp"

namespace curvemesh::testing_support {

// The control points of the six cubics: the two arcs first, then the frame's sides (straight).
inline std::vector<std::array<geometry::Vec2, 4>> tangent_junction(double degrees) {
  using geometry::Vec2;
  const double r = 10, turn = std::numbers::pi / 3, k = 4.0 / 3.0 * std::tan(turn / 4) * r;
  const double a = degrees * std::numbers::pi / 180;
  // Clockwise from (0, 0), heading along +x, about the centre (0, -r).
  const Vec2 end(r * std::sin(turn), -r + r * std::cos(turn)), heading(std::cos(turn), -std::sin(turn));
  const std::array<Vec2, 4> down{Vec2(0, 0), Vec2(k, 0), end - k * heading, end};
  std::array<Vec2, 4> up;  // mirrored, then turned by the angle
  for (int i = 0; i < 4; ++i) {
    const Vec2 m(down[i].x(), -down[i].y());
    up[i] = Vec2(std::cos(a) * m.x() - std::sin(a) * m.y(), std::sin(a) * m.x() + std::cos(a) * m.y());
  }
  std::vector<std::array<Vec2, 4>> curves{down, up};
  const Vec2 c[4] = {{-50, -50}, {50, -50}, {50, 50}, {-50, 50}};
  for (int i = 0; i < 4; ++i) {
    const Vec2 p = c[i], q = c[(i + 1) % 4];
    curves.push_back({p, (2 * p + q) / 3, (p + 2 * q) / 3, q});
  }
  return curves;
}

}  // namespace curvemesh::testing_support
