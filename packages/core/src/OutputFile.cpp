#include "tribos/core/OutputFile.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include "tribos/core/Errors.hpp"

namespace tribos::core {

namespace {
std::string lastError() { return std::strerror(errno); }

/// A reader that takes nothing for this long is taken for gone (a FIFO whose reader hangs).
constexpr int kStreamTimeoutMs = 60 * 1000;

/// Every byte of `text` to `fd`; false (errno set) on failure. A non-blocking descriptor (a
/// FIFO) waits for its reader at most kStreamTimeoutMs per chunk (errno ETIMEDOUT).
bool writeAll(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) {
      pollfd wait{fd, POLLOUT, 0};
      const int ready = ::poll(&wait, 1, kStreamTimeoutMs);
      if (ready == 0) errno = ETIMEDOUT;
      if (ready <= 0) return false;
      continue;
    }
    if (n == 0) errno = EIO;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

/// The mode of a new file under the process's umask, read from /proc (setting the umask to
/// read it would change it for every thread a moment); 0644 where /proc does not say.
mode_t newFileMode() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Umask:", 0) == 0) return 0666 & ~static_cast<mode_t>(std::strtol(line.c_str() + 6, nullptr, 8));
  return 0644;
}

/// The descriptor of this process that `path` names (/dev/stdout, /dev/fd/2, a link to the
/// file standard output goes to), or -1: written in place through a copy of it, at its
/// offset, so that the summary follows what the run printed there instead of replacing the
/// log that standard output is redirected to.
int processDescriptor(const std::string& path) {
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"})
    if (path.rfind(prefix, 0) == 0) return std::atoi(path.c_str() + std::strlen(prefix));
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  struct stat target {}, open {};
  if (::stat(path.c_str(), &target) != 0) return -1;
  for (int fd : {1, 2})
    if (::fstat(fd, &open) == 0 && S_ISREG(open.st_mode) && open.st_dev == target.st_dev &&
        open.st_ino == target.st_ino)
      return fd;
  return -1;
}

/// The temporary files being written, removed by a signal that ends the run (SIGINT, SIGTERM,
/// SIGHUP) before it ends it as it would have (issue 44: a signal during the write left a
/// 20-33 MB partial file). The handler only reads fixed buffers and calls unlink, sigaction
/// and raise, which are async-signal-safe.
namespace partial {
constexpr int kSlots = 4;
constexpr size_t kPathBytes = 4096;
char paths[kSlots][kPathBytes];
volatile sig_atomic_t used[kSlots];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction previous[sizeof kSignals / sizeof kSignals[0]];

extern "C" void removeAndReraise(int signal) {
  for (int s = 0; s < kSlots; ++s)
    if (used[s]) ::unlink(paths[s]);
  for (size_t i = 0; i < sizeof kSignals / sizeof kSignals[0]; ++i)
    if (kSignals[i] == signal) ::sigaction(signal, &previous[i], nullptr);
  ::raise(signal);
}

/// Installs the handler once, keeping what was there to hand the signal on to; a signal the
/// run ignores (SIGHUP under nohup, SIGINT in a background job) stays ignored.
void installOnce() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  struct sigaction action {};
  action.sa_handler = removeAndReraise;
  sigemptyset(&action.sa_mask);
  for (size_t i = 0; i < sizeof kSignals / sizeof kSignals[0]; ++i) {
    ::sigaction(kSignals[i], nullptr, &previous[i]);
    if (previous[i].sa_handler != SIG_IGN) ::sigaction(kSignals[i], &action, nullptr);
  }
}

/// Holds `path` for the handler while it lives (no slot or too long a path: not held).
class Guard {
 public:
  explicit Guard(const std::string& path) {
    installOnce();
    if (path.size() >= kPathBytes) return;
    for (int s = 0; s < kSlots; ++s)
      if (!used[s]) {
        std::memcpy(paths[s], path.c_str(), path.size() + 1);
        used[s] = 1;
        slot_ = s;
        return;
      }
  }
  ~Guard() {
    if (slot_ >= 0) used[slot_] = 0;
  }
  Guard(const Guard&) = delete;
  Guard& operator=(const Guard&) = delete;

 private:
  int slot_ = -1;
};
}  // namespace partial

/// `path` with its symbolic links followed, even to a target that does not exist yet
/// (weakly_canonical would stop at a dangling link, and the rename would replace the link).
std::string followLinks(std::string path) {
  std::error_code error;
  for (int hop = 0; hop < 40 && std::filesystem::is_symlink(path, error); ++hop) {
    std::filesystem::path target = std::filesystem::read_symlink(path, error);
    if (error) break;
    if (target.is_relative()) target = std::filesystem::path(path).parent_path() / target;
    path = target.lexically_normal().string();
  }
  return path;
}
}  // namespace

OutputFile::OutputFile(std::string path, std::string option, bool streamAllowed)
    : path_(std::move(path)), option_(std::move(option)) {
  const std::string where = path_ + " (" + option_ + ")";
  if (const int fd = processDescriptor(path_); fd >= 0) {
    if (!streamAllowed) throw InputError(where + ": is a descriptor of this process; this result needs a regular file");
    streamFd_ = ::fcntl(fd, F_DUPFD_CLOEXEC, 3);
    if (streamFd_ < 0) throw InputError(where + ": cannot write to it (" + lastError() + ")");
    return;
  }
  path_ = followLinks(path_);
  struct stat info {};
  if (::stat(path_.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) throw InputError(where + ": is a directory; give a file name");
    if (S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode)) {
      openStream(where, S_ISFIFO(info.st_mode) ? "a FIFO" : "a character device", streamAllowed);
      return;
    }
    if (!S_ISREG(info.st_mode)) throw InputError(where + ": is not a regular file, a device or a FIFO");
  }
  // A trial file where the result will be written, removed at once: an unwritable directory
  // is found now, not after the solve.
  try {
    const auto [trial, fd] = createTemporary();
    ::close(fd);
    ::unlink(trial.c_str());
  } catch (const IoError& e) {
    throw InputError(std::string(e.what()) + ": check that its directory exists and is writable");
  }
}

