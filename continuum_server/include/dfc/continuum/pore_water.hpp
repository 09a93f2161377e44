#pragma once
// The pore water of the u–p_w formulation (docs/continuum_pile.md §6): its
// parameters and the storage they give. Biot (1941, J. Appl. Phys.
// 12:155–164, doi:10.1063/1.1712886): effective stress σ′ = σ + α p_w I
// (stresses tension positive, the pore pressure p_w compression positive),
// fluid mass balance (1/M_w) ∂p_w/∂t + α ∂ε_v/∂t + ∇·q = 0 with Darcy's
// q = −(k/γ_w) ∇p_w, where p_w is the excess over the hydrostatic pressure
// (gravity is not modelled). Grains incompressible: the Biot modulus is
// M_w = K_f/n (in general 1/M_w = n/K_f + (α − n)/K_s, K_s → ∞ here).
namespace dfc::continuum {

struct PoreWaterSettings {
  bool enabled = false;
  double fluid_bulk_modulus = 2.2e9;       ///< K_f, Pa (water at 20 °C)
  double porosity = 0.4;                   ///< n
  double biot_coefficient = 1.0;           ///< α (1: incompressible grains)
  double hydraulic_conductivity = 1e-7;    ///< k, m/s (Darcy's coefficient of permeability)
  double water_unit_weight = 9810.0;       ///< γ_w, N/m³
  /// Real time the flow advances per mechanical step, s (0: undrained).
  double time_per_step = 0.0;
  /// Flow substeps allowed per mechanical step before the solver refuses
  /// (std::runtime_error naming this setting and time_per_step).
  int max_flow_substeps = 100;

  /// Biot modulus M_w = K_f / n, Pa: the pore pressure rise per unit of
  /// water volume pressed into the pores per unit volume.
  [[nodiscard]] double biot_modulus() const { return fluid_bulk_modulus / porosity; }
  /// k/γ_w, m²/(Pa s): Darcy flux per unit pore-pressure gradient.
  [[nodiscard]] double mobility() const { return hydraulic_conductivity / water_unit_weight; }
};

}  // namespace dfc::continuum
