#include "base/files.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>

namespace curvemesh::base {

namespace {

std::string reason(int error) {
  return std::strerror(error);
}

// What a file that is not a regular one is, for messages.
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

// A file descriptor closed when it goes out of scope.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  // close(2)'s own result: a write that failed late (NFS, a quota) shows here.
  int close() {
    const int r = ::close(fd_);
    fd_ = -1;
    return r;
  }

 private:
  int fd_;
};

// All of `content` into `fd`; 0, or the errno of the write that failed.
int write_all(int fd, std::string_view content) {
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    if (n == 0) return EIO;
    done += static_cast<std::size_t>(n);
  }
  return 0;
}

// PATH.tmp. and 12 characters from the kernel's random source: not guessable by another user, and
// created with O_EXCL, so even a guessed name planted as a link fails the open instead of being
// followed. Returns the descriptor and sets `name`.
int create_temporary(const std::string& path, std::string& name) {
  static constexpr char kAlphabet[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  for (int attempt = 0; attempt < 64; ++attempt) {
    unsigned char bytes[12];
    if (::getrandom(bytes, sizeof bytes, 0) != static_cast<ssize_t>(sizeof bytes)) return -1;
    name = path + ".tmp.";
    for (unsigned char b : bytes) name += kAlphabet[b % 36];
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

// Whether `path` is written in place rather than replaced: a device or a FIFO, or a link to one
// that its owner (root or this user) made. Throws for what cannot be an output at all.
bool written_in_place(const std::string& path) {
  struct stat link {};
  if (::lstat(path.c_str(), &link) != 0) return false;  // nothing there (or the open will say why)
  if (S_ISDIR(link.st_mode) || S_ISSOCK(link.st_mode))
    throw OutputError(path + ": cannot write: it is " + kind_of(link.st_mode));
  if (S_ISCHR(link.st_mode) || S_ISBLK(link.st_mode) || S_ISFIFO(link.st_mode)) return true;
  if (!S_ISLNK(link.st_mode)) return false;
  struct stat target {};
  if (::stat(path.c_str(), &target) != 0) return false;
  const bool device = S_ISCHR(target.st_mode) || S_ISBLK(target.st_mode) || S_ISFIFO(target.st_mode);
  return device && (link.st_uid == 0 || link.st_uid == ::geteuid());
}

void write_in_place(const std::string& path, std::string_view content) {
  Descriptor fd(::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) throw OutputError(path + ": cannot write (" + reason(errno) + ")");
  struct stat st {};
  // Replaced by a regular file since add() looked: it would be written over, not replaced.
  if (::fstat(fd.get(), &st) != 0 || S_ISREG(st.st_mode) || S_ISDIR(st.st_mode))
    throw OutputError(path + ": cannot write: it changed while the run went on");
  if (const int e = write_all(fd.get(), content)) throw OutputError(path + ": cannot write (" + reason(e) + ")");
  if (fd.close() != 0) throw OutputError(path + ": cannot write (" + reason(errno) + ")");
}

// A string of `size` zero bytes whose pages are mapped in one call: touching them one by one, as
// filling the string does, costs a page fault each (1.5 µs on a virtual machine; 30 for the
// 122 kB of a small mesh, a sixth of reading it). Where the kernel does not know the advice
// (before Linux 5.14), the pages fault as before.
std::string zeros_mapped_at_once(std::size_t size) {
  std::string text;
  text.reserve(size);
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto at = reinterpret_cast<std::uintptr_t>(text.data());
  const std::uintptr_t first = (at + page - 1) / page * page, last = (at + size) / page * page;
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);
  text.resize(size);
  return text;
}

}  // namespace

std::string mebibytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g MiB", double(bytes) / (1024.0 * 1024.0));
  return text;
}

