#include "dfc/constitutive/cam_clay_return.hpp"

#include <algorithm>
#include <cmath>

namespace dfc::constitutive {

namespace {

// Newton's method stops when the update is below this fraction of the plastic
// strain and f below this fraction of p_c²: round-off level for doubles with
// a margin for the exponentials.
constexpr double kRelativeTolerance = 1e-12;
// r2 is |(u,w)||∇g| times the sine of the angle between them.
constexpr double kCollinearityTolerance = 1e-9;
constexpr int kMaxIterations = 60;
constexpr int kMaxLineSearchHalvings = 12;

struct Residual {
  double r1 = 0.0, r2 = 0.0;                        // f and the collinearity u g_q − w g_p
  double j11 = 0.0, j12 = 0.0, j21 = 0.0, j22 = 0.0;  // ∂(r1, r2)/∂(u, w)
  double scale1 = 1.0, scale2 = 1.0;                // for a dimensionless norm
  [[nodiscard]] double norm() const { return std::hypot(r1 / scale1, r2 / scale2); }
};

Residual residual(double p_trial, double q_trial, double u, double w, const CamClayHardening& h, const StructuredCamClayParameters& m) {
  const double bulk = m.moduli.bulk;
  const double shear3 = 3.0 * m.moduli.shear;
  const double p = p_trial - bulk * u;
  const double q = q_trial - shear3 * w;
  const CamClayHardening hh = cam_clay_hardened(h, u, w, m);
  const double a = p + hh.pt;
  const double pc = hh.ps + (1.0 + m.k) * hh.pt;
  const double mf2 = m.mf * m.mf;
  const double mg2 = m.mg * m.mg;
  const double gp = 2.0 * a - pc;  // ∂g/∂p = ∂f/∂p
  const double gq = 2.0 * q / mg2;
  const double fq = 2.0 * q / mf2;

  // Derivatives of the hardening variables (the |u| of the p_t law has slope sgn u).
  const double sign_u = u > 0.0 ? 1.0 : (u < 0.0 ? -1.0 : 0.0);
  const double ps_u = m.rho_s * hh.ps;
  const double ps_w = m.rho_s * m.xi_s * hh.ps;
  const double pt_u = -m.rho_t * sign_u * hh.pt;
  const double pt_w = -m.rho_t * m.xi_t * hh.pt;
  const double a_u = -bulk + pt_u;
  const double a_w = pt_w;
  const double pc_u = ps_u + (1.0 + m.k) * pt_u;
  const double pc_w = ps_w + (1.0 + m.k) * pt_w;
  const double gp_u = 2.0 * a_u - pc_u;
  const double gp_w = 2.0 * a_w - pc_w;
  const double gq_w = -2.0 * shear3 / mg2;

  Residual r;
  r.r1 = q * q / mf2 + a * (a - pc);
  r.r2 = u * gq - w * gp;
  r.j11 = a_u * gp - a * pc_u;
  r.j12 = -fq * shear3 + a_w * gp - a * pc_w;
  r.j21 = gq - w * gp_u;
  r.j22 = u * gq_w - gp - w * gp_w;
  r.scale1 = pc * pc;
  r.scale2 = std::max(std::hypot(u, w) * std::hypot(gp, gq), 1e-300);
  return r;
}

}  // namespace

double cam_clay_yield(double p, double q, const CamClayHardening& h, const StructuredCamClayParameters& m) {
  const double a = p + h.pt;
  const double pc = h.ps + (1.0 + m.k) * h.pt;
  return (q / m.mf) * (q / m.mf) + a * (a - pc);
}

CamClayHardening cam_clay_hardened(const CamClayHardening& h, double u, double w, const StructuredCamClayParameters& m) {
  return {h.ps * std::exp(m.rho_s * (u + m.xi_s * w)), h.pt * std::exp(-m.rho_t * (std::abs(u) + m.xi_t * w))};
}

std::optional<CamClayReturn> cam_clay_return(double p_trial, double q_trial, const CamClayHardening& h,
                                             const StructuredCamClayParameters& m) {
  const double bulk = m.moduli.bulk;
  const double shear3 = 3.0 * m.moduli.shear;
  // Start from the elastic-predictor estimate without hardening (cutting plane):
  // λ = f/(∂f/∂σ : D : ∂g/∂σ) = f / (K f_p g_p + 3G f_q g_q).
  const double a = p_trial + h.pt;
  const double pc = h.ps + (1.0 + m.k) * h.pt;
  const double gp0 = 2.0 * a - pc;
  const double gq0 = 2.0 * q_trial / (m.mg * m.mg);
  const double fq0 = 2.0 * q_trial / (m.mf * m.mf);
  const double denominator = bulk * gp0 * gp0 + shear3 * fq0 * gq0;
  if (!(denominator > 0.0)) return std::nullopt;
  const double lambda = cam_clay_yield(p_trial, q_trial, h, m) / denominator;
  double u = lambda * gp0;
  double w = std::clamp(lambda * gq0, 0.0, q_trial / shear3);

  Residual r = residual(p_trial, q_trial, u, w, h, m);
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const double det = r.j11 * r.j22 - r.j12 * r.j21;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return std::nullopt;
    const double du = -(r.r1 * r.j22 - r.r2 * r.j12) / det;
    const double dw = -(r.j11 * r.r2 - r.j21 * r.r1) / det;
    // Backtracking line search on the dimensionless residual norm keeps the
    // iteration inside the basin of the admissible root (w in [0, q_tr/3G]).
    double step = 1.0;
    Residual next;
    double u_next = u;
    double w_next = w;
    for (int halving = 0; halving <= kMaxLineSearchHalvings; ++halving, step *= 0.5) {
      u_next = u + step * du;
      w_next = std::clamp(w + step * dw, 0.0, q_trial / shear3);
      next = residual(p_trial, q_trial, u_next, w_next, h, m);
      if (next.norm() < r.norm() || next.norm() < kRelativeTolerance) break;
    }
    u = u_next;
    w = w_next;
    r = next;
    if (std::abs(r.r1) <= kRelativeTolerance * r.scale1 && std::abs(r.r2) <= kCollinearityTolerance * r.scale2) {
      CamClayReturn out;
      out.p = p_trial - bulk * u;
      out.q = q_trial - shear3 * w;
      out.u = u;
      out.w = w;
      out.hardening = cam_clay_hardened(h, u, w, m);
      // Admissible root: a non-negative multiplier, i.e. u has the sign of
      // ∂g/∂p (w >= 0 already has that of ∂g/∂q). Near the critical state both
      // vanish, hence the round-off allowance.
      const double pc_final = out.hardening.ps + (1.0 + m.k) * out.hardening.pt;
      const double gp = 2.0 * (out.p + out.hardening.pt) - pc_final;
      if (u * gp < -kCollinearityTolerance * std::abs(u) * pc_final) return std::nullopt;
      return out;
    }
  }
  return std::nullopt;
}

double cam_clay_yield_q_on_path(double p0, double slope, const CamClayHardening& h, const StructuredCamClayParameters& m) {
  // f(p0 + q/s, q) = (1/M² + 1/s²) q² + (2A − p_c) q/s + A(A − p_c) = 0, A = p0 + p_t.
  const double a0 = p0 + h.pt;
  const double pc = h.ps + (1.0 + m.k) * h.pt;
  const double qa = 1.0 / (m.mf * m.mf) + 1.0 / (slope * slope);
  const double qb = (2.0 * a0 - pc) / slope;
  const double qc = a0 * (a0 - pc);
  return (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
}

}  // namespace dfc::constitutive
