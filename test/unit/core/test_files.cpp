// The files a run reads and writes: inputs only from regular files (a FIFO or a device is
// refused without being opened), outputs that never replace an input, a device or a FIFO,
// temporary names unique to the run, and nothing partial left when a write fails.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "tribos/core/Errors.hpp"
#include "tribos/core/InputFiles.hpp"
#include "tribos/core/OutputFile.hpp"

namespace fs = std::filesystem;
using tribos::core::InputError;
using tribos::core::IoError;
using tribos::core::OutputFile;

namespace {
class Files : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tribos_files_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  std::string fifo(const std::string& name) const {
    EXPECT_EQ(::mkfifo(path(name).c_str(), 0600), 0);
    return path(name);
  }
  /// Every entry of the directory but `keep`: what a run left behind.
  std::vector<std::string> leftovers(const std::vector<std::string>& keep) const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_))
      if (std::find(keep.begin(), keep.end(), e.path().filename().string()) == keep.end())
        out.push_back(e.path().filename().string());
    return out;
  }
  static std::string read(const std::string& p) {
    std::ostringstream s;
    s << std::ifstream(p).rdbuf();
    return s.str();
  }
  fs::path dir_;
};

template <class E, class F>
std::string messageOf(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "nothing thrown";
  return "";
}
}  // namespace

TEST_F(Files, inputsAreRegularFilesOnly) {
  const auto scene = write("scene.xml", "<ParameterList/>");
  EXPECT_NO_THROW(tribos::core::requireRegularInputFile(scene, "the scene file"));
  EXPECT_EQ(tribos::core::readRegularTextFile(scene, "the scene file", 1000), "<ParameterList/>");
  // Never opened, so the FIFO without a writer cannot block.
  auto why = messageOf<InputError>([&] { tribos::core::requireRegularInputFile(fifo("pipe"), "the scene file"); });
  EXPECT_NE(why.find("pipe: the scene file is a FIFO"), std::string::npos) << why;
  why = messageOf<InputError>([&] { tribos::core::readRegularTextFile("/dev/zero", "the scene file", 1000); });
  EXPECT_NE(why.find("/dev/zero: the scene file is a character device"), std::string::npos) << why;
  why = messageOf<InputError>([&] { tribos::core::requireRegularInputFile(dir_.string(), "Mesh/File"); });
  EXPECT_NE(why.find("Mesh/File is a directory"), std::string::npos) << why;
  why = messageOf<InputError>([&] { tribos::core::requireRegularInputFile(path("missing.exo"), "the mesh file"); });
  EXPECT_NE(why.find("missing.exo: cannot open the mesh file"), std::string::npos) << why;
}

TEST_F(Files, aSceneFileOverItsCapIsRefusedWithTheCap) {
  const auto big = write("big.xml", std::string(2000, 'x'));
  const auto why = messageOf<InputError>([&] { tribos::core::readRegularTextFile(big, "the scene file", 1000); });
  EXPECT_NE(why.find("big.xml: the scene file is larger than 1000 bytes"), std::string::npos) << why;
}

TEST_F(Files, sameFileSeesLinksAndSpellings) {
  const auto a = write("a.txt", "a");
  write("b.txt", "b");
  fs::create_symlink(a, path("link.txt"));
  fs::create_hard_link(a, path("hard.txt"));
  EXPECT_TRUE(tribos::core::sameFile(a, path("link.txt")));
  EXPECT_TRUE(tribos::core::sameFile(a, path("hard.txt")));
  EXPECT_TRUE(tribos::core::sameFile(a, (dir_ / "." / "a.txt").string()));
  EXPECT_FALSE(tribos::core::sameFile(a, path("b.txt")));
  EXPECT_TRUE(tribos::core::sameFile(path("new.json"), (dir_ / "sub" / ".." / "new.json").string()));
  EXPECT_FALSE(tribos::core::sameFile(path("new.json"), path("new.exo")));
}

