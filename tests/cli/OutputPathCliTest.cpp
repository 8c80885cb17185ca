// Where the CLI writes: special files are written through or refused, never replaced (a device
// node, a FIFO, a symbolic link), every output path is checked before the render (no partial
// outputs), and a failed write to stdout is an error.
#include "CliSupport.h"

#include <penumbra/ImageIO.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

constexpr unsigned kNullMajor = 1, kNullMinor = 3;  // Linux's memory devices: 1:3 is "null"
constexpr int kReaderPollMs = 50;

struct stat lstatOf(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(lstat(path.c_str(), &st), 0) << path;
  return st;
}

size_t countLines(const std::string& s) { return static_cast<size_t>(std::count(s.begin(), s.end(), '\n')); }

/// Reads a FIFO on a thread until its writer closes it (or stop() is called), as a pipe's
/// consumer would. The FIFO is opened before the writer starts, so the writer finds a reader.
class FifoReader {
public:
  explicit FifoReader(const std::string& path) : mFd(open(path.c_str(), O_RDONLY | O_NONBLOCK)) {
    mThread = std::thread([this] { run(); });
  }
  ~FifoReader() { stop(); }
  void stop() {
    mStop = true;
    if (mThread.joinable()) mThread.join();
    if (mFd >= 0) close(mFd);
    mFd = -1;
  }
  bool opened() const { return mFd >= 0; }
  const std::vector<char>& bytes() const { return mBytes; }

private:
  void run() {
    char block[4096];
    while (!mStop && mFd >= 0) {
      pollfd p{mFd, POLLIN, 0};
      if (poll(&p, 1, kReaderPollMs) <= 0) continue;
      const ssize_t n = read(mFd, block, sizeof block);
      if (n > 0) mBytes.insert(mBytes.end(), block, block + n);
      else if (n == 0 && !mBytes.empty()) return;  // the writer is done
      else if (n == 0) std::this_thread::sleep_for(std::chrono::milliseconds(kReaderPollMs));  // no writer yet
    }
  }
  int mFd;
  std::atomic<bool> mStop{false};
  std::vector<char> mBytes;
  std::thread mThread;
};

}  // namespace

