// A load history's result, written step by step (HistoryResults.hpp).
#include "HistoryResults.hpp"

#include <iostream>

#include "tribos/core/Errors.hpp"
#include "tribos/stack/OutputRegistry.hpp"
#include "tribos/stack/RunReport.hpp"

namespace tribos::driver {

HistoryResults::HistoryResults(const stack::Scene& scene, core::OutputFile* exodus, double checkpointSeconds,
                               std::vector<std::string> info, int rank)
    : scene_(scene), exodus_(exodus), seconds_(checkpointSeconds), rank_(rank) {
  if (rank_ != 0 || !exodus_) return;
  subdomain_ = subdomainField(scene_);
  try {
    draft_ = exodus_->startDraft();
    draft_->write([&](const std::string& path) {
      writer_ = std::make_unique<mesh::ExodusWriter>(path, scene_.mesh, std::move(info));
    });
  } catch (const core::IoError& e) {  // reported by finish, as a final write's failure
    startError_ = e.what();
    std::cout << "  warning: the result file cannot be written as the history goes: " << startError_ << "\n";
  }
}

HistoryResults::~HistoryResults() = default;

void HistoryResults::operator()(const stack::ContactSolveResult& soFar) {
  if (rank_ != 0) return;
  const size_t before = taken();
  for (size_t i = before; i < soFar.earlierSteps.size(); ++i) take(soFar, i);
  if (draft_ && taken() > before && since_.seconds() >= seconds_)
    checkpoint(soFar.steps.front().step, soFar.steps[taken() - 1].step);
}

/// Step i's stresses, force balance and global variables, as the final write would compute
/// them, into the draft.
void HistoryResults::take(const stack::ContactSolveResult& soFar, size_t i) {
  const stack::StepResults& step = soFar.earlierSteps[i];
  const stack::StressResults stress = stack::evaluateStresses(scene_, step.displacement.value);
  const auto balance = stack::forceBalance(scene_, step.reaction, step.appliedLoad, step.appliedLoadMagnitude);
  nlohmann::json extra;
  stack::addResultsToSummary(stress, balance, extra);
  extras_.push_back(extra);
  if (!draft_) return;
  OutputStep out;
  out.time = soFar.steps[i].time;
  out.displacement = &step.displacement.value;
  out.reaction = &step.reaction;
  out.stress = &stress;
  if (!scene_.contacts.empty()) out.contact = &step;
  out.globals = stack::globalVariables(stack::withStresses(stack::outcomeOf(soFar, i), stress, balance));
  append(out);
}

void HistoryResults::append(const OutputStep& step) {
  if (!writer_) return;
  try {
    draft_->write([&](const std::string&) { writer_->append(timeStep(step, subdomain_)); });
  } catch (const core::IoError& e) {  // the draft is gone; finish reports it
    std::cout << "  warning: the result file stops at its last checkpoint: " << e.what() << "\n";
    writer_.reset();
  }
}

/// A copy of the draft replaces the target: the steps `first` (1, or the one after a restart's)
/// to `step`, whole.
void HistoryResults::checkpoint(int first, int step) {
  if (!writer_) return;
  try {
    draft_->publishCopy();
    ++checkpoints_;
    std::cout << "  checkpoint: wrote steps " << first << " to " << step << " of the history to " << exodus_->path() << "\n";
  } catch (const core::IoError& e) {
    std::cout << "  warning: no checkpoint after step " << step << ": " << e.what() << "\n";
  }
  since_ = core::Stopwatch();
}

void HistoryResults::finish(const std::vector<OutputStep>& rest) {
  if (!draft_) throw core::IoError(startError_);
  for (const auto& step : rest) append(step);
  draft_->write([&](const std::string&) {
    if (writer_) writer_->close();
  });
  draft_->commit();
}

}  // namespace tribos::driver
