#pragma once
// Constitutive model interface (docs/theory/fdm.md §1.6), shared by fdm_server
// and continuum_server. A solver calls a model once per element (tetrahedron,
// triangle) per step with the strain increment Δε = ξ Δt (after mixed
// discretization) and the element's stress, which the model updates in place.
// Plastic models keep history per element in a slice of doubles (`state_size()`
// of them) owned by the solver, like the Itasca SDK `State`.
#include <cstddef>
#include <span>
#include <string_view>

#include "dfc/constitutive/sym_tensor.hpp"

namespace dfc::constitutive {

/// Per-tetrahedron history variables of a model (e.g. plastic strains, p_s, p_t).
using StateSpan = std::span<double>;

struct StrainIncrement {
  SymTensor strain;  ///< Δε_ij = ξ_ij Δt, extension positive (tensor shear components)
  // Large strain will add the rotation increment ω Δt here (§1.12).
};

/// Bulk and shear modulus, Pa.
struct ElasticModuli {
  double bulk = 0.0;
  double shear = 0.0;
  /// Constrained (P-wave) modulus α₁ = K + 4G/3 (§1.10).
  [[nodiscard]] double p_wave() const { return bulk + 4.0 * shear / 3.0; }
};

class ConstitutiveModel {
 public:
  virtual ~ConstitutiveModel() = default;

  /// Registry keyword, e.g. "elastic".
  [[nodiscard]] virtual std::string_view keyword() const = 0;
  /// Number of history doubles per tetrahedron.
  [[nodiscard]] virtual std::size_t state_size() const { return 0; }
  /// Sets a tetrahedron's history for its initial stress (e.g. preconsolidation).
  virtual void initialize_state(const Stress& /*initial_stress*/, StateSpan /*state*/) const {}
  /// Updates `stress` for one strain increment. Must be thread-safe for
  /// distinct tetrahedra (called concurrently), i.e. const and without shared scratch.
  virtual void update(const StrainIncrement& increment, Stress& stress, StateSpan state) const = 0;
  /// The stiffest elastic moduli the model can reach: the timestep and the
  /// scaled masses are computed from them (§1.10).
  [[nodiscard]] virtual ElasticModuli stiffest_moduli() const = 0;
  /// True for models whose plastic flow changes the mean stress (plastic
  /// volume change, tension cut-off). The solver then applies mixed
  /// discretization to the stress as well (§1.5, last paragraph; the Itasca SDK
  /// `State::pore_pressure_increment_`): after the update, each tetrahedron's
  /// mean-stress increment is replaced by the zone's volume average. For a
  /// linear elastic law the increments are already equal after the strain-rate
  /// averaging, so the pass is skipped (false) to keep the elastic path fast.
  [[nodiscard]] virtual bool needs_mean_stress_averaging() const { return false; }
  /// Names of the history doubles (state_size() of them), for output and tests.
  [[nodiscard]] virtual std::span<const std::string_view> state_names() const { return {}; }
};

}  // namespace dfc::constitutive