TEST_F(Files, aRegularOutputIsReplacedWholeAndLeavesNothingElse) {
  const auto target = write("summary.json", "old");
  OutputFile out(target, "--summary", true);
  out.writeText("new\n");
  EXPECT_EQ(read(target), "new\n");
  EXPECT_TRUE(leftovers({"summary.json"}).empty());
  // Permissions of a new file (umask applied), not mkstemp's 0600.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(fs::status(target).permissions(), static_cast<fs::perms>(0666 & ~mask));
}

TEST_F(Files, aFailedWriteKeepsTheOldFileAndLeavesNoPartial) {
  const auto target = write("result.exo", "the earlier result");
  OutputFile out(target, "--output", false);
  const auto why = messageOf<IoError>([&] {
    out.writeWith([](const std::string& temporary) {
      std::ofstream(temporary) << "half a file";
      throw IoError("disk full");
    });
  });
  EXPECT_NE(why.find("result.exo (--output): could not write the results: disk full"), std::string::npos) << why;
  EXPECT_EQ(read(target), "the earlier result");
  EXPECT_TRUE(leftovers({"result.exo"}).empty());
  // Not a write failure (a bug in the writer): it stays what it is, nothing partial either.
  EXPECT_THROW(out.writeWith([](const std::string& temporary) {
    std::ofstream(temporary) << "half a file";
    throw std::logic_error("inconsistent fields");
  }),
               std::logic_error);
  EXPECT_EQ(read(target), "the earlier result");
  EXPECT_TRUE(leftovers({"result.exo"}).empty());
}

// A result built over time (a load history's, OutputFile::Draft): written next to the target,
// a published copy replaces the target whole while the draft goes on, commit puts the draft
// itself in place; a draft dropped uncommitted leaves nothing.
TEST_F(Files, aDraftIsPublishedWholeAndCommittedInPlace) {
  const auto target = write("history.exo", "the earlier result");
  OutputFile out(target, "--output", false);
  {
    const auto dropped = out.startDraft();
    std::ofstream(dropped->path()) << "step 1";
  }
  EXPECT_EQ(read(target), "the earlier result");
  EXPECT_TRUE(leftovers({"history.exo"}).empty());

  const auto draft = out.startDraft();
  EXPECT_EQ(fs::path(draft->path()).parent_path(), fs::path(target).parent_path());
  draft->write([](const std::string& p) { std::ofstream(p, std::ios::app) << "step 1;"; });
  draft->publishCopy();
  EXPECT_EQ(read(target), "step 1;");
  draft->write([](const std::string& p) { std::ofstream(p, std::ios::app) << "step 2;"; });
  EXPECT_EQ(read(target), "step 1;");  // the checkpoint stays until the next one
  draft->commit();
  EXPECT_EQ(read(target), "step 1;step 2;");
  EXPECT_TRUE(leftovers({"history.exo"}).empty());
}

// A failed write into a draft is an IoError naming the target and the option; the draft is
// removed, its later writes and commit say the same, and the last checkpoint stays.
TEST_F(Files, aFailedDraftWriteRemovesTheDraftAndKeepsTheCheckpoint) {
  const auto target = path("history.exo");
  OutputFile out(target, "--output", false);
  const auto draft = out.startDraft();
  draft->write([](const std::string& p) { std::ofstream(p) << "step 1;"; });
  draft->publishCopy();
  const auto why = messageOf<IoError>([&] { draft->write([](const std::string&) { throw IoError("disk full"); }); });
  EXPECT_NE(why.find("history.exo (--output): could not write the results: disk full"), std::string::npos) << why;
  EXPECT_TRUE(leftovers({"history.exo"}).empty());
  EXPECT_EQ(messageOf<IoError>([&] { draft->commit(); }), why);
  EXPECT_EQ(read(target), "step 1;");
}

TEST_F(Files, temporaryNamesAreUniqueToEachWrite) {
  const auto target = path("shared.exo");
  OutputFile first(target, "--output", false), second(target, "--output", false);
  std::string a, b;
  first.writeWith([&](const std::string& temporary) {
    a = temporary;
    second.writeWith([&](const std::string& other) {
      b = other;
      std::ofstream(other) << "second";
    });
    std::ofstream(temporary) << "first";
  });
  EXPECT_NE(a, b);
  EXPECT_EQ(fs::path(a).parent_path(), dir_);  // next to the target: rename stays on one filesystem
  EXPECT_EQ(read(target), "first");            // one run's whole result
  EXPECT_TRUE(leftovers({"shared.exo"}).empty());
}