// `mknod n c 1 3; penumbra render --out n` once replaced the node with a PNG: as root (the
// README's set-up), `--out /dev/null` would have replaced the system's /dev/null. The node here
// is a private one in a scratch folder.
TEST(OutputPathCli, DeviceNodeIsWrittenThroughNotReplaced) {
  const std::string dir = freshDir("out-device");
  const std::string node = dir + "/n";
  if (mknod(node.c_str(), S_IFCHR | 0666, makedev(kNullMajor, kNullMinor)) != 0)
    GTEST_SKIP() << "mknod needs CAP_MKNOD (run as root): " << std::strerror(errno);
  const RunResult r = runPenumbra("render --size 16x16 --out n", dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  const struct stat st = lstatOf(node);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  EXPECT_EQ(major(st.st_rdev), kNullMajor);
  EXPECT_EQ(minor(st.st_rdev), kNullMinor);
  for (const auto& e : fs::directory_iterator(dir))  // no temporary file left beside the node
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(OutputPathCli, FifoWithAReaderReceivesThePng) {
  const std::string dir = freshDir("out-fifo");
  const std::string fifo = dir + "/f";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  FifoReader reader(fifo);
  ASSERT_TRUE(reader.opened());
  const RunResult r = runPenumbra("render --size 16x16 --out f", dir);
  reader.stop();
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(S_ISFIFO(lstatOf(fifo).st_mode)) << "the FIFO was replaced";
  const std::string copy = dir + "/received.png";
  std::ofstream(copy, std::ios::binary).write(reader.bytes().data(), static_cast<std::streamsize>(reader.bytes().size()));
  int w = 0, h = 0;
  const std::vector<uint8_t> rgba = readPng(copy, w, h);
  EXPECT_EQ(w, 16);
  EXPECT_EQ(h, 16);
}

TEST(OutputPathCli, FifoWithoutAReaderIsRefusedNotAHang) {
  const std::string dir = freshDir("out-fifo-alone");
  const std::string fifo = dir + "/f";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  const RunResult r = runPenumbra("render --size 16x16 --out f", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("f: is a FIFO that no process reads"), std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
  EXPECT_TRUE(S_ISFIFO(lstatOf(fifo).st_mode));
}

TEST(OutputPathCli, SymbolicLinkIsFollowedAndKept) {
  const std::string dir = freshDir("out-symlink");
  std::ofstream(dir + "/target.png") << "old";
  fs::create_symlink("target.png", dir + "/link.png");
  fs::create_symlink("made/by/render.png", dir + "/dangling.png");
  RunResult r = runPenumbra("render --size 16x16 --out link.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runPenumbra("render --size 24x16 --out dangling.png", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(S_ISLNK(lstatOf(dir + "/link.png").st_mode)) << "the link was replaced";
  EXPECT_TRUE(S_ISLNK(lstatOf(dir + "/dangling.png").st_mode)) << "the link was replaced";
  int w = 0, h = 0;
  readPng(dir + "/target.png", w, h);
  EXPECT_EQ(w, 16);
  readPng(dir + "/made/by/render.png", w, h);
  EXPECT_EQ(w, 24);
}

TEST(OutputPathCli, FolderOrEmptyPathSaysWhatIsWrong) {
  const std::string dir = freshDir("out-folder");
  fs::create_directories(dir + "/sub");
  RunResult r = runPenumbra("render --size 16x16 --out sub", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--out: sub: is a folder, not a file"), std::string::npos) << r.err;
  r = runPenumbra("render --size 16x16 --out ''", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--out: an empty path names no file"), std::string::npos) << r.err;
  r = runPenumbra("render --size 16x16 --out sub/", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("ends in '/'"), std::string::npos) << r.err;
  std::ofstream(dir + "/file") << "x";
  r = runPenumbra("compare --size 16x16 --samples 1 --out file", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--out: file: exists and is not a folder"), std::string::npos) << r.err;
  EXPECT_EQ(countLines(r.err), 1u) << r.err;
}

// A bad --visibility or --dump path used to fail after --out had been written.
TEST(OutputPathCli, EveryOutputIsCheckedBeforeAnyIsWritten) {
  const std::string dir = freshDir("out-partial");
  std::ofstream(dir + "/file") << "x";  // "file/v.exr" cannot exist: its folder is a file
  RunResult r = runPenumbra("render --size 16x16 --out ok.png --visibility file/v.exr", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--visibility: file/v.exr"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/ok.png")) << "--out was written before the run failed";
  r = runPenumbra("render --size 16x16 --out ok.png --dump file", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--dump: file: exists and is not a folder"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/ok.png")) << "--out was written before the run failed";
}

TEST(OutputPathCli, StdoutWriteErrorsExitNonZero) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  for (const char* args : {"list", "list --json", "render --size 16x16 --out a.png"}) {
    const RunResult r = runPenumbra(args, "", "", "/dev/full");
    EXPECT_EQ(r.exitCode, 1) << args;
    EXPECT_NE(r.err.find("penumbra: cannot write to standard output ("), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(countLines(r.err), 1u) << r.err;
  }
  const RunResult r = runPenumbra("compare --json --size 16x16 --samples 1 --no-cache", "", "", "/dev/full");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("standard output"), std::string::npos) << r.err;
}

// A file name of 244-255 bytes is a legal name, but its temporary name (".tmp.<pid>.<n>"
// appended) was not: the run failed after the render with no reason. The temporary name is cut
// to fit; a name past the file system's limit is refused before the render, with its length.
TEST(OutputPathCli, LongFileNamesAreWrittenOrRefusedBeforeTheRender) {
  const std::string dir = freshDir("long-names");
  const long max = pathconf(dir.c_str(), _PC_NAME_MAX);
  ASSERT_GT(max, 16) << "the file system's name limit";
  const std::string fits = std::string(static_cast<size_t>(max) - 4, 'a') + ".png";  // exactly the limit
  RunResult r = runPenumbra("render --size 16x16 --shadow-map 1024 --out " + fits, dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/" + fits));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "a temporary file is left: " << e.path();

  const std::string tooLong = std::string(static_cast<size_t>(max) - 3, 'b') + ".png";
  for (const std::string& args : {"render --size 16x16 --out " + tooLong, "render --size 16x16 --visibility " + tooLong,
                                  "render --size 16x16 --frames 2 --out " + std::string(static_cast<size_t>(max) - 6, 'c') + ".png"}) {
    r = runPenumbra(args, dir);
    EXPECT_EQ(r.exitCode, 1) << args;
    EXPECT_NE(r.err.find("bytes, more than the " + std::to_string(max) + " the file system takes; give a shorter name"), std::string::npos)
        << r.err;
    EXPECT_EQ(countLines(r.err), 1u) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir + "/penumbra.png")) << "refused before the render";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3) << "the image, .stdout and .stderr only";
}
