#pragma once
/// \file OutputFile.hpp
/// One result file of a run (--output, --summary): checked before any work, written once at
/// the end, and never destroying anything on the way.
/// - A regular file (or a name not yet taken) is written under a temporary name unique to the
///   run, created exclusively in the target's directory (two runs with the same target never
///   share one), and renamed over the target only once complete; a write that fails removes
///   the temporary file, so no partial file is left and the earlier file stays; so does
///   SIGINT, SIGTERM or SIGHUP during the write (the temporary file is removed, then the
///   signal ends the run as it would have).
/// - A character device or a FIFO (/dev/null, a pipe to another program) is written in place,
///   never replaced; a FIFO is opened when checked, without blocking, so that one with no
///   reader is refused before any work instead of hanging at the end, and a reader that stops
///   reading for a minute is a failed write, not a hang.
/// - A symbolic link is followed (a dangling one too): the file it points to is written. A
///   descriptor of the process (/dev/stdout, /dev/fd/N, or a name of the file standard output
///   goes to) is written in place through a copy of it, after what the run printed.
/// - A replaced file keeps its permissions.
#include <functional>
#include <memory>
#include <string>
#include <utility>

namespace tribos::core {

class OutputFile {
 public:
  /// Checks that `path` can be written, before any work. `option` names it in messages
  /// ("--summary"); `streamAllowed` false: a regular file only (an Exodus result is written
  /// by seeking, so it cannot go to a device or a pipe). Throws InputError naming the path
  /// and the option otherwise.
  OutputFile(std::string path, std::string option, bool streamAllowed);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& path() const { return path_; }
  const std::string& option() const { return option_; }

  /// The whole file through `write(p)`, which writes a complete file at the path `p` it is
  /// given (a temporary name next to the target). Regular targets only. Throws IoError naming
  /// the file and the option when `write` throws IoError or InputError (a failed write), with
  /// nothing partial left; anything else `write` throws passes through, nothing left either.
  void writeWith(const std::function<void(const std::string& path)>& write);
  /// `text` as the whole file. Throws IoError naming the file and the option on failure.
  void writeText(const std::string& text);

  /// A file built over time (a load history's result, step by step) at a temporary name next
  /// to the target, removed when it is dropped uncommitted or a signal ends the run (as
  /// writeWith's). Regular targets only.
  class Draft {
   public:
    ~Draft();
    Draft(const Draft&) = delete;
    Draft& operator=(const Draft&) = delete;
    /// Where the draft is written.
    const std::string& path() const;
    /// `write(path())` adds to the draft. A failed write (IoError or InputError) throws IoError
    /// naming the target and the option, and removes the draft: later writes and commit throw
    /// the same error, and nothing partial is left.
    void write(const std::function<void(const std::string& path)>& write);
    /// A copy of the draft as it is now replaces the target (a checkpoint), never partial.
    /// Throws IoError as writeWith.
    void publishCopy();
    /// The draft itself replaces the target; it is no longer a draft. Throws IoError (the
    /// draft removed) on failure.
    void commit();

   private:
    friend class OutputFile;
    struct Held;
    explicit Draft(OutputFile& target);
    OutputFile& target_;
    std::unique_ptr<Held> held_;
  };
  std::unique_ptr<Draft> startDraft();

 private:
  /// A new, empty file with a name unique to this run in the target's directory: its path and
  /// an open descriptor of it.
  std::pair<std::string, int> createTemporary() const;
  /// A device or FIFO target, opened for writing in place.
  void openStream(const std::string& where, const std::string& kind, bool streamAllowed);
  /// Renames the completed `temporary` over the target (with the replaced file's permissions,
  /// or a new file's).
  void commit(const std::string& temporary) const;
  [[noreturn]] void fail(const std::string& temporary, const std::string& why) const;

  std::string path_;    ///< the file written (a link's target)
  std::string option_;
  int streamFd_ = -1;   ///< a device or FIFO, open from the check on
};

}  // namespace tribos::core
