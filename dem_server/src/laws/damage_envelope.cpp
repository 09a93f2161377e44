#include "dfc/dem/damage_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfc::dem {

namespace {

constexpr double bending_exponent = 1.001;  // Ciantia et al. 2024 Eq. 1: |M̆/M̃|^1.001
constexpr double inf = std::numeric_limits<double>::infinity();

/// The (n, v) part h = n² + v⁴/(1 - n²) and the objective of the inner problem.
struct InnerProblem {
  EnvelopePoint trial;
  ReturnWeights w;
  double mu = 0.0;

  [[nodiscard]] static double shear_normal_part(double n, double v) noexcept {
    if (v == 0.0) return n * n;
    const double a = 1.0 - n * n;
    return a > 0.0 ? n * n + v * v * v * v / a : inf;
  }
  [[nodiscard]] double objective(double n, double v) const noexcept {
    if (v < 0.0) return inf;
    const double dn = n - trial.n, dv = v - trial.v;
    return 0.5 * (w.n * dn * dn + w.v * dv * dv) + mu * shear_normal_part(n, v);
  }

  /// argmin over (n, v) of objective: damped Newton from a feasible start (convex problem).
  void solve_nv(double& n, double& v) const noexcept {
    for (int it = 0; it < 100; ++it) {
      const double a = 1.0 - n * n;
      const double v2 = v * v, v3 = v2 * v, v4 = v2 * v2;
      const double hn = v == 0.0 ? 2.0 * n : 2.0 * n + 2.0 * n * v4 / (a * a);
      const double hv = v == 0.0 ? 0.0 : 4.0 * v3 / a;
      const double hnn = v == 0.0 ? 2.0 : 2.0 + v4 * (2.0 + 6.0 * n * n) / (a * a * a);
      const double hvv = v == 0.0 ? 0.0 : 12.0 * v2 / a;
      const double hnv = v == 0.0 ? 0.0 : 8.0 * n * v3 / (a * a);
      const double gn = w.n * (n - trial.n) + mu * hn;
      const double gv = w.v * (v - trial.v) + mu * hv;
      const double Hnn = w.n + mu * hnn, Hvv = w.v + mu * hvv, Hnv = mu * hnv;
      const double det = Hnn * Hvv - Hnv * Hnv;
      const double sn = -(Hvv * gn - Hnv * gv) / det;
      const double sv = -(Hnn * gv - Hnv * gn) / det;
      if (std::abs(sn) + std::abs(sv) < 1e-15) return;
      // Near the minimiser full Newton steps converge quadratically, while the
      // decrease they promise (~|s|²) falls below the round-off of the
      // objective from |s| ~ 1e-8 on, so a line search there would shrink them
      // at random (measured: thousands of halvings per return, 13x the time): take them as they are.
      if (std::abs(sn) + std::abs(sv) < 1e-8 && std::abs(n + sn) < 1.0) {
        n += sn;
        v = std::max(0.0, v + sv);
        continue;
      }
      const double f0 = objective(n, v);
      const double slope = gn * sn + gv * sv;
      // Fraction to the boundary: the objective is +inf at |n| >= 1 (v > 0),
      // so a full step across it would only be halved back; stop short of it.
      double step = 1.0;
      if (v + sv > 0.0 && std::abs(n + sn) >= 1.0) step = 0.99 * (sn > 0.0 ? (1.0 - n) / sn : (1.0 + n) / -sn);
      while (step > 1e-12) {
        const double cn = n + step * sn, cv = v + step * sv;
        if (objective(cn, cv) <= f0 + 1e-4 * step * slope) {
          n = cn;
          v = cv;
          break;
        }
        step *= 0.5;
      }
      if (step <= 1e-12) return;
    }
  }