std::string read_input_file(const std::string& path, std::uint64_t max_bytes, const std::string& limit_option) {
  Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) throw InputFileError(path + ": cannot open the file (" + reason(errno) + ")");
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw InputFileError(path + ": cannot read the file (" + reason(errno) + ")");
  if (!S_ISREG(st.st_mode)) throw InputFileError(path + ": is " + kind_of(st.st_mode) + ", not a regular file");
  const auto too_large = [&](std::uint64_t size) {
    return InputFileError(path + ": the file is larger than the limit of " + mebibytes(max_bytes) + " (" +
                          mebibytes(size) + (limit_option.empty() ? "" : "; " + limit_option + " raises it") + ")");
  };
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) throw too_large(static_cast<std::uint64_t>(st.st_size));
  std::string text = zeros_mapped_at_once(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  for (;;) {
    // Past the size fstat gave (the end, or a file that grows while it is read, or one whose size
    // the kernel does not know), look for more in a small buffer: making room by doubling the text
    // first cost as much as reading a large file.
    std::array<char, 4096> more;
    const bool past_size = done == text.size();
    const ssize_t n = past_size ? ::read(fd.get(), more.data(), more.size())
                                : ::read(fd.get(), text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputFileError(path + ": cannot read the file (" + reason(errno) + ")");
    if (n == 0) break;
    if (past_size) text.append(more.data(), static_cast<std::size_t>(n));
    done += static_cast<std::size_t>(n);
    if (done > max_bytes) throw too_large(done);  // it grew while being read
  }
  text.resize(done);
  return text;
}

OutputFiles::~OutputFiles() {
  discard();
}

void OutputFiles::add(const std::string& path, std::string_view content) {
  if (path.empty()) throw OutputError("an output's path is empty");
  if (written_in_place(path)) {
    pending_.push_back({path, "", std::string(content)});
    return;
  }
  Pending p{path, "", ""};
  Descriptor fd(create_temporary(path, p.temporary));
  if (fd.get() < 0) throw OutputError(path + ": cannot write (" + reason(errno) + ")");
  int error = write_all(fd.get(), content);
  if (fd.close() != 0 && !error) error = errno;
  if (error) {
    ::unlink(p.temporary.c_str());
    throw OutputError(path + ": cannot write (" + reason(error) + ")");
  }
  pending_.push_back(std::move(p));
}

void OutputFiles::commit() {
  try {
    // Devices first: the likeliest to fail (a full disk behind them), and nothing renamed yet.
    for (const Pending& p : pending_)
      if (p.temporary.empty()) write_in_place(p.path, p.content);
    for (Pending& p : pending_) {
      if (p.temporary.empty()) continue;
      if (::rename(p.temporary.c_str(), p.path.c_str()) != 0)
        throw OutputError(p.path + ": cannot write (" + reason(errno) + ")");
      committed_.push_back(p.path);
      p.temporary.clear();
    }
  } catch (const OutputError&) {
    for (const std::string& path : committed_) ::unlink(path.c_str());
    committed_.clear();
    discard();
    throw;
  }
  pending_.clear();
  committed_.clear();
}

void OutputFiles::discard() {
  for (const Pending& p : pending_)
    if (!p.temporary.empty()) ::unlink(p.temporary.c_str());
  pending_.clear();
}

void write_file_atomically(const std::string& path, std::string_view content) {
  OutputFiles out;
  out.add(path, content);
  out.commit();
}

bool is_temporary_of(std::string_view file, std::string_view name) {
  constexpr std::string_view kMark = ".tmp.";
  if (file.size() <= name.size() + kMark.size() || file.substr(0, name.size()) != name ||
      file.substr(name.size(), kMark.size()) != kMark)
    return false;
  const std::string_view suffix = file.substr(name.size() + kMark.size());
  return suffix.find_first_not_of("0123456789abcdefghijklmnopqrstuvwxyz") == std::string_view::npos;
}

std::string output_clash(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  namespace fs = std::filesystem;
  struct Identity {
    dev_t dev;
    ino_t ino;
    bool operator<(const Identity& o) const { return dev != o.dev ? dev < o.dev : ino < o.ino; }
  };
  std::vector<std::pair<Identity, const NamedPath*>> read;
  for (const NamedPath& in : inputs) {
    struct stat st {};
    if (::stat(in.second.c_str(), &st) == 0) read.push_back({{st.st_dev, st.st_ino}, &in});
  }
  std::map<std::string, const NamedPath*> written;  // file -> the output that names it
  for (const NamedPath& out : outputs) {
    struct stat st {};
    bool character_device = false;
    std::string key;
    for (const bool follow : {false, true}) {
      if ((follow ? ::stat(out.second.c_str(), &st) : ::lstat(out.second.c_str(), &st)) != 0) continue;
      for (const auto& [identity, in] : read)
        if (identity.dev == st.st_dev && identity.ino == st.st_ino)
          return out.first + " " + out.second + " is the same file as the " + in->first + " " + in->second +
                 ": refusing to write over an input";
      character_device = S_ISCHR(st.st_mode);
      key = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
    }
    if (character_device) continue;  // -o /dev/null --vtu /dev/null is harmless
    if (key.empty()) {
      std::error_code ec;
      key = fs::weakly_canonical(fs::absolute(out.second, ec), ec).string();
    }
    if (const auto [it, added] = written.emplace(key, &out); !added)
      return it->second->first + " " + it->second->second + " and " + out.first + " " + out.second +
             " name the same file";
  }
  return {};
}

}  // namespace curvemesh::base
