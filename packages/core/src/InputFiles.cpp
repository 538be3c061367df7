#include "tribos/core/InputFiles.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "tribos/core/Errors.hpp"

namespace tribos::core {

namespace {
/// What a file that is not regular is, for the message.
std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}
}  // namespace

void requireRegularInputFile(const std::string& path, const std::string& what) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    throw InputError(path + ": cannot open " + what + " (" + std::strerror(errno) + ")");
  if (!S_ISREG(info.st_mode))
    throw InputError(path + ": " + what + " is " + kindOf(info.st_mode) +
                     "; Tribos reads its inputs from regular files only");
}

std::string readRegularTextFile(const std::string& path, const std::string& what, std::uintmax_t maxBytes) {
  requireRegularInputFile(path, what);
  // Opened without blocking and checked again on the descriptor: a name replaced by a FIFO
  // between the check and the open cannot hang the read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot open " + what + " (" + std::strerror(errno) + ")");
  struct stat info {};
  const auto fail = [&](const std::string& why) {
    ::close(fd);
    return InputError(path + ": " + what + " " + why);
  };
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode))
    throw fail("is " + kindOf(info.st_mode) + "; Tribos reads its inputs from regular files only");
  const std::string tooLarge = "is larger than " + std::to_string(maxBytes) +
                               " bytes, more than any scene needs: is it the right file?";
  if (static_cast<std::uintmax_t>(info.st_size) > maxBytes) throw fail(tooLarge);
  std::string text;
  std::vector<char> chunk(1 << 16);
  for (;;) {
    const ssize_t n = ::read(fd, chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw fail(std::string("could not be read (") + std::strerror(errno) + ")");
    if (n == 0) break;
    text.append(chunk.data(), static_cast<size_t>(n));
    if (text.size() > maxBytes) throw fail(tooLarge);  // it grew since it was measured
  }
  ::close(fd);
  return text;
}

bool sameFile(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  const bool aExists = ::stat(a.c_str(), &sa) == 0, bExists = ::stat(b.c_str(), &sb) == 0;
  if (aExists && bExists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (aExists != bExists) return false;
  // Not throwing: a working directory that no longer exists makes absolute() fail.
  const auto resolved = [](const std::string& p, std::filesystem::path& out) {
    std::error_code error;
    const auto absolute = std::filesystem::absolute(p, error);
    if (error) return false;
    out = std::filesystem::weakly_canonical(absolute, error);
    return !error;
  };
  std::filesystem::path ca, cb;
  return resolved(a, ca) && resolved(b, cb) && ca == cb;
}

}  // namespace tribos::core
