#pragma once
/// \file RankErrors.hpp
/// How an MPI run ends when something fails on some ranks only: one message, one exit
/// status, every rank gone within seconds.
///
/// A rank that throws leaves the collective sequence of the program: if the other ranks
/// then wait in a collective it will never enter, only MPI_Abort can end them. But often
/// they do reach the end of their work (the error was found by every rank, or the others
/// had finished), and then the ranks can agree: exchange their statuses and messages,
/// print each message once (by rank 0), and all exit normally with the same status —
/// no "MPI_ABORT was invoked" noise. So a rank that failed waits a few seconds (the grace)
/// for the others to reach that agreement, and aborts the job only if they do not.
///
/// The agreement runs on a duplicate of MPI_COMM_WORLD, so that its collectives can never
/// match a collective of the program (or of Trilinos) on another rank.
#include <mpi.h>

#include <functional>
#include <string>

#include "tribos/core/Errors.hpp"

namespace tribos::core {

/// Runs `work` on every rank of `comm` and makes the outcome collective: when it throws on
/// some ranks, every rank throws (those ranks their own exception; the others an InputError
/// `othersWhat` when every failure was bad input, else a std::runtime_error with it), so that
/// no rank goes on into a collective the failed ones never reach. Collective.
void onEveryRankOrNone(const std::function<void()>& work, const std::string& othersWhat, MPI_Comm comm);

/// What one rank knows when its work ends.
struct RankOutcome {
  int status = kExitOk;  ///< an ExitStatus
  std::string message;   ///< e.g. "error: mesh.exo: ..."; empty: nothing to print
};

/// Construct on every rank right after MPI_Init, before any work (duplicating the
/// communicator is collective); destroy before MPI_Finalize.
class RankErrors {
 public:
  /// How long a failed rank waits for the others before it aborts the job: long enough for
  /// ranks that found the same error a little later, short enough to count as prompt.
  static constexpr double kDefaultGraceSeconds = 5.0;

  explicit RankErrors(double graceSeconds = kDefaultGraceSeconds);
  ~RankErrors();
  RankErrors(const RankErrors&) = delete;
  RankErrors& operator=(const RankErrors&) = delete;

  /// Every rank calls this once with its outcome and exits with the status it returns. The
  /// status is the same on every rank: an input error (2) wins over an internal error (1),
  /// which wins over results that could not be written (4), which win over "not converged"
  /// (3). Rank 0 prints each distinct message once on stderr
  /// as "<program>: <message>", with "(rank r of n)" after the program when not every rank
  /// had it. A rank whose status is 1 or 2 waits at most the grace for the others; then it
  /// prints its own message with its rank and calls MPI_Abort with its status.
  int finish(const RankOutcome& outcome, const std::string& program);

  /// For a test harness, after each test: every rank calls this. A rank where `what` failed
  /// waits at most the grace for the others; if they do not come (they wait in a collective
  /// the test skipped on this rank), it says so on stderr and aborts the job (status 1)
  /// instead of hanging. Ranks where it passed wait as long as it takes.
  void meet(bool failedHere, const std::string& what);

 private:
  /// Waits on a barrier of all ranks; false if `bounded` and the grace ran out first.
  bool allArrive(bool bounded);
  [[noreturn]] void abortJob(const std::string& text, int status) const;
  void printMessages(const RankOutcome& outcome, const std::string& program) const;

  MPI_Comm comm_ = MPI_COMM_NULL;
  double graceSeconds_;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace tribos::core
