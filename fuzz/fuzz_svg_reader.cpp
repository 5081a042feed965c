// libFuzzer target for the SVG reader: any byte string must either read or be refused with an
// InputError; anything else (a crash, a sanitizer report, another exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "svg/error.hpp"
#include "svg/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvemesh::svg::ReadOptions options;
  // Smaller limits keep each run fast; the code paths are the same.
  options.max_curves = 200'000;
  options.max_elements = 200'000;
  options.max_entity_expansion = 1u << 20;
  options.degenerate_tolerance_rel = 1e-8;  // the default epsilon_m
  try {
    const auto soup =
        curvemesh::svg::read_svg(std::string_view(reinterpret_cast<const char*>(data), size), options, "fuzz.svg");
    (void)soup.bounds();
  } catch (const curvemesh::svg::InputError&) {
  }
  return 0;
}
