#include "dfc/dem/seam_balance.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "dfc/common/work_progress.hpp"

namespace dfc::dem {

namespace {

/// The bonds' graph on compact node numbers: adjacency in CSR form (a
/// neighbour once per bond joining them, with that bond's conductance).
struct BondGraph {
  std::vector<std::uint32_t> particle;  ///< node -> particle
  std::vector<std::uint32_t> start;     ///< node -> first entry in `neighbour`, nodes + 1
  std::vector<std::uint32_t> neighbour;
  std::vector<double> conductance;      ///< per entry of `neighbour`
  std::vector<double> degree;           ///< node -> sum of its entries' conductances
  std::vector<std::array<std::uint32_t, 2>> ends;  ///< bond -> nodes

  [[nodiscard]] std::size_t nodes() const noexcept { return particle.size(); }
};

BondGraph build_graph(std::size_t particle_count, std::span<const BondEnds> bonds, std::span<const double> conductance) {
  BondGraph g;
  std::vector<std::int64_t> node(particle_count, -1);
  const auto node_of = [&](std::uint32_t p) {
    if (node[p] < 0) {
      node[p] = std::int64_t(g.particle.size());
      g.particle.push_back(p);
    }
    return std::uint32_t(node[p]);
  };
  for (const auto& b : bonds) g.ends.push_back({node_of(b[0]), node_of(b[1])});
  std::vector<std::uint32_t> count(g.nodes() + 1, 0);
  for (const auto& e : g.ends) ++count[e[0] + 1], ++count[e[1] + 1];
  std::partial_sum(count.begin(), count.end(), count.begin());
  g.start = count;
  g.neighbour.resize(g.start.back());
  g.conductance.resize(g.start.back());
  g.degree.assign(g.nodes(), 0.0);
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t b = 0; b < g.ends.size(); ++b) {
    const auto& e = g.ends[b];
    g.conductance[fill[e[0]]] = g.conductance[fill[e[1]]] = conductance[b];
    g.neighbour[fill[e[0]]++] = e[1];
    g.neighbour[fill[e[1]]++] = e[0];
    g.degree[e[0]] += conductance[b];
    g.degree[e[1]] += conductance[b];
  }
  return g;
}

/// Connected component of every node (numbered in order of first node).
std::vector<std::uint32_t> components(const BondGraph& g, std::size_t& count) {
  constexpr auto unset = std::uint32_t(-1);
  std::vector<std::uint32_t> component(g.nodes(), unset);
  std::vector<std::uint32_t> stack;
  count = 0;
  for (std::size_t n = 0; n < g.nodes(); ++n) {
    if (component[n] != unset) continue;
    component[n] = std::uint32_t(count);
    stack.push_back(std::uint32_t(n));
    while (!stack.empty()) {
      const std::uint32_t a = stack.back();
      stack.pop_back();
      for (std::uint32_t e = g.start[a]; e < g.start[a + 1]; ++e)
        if (component[g.neighbour[e]] == unset) component[g.neighbour[e]] = std::uint32_t(count), stack.push_back(g.neighbour[e]);
    }
    ++count;
  }
  return component;
}

/// L y on the free nodes (a held node's row is dropped and its y stays 0).
void apply_laplacian(const BondGraph& g, const std::vector<bool>& held, const std::vector<double>& y, std::vector<double>& out) {
  for (std::size_t n = 0; n < g.nodes(); ++n) {
    if (held[n]) {
      out[n] = 0.0;
      continue;
    }
    double sum = g.degree[n] * y[n];
    for (std::uint32_t e = g.start[n]; e < g.start[n + 1]; ++e) sum -= g.conductance[e] * y[g.neighbour[e]];
    out[n] = sum;
  }
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

/// Solves L y = b on the free nodes with y = 0 on the held ones (b zero
/// there, and with zero mean on every component without a held node) by
/// conjugate gradients preconditioned by the degree. Returns the iterations.
std::size_t solve_laplacian(const BondGraph& g, const std::vector<bool>& held, const std::vector<double>& b, std::vector<double>& y) {
  const std::size_t n = g.nodes();
  y.assign(n, 0.0);
  std::vector<double> r = b, z(n), p(n), q(n);
  for (std::size_t i = 0; i < n; ++i) z[i] = r[i] / g.degree[i];
  p = z;
  double rz = dot(r, z);
  // Relative 1e-12 in the residual norm: far below the forces' own round-off
  // relevance; a 3-D bond graph's Laplacian needs O(n^(1/3)) sweeps, so the
  // cap is never the stop in practice.
  const double target = 1e-24 * dot(b, b);
  const std::size_t limit = 20000;
  std::size_t it = 0;
  while (it < limit && dot(r, r) > target) {
    work_progress::advance();  // one conjugate-gradient sweep over the bond graph
    apply_laplacian(g, held, p, q);
    const double pq = dot(p, q);
    if (!(pq > 0.0)) break;
    const double alpha = rz / pq;
    for (std::size_t i = 0; i < n; ++i) y[i] += alpha * p[i], r[i] -= alpha * q[i];
    for (std::size_t i = 0; i < n; ++i) z[i] = r[i] / g.degree[i];
    const double rz_next = dot(r, z);
    for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + rz_next / rz * p[i];
    rz = rz_next;
    ++it;
  }
  return it;
}

}  // namespace

std::vector<bool> within_bond_hops(std::size_t particle_count, std::span<const BondEnds> bonds, const std::vector<bool>& seeds, int hops) {
  std::vector<bool> reached = seeds;
  reached.resize(particle_count, false);
  for (int h = 0; h < hops; ++h) {
    std::vector<bool> next = reached;
    for (const auto& b : bonds)
      if (reached[b[0]] || reached[b[1]]) next[b[0]] = next[b[1]] = true;
    reached = std::move(next);
  }
  return reached;
}

BondNetworkBalance balance_bond_network(std::size_t particle_count, std::span<const BondEnds> bonds, std::span<const double> conductance,
                                        std::span<const Vec3> residual, const std::vector<bool>& supported) {
  BondNetworkBalance out;
  out.correction.assign(bonds.size(), Vec3{});
  if (bonds.empty()) return out;
  const BondGraph g = build_graph(particle_count, bonds, conductance);
  std::size_t component_count = 0;
  const std::vector<std::uint32_t> component = components(g, component_count);
  std::vector<bool> held(g.nodes());
  for (std::size_t n = 0; n < g.nodes(); ++n) held[n] = supported[g.particle[n]];
  // A component held nowhere cannot pass its total to a support: its mean stays.
  std::vector<Vec3> mean(component_count);
  std::vector<double> size(component_count, 0.0);
  std::vector<bool> component_held(component_count, false);
  for (std::size_t n = 0; n < g.nodes(); ++n) {
    mean[component[n]] += residual[g.particle[n]];
    size[component[n]] += 1.0;
    if (held[n]) component_held[component[n]] = true;
  }
  for (std::size_t c = 0; c < component_count; ++c) mean[c] = component_held[c] ? Vec3{} : (1.0 / size[c]) * mean[c];

  std::array<std::vector<double>, 3> y;
  for (int axis = 0; axis < 3; ++axis) {
    const auto pick = [axis](const Vec3& v) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
    std::vector<double> b(g.nodes());
    for (std::size_t n = 0; n < g.nodes(); ++n) b[n] = held[n] ? 0.0 : pick(residual[g.particle[n]]) - pick(mean[component[n]]);
    out.iterations = std::max(out.iterations, solve_laplacian(g, held, b, y[std::size_t(axis)]));
  }
  std::vector<Vec3> after(g.nodes());
  for (std::size_t n = 0; n < g.nodes(); ++n) after[n] = residual[g.particle[n]];
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    const auto [a, b] = g.ends[k];
    const Vec3 f = conductance[k] * Vec3{y[0][b] - y[0][a], y[1][b] - y[1][a], y[2][b] - y[2][a]};
    out.correction[k] = f;
    after[a] += f;
    after[b] -= f;
  }
  for (std::size_t n = 0; n < g.nodes(); ++n) {
    if (held[n]) continue;
    out.residual_before += norm(residual[g.particle[n]]);
    out.residual_after += norm(after[n]);
  }
  return out;
}

}  // namespace dfc::dem
