#include "dfc/continuum/triangle_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>

namespace dfc::continuum {

double TriangleGeometry::volume() const { return 2.0 * std::numbers::pi * centroid_r * area; }

NodalVectors gather(std::span<const Point> values, const Triangle& triangle) {
  return {values[triangle[0]], values[triangle[1]], values[triangle[2]]};
}

TriangleGeometry triangle_geometry(const NodalVectors& p) {
  TriangleGeometry g;
  const double twice_area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[2].x() - p[0].x()) * (p[1].y() - p[0].y());
  g.area = 0.5 * twice_area;
  g.centroid_r = (p[0].x() + p[1].x() + p[2].x()) / 3.0;
  for (int i = 0; i < 3; ++i) {
    const Point& pj = p[(i + 1) % 3];
    const Point& pk = p[(i + 2) % 3];
    g.dn_dr[i] = (pj.y() - pk.y()) / twice_area;
    g.dn_dz[i] = (pk.x() - pj.x()) / twice_area;
  }
  return g;
}

double smallest_angle_deg(const NodalVectors& p) {
  double smallest = 180.0;
  for (int i = 0; i < 3; ++i) {
    const Point u = p[(i + 1) % 3] - p[i];
    const Point v = p[(i + 2) % 3] - p[i];
    const double cosine = std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0);
    smallest = std::min(smallest, std::acos(cosine) * 180.0 / std::numbers::pi);
  }
  return smallest;
}

VelocityGradient velocity_gradient(const TriangleGeometry& g, const NodalVectors& v) {
  VelocityGradient l;
  double mean_radial_velocity = 0.0;
  for (int i = 0; i < 3; ++i) {
    l.rr += v[i].x() * g.dn_dr[i];
    l.rz += v[i].x() * g.dn_dz[i];
    l.zr += v[i].y() * g.dn_dr[i];
    l.zz += v[i].y() * g.dn_dz[i];
    mean_radial_velocity += v[i].x() / 3.0;
  }
  l.hoop = mean_radial_velocity / g.centroid_r;
  return l;
}

SymTensor rate_of_deformation(const VelocityGradient& l) {
  SymTensor d;
  d.xx = l.rr;
  d.yy = l.hoop;
  d.zz = l.zz;
  d.zx = 0.5 * (l.rz + l.zr);
  return d;
}

double spin_rz(const VelocityGradient& l) { return 0.5 * (l.rz - l.zr); }

void rotate_by_jaumann(Stress& stress, double spin_increment) {
  Eigen::Matrix3d omega = Eigen::Matrix3d::Zero();
  omega(0, 2) = spin_increment;  // r (x) – z (z) plane
  omega(2, 0) = -spin_increment;
  const Eigen::Matrix3d s = stress.matrix();
  stress += SymTensor::symmetric_part(omega * s - s * omega);
}

NodalVectors internal_forces(const TriangleGeometry& g, const Stress& s) {
  const double volume = g.volume();
  NodalVectors f;
  for (int i = 0; i < 3; ++i) {
    f[i].x() = volume * (s.xx * g.dn_dr[i] + s.zx * g.dn_dz[i] + s.yy / (3.0 * g.centroid_r));
    f[i].y() = volume * (s.zx * g.dn_dr[i] + s.zz * g.dn_dz[i]);
  }
  return f;
}

std::array<double, 3> stiffness_row_sums(const TriangleGeometry& g, double bulk, double shear) {
  // Engineering strains (ε_rr, ε_zz, ε_θθ, γ_rz) of the six nodal displacements (u_r0, u_z0, …).
  Eigen::Matrix<double, 4, 6> b = Eigen::Matrix<double, 4, 6>::Zero();
  for (int i = 0; i < 3; ++i) {
    b(0, 2 * i) = g.dn_dr[i];
    b(1, 2 * i + 1) = g.dn_dz[i];
    b(2, 2 * i) = 1.0 / (3.0 * g.centroid_r);
    b(3, 2 * i) = g.dn_dz[i];
    b(3, 2 * i + 1) = g.dn_dr[i];
  }
  const double lambda = bulk - 2.0 * shear / 3.0;
  Eigen::Matrix4d d = Eigen::Matrix4d::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  d.topLeftCorner<3, 3>().diagonal().array() += 2.0 * shear;
  d(3, 3) = shear;
  const Eigen::Matrix<double, 6, 6> k = g.volume() * b.transpose() * d * b;
  const Eigen::Matrix<double, 6, 1> rows = k.cwiseAbs().rowwise().sum();
  return {std::max(rows(0), rows(1)), std::max(rows(2), rows(3)), std::max(rows(4), rows(5))};
}

}  // namespace dfc::continuum
