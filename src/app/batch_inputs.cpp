// The drawings of `curvemesh batch`: expanding the inputs, naming the outputs, sharding.
#include "app/batch_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string_view>
#include <system_error>
#include <utility>

#include "app/batch_error.hpp"
#include "app/commands.hpp"

namespace curvemesh::app::batch {

namespace {

bool has_extension(const fs::path& p, std::string_view ext) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e == ext;
}

// Every *.svg below `root`; outputs mirror the folders below it.
void add_directory(const fs::path& root, std::vector<Drawing>& out) {
  std::error_code ec;
  fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    std::error_code regular;
    if (has_extension(it->path(), ".svg") && it->is_regular_file(regular))
      out.push_back({it->path().lexically_normal().string(), it->path().lexically_relative(root), {}, {}});
  }
  if (ec)
    throw BatchError(kInvalidInput,
                     "curvemesh: " + root.string() + ": cannot read the folder (" + ec.message() + ")");
}

// One path per line, '#' starts a comment, relative paths are relative to the list's folder (so a
// list travels with its drawings). Folders listed are searched like folders given; a listed file
// that does not exist stays in: it fails as invalid-input and shows up in the report.
void add_list(const fs::path& list, std::vector<Drawing>& out) {
  std::ifstream in(list);
  if (!in)
    throw BatchError(kInvalidInput,
                     "curvemesh: " + list.string() + ": cannot read the list (" + std::strerror(errno) + ")");
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    line = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
    fs::path p(line);
    if (p.is_relative()) p = list.parent_path() / p;
    p = p.lexically_normal();
    std::error_code ec;
    if (fs::is_directory(p, ec))
      add_directory(p, out);
    else
      out.push_back({p.string(), p.filename(), {}, {}});
  }
}

std::uint64_t fnv1a(std::string_view s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace

std::vector<Drawing> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<Drawing> out;
  for (const std::string& input : inputs) {
    const fs::path p = fs::path(input).lexically_normal();
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);
    if (!fs::exists(st)) throw BatchError(kUsage, "curvemesh: " + input + ": no such file or folder");
    if (fs::is_directory(st))
      add_directory(p, out);
    else if (has_extension(p, ".svg") || has_extension(p, ".poly"))
      out.push_back({p.string(), p.filename(), {}, {}});
    else
      add_list(p, out);
  }
  // Sorted by path, one entry per file (the same file reached twice, by any spelling, is meshed
  // once); the first spelling in sorted order names its output.
  std::stable_sort(out.begin(), out.end(),
                   [](const Drawing& a, const Drawing& b) { return a.path < b.path; });
  std::vector<Drawing> unique;
  std::set<std::string> seen;
  for (Drawing& d : out) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(d.path, ec);
    if (ec) key = fs::absolute(d.path).lexically_normal();
    if (seen.insert(key.string()).second) unique.push_back(std::move(d));
  }
  return unique;
}

// Output names. One folder's drawings never collide, but two inputs can (a.svg from two folders
// given as files, x.svg beside x.poly): those get a suffix hashed from their own path, not from
// their position or the order of the inputs. Names are assigned on the whole sorted list, before
// sharding, so a resumed or sharded run finds the same files.
void assign_outputs(std::vector<Drawing>& drawings, const fs::path& output_dir) {
  const auto msh_name = [](fs::path p) {
    return p.replace_extension(".msh").lexically_normal().generic_string();
  };
  std::map<std::string, int> uses;
  for (const Drawing& d : drawings) ++uses[msh_name(d.relative)];
  std::set<std::string> taken;
  for (std::size_t i = 0; i < drawings.size(); ++i) {
    Drawing& d = drawings[i];
    std::string name = msh_name(d.relative);
    if (uses[name] > 1) {
      char suffix[24];
      std::snprintf(suffix, sizeof suffix, "-%08llx",
                    static_cast<unsigned long long>(fnv1a(d.path) & 0xffffffffull));
      fs::path r = d.relative;
      name = msh_name(r.replace_filename(r.stem().string() + suffix));
    }
    // A hashed name that meets another drawing's own name is practically impossible; the index
    // keeps it deterministic all the same.
    if (!taken.insert(name).second) {
      name = fs::path(name).replace_extension().generic_string() + "-" + std::to_string(i) + ".msh";
      taken.insert(name);
    }
    d.msh = output_dir / fs::path(name);
    d.stats = fs::path(d.msh).replace_extension(".json");
  }
}

std::optional<Shard> parse_shard(const std::string& s) {
  std::size_t k = 0, n = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%zu %c %zu %c", &k, &slash, &n, &extra) != 3 || slash != '/')
    return std::nullopt;
  if (s.find_first_not_of("0123456789/ ") != std::string::npos || n < 1 || k < 1 || k > n)
    return std::nullopt;
  return Shard{k, n};
}

// Every N-th drawing of the whole sorted list, so the shards' reports add up to the whole.
std::vector<Drawing> shard_of(std::vector<Drawing> all, Shard shard) {
  std::vector<Drawing> mine;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (i % shard.n == shard.k - 1) mine.push_back(std::move(all[i]));
  return mine;
}

// Shards may share OUTDIR; by default each writes a report of its own.
fs::path default_report_path(const fs::path& output_dir, Shard shard) {
  return output_dir /
         (shard.n == 1 ? std::string("report.jsonl")
                       : "report-" + std::to_string(shard.k) + "-of-" + std::to_string(shard.n) + ".jsonl");
}

}  // namespace curvemesh::app::batch
