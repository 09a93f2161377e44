#include "dfc/constitutive/structured_cam_clay_model.hpp"

#include <cmath>
#include <limits>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/errors.hpp"

namespace dfc::constitutive {

namespace {

constexpr std::array<std::string_view, StructuredCamClayModel::kStateSize> kStateNames = {
    "ps_pa",                       // p_s
    "pt_pa",                       // p_t
    "plastic_volumetric_strain",   // Σ Δε_v^p, compression positive
    "plastic_deviatoric_strain",   // Σ Δε_q^p
};

// Halving the strain increment up to 2^10 times: explicit FDM increments are
// small, so the implicit return practically never needs it; it is the safety
// net for a large first increment in an element-test driver.
constexpr int kMaxSubstepDepth = 10;

double mean_pressure(const Stress& s) { return -s.trace() / 3.0; }  // compression positive
double deviatoric_q(const SymTensor& deviator) { return std::sqrt(1.5) * deviator.norm(); }

}  // namespace

StructuredCamClayModel::StructuredCamClayModel(const StructuredCamClayParameters& parameters) : parameters_(parameters) {
  const auto& m = parameters_;
  if (!(m.ps0 > 0.0)) throw UserError("structured_cam_clay: ps0_pa must be > 0");
  if (!(m.pt0 >= 0.0)) throw UserError("structured_cam_clay: pt0_pa must be >= 0");
  if (!(m.mf > 0.0) || !(m.mg > 0.0)) throw UserError("structured_cam_clay: mf and mg must be > 0");
  if (!(m.k >= 0.0)) throw UserError("structured_cam_clay: k must be >= 0");
}

std::unique_ptr<ConstitutiveModel> StructuredCamClayModel::from_config(ConfigReader& material) {
  StructuredCamClayParameters m;
  m.moduli = read_elastic_moduli(material);
  m.ps0 = material.number("ps0_pa");
  m.pt0 = material.number("pt0_pa");
  m.mf = material.number("mf");
  m.mg = material.has("mg") ? material.number("mg") : m.mf;
  m.rho_s = material.number("rho_s");
  m.rho_t = material.number("rho_t");
  m.xi_s = material.number("xi_s");
  m.xi_t = material.number("xi_t");
  m.k = material.number("k");
  return std::make_unique<StructuredCamClayModel>(m);
}

std::span<const std::string_view> StructuredCamClayModel::state_names() const { return kStateNames; }

void StructuredCamClayModel::initialize_state(const Stress& initial_stress, StateSpan state) const {
  const auto& m = parameters_;
  CamClayHardening h{m.ps0, m.pt0};
  const double p = mean_pressure(initial_stress);
  const double q = deviatoric_q(initial_stress.deviator());
  if (cam_clay_yield(p, q, h, m) > 0.0) {
    const double a = p + h.pt;
    if (!(a > 0.0))
      throw UserError("structured_cam_clay: the initial stress (p = " + std::to_string(p) + " Pa, q = " + std::to_string(q) +
                      " Pa) is beyond the tensile strength p_t = " + std::to_string(h.pt) + " Pa; start from a compressive state");
    // f = (q/M_f)² + a(a − p_c) = 0  ⇒  p_c = a + (q/M_f)²/a.
    h.ps = a + (q / m.mf) * (q / m.mf) / a - (1.0 + m.k) * h.pt;
  }
  state[kPs] = h.ps;
  state[kPt] = h.pt;
  state[kPlasticVolumetricStrain] = 0.0;
  state[kPlasticDeviatoricStrain] = 0.0;
}

void StructuredCamClayModel::update(const StrainIncrement& increment, Stress& stress, StateSpan state) const {
  update_substepped(increment.strain, stress, state, 0);
}

void StructuredCamClayModel::update_substepped(const SymTensor& strain_increment, Stress& stress, StateSpan state, int depth) const {
  Stress trial_stress = stress;
  std::array<double, kStateSize> trial_state{};
  std::copy(state.begin(), state.end(), trial_state.begin());
  if (update_once(strain_increment, trial_stress, trial_state)) {
    stress = trial_stress;
    std::copy(trial_state.begin(), trial_state.end(), state.begin());
    return;
  }
  if (depth >= kMaxSubstepDepth) {
    // Called inside the solver's parallel loop, where throwing is not allowed:
    // a NaN stress makes the solver stop with a SolverError naming the gridpoint.
    stress = SymTensor::isotropic(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const SymTensor half = strain_increment * 0.5;
  update_substepped(half, stress, state, depth + 1);
  update_substepped(half, stress, state, depth + 1);
}

bool StructuredCamClayModel::update_once(const SymTensor& strain_increment, Stress& stress, StateSpan state) const {
  const auto& m = parameters_;
  const Stress trial = stress + elastic_stress_increment(m.moduli, strain_increment);
  const CamClayHardening h{state[kPs], state[kPt]};
  const SymTensor trial_deviator = trial.deviator();
  const double p_trial = mean_pressure(trial);
  const double q_trial = deviatoric_q(trial_deviator);
  if (cam_clay_yield(p_trial, q_trial, h, m) <= 0.0) {
    stress = trial;
    return true;
  }
  const std::optional<CamClayReturn> r = cam_clay_return(p_trial, q_trial, h, m);
  if (!r) return false;
  // Radial return in the deviatoric plane: the deviator keeps its direction.
  const double deviator_scale = q_trial > 0.0 ? r->q / q_trial : 0.0;
  stress = trial_deviator * deviator_scale + SymTensor::isotropic(-r->p);
  state[kPs] = r->hardening.ps;
  state[kPt] = r->hardening.pt;
  state[kPlasticVolumetricStrain] += r->u;
  state[kPlasticDeviatoricStrain] += r->w;
  return true;
}

}  // namespace dfc::constitutive
