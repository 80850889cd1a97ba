// Non-regular files and OS errors on every reader of user files in io (the job config's reader, which uses the same
// gate, is tested in config/job_config_test.cc) (issue 14: a FIFO in place of a depth map or LAS
// hung forever; permission denied was reported as "corrupt" or "missing"). One gate, io/input_file.h.
#include "io/input_file.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/camera_file.h"
#include "io/colmap_array.h"
#include "io/colmap_model.h"
#include "io/las_reader.h"
#include "io/openmvs_dmap.h"
#include "io/rgb_image_file.h"
#include "io/tiff_depth.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using sacfuse::testing::TempDir;

// The readers of user files, each reading `path` (a file with the name that reader expects).
struct NamedReader {
  const char* name;
  const char* file_name;
  std::function<void(const std::string&)> read;
};

std::vector<NamedReader> Readers() {
  return {
      {"dense array", "a.png.geometric.bin", [](const std::string& p) { ReadColmapArray(p); }},
      {"OpenMVS depth map", "depth0001.dmap", [](const std::string& p) { ReadDmapDepth(p); }},
      {"TIFF depth raster", "a.tif", [](const std::string& p) { ReadTiffDepth(p); }},
      {"YAML camera file", "cameras.yaml", [](const std::string& p) { ReadCameraFile(p); }},
      {"CSV camera file", "cameras.csv", [](const std::string& p) { ReadCameraFile(p); }},
      {"image", "a.jpg", [](const std::string& p) { ReadRgbImageFile(p, "image \"a.jpg\""); }},
      {"LAS", "a.las", [](const std::string& p) { LasReader reader(p); }},
      {"COLMAP model", "cameras.bin", [](const std::string& p) { ReadColmapModel(fs::path(p).parent_path()); }},
      {"COLMAP text model", "cameras.txt", [](const std::string& p) { ReadColmapModel(fs::path(p).parent_path()); }},
  };
}

// The message of the sacfuse::Error `read` throws; fails (instead of hanging the suite) when it does not return
// within 10 s, after unblocking a reader stuck on a FIFO.
std::string MessageWithin10s(const std::function<void()>& read, const std::string& path) {
  auto result = std::async(std::launch::async, [&]() -> std::string {
    try {
      read();
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  });
  if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << path << ": the reader hangs";
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);  // gives the blocked open its writer
    if (fd >= 0) ::close(fd);
  }
  return result.get();
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(InputFileTest, AFifoInPlaceOfAnyInputFileIsRefusedWithoutHanging) {
  for (const NamedReader& r : Readers()) {
    TempDir dir;
    const fs::path path = dir / r.file_name;
    ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
    const std::string err = MessageWithin10s([&] { r.read(path.string()); }, path.string());
    EXPECT_TRUE(Has(err, path.string())) << r.name << ": " << err;
    EXPECT_TRUE(Has(err, "it is a FIFO (named pipe), not a regular file")) << r.name << ": " << err;
  }
}

TEST(InputFileTest, ADirectoryOrDeviceInPlaceOfAFileIsRefused) {
  for (const NamedReader& r : Readers()) {
    TempDir dir;
    const fs::path path = dir / r.file_name;
    fs::create_directories(path);
    const std::string err = MessageWithin10s([&] { r.read(path.string()); }, path.string());
    EXPECT_TRUE(Has(err, "it is a directory, not a regular file")) << r.name << ": " << err;
  }
  const std::string dev = MessageWithin10s([] { ReadColmapArray("/dev/zero"); }, "/dev/zero");
  EXPECT_TRUE(Has(dev, "/dev/zero: cannot read dense array: it is a character device, not a regular file")) << dev;
}

TEST(InputFileTest, OsErrorsKeepTheirReason) {
  for (const NamedReader& r : Readers()) {
    TempDir dir;
    const fs::path path = dir / r.file_name;
    fs::remove(path);
    fs::create_symlink(path, path);  // a loop: ELOOP
    const std::string err = MessageWithin10s([&] { r.read(path.string()); }, path.string());
    EXPECT_TRUE(Has(err, "Too many levels of symbolic links")) << r.name << ": " << err;
    EXPECT_FALSE(Has(err, "corrupt") || Has(err, "missing")) << r.name << ": " << err;
    fs::remove(path);
    const std::string missing = MessageWithin10s([&] { r.read(path.string()); }, path.string());
    EXPECT_TRUE(Has(missing, "missing")) << r.name << ": " << missing;
  }
}

// Permission denied, as an unprivileged user: a forked child drops to nobody when the suite runs as root (root
// may read any file, so only a child can see EACCES there).
TEST(InputFileTest, PermissionDeniedSaysSoForEveryReader) {
  for (const NamedReader& r : Readers()) {
    TempDir dir;
    fs::permissions(dir.path(), fs::perms::all);
    const fs::path path = dir / r.file_name;
    std::ofstream(path) << "not read";
    fs::permissions(path, fs::perms::none);
    int pipe_fds[2];
    ASSERT_EQ(::pipe(pipe_fds), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(pipe_fds[0]);
      if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(3);
      std::string err = "(no error)";
      try {
        r.read(path.string());
      } catch (const Error& e) {
        err = e.what();
      } catch (...) {
        err = "(another exception)";
      }
      if (::write(pipe_fds[1], err.data(), err.size()) < 0) ::_exit(4);
      ::_exit(0);
    }
    ::close(pipe_fds[1]);
    std::string err;
    char buf[4096];
    for (ssize_t n; (n = ::read(pipe_fds[0], buf, sizeof(buf))) > 0;) err.append(buf, static_cast<size_t>(n));
    ::close(pipe_fds[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << r.name << ": child status " << status;
    EXPECT_TRUE(Has(err, path.string() + ": cannot open")) << r.name << ": " << err;
    EXPECT_TRUE(Has(err, "Permission denied")) << r.name << ": " << err;
    EXPECT_FALSE(Has(err, "corrupt") || Has(err, "missing")) << r.name << ": " << err;
  }
}

TEST(InputFileTest, RegularFilesPass) {
  TempDir dir;
  std::ofstream(dir / "f") << "x";
  EXPECT_NO_THROW(CheckInputFile((dir / "f").string(), "file"));
  std::ifstream in = OpenInputStream((dir / "f").string(), "file");
  EXPECT_EQ(in.get(), 'x');
}

}  // namespace
}  // namespace sacfuse
