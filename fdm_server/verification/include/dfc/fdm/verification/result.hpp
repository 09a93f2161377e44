#pragma once
// What a verification problem reports: rows comparing a computed quantity with
// its closed-form value, with the relative error and the tolerance it must meet.
#include <cstddef>
#include <string>
#include <vector>

namespace dfc::fdm::verification {

struct VerificationRow {
  std::string quantity;      ///< what and where, e.g. "σ_θ at the wall, θ = 88°"
  std::string unit;          ///< unit of computed/closed_form as printed, e.g. "MPa"
  double computed = 0.0;
  double closed_form = 0.0;
  double error = 0.0;        ///< relative error |computed − closed_form| / scale
  double tolerance = 0.0;    ///< relative
  [[nodiscard]] bool passed() const { return error <= tolerance; }
};

/// A row whose error is |computed − closed_form| / scale (scale = |closed_form|
/// unless a quantity that passes through zero needs a reference magnitude).
[[nodiscard]] VerificationRow compare(std::string quantity, std::string unit, double computed, double closed_form, double tolerance,
                                      double scale = 0.0);

struct ProblemResult {
  std::string mesh;               ///< e.g. "quarter annulus 12×12×1, b = 6a"
  std::size_t zones = 0;
  double zone_size = 0.0;         ///< characteristic (smallest) zone size where the error is measured, m
  int steps = 0;                  ///< solver steps taken
  double seconds = 0.0;           ///< wall-clock run time
  std::vector<VerificationRow> rows;
  [[nodiscard]] bool passed() const;
  [[nodiscard]] double worst_error_ratio() const;  ///< max error/tolerance over the rows
};

}  // namespace dfc::fdm::verification
