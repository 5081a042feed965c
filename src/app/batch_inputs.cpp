// The drawings of `curvemesh batch`: expanding the inputs, naming the outputs, sharding.
#include "app/batch_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>

#include "app/batch_error.hpp"
#include "app/commands.hpp"
#include "base/files.hpp"

namespace curvemesh::app::batch {

namespace {

bool has_extension(const fs::path& p, std::string_view ext) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e == ext;
}

// A drawing by its name: .svg, or .svgz (gzip-compressed).
bool is_drawing(const fs::path& p) {
  return has_extension(p, ".svg") || has_extension(p, ".svgz");
}

// Every *.svg and *.svgz below `root`; outputs mirror the folders below it.
void add_directory(const fs::path& root, std::vector<Drawing>& out) {
  std::error_code ec;
  fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    std::error_code regular;
    if (is_drawing(it->path()) && it->is_regular_file(regular))
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
  // A list of a whole collection is under a megabyte; a FIFO or /dev/zero given as one is refused.
  constexpr std::uint64_t kMaxListBytes = std::uint64_t(1) << 30;
  std::istringstream in;
  try {
    in.str(base::read_input_file(list.string(), kMaxListBytes, ""));
  } catch (const base::InputFileError& e) {
    throw BatchError(kInvalidInput, std::string("curvemesh: ") + e.what() + " (a list of drawings)");
  }
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

// The names in `folder`; none when it does not exist, nothing known when it cannot be read.
std::optional<std::set<std::string>> names_in(const fs::path& folder) {
  std::error_code ec;
  std::set<std::string> names;
  fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec);
  for (; !ec && it != fs::directory_iterator(); it.increment(ec))
    names.insert(it->path().filename().string());
  if (ec == std::errc::no_such_file_or_directory) return names;
  if (ec) return std::nullopt;
  return names;
}

std::uint64_t fnv1a(std::string_view s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace

Inputs expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<Drawing> out;
  std::vector<std::string> lists;
  for (const std::string& input : inputs) {
    const fs::path p = fs::path(input).lexically_normal();
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);
    if (!fs::exists(st)) throw BatchError(kUsage, "curvemesh: " + input + ": no such file or folder");
    if (fs::is_directory(st))
      add_directory(p, out);
    else if (is_drawing(p) || has_extension(p, ".poly"))
      out.push_back({p.string(), p.filename(), {}, {}});
    else {
      add_list(p, out);
      lists.push_back(input);
    }
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
  return {std::move(unique), std::move(lists)};
}

// Output names. Two inputs can collide (a.svg from two folders given as files, x.svg beside x.poly
// or x.svgz): those get a suffix hashed from their own path, not from
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

// Only a file that exists can be an input, and a folder's listing says which outputs exist at the
// cost of a few system calls, where a stat and a canonical path per output cost some seventeen:
// over a network file system, seconds to minutes before a run of 8,000 drawings starts. So the
// outputs compared are the report, those that exist, and those of the report's name (`--report
// OUTDIR/a.json` must not meet a.svg's statistics). Outputs that do not exist yet are distinct by
// construction (assign_outputs).
std::string output_clash(const Inputs& inputs, const std::vector<Drawing>& mine, const fs::path& report) {
  std::vector<base::NamedPath> read, written;
  read.reserve(inputs.drawings.size() + inputs.lists.size());
  for (const Drawing& d : inputs.drawings) read.emplace_back("drawing", d.path);
  for (const std::string& list : inputs.lists) read.emplace_back("list", list);
  written.emplace_back("report", report.string());
  std::map<fs::path, std::optional<std::set<std::string>>> listed;  // folder -> its files' names
  const auto may_exist = [&](const fs::path& p) {
    auto [it, added] = listed.try_emplace(p.parent_path());
    if (added) it->second = names_in(p.parent_path());
    return !it->second || it->second->count(p.filename().string()) > 0;
  };
  for (const Drawing& d : mine)
    for (const auto& [what, path] : {std::pair{"mesh", &d.msh}, std::pair{"statistics", &d.stats}})
      if (path->filename() == report.filename() || may_exist(*path))
        written.emplace_back(what, path->string());
  return base::output_clash(read, written);
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
