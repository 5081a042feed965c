#pragma once
// CURVEMESH_API marks what the shared library libcurvemesh exports. The library is built with
// hidden visibility, so that a program linking it sees the public API (curvemesh.hpp,
// parameters.hpp) and nothing of the engine underneath (its stages, CGAL, Eigen, GMP).
#if defined(__GNUC__) || defined(__clang__)
#define CURVEMESH_API __attribute__((visibility("default")))
#else
#define CURVEMESH_API
#endif
