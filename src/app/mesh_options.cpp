#include "app/mesh_options.hpp"

#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string>
#include <string_view>

#include "app/messages.hpp"

namespace curvemesh::app {

namespace {

// The default of an option as --help shows it.
std::string default_text(const ParameterOption& o) {
  const double v = o.get(Parameters{});
  if (o.kind == ParameterOption::Kind::choice) return o.choices.at(static_cast<std::size_t>(v));
  std::ostringstream s;
  s << v;
  return s.str();
}

// The checks CLI11 shows beside an option: the same ranges Parameters::validate holds it to.
CLI::Validator range_of(const ParameterOption& o) {
  if (o.min == 0 && std::isinf(o.max)) return o.min_open ? CLI::PositiveNumber : CLI::NonNegativeNumber;
  return CLI::Range(o.min, o.max);
}

// One option of the table, registered to set its field of `p`.
CLI::Option* add_parameter(CLI::App& cmd, const ParameterOption& o, Parameters& p) {
  switch (o.kind) {
    case ParameterOption::Kind::flag:
      return cmd.add_flag_callback(
          o.names, [&p, set = o.set, v = o.flag_value] { set(p, v); }, o.help);
    case ParameterOption::Kind::choice: {
      std::vector<std::string> names(o.choices.begin(), o.choices.end());
      return cmd
          .add_option_function<std::string>(
              o.names,
              [&p, set = o.set, names](const std::string& name) {
                set(p, double(std::find(names.begin(), names.end(), name) - names.begin()));
              },
              o.help)
          ->default_str(default_text(o))
          ->check(CLI::IsMember(names));
    }
    case ParameterOption::Kind::integer:
      return cmd
          .add_option_function<long long>(
              o.names, [&p, set = o.set](long long v) { set(p, double(v)); }, o.help)
          ->default_str(default_text(o))
          ->check(range_of(o));
    case ParameterOption::Kind::number:
      break;
  }
  return cmd
      .add_option_function<double>(
          o.names, [&p, set = o.set](double v) { set(p, v); }, o.help)
      ->default_str(default_text(o))
      ->check(range_of(o));
}

// The options of the table whose `field` is one of `values`, in the table's order; returns what
// it registered.
std::vector<const CLI::Option*> add_where(CLI::App& cmd, Parameters& p, const char* ParameterOption::*field,
                                          std::initializer_list<std::string_view> values) {
  std::vector<const CLI::Option*> added;
  for (const ParameterOption& o : parameter_options())
    if (std::find(values.begin(), values.end(), std::string_view(o.*field)) != values.end())
      added.push_back(add_parameter(cmd, o, p));
  return added;
}

// The options of these groups.
std::vector<const CLI::Option*> add_groups(CLI::App& cmd, Parameters& p,
                                           std::initializer_list<std::string_view> groups) {
  return add_where(cmd, p, &ParameterOption::group, groups);
}

}  // namespace

void add_memory_limit_option(CLI::App& cmd, double& gigabytes) {
  cmd.add_option(
         "--memory-limit", gigabytes,
         "address space of the run in GB (2^30 bytes; setrlimit RLIMIT_AS): reaching it ends the run with "
         "exit 1, out of memory, and nothing written (default: no limit)")
      ->check(CLI::Range(0.1, 1e6));
}

void limit_memory(double gigabytes) {
  if (!(gigabytes > 0)) return;
  rlimit limit{};
  ::getrlimit(RLIMIT_AS, &limit);
  limit.rlim_cur = std::min<rlim_t>(static_cast<rlim_t>(gigabytes * 1073741824.0), limit.rlim_max);
  ::setrlimit(RLIMIT_AS, &limit);
}

void add_feature_options(CLI::App& cmd, pipeline::Parameters& p) {
  add_groups(cmd, p, {"features", "limits"});
}

std::vector<const CLI::Option*> add_mesh_options(CLI::App& cmd, pipeline::Parameters& p,
                                                 io::MshOptions& msh) {
  std::vector<const CLI::Option*> added = add_groups(cmd, p, {"mesh"});
  added.push_back(
      cmd.add_option("--msh-version", msh.version,
                     "Gmsh file format: 41 (4.1) or 22 (2.2); a line in several physical groups is one "
                     "element of an entity with several physical tags in 4.1, one element per group in 2.2")
          ->capture_default_str()
          ->transform(CLI::CheckedTransformer(
              std::map<std::string, int>{{"4.1", 41}, {"41", 41}, {"2.2", 22}, {"22", 22}})));
  added.push_back(cmd.add_flag("--msh-boundary-only", msh.boundary_only,
                               "the .msh gets only the lines on the border of the meshed domain, each in one "
                               "physical group: the drawn "
                               "element it lies on (the first drawn, when several), else boundary (a side of "
                               "the box). For deal.II, whose "
                               "GridIn::read_msh refuses a line inside the mesh or in two groups; with "
                               "--order 1, as it reads straight "
                               "triangles only"));
  for (const CLI::Option* o : add_groups(cmd, p, {"features", "limits"})) added.push_back(o);
  return added;
}

void add_run_options(CLI::App& cmd, pipeline::Parameters& p) {
  add_groups(cmd, p, {"run"});
}

std::vector<const CLI::Option*> add_batch_run_options(CLI::App& cmd, pipeline::Parameters& p) {
  return add_where(cmd, p, &ParameterOption::option, {"--regions", "--domain"});
}

void add_threads_option(CLI::App& cmd, pipeline::Parameters& p) {
  add_where(cmd, p, &ParameterOption::option, {"--threads"});
}

bool parameters_valid(const pipeline::Parameters& p) {
  try {
    p.validate();
    return true;
  } catch (const Error& e) {
    say(e.what());
    return false;
  }
}

}  // namespace curvemesh::app
