#include "tribos/core/OutputFile.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "tribos/core/Errors.hpp"

namespace tribos::core {

namespace {
std::string lastError() { return std::strerror(errno); }

/// Every byte of `text` to `fd`; false (errno set) on failure.
bool writeAll(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

/// The mode of a new file under the process's umask (umask can only be read by setting it).
mode_t newFileMode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

/// One of this process's open descriptors (--summary /dev/stdout): whatever it leads to, it is
/// written in place and appended to; renaming over its target would replace, say, the log
/// file that standard output is redirected to.
bool isDescriptorPath(const std::string& path) {
  for (const char* prefix : {"/dev/stdout", "/dev/stderr", "/dev/fd/", "/proc/self/fd/"})
    if (path.rfind(prefix, 0) == 0) return true;
  return false;
}
}  // namespace

OutputFile::OutputFile(std::string path, std::string option, bool streamAllowed)
    : path_(std::move(path)), option_(std::move(option)) {
  const std::string where = path_ + " (" + option_ + ")";
  if (isDescriptorPath(path_)) {
    if (!streamAllowed) throw InputError(where + ": is a file descriptor; this result needs a regular file");
    streamFd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (streamFd_ < 0) throw InputError(where + ": cannot write to it (" + lastError() + ")");
    return;
  }
  std::error_code error;
  if (std::filesystem::is_symlink(path_, error)) {
    const auto target = std::filesystem::weakly_canonical(path_, error);
    if (!error) path_ = target.string();
  }
  struct stat info {};
  if (::stat(path_.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) throw InputError(where + ": is a directory; give a file name");
    if (S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode)) {
      const std::string kind = S_ISFIFO(info.st_mode) ? "a FIFO" : "a character device";
      if (!streamAllowed)
        throw InputError(where + ": is " + kind + "; this result needs a regular file (leave " + option_ +
                         " out to write none)");
      // Without O_NONBLOCK, opening a FIFO waits for a reader; with it, ENXIO says there is none.
      streamFd_ = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
      if (streamFd_ < 0)
        throw InputError(where + ": cannot write to " + kind + " (" +
                         (errno == ENXIO ? std::string("no process reads it") : lastError()) + ")");
      ::fcntl(streamFd_, F_SETFL, ::fcntl(streamFd_, F_GETFL) & ~O_NONBLOCK);
      return;
    }
    if (!S_ISREG(info.st_mode)) throw InputError(where + ": is not a regular file, a device or a FIFO");
  }
  // A trial file where the result will be written, removed at once: an unwritable directory
  // is found now, not after the solve.
  try {
    ::unlink(createTemporary().c_str());
  } catch (const IoError& e) {
    throw InputError(std::string(e.what()) + ": check that its directory exists and is writable");
  }
}

OutputFile::~OutputFile() {
  if (streamFd_ >= 0) ::close(streamFd_);
}

std::string OutputFile::createTemporary() const {
  std::string name = path_ + ".tribos-partial-XXXXXX";
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = ::mkstemp(buffer.data());  // O_EXCL: a name no other run holds
  if (fd < 0) throw IoError(path_ + " (" + option_ + "): cannot create a file next to it (" + lastError() + ")");
  ::close(fd);
  return buffer.data();
}

void OutputFile::commit(const std::string& temporary) const {
  if (::chmod(temporary.c_str(), newFileMode()) != 0) fail(temporary, "cannot set its permissions: " + lastError());
  if (::rename(temporary.c_str(), path_.c_str()) != 0) fail(temporary, "cannot rename it into place: " + lastError());
}

void OutputFile::fail(const std::string& temporary, const std::string& why) const {
  if (!temporary.empty()) ::unlink(temporary.c_str());
  throw IoError(path_ + " (" + option_ + "): could not write the results: " + why);
}

void OutputFile::writeWith(const std::function<void(const std::string& path)>& write) {
  const std::string temporary = createTemporary();
  try {
    write(temporary);
  } catch (const std::exception& e) {
    fail(temporary, e.what());
  }
  commit(temporary);
}

void OutputFile::writeText(const std::string& text) {
  if (streamFd_ >= 0) {
    if (!writeAll(streamFd_, text)) fail("", lastError());
    return;
  }
  writeWith([&](const std::string& temporary) {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) throw IoError(lastError());
    const bool written = writeAll(fd, text);
    const std::string why = written ? "" : lastError();
    if (::close(fd) != 0 && written) throw IoError(lastError());
    if (!written) throw IoError(why);
  });
}

}  // namespace tribos::core
