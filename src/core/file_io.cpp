#include "fastron/core/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "fastron/core/error.h"

namespace fastron {

std::string readFile(const std::filesystem::path& path, std::string_view what) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ec))
    throw FileNotFound(path.string() + ": cannot open " + std::string(what));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw FileError(path.string() + ": cannot read " + std::string(what));
  return std::move(bytes).str();
}

namespace {

[[noreturn]] void failWrite(const std::filesystem::path& path, std::string_view what, int error) {
  throw FileError(path.string() + ": cannot write " + std::string(what) + " (" +
                  std::strerror(error) + ")");
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes,
                         std::string_view what) {
  // The temporary sits in the same folder, so the rename never crosses file systems.
  std::string temporary = path.string() + ".XXXXXX";
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) failWrite(path, what, errno);
  const auto abandon = [&](int error) {
    ::close(fd);
    ::unlink(temporary.c_str());
    failWrite(path, what, error);
  };
  for (std::size_t written = 0; written < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) abandon(n < 0 ? errno : EIO);
    written += static_cast<std::size_t>(n);
  }
  // mkstemp creates the file 0600: a replaced file keeps its permissions, a new one gets 0644
  // (reading the umask would mean changing it, which is not thread-safe).
  struct stat existing {};
  const mode_t mode = ::stat(path.c_str(), &existing) == 0 ? existing.st_mode & 07777 : 0644;
  if (::fchmod(fd, mode) != 0 || ::fsync(fd) != 0) abandon(errno);
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    failWrite(path, what, error);
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    failWrite(path, what, error);
  }
}

}  // namespace fastron
