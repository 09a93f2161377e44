#pragma once
// The verification suite (docs/theory/fdm.md §2): one table of problems, each a
// fixture run by the library directly and compared with its closed form. The
// executable fdm_verification and the CTest entries both run this table.
#include <span>
#include <string_view>

#include "dfc/fdm/verification/result.hpp"

namespace dfc::fdm::verification {

struct VerificationProblem {
  std::string_view key;        ///< command-line name, e.g. "kirsch"
  std::string_view title;      ///< e.g. "Kirsch: hole in a plate under far-field stress"
  std::string_view reference;  ///< section of docs/theory/fdm.md
  double tolerance;            ///< relative, for every row
  std::string_view why;        ///< why that tolerance
  int unit_level;              ///< fast mesh (CTest label "unit", < ~20 s)
  int slow_level;              ///< finer mesh (CTest label "slow")
  bool refinement_study;       ///< part of the mesh-refinement table
  ProblemResult (*run)(int level);
};

[[nodiscard]] std::span<const VerificationProblem> verification_problems();
/// nullptr when unknown.
[[nodiscard]] const VerificationProblem* find_verification_problem(std::string_view key);

}  // namespace dfc::fdm::verification
