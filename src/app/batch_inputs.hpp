#pragma once
// The drawings of `curvemesh batch`: the inputs (files, folders, list files) expanded into one
// sorted list without repeats, each drawing's output paths under OUTDIR, and the share of them that
// `--shard K/N` runs.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace curvemesh::app::batch {

namespace fs = std::filesystem;

struct Drawing {
  std::string path;   // as given or found (relative stays relative): the report's key and order
  fs::path relative;  // where its output goes under OUTDIR, before the extension becomes .msh
  fs::path msh, stats;
};

struct Inputs {
  std::vector<Drawing> drawings;
  std::vector<std::string> lists;  // the list files read, as given
};

// Every drawing the inputs name, sorted by path, each file once. Throws BatchError when an input
// does not exist or a folder or list cannot be read.
Inputs expand_inputs(const std::vector<std::string>& inputs);

// Sets each drawing's `msh` and `stats` under `output_dir`.
void assign_outputs(std::vector<Drawing>& drawings, const fs::path& output_dir);

// The first output of this run (`report`, and the meshes and statistics of `mine`) that is the
// same file as an input (any drawing, any list) or as another output, said as a message; empty
// when there is none.
std::string output_clash(const Inputs& inputs, const std::vector<Drawing>& mine, const fs::path& report);

// `--shard K/N`: run K of N, K from 1.
struct Shard {
  std::size_t k = 1, n = 1;
};

std::optional<Shard> parse_shard(const std::string& s);

// The drawings of one shard, in their order.
std::vector<Drawing> shard_of(std::vector<Drawing> all, Shard shard);

// Where the report goes when --report does not say.
fs::path default_report_path(const fs::path& output_dir, Shard shard);

}  // namespace curvemesh::app::batch