void OutputFile::openStream(const std::string& where, const std::string& kind, bool streamAllowed) {
  if (!streamAllowed)
    throw InputError(where + ": is " + kind + "; this result needs a regular file (leave " + option_ +
                     " out to write none)");
  // Without O_NONBLOCK, opening a FIFO waits for a reader; with it, ENXIO says there is none.
  // It stays non-blocking: writeAll waits for a slow reader, but not for ever.
  streamFd_ = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (streamFd_ < 0)
    throw InputError(where + ": cannot write to " + kind + " (" +
                     (errno == ENXIO ? std::string("no process reads it") : lastError()) + ")");
}

OutputFile::~OutputFile() {
  if (streamFd_ >= 0) ::close(streamFd_);
}

std::pair<std::string, int> OutputFile::createTemporary() const {
  std::string name = path_ + ".tribos-partial-XXXXXX";
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = ::mkstemp(buffer.data());  // O_EXCL: a name no other run holds
  if (fd < 0) throw IoError(path_ + " (" + option_ + "): cannot create a file next to it (" + lastError() + ")");
  return {buffer.data(), fd};
}

void OutputFile::commit(const std::string& temporary) const {
  // The mode of the file it replaces, or a new file's.
  struct stat old {};
  const mode_t mode = ::stat(path_.c_str(), &old) == 0 ? (old.st_mode & 07777) : newFileMode();
  if (::chmod(temporary.c_str(), mode) != 0) fail(temporary, "cannot set its permissions: " + lastError());
  if (::rename(temporary.c_str(), path_.c_str()) != 0) fail(temporary, "cannot rename it into place: " + lastError());
}

void OutputFile::fail(const std::string& temporary, const std::string& why) const {
  if (!temporary.empty()) ::unlink(temporary.c_str());
  throw IoError(path_ + " (" + option_ + "): could not write the results: " + why);
}

void OutputFile::writeWith(const std::function<void(const std::string& path)>& write) {
  const auto [temporary, fd] = createTemporary();
  const partial::Guard guard(temporary);
  ::close(fd);  // the writer opens it by name (netCDF)
  try {
    write(temporary);
  } catch (const IoError& e) {
    fail(temporary, e.what());
  } catch (const InputError& e) {  // the Exodus writer's failed calls (a full disk among them)
    fail(temporary, e.what());
  } catch (...) {  // not a write failure: no partial file, and the error stays what it is
    ::unlink(temporary.c_str());
    throw;
  }
  commit(temporary);
}

void OutputFile::writeText(const std::string& text) {
  if (streamFd_ >= 0) {
    std::cout.flush();  // a descriptor shared with standard output: what was printed comes first
    std::fflush(stdout);
    if (!writeAll(streamFd_, text)) fail("", lastError());
    return;
  }
  const auto [temporary, fd] = createTemporary();
  const partial::Guard guard(temporary);
  const bool written = writeAll(fd, text);
  const std::string why = written ? "" : lastError();
  if (::close(fd) != 0 && written) fail(temporary, lastError());
  if (!written) fail(temporary, why);
  commit(temporary);
}

/// The draft's temporary file and its guard against signals.
struct OutputFile::Draft::Held {
  std::string path;
  std::unique_ptr<partial::Guard> guard;
  bool committed = false;
  std::string failure;  ///< the first failed write's message (the draft removed)
};

OutputFile::Draft::Draft(OutputFile& target) : target_(target), held_(std::make_unique<Held>()) {
  const auto [temporary, fd] = target_.createTemporary();
  ::close(fd);  // the writer opens it by name (netCDF)
  held_->path = temporary;
  held_->guard = std::make_unique<partial::Guard>(temporary);
}

OutputFile::Draft::~Draft() {
  if (!held_->committed) ::unlink(held_->path.c_str());
}

const std::string& OutputFile::Draft::path() const { return held_->path; }

void OutputFile::Draft::write(const std::function<void(const std::string& path)>& write) {
  if (!held_->failure.empty()) throw IoError(held_->failure);
  try {
    write(held_->path);
    return;
  } catch (const IoError& e) {
    held_->failure = e.what();
  } catch (const InputError& e) {  // the Exodus writer's failed calls (a full disk among them)
    held_->failure = e.what();
  }
  try {
    target_.fail(held_->path, held_->failure);
  } catch (const IoError& e) {
    held_->failure = e.what();
    throw;
  }
}

void OutputFile::Draft::publishCopy() {
  if (!held_->failure.empty()) throw IoError(held_->failure);
  target_.writeWith([&](const std::string& copy) {
    std::error_code error;
    std::filesystem::copy_file(held_->path, copy, std::filesystem::copy_options::overwrite_existing, error);
    if (error) throw IoError("cannot copy " + held_->path + ": " + error.message());
  });
}

void OutputFile::Draft::commit() {
  if (!held_->failure.empty()) throw IoError(held_->failure);
  held_->committed = true;  // commit() removes the file itself where it fails
  target_.commit(held_->path);
  held_->guard.reset();
}

std::unique_ptr<OutputFile::Draft> OutputFile::startDraft() {
  if (streamFd_ >= 0) throw std::logic_error("tribos::core::OutputFile::startDraft: " + path_ + " is not a regular file");
  return std::unique_ptr<Draft>(new Draft(*this));
}

}  // namespace tribos::core
