#pragma once
// What a curvemesh::Mesh holds: the pipeline's result (so that Mesh::write goes through the very
// writers the command line uses) and the arrays the accessors give out, made once. Also the one
// place where every other exception becomes curvemesh::Error.
#include <curvemesh/curvemesh.hpp>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/output_file.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh {

struct Mesh::Impl {
  std::optional<pipeline::Result> result;  // none in the empty Impl a default-constructed Mesh reads
  int order = 0;
  std::vector<std::array<double, 2>> nodes;
  std::vector<std::int64_t> triangles;
  std::vector<std::int64_t> lines;
  std::vector<LineTag> line_tags;
  std::vector<std::int64_t> line_curves;
  std::vector<int> triangle_groups;
  std::vector<std::vector<int>> line_groups;
  std::vector<Group> groups;
  std::string stats_json;
  std::vector<std::string> warnings;
  std::string input_path;  // the file it was read from (none for text or curves): never written over
};

// The Mesh of a finished pipeline result (one that ran to its last stage).
Mesh make_mesh(std::shared_ptr<const Mesh::Impl> impl);
std::shared_ptr<const Mesh::Impl> mesh_impl(pipeline::Result result, std::string input_path = {});

namespace api {

// Runs f, letting curvemesh::Error through and turning anything else into one: a writer's
// io::OutputError into Kind::output, memory running out into Kind::invalid_input, the rest (a bug)
// into Kind::internal with the message the command line prints for it.
template <class F>
decltype(auto) translate_errors(F&& f) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const io::OutputError& e) {
    throw Error(Error::Kind::output, e.what());
  } catch (const std::bad_alloc&) {
    // A drawing too large for the memory there is, within the Limits: the input's cost, not a bug.
    throw Error(Error::Kind::invalid_input, "out of memory (std::bad_alloc): the drawing needs more memory than "
                                            "there is; lower the Limits to refuse such drawings sooner");
  } catch (const std::exception& e) {
    throw Error(Error::Kind::internal, std::string("internal error (this is a bug): ") + e.what());
  } catch (...) {
    throw Error(Error::Kind::internal, "internal error (this is a bug): an unknown exception");
  }
}

}  // namespace api
}  // namespace curvemesh
