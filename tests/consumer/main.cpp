// A consumer of the installed library: `app DRAWING.svg OUT.msh` meshes the drawing with the
// default parameters, prints its counts, writes the .msh, certifies the mesh and the file, and
// makes sure a broken drawing and bad parameters come back as curvemesh::Error. Exits 1 on any
// failure.
#include <curvemesh/curvemesh.hpp>
#include <exception>
#include <iostream>
#include <string>

namespace {

int failures = 0;

void expect(bool ok, const std::string& what) {
  if (!ok) {
    std::cerr << "app: FAILED: " << what << "\n";
    ++failures;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: app DRAWING.svg OUT.msh\n";
    return 2;
  }
  try {
    std::cout << "curvemesh " << curvemesh::version() << "\n";
    const curvemesh::Mesh m = curvemesh::mesh_file(argv[1]);
    std::size_t per_tag[3] = {0, 0, 0};
    for (curvemesh::LineTag t : m.line_tags()) ++per_tag[static_cast<int>(t)];
    std::cout << m.node_count() << " nodes, " << m.triangle_count() << " triangles of "
              << m.nodes_per_triangle() << " nodes, " << m.line_count() << " lines (";
    for (int t = 0; t < 3; ++t)
      std::cout << (t ? ", " : "") << per_tag[t] << " "
                << curvemesh::tag_name(static_cast<curvemesh::LineTag>(t));
    std::cout << ")\n";
    expect(m.order() == 3 && m.nodes_per_triangle() == 10 && m.nodes_per_line() == 4, "a cubic mesh");
    expect(m.triangle_count() > 0 && m.triangles().size() == 10 * m.triangle_count(),
           "10 nodes per triangle");
    expect(m.lines().size() == 4 * m.line_count() && m.line_curves().size() == m.line_count(),
           "4 nodes per line");
    for (std::int64_t id : m.triangles())
      if (id < 0 || id >= static_cast<std::int64_t>(m.node_count())) {
        expect(false, "node ids in range");
        break;
      }

    m.write(argv[2]);
    const curvemesh::CheckReport mesh = curvemesh::check(m), file = curvemesh::check_file(argv[2]);
    std::cout << "check: " << file.triangles << " triangles, " << file.invalid
              << " invalid, min scaled Jacobian " << file.min_scaled_jacobian << "\n";
    expect(mesh.invalid == 0 && file.invalid == 0, "no invalid element");
    expect(file.triangles == m.triangle_count() && file.order == 3, "the file holds the mesh");
    expect(file.min_scaled_jacobian == mesh.min_scaled_jacobian, "the file checks as the mesh");
  } catch (const curvemesh::Error& e) {
    std::cerr << "app: curvemesh::Error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "app: not a curvemesh::Error: " << e.what() << "\n";
    return 1;
  }

  // Failures cross the library's boundary as curvemesh::Error, with their kind.
  try {
    curvemesh::mesh_svg("<svg", {}, "broken.svg");
    expect(false, "a broken SVG is refused");
  } catch (const curvemesh::Error& e) {
    std::cout << "broken SVG: " << e.what() << "\n";
    expect(e.kind() == curvemesh::Error::Kind::invalid_input, "a broken SVG is invalid input");
  }
  try {
    curvemesh::Parameters p;
    p.epsilon_rel = p.mu_rel / 2;
    p.validate();
    expect(false, "--epsilon below --mu is refused");
  } catch (const curvemesh::Error& e) {
    std::cout << "bad parameters: " << e.what() << "\n";
    expect(e.kind() == curvemesh::Error::Kind::invalid_parameters, "bad parameters are invalid_parameters");
  }
  return failures ? 1 : 0;
}
