// What a solve hands to the results (SolveResults.hpp): releasing a written step's fields.
#include "tribos/stack/SolveResults.hpp"

namespace tribos::stack {

void releaseNodalFields(StepResults& step) {
  for (const auto& field : kContactNodalFields) std::vector<double>().swap(step.*field.values);
  std::vector<std::array<double, 3>>().swap(step.displacement.value);
  std::vector<std::array<double, 3>>().swap(step.reaction);
}

void releaseWrittenSteps(ContactSolveResult& result) {
  for (size_t i = 0; i + 1 < result.earlierSteps.size(); ++i) releaseNodalFields(result.earlierSteps[i]);
}

}  // namespace tribos::stack