TEST_F(Files, devicesAndFifosAreWrittenInPlaceNeverReplaced) {
  {
    OutputFile null("/dev/null", "--summary", true);
    null.writeText("{}\n");
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  auto why = messageOf<InputError>([] { OutputFile("/dev/null", "--output", false); });
  EXPECT_NE(why.find("/dev/null (--output): is a character device; this result needs a regular file"),
            std::string::npos)
      << why;

  const auto pipe = fifo("summary.fifo");
  why = messageOf<InputError>([&] { OutputFile(pipe, "--summary", true); });
  EXPECT_NE(why.find("cannot write to a FIFO (no process reads it)"), std::string::npos) << why;
  std::string received;
  std::thread reader([&] { received = read(pipe); });
  // The reader opens the FIFO at some point; until then there is no reader to find.
  std::unique_ptr<OutputFile> out;
  for (int attempt = 0; attempt < 20000 && !out; ++attempt) {  // up to 20 s on a loaded machine
    try {
      out = std::make_unique<OutputFile>(pipe, "--summary", true);
    } catch (const InputError&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  if (!out) {
    std::ofstream(pipe) << "";  // lets the reader's open return, so that it can be joined
    reader.join();
    FAIL() << "the FIFO never had a reader";
  }
  out->writeText("{\"converged\": true}\n");
  out.reset();  // closes: the reader sees the end
  reader.join();
  EXPECT_EQ(received, "{\"converged\": true}\n");
  EXPECT_TRUE(fs::is_fifo(pipe));
}

TEST_F(Files, aDescriptorIsWrittenInPlaceAfterWhatWasPrinted) {
  // Standard output redirected to a log as a shell does it (truncated, not appending):
  // --summary /dev/stdout, or the log's own name, must go into the log after what the run
  // printed, and what it prints afterwards after the summary; never a new file renamed over it.
  for (const std::string name : {"/dev/stdout", "run.log"}) {
    SCOPED_TRACE(name);
    const auto log = path("run.log");
    const int saved = ::dup(1);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    ::dup2(fd, 1);
    ::close(fd);
    ASSERT_EQ(::write(1, "progress\n", 9), 9);
    {
      OutputFile out(name == "run.log" ? log : name, "--summary", true);
      out.writeText("{}\n");
    }
    ASSERT_EQ(::write(1, "wrote\n", 6), 6);
    ::dup2(saved, 1);
    ::close(saved);
    EXPECT_EQ(read(log), "progress\n{}\nwrote\n");
    EXPECT_TRUE(leftovers({"run.log"}).empty());
  }
  EXPECT_THROW(OutputFile("/dev/stdout", "--output", false), InputError);
}

TEST_F(Files, aReplacedFileKeepsItsPermissionsAndADanglingLinkIsWrittenThrough) {
  const auto target = write("private.json", "old");
  fs::permissions(target, static_cast<fs::perms>(0600));
  OutputFile(target, "--summary", true).writeText("new");
  EXPECT_EQ(fs::status(target).permissions(), static_cast<fs::perms>(0600));
  fs::create_symlink("later.json", path("link.json"));  // its target does not exist yet
  OutputFile(path("link.json"), "--summary", true).writeText("through");
  EXPECT_TRUE(fs::is_symlink(path("link.json")));
  EXPECT_EQ(read(path("later.json")), "through");
}

TEST_F(Files, anOutputInAMissingDirectoryIsRefusedBeforeAnyWork) {
  const auto why = messageOf<InputError>([&] { OutputFile(path("nowhere/r.exo"), "--output", false); });
  EXPECT_NE(why.find("nowhere/r.exo (--output): cannot create a file next to it"), std::string::npos) << why;
  EXPECT_NE(why.find("check that its directory exists and is writable"), std::string::npos) << why;
  EXPECT_TRUE(leftovers({}).empty());
}
