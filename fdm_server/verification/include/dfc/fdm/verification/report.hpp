#pragma once
// Tables of verification results: plain text for the terminal, markdown for
// docs/verification.md.
#include <string>
#include <vector>

#include "dfc/fdm/verification/problems.hpp"

namespace dfc::fdm::verification {

/// One problem run at one mesh level.
struct ProblemRun {
  const VerificationProblem* problem = nullptr;
  int level = 0;
  ProblemResult result;
};

/// A problem's runs over increasing levels (the refinement study).
struct RefinementSeries {
  const VerificationProblem* problem = nullptr;
  std::vector<ProblemRun> runs;
  /// True when the largest row error falls at every refinement.
  [[nodiscard]] bool error_falls() const;
};

[[nodiscard]] std::string text_table(const std::vector<ProblemRun>& runs);
[[nodiscard]] std::string text_refinement_table(const std::vector<RefinementSeries>& series);

/// The whole docs/verification.md: the table, the tolerances and why, and the
/// refinement study when `series` is not empty. `command` is the command line
/// that produced it.
[[nodiscard]] std::string markdown_report(const std::vector<ProblemRun>& runs, const std::vector<RefinementSeries>& series,
                                          const std::string& command);

}  // namespace dfc::fdm::verification
