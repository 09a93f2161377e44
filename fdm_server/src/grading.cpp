#include "dfc/fdm/grading.hpp"

#include <cmath>

namespace dfc::fdm {

std::vector<double> geometric_spacing(double start, double end, Index n, double ratio) {
  const double length = end - start;
  // Δ_k = Δ_0 qᵏ with Σ Δ_k = length; q = 1 is the uniform limit (the closed
  // form divides by zero there, so it has its own branch).
  const bool uniform = std::abs(ratio - 1.0) < 1e-12;
  std::vector<double> x;
  x.reserve(n + 1);
  x.push_back(start);
  if (uniform) {
    for (Index k = 1; k < n; ++k) x.push_back(start + length * (double(k) / double(n)));
  } else {
    double step = length * (ratio - 1.0) / (std::pow(ratio, double(n)) - 1.0);
    for (Index k = 1; k < n; ++k) {
      x.push_back(x.back() + step);
      step *= ratio;
    }
  }
  x.push_back(end);  // exact, not accumulated
  return x;
}

}  // namespace dfc::fdm
