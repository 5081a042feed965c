#pragma once
// Files as a careful Unix tool treats them. Inputs: regular files only (a FIFO, a device or a
// folder is refused before it is read, so /dev/zero or a FIFO without a writer cannot hang a run),
// of a bounded size. Outputs: written all or nothing, never through a link planted at a temporary
// name, never over an input.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace curvemesh::base {

// An input file that cannot be read, is not a regular file, or is larger than allowed. what()
// starts with the path.
class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output that cannot be written. what() names the path and the reason.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `bytes` as the messages about sizes say it ("64 MiB").
std::string mebibytes(std::uint64_t bytes);

// The whole of a regular file of at most `max_bytes` bytes (beyond it, the message names
// `limit_option`, the option that raises the limit, when there is one). Opened without blocking (a FIFO is refused,
// not waited on) and read through the descriptor that was checked.
std::string read_input_file(const std::string& path, std::uint64_t max_bytes, const std::string& limit_option);

// Outputs written together or not at all. add() writes each to a temporary file created
// exclusively beside its target (PATH.tmp.RANDOM, O_EXCL|O_NOFOLLOW: a link planted there is
// never followed); commit() renames them into place. A target that is a device or a FIFO (or a
// link to one owned by root or by the user, as /dev/stdout) is written in place at commit, its
// errors reported (ENOSPC from /dev/full); a folder or a socket is refused; a link to anything
// else is replaced, never written through. Destroyed before commit(), or when commit() fails,
// nothing is left of any of them.
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  // Throws OutputError; what was added before stays pending.
  void add(const std::string& path, std::string_view content);
  // Throws OutputError after taking back every output of this set.
  void commit();

 private:
  struct Pending {
    std::string path;
    std::string temporary;  // empty: written in place at commit
    std::string content;    // kept for those written in place only
  };
  void discard();
  std::vector<Pending> pending_;
  std::vector<std::string> committed_;
};

// One output, all or nothing (an OutputFiles of one).
void write_file_atomically(const std::string& path, std::string_view content);

// Whether `file` is what OutputFiles leaves beside NAME when its process is killed between
// writing and renaming: NAME.tmp. and a suffix of [0-9a-z] (12 random characters; the digits of a
// process id in files left by earlier versions).
bool is_temporary_of(std::string_view file, std::string_view name);

// A path given on the command line with the option that named it ("-o", "--svg", "input").
using NamedPath = std::pair<std::string, std::string>;

// The first clash among the files a run would read and write: an output that is the same file as
// an input (same device and inode, through any link or spelling), or two outputs naming the same
// file. The message says which; empty when there is none.
std::string output_clash(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace curvemesh::base
