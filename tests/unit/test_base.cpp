// The base layer: text from outside kept well-formed and printable, inputs read only when they are
// regular files of a bounded size, outputs written all or nothing and never through a link.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/files.hpp"
#include "base/text.hpp"

namespace curvemesh::base {
namespace {

namespace fs = std::filesystem;

class Folder {
 public:
  Folder() {
    std::string pattern = (fs::temp_directory_path() / "curvemesh-base-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(path_)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  fs::path path_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void put(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(Utf8, ValidAndMalformedSequences) {
  EXPECT_TRUE(valid_utf8("plain ascii"));
  EXPECT_TRUE(valid_utf8("\xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"));  // été € 😀
  for (const char* bad : {"\xff", "\xc0\xaf", "\xe0\x80\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xc3", "a\x80"})
    EXPECT_FALSE(valid_utf8(bad)) << bad;
}

TEST(Utf8, RepairReplacesEachBadByteAndKeepsTheRest) {
  std::size_t replaced = 0;
  const std::string fixed = repair_utf8("a\xff\xfe\xc3\xa9z", &replaced);
  EXPECT_EQ(fixed, "a\xef\xbf\xbd\xef\xbf\xbd\xc3\xa9z");
  EXPECT_EQ(replaced, 2u);
  EXPECT_TRUE(valid_utf8(fixed));
  EXPECT_EQ(repair_utf8("\xc3\xa9t\xc3\xa9"), "\xc3\xa9t\xc3\xa9");
}

TEST(Printable, EscapesWhatDrivesATerminal) {
  EXPECT_EQ(printable("a\x1b[2Jb"), "a\\x1b[2Jb");
  EXPECT_EQ(printable("line\nbreak\rand\x07" "bell\x7f"), "line\\x0abreak\\x0dand\\x07bell\\x7f");
  EXPECT_EQ(printable("csi \xc2\x9b here"), "csi \\u009b here");  // U+009B, the C1 CSI
  EXPECT_EQ(printable("bad \xff byte"), "bad \\xff byte");
  EXPECT_EQ(printable("tab\tand \xc3\xa9t\xc3\xa9 stay"), "tab\tand \xc3\xa9t\xc3\xa9 stay");
}

TEST(ReadInputFile, ReadsARegularFile) {
  Folder f;
  put(f / "a.svg", "<svg/>");
  EXPECT_EQ(read_input_file(f / "a.svg", 100, "--max-input-mb"), "<svg/>");
}

TEST(ReadInputFile, RefusesWhatIsNotARegularFileWithoutBlocking) {
  Folder f;
  ASSERT_EQ(::mkfifo((f / "fifo").c_str(), 0600), 0);  // no writer: a blocking open would wait forever
  for (const std::string& path : {f / "fifo", std::string("/dev/zero"), f / ""}) {
    try {
      read_input_file(path, 1 << 20, "--max-input-mb");
      ADD_FAILURE() << path << " was read";
    } catch (const InputFileError& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_input_file(f / "missing", 100, ""), InputFileError);
}

TEST(ReadInputFile, RefusesALargerFileNamingTheOption) {
  Folder f;
  put(f / "big", std::string(2000, 'x'));
  try {
    read_input_file(f / "big", 1000, "--max-input-mb");
    ADD_FAILURE() << "a file above the limit was read";
  } catch (const InputFileError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-input-mb raises it"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_input_file(f / "big", 2000, "").size(), 2000u);
}

// The attack on predictable temporaries: a link planted at PATH.tmp.PID (this process's id, what
// the name used to be) to a file of the victim's. Neither it nor its target may change.
TEST(OutputFiles, ALinkPlantedAtTheOldTemporaryNameIsNotFollowed) {
  Folder f;
  put(f / "victim", "precious");
  const std::string planted = f / "out.msh" + ".tmp." + std::to_string(::getpid());
  fs::create_symlink(f / "victim", planted);
  write_file_atomically(f / "out.msh", "mesh");
  EXPECT_EQ(slurp(f / "victim"), "precious");
  EXPECT_TRUE(fs::is_symlink(planted));
  EXPECT_EQ(slurp(f / "out.msh"), "mesh");
}

TEST(OutputFiles, TemporariesAreBesideTheTargetAndRecognised) {
  Folder f;
  OutputFiles out;
  out.add(f / "a.msh", "a");
  const std::vector<std::string> names = f.names();
  ASSERT_EQ(names.size(), 1u);
  EXPECT_TRUE(is_temporary_of(names[0], "a.msh")) << names[0];
  EXPECT_EQ(names[0].size(), std::string("a.msh.tmp.").size() + 12);
  EXPECT_TRUE(is_temporary_of("a.msh.tmp.12345", "a.msh"));  // an older run's
  EXPECT_FALSE(is_temporary_of("a.msh.tmp.", "a.msh"));
  EXPECT_FALSE(is_temporary_of("b.msh.tmp.abc", "a.msh"));
  EXPECT_FALSE(is_temporary_of("a.msh.tmp.ab/c", "a.msh"));
  out.commit();
  EXPECT_EQ(f.names(), std::vector<std::string>{"a.msh"});
}

TEST(OutputFiles, NothingIsLeftWhenNotCommitted) {
  Folder f;
  put(f / "old.msh", "earlier");
  {
    OutputFiles out;
    out.add(f / "new.msh", "new");
    out.add(f / "old.msh", "replacement");
  }
  EXPECT_EQ(f.names(), std::vector<std::string>{"old.msh"});
  EXPECT_EQ(slurp(f / "old.msh"), "earlier");
}

TEST(OutputFiles, AFailedCommitTakesBackWhatItRenamed) {
  Folder f;
  OutputFiles out;
  out.add(f / "a.msh", "a");
  out.add(f / "b.vtu", "b");
  fs::create_directory(f / "sub");
  out.add(f / "sub" + "/c.svg", "c");
  fs::remove_all(f / "sub");  // c's temporary is gone with its folder: its rename fails
  EXPECT_THROW(out.commit(), OutputError);
  EXPECT_EQ(f.names(), std::vector<std::string>{});
}

TEST(OutputFiles, ALinkAtTheTargetIsReplacedNotWrittenThrough) {
  Folder f;
  put(f / "victim", "precious");
  fs::create_symlink(f / "victim", f / "out.svg");
  write_file_atomically(f / "out.svg", "drawing");
  EXPECT_EQ(slurp(f / "victim"), "precious");
  EXPECT_FALSE(fs::is_symlink(f / "out.svg"));
  EXPECT_EQ(slurp(f / "out.svg"), "drawing");
}

TEST(OutputFiles, FoldersAreRefusedAndDeviceErrorsReported) {
  Folder f;
  fs::create_directory(f / "dir");
  EXPECT_THROW(write_file_atomically(f / "dir", "x"), OutputError);
  EXPECT_TRUE(fs::is_directory(f / "dir"));
  if (fs::exists("/dev/full")) {
    try {
      write_file_atomically("/dev/full", "x");
      ADD_FAILURE() << "/dev/full took the bytes";
    } catch (const OutputError& e) {
      EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
    }
  }
  write_file_atomically("/dev/null", "x");  // in place: a device stays a device
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(OutputClash, AnInputByAnyNameOrTwoOutputsForOneFile) {
  Folder f;
  put(f / "in.svg", "<svg/>");
  fs::create_hard_link(f / "in.svg", f / "hard.svg");
  fs::create_symlink(f / "in.svg", f / "soft.svg");
  const std::vector<NamedPath> inputs = {{"input", f / "in.svg"}};
  EXPECT_EQ(output_clash(inputs, {{"-o", f / "out.msh"}, {"--svg", f / "out.svg"}}), "");
  for (const std::string& name : {f / "in.svg", f / "hard.svg", f / "soft.svg", f / "./in.svg"}) {
    const std::string clash = output_clash(inputs, {{"-o", f / "out.msh"}, {"--svg", name}});
    EXPECT_NE(clash.find("--svg " + name + " is the same file as the input"), std::string::npos) << clash;
  }
  const std::string twice = output_clash(inputs, {{"-o", f / "x.msh"}, {"--vtu", f / "./x.msh"}});
  EXPECT_NE(twice.find("name the same file"), std::string::npos) << twice;
  EXPECT_EQ(output_clash(inputs, {{"-o", "/dev/null"}, {"--vtu", "/dev/null"}}), "");
}

}  // namespace
}  // namespace curvemesh::base
