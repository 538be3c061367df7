#include "tribos/core/InputFiles.hpp"

#include <sys/stat.h>

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
  const auto tooLarge = [&] {
    return InputError(path + ": " + what + " is larger than " + std::to_string(maxBytes) +
                      " bytes, more than any scene needs: is it the right file?");
  };
  std::error_code error;
  if (std::filesystem::file_size(path, error) > maxBytes && !error) throw tooLarge();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what + " (unreadable)");
  std::string text;
  std::vector<char> chunk(1 << 16);
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    text.append(chunk.data(), static_cast<size_t>(in.gcount()));
    if (text.size() > maxBytes) throw tooLarge();  // it grew since it was measured
  }
  if (in.bad()) throw InputError(path + ": reading " + what + " failed");
  return text;
}

bool sameFile(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  const bool aExists = ::stat(a.c_str(), &sa) == 0, bExists = ::stat(b.c_str(), &sb) == 0;
  if (aExists && bExists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (aExists != bExists) return false;
  std::error_code ea, eb;
  const auto ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ea);
  const auto cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b), eb);
  return !ea && !eb && ca == cb;
}

}  // namespace tribos::core
