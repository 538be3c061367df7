#include "tribos/core/RankErrors.hpp"

#include <chrono>
#include <exception>
#include <stdexcept>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <thread>
#include <vector>

#include "tribos/core/Format.hpp"

namespace tribos::core {

namespace {
// Which status the ranks agree on: the most telling one. Bad input explains an internal
// error elsewhere (a rank that read garbage), and both explain a solve that did not end. A
// result that could not be written outranks "not converged": the user has nothing to look at.
int severity(int status) {
  switch (status) {
    case kExitOk: return 0;
    case kExitNotConverged: return 1;
    case kExitIoFailure: return 2;
    case kExitInternal: return 3;
    default: return 4;  // kExitBadInput
  }
}

int statusOfSeverity(int s) {
  constexpr int statuses[] = {kExitOk, kExitNotConverged, kExitIoFailure, kExitInternal, kExitBadInput};
  return statuses[s];
}

bool isFailure(int status) { return status == kExitBadInput || status == kExitInternal; }

/// "rank 1 of 4" or "ranks 1, 3 of 4".
std::string rankList(const std::vector<int>& ranks, int size) {
  std::string text = ranks.size() == 1 ? "rank " : "ranks ";
  for (size_t i = 0; i < ranks.size(); ++i) text += (i ? ", " : "") + std::to_string(ranks[i]);
  return text + " of " + std::to_string(size);
}
}  // namespace

void onEveryRankOrNone(const std::function<void()>& work, const std::string& othersWhat, MPI_Comm comm) {
  std::exception_ptr failure;
  int mine = 0;  // 0 ok, 1 bad input, 2 anything else
  try {
    work();
  } catch (const InputError&) {
    failure = std::current_exception();
    mine = 1;
  } catch (...) {
    failure = std::current_exception();
    mine = 2;
  }
  int worst = 0;
  MPI_Allreduce(&mine, &worst, 1, MPI_INT, MPI_MAX, comm);
  if (failure) std::rethrow_exception(failure);
  if (worst == 1) throw InputError(othersWhat);
  if (worst == 2) throw std::runtime_error(othersWhat);
}

RankErrors::RankErrors(double graceSeconds) : graceSeconds_(graceSeconds) {
  MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

RankErrors::~RankErrors() {
  if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

bool RankErrors::allArrive(bool bounded) {
  if (size_ == 1) return true;
  MPI_Request request;
  MPI_Ibarrier(comm_, &request);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(graceSeconds_);
  // Polled with short sleeps rather than MPI_Wait: a rank that waits here for a slow one
  // then leaves its core to it (Open MPI's blocking wait spins).
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (bounded && std::chrono::steady_clock::now() > deadline) return false;  // the caller aborts
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void RankErrors::abortJob(const std::string& text, int status) const {
  std::cout.flush();
  std::cerr << text << std::endl;
  MPI_Abort(MPI_COMM_WORLD, status);
  std::abort();  // not reached: MPI_Abort does not return
}

int RankErrors::finish(const RankOutcome& outcome, const std::string& program) {
  if (!allArrive(isFailure(outcome.status))) {
    const std::string who = program + " (rank " + std::to_string(rank_) + " of " + std::to_string(size_) + ")";
    abortJob(who + ": " + outcome.message + "\n" + who + ": the other ranks did not reach the end of the run within " +
                 formatNumber(graceSeconds_) + " s (they wait in a communication this rank left): aborting all ranks",
             outcome.status);
  }
  int mine = severity(outcome.status), worst = mine;
  MPI_Allreduce(&mine, &worst, 1, MPI_INT, MPI_MAX, comm_);
  printMessages(outcome, program);
  return statusOfSeverity(worst);
}

void RankErrors::printMessages(const RankOutcome& outcome, const std::string& program) const {
  // Every rank's message to rank 0: lengths, then the characters.
  int length = static_cast<int>(outcome.message.size());
  std::vector<int> lengths(rank_ == 0 ? size_ : 0), offsets(rank_ == 0 ? size_ + 1 : 0, 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, comm_);
  for (int r = 0; r < static_cast<int>(lengths.size()); ++r) offsets[r + 1] = offsets[r] + lengths[r];
  std::string all(rank_ == 0 ? static_cast<size_t>(offsets.back()) : 0, '\0');
  MPI_Gatherv(outcome.message.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
              comm_);
  if (rank_ != 0) return;
  // Distinct messages in rank order, each with the ranks that had it.
  std::vector<std::pair<std::string, std::vector<int>>> distinct;
  for (int r = 0; r < size_; ++r) {
    if (lengths[r] == 0) continue;
    std::string text = all.substr(offsets[r], lengths[r]);
    auto it = distinct.begin();
    while (it != distinct.end() && it->first != text) ++it;
    if (it == distinct.end()) distinct.push_back({std::move(text), {r}});
    else it->second.push_back(r);
  }
  std::cout.flush();
  for (const auto& [text, ranks] : distinct) {
    const bool everywhere = static_cast<int>(ranks.size()) == size_;
    std::cerr << program << (everywhere ? "" : " (" + rankList(ranks, size_) + ")") << ": " << text << "\n";
  }
  std::cerr.flush();
}

void RankErrors::meet(bool failedHere, const std::string& what) {
  if (allArrive(failedHere)) return;
  abortJob(what + " failed on rank " + std::to_string(rank_) + " of " + std::to_string(size_) +
               ", and the other ranks did not finish it within " + formatNumber(graceSeconds_) +
               " s (they wait in a communication that it skipped on this rank): aborting all ranks",
           kExitInternal);
}

}  // namespace tribos::core
