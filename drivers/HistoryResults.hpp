#pragma once
// The result of a load history, written step by step as the steps converge (issue 43), so that
// rank 0 holds no step's fields after it is written and a killed job leaves a checkpoint to
// restart from (Load Steps/Checkpoint Seconds; doc/load_history.md, "Checkpoints").
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ResultFile.hpp"
#include "tribos/core/OutputFile.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/stack/ContactSolve.hpp"

namespace tribos::driver {

/// The StepObserver of every load history (given on every rank; rank 0 works). For each step
/// it sees for the first time it computes what the final write would (stresses, force balance,
/// global variables) and, with --output, appends the time step to a draft of the result file
/// (core::OutputFile::Draft) next to the target. After a converged step, once the interval has
/// passed since the run started or the last checkpoint, a copy of the draft replaces the target:
/// a whole result of the steps so far, never a partial one. A failed write ends the writing (the
/// draft removed) but not the run: finish reports it, as the final write of a run always did.
class HistoryResults {
 public:
  /// `exodus`: the result file on rank 0 (null elsewhere, or without --output).
  HistoryResults(const stack::Scene& scene, core::OutputFile* exodus, double checkpointSeconds,
                 std::vector<std::string> info, int rank);
  ~HistoryResults();
  void operator()(const stack::ContactSolveResult& soFar);

  /// The steps taken so far (rank 0): their results are in the draft, and what they add to the
  /// summary's step entries in summaryOfStep.
  size_t taken() const { return extras_.size(); }
  /// Step i's stresses and force balance as summary keys (stack::addResultsToSummary).
  const nlohmann::json& summaryOfStep(size_t i) const { return extras_[i]; }
  /// Appends the steps not taken (the last state among them), then the draft replaces the
  /// target. Throws core::IoError naming the file where any write failed.
  void finish(const std::vector<OutputStep>& rest);
  int checkpoints() const { return checkpoints_; }

 private:
  void take(const stack::ContactSolveResult& soFar, size_t i);
  void append(const OutputStep& step);
  void checkpoint(int first, int step);
  const stack::Scene& scene_;
  core::OutputFile* exodus_;
  double seconds_;
  int rank_;
  std::unique_ptr<core::OutputFile::Draft> draft_;
  std::unique_ptr<mesh::ExodusWriter> writer_;
  mesh::Field subdomain_;
  core::Stopwatch since_;
  std::vector<nlohmann::json> extras_;
  std::string startError_;  ///< why the draft could not be started (its IoError), reported by finish
  int checkpoints_ = 0;
};

}  // namespace tribos::driver