  /// argmin over m >= 0 of w_m (m - t)²/2 + mu m^1.001: the root of a monotone
  /// function on [0, t]; Newton safeguarded by the bracket, stopped when the
  /// Newton step is below round-off of t (the iterate that just moved a bound
  /// is never strictly inside it, and a one-sided approach never shrinks the
  /// bracket, so neither can be the test).
  [[nodiscard]] double solve_m() const noexcept {
    const double t = trial.m;
    if (t == 0.0 || mu == 0.0) return t;
    // m^0.001 is still ~0.96 at m = 1e-16 t: when the gradient is already
    // positive there, the root lies below the round-off of t and is 0 (else
    // the iteration would creep down through hundreds of decades).
    const double floor_m = 1e-16 * t;
    if (w.m * (floor_m - t) + mu * bending_exponent * std::pow(floor_m, bending_exponent - 1.0) >= 0.0) return 0.0;
    double lo = floor_m, hi = t, m = 0.5 * t;
    for (int it = 0; it < 200 && hi - lo > 1e-16 * t; ++it) {
      const double power = std::pow(m, bending_exponent - 1.0);  // m^0.001; m^-0.999 = power / m
      const double gm = w.m * (m - t) + mu * bending_exponent * power;
      if (gm > 0.0) hi = m;
      else lo = m;
      const double slope = w.m + mu * bending_exponent * (bending_exponent - 1.0) * power / m;
      const double next = m - gm / slope;
      if (std::abs(next - m) <= 1e-15 * t) return std::clamp(next, lo, hi);
      m = next > lo && next < hi ? next : 0.5 * (lo + hi);
    }
    return m;
  }
};

}  // namespace

double damage_envelope(const EnvelopePoint& x) noexcept {
  return std::pow(std::abs(x.m), bending_exponent) + InnerProblem::shear_normal_part(x.n, std::abs(x.v)) - 1.0;
}

bool outside_damage_envelope(const EnvelopePoint& x) noexcept {
  const double m = std::abs(x.m);
  if (m <= 1.0 && InnerProblem::shear_normal_part(x.n, std::abs(x.v)) + m <= 1.0 - 1e-12) return false;
  return damage_envelope(x) > 0.0;
}

EnvelopePoint closest_admissible_point(const EnvelopePoint& trial, const ReturnWeights& weights) noexcept {
  if (damage_envelope(trial) <= 0.0) return trial;
  // Scale the weights to O(1): only their ratios matter.
  const double wmax = std::max({weights.n, weights.v, weights.m});
  InnerProblem p{trial, {weights.n / wmax, weights.v / wmax, weights.m / wmax}, 0.0};
  double n = 0.0, v = 0.0;  // feasible start; later solves start from the last solution
  const auto point_at = [&](double mu) {
    p.mu = mu;
    p.solve_nv(n, v);
    return EnvelopePoint{n, v, p.solve_m()};
  };
  // x(mu) = argmin ½|x - t|²_w + mu f(x) tends to the trial point as mu -> 0 and
  // into the surface as mu grows; phi(mu) = f(x(mu)) decreases with mu, and
  // phi(0) = f(trial) > 0. Bracket the root, then close in on it by regula
  // falsi with the Illinois modification (a bound kept twice in a row has its
  // phi halved, so both ends converge: Dahlquist & Björck, Numerical Methods,
  // §6.2), far fewer inner solves than bisection to |f| <= 1e-12.
  double lo = 0.0, hi = 1.0;
  double phi_lo = damage_envelope(trial);
  EnvelopePoint best = point_at(hi);
  double phi_hi = damage_envelope(best);
  for (int it = 0; it < 200 && phi_hi > 0.0; ++it) {
    lo = hi;
    phi_lo = phi_hi;
    hi *= 4.0;
    best = point_at(hi);
    phi_hi = damage_envelope(best);
  }
  double phi_best = phi_hi;  // f of `best` (phi_hi may be halved below)
  int kept = 0;              // +1: hi was replaced last time, -1: lo was
  for (int it = 0; it < 200 && phi_best < -1e-12; ++it) {
    double mid = (lo * phi_hi - hi * phi_lo) / (phi_hi - phi_lo);
    if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const EnvelopePoint x = point_at(mid);
    const double phi = damage_envelope(x);
    if (phi > 0.0) {
      lo = mid;
      phi_lo = phi;
      if (kept == -1) phi_hi *= 0.5;
      kept = -1;
    } else {
      hi = mid;
      phi_hi = phi;
      phi_best = phi;
      best = x;
      if (kept == +1) phi_lo *= 0.5;
      kept = +1;
    }
  }
  // `best` is the last admissible point, within 1e-12 of the surface.
  best.n = std::copysign(best.n, trial.n);  // a point on n = 0 keeps the trial's side
  return best;
}

}  // namespace dfc::dem
