#include "dfc/continuum/rigid_pile.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "dfc/continuum/local_damping.hpp"

namespace dfc::continuum {

namespace {

/// Where a face is, which coordinate is its normal and which way the soil is.
struct FaceFrame {
  int normal_axis;      ///< 0: r, 1: z
  double position;      ///< the face's coordinate along the normal axis after the step
  double outward;       ///< +1 or −1: the direction from the pile into the soil
  double pile_tangential_velocity;  ///< the pile's velocity along the face
};

}  // namespace

RigidPile::RigidPile(const RigidPileSpec& spec) : spec_(spec), tip_(spec.tip) {
  assert(spec.inner_radius >= 0.0 && spec.outer_radius > spec.inner_radius && spec.friction >= 0.0);
}

void RigidPile::move() { tip_ -= spec_.velocity; }

bool RigidPile::inside(const Point& x, double tip) const {
  // Closed: a node on a face is in contact if it presses on it (contact()
  // drops a contact whose force would pull). A solid punch (r_i = 0) covers the axis.
  return x.x() >= spec_.inner_radius && x.x() <= spec_.outer_radius && x.y() >= tip;
}

PileFace RigidPile::face_met(const Point& x, const Point& end) const {
  // In the pile's frame the node moves from x (the pile at tip_) to end (the
  // pile at tip_ − velocity). Each face's signed distance outwards, at the
  // start (d) and at the end (e ≤ 0: inside that face's half-plane). The node
  // enters through the face whose half-plane it enters last, among those it
  // was outside of (or on) at the start; without one (it was already inside,
  // past a corner) through the face it penetrates least.
  const double next_tip = tip_ - spec_.velocity;
  const bool bore = spec_.inner_radius > 0.0;
  const std::array<PileFace, 3> faces{PileFace::annulus, PileFace::inner_shaft, PileFace::outer_shaft};
  const std::array<double, 3> start{tip_ - x.y(), spec_.inner_radius - x.x(), x.x() - spec_.outer_radius};
  const std::array<double, 3> finish{next_tip - end.y(), spec_.inner_radius - end.x(), end.x() - spec_.outer_radius};
  // A node on a face stays there to round-off: 1e-9 of the pile's radius is
  // far above the round-off of coordinates and far below any element size.
  const double tolerance = 1e-9 * spec_.outer_radius;
  PileFace entered = PileFace::none;
  double latest = -1.0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if ((f == 1 && !bore) || start[f] < -tolerance) continue;
    const double before = std::max(0.0, start[f]);
    const double crossing = before > 0.0 ? before / (before - finish[f]) : 0.0;
    // Ties (a node on the corner): the annulus, listed first.
    if (crossing > latest) {
      latest = crossing;
      entered = faces[f];
    }
  }
  if (entered != PileFace::none) return entered;
  std::size_t least = 0;
  for (std::size_t f = 1; f < faces.size(); ++f)
    if ((f != 1 || bore) && finish[f] > finish[least]) least = f;
  return faces[least];
}

NodeContact RigidPile::contact(const ContactNodeState& node) const {
  const double next_tip = tip_ - spec_.velocity;
  const Point end = node.position + node.trial_velocity;
  if (!inside(end, next_tip)) return {};
  const PileFace face = face_met(node.position, end);
  FaceFrame frame{};
  switch (face) {
    case PileFace::annulus: frame = {1, next_tip, -1.0, 0.0}; break;
    case PileFace::inner_shaft: frame = {0, spec_.inner_radius, -1.0, -spec_.velocity}; break;
    case PileFace::outer_shaft: frame = {0, spec_.outer_radius, 1.0, -spec_.velocity}; break;
    case PileFace::none: return {};
  }
  const auto n = static_cast<Eigen::Index>(frame.normal_axis);
  const auto t = static_cast<Eigen::Index>(1 - frame.normal_axis);
  if (node.prescribed[static_cast<std::size_t>(n)]) return {};
  // Normal: the total force that ends the step on the face, less the force already there.
  const double normal_change = frame.position - node.position[n] - node.velocity[n];
  const double normal =
      force_for_velocity_change(normal_change, node.velocity[n], node.mass, node.damping) - node.force[n];
  if (normal * frame.outward <= 0.0) return {};  // the face would have to pull: no contact
  NodeContact contact{face, Point::Zero(), false};
  contact.force[n] = normal;
  if (!node.prescribed[static_cast<std::size_t>(t)]) {
    // Tangential: sticking moves the node with the pile; Coulomb bounds it.
    const double stick_change = frame.pile_tangential_velocity - node.velocity[t];
    double tangential =
        force_for_velocity_change(stick_change, node.velocity[t], node.mass, node.damping) - node.force[t];
    const double limit = spec_.friction * std::abs(normal);
    if (std::abs(tangential) > limit) {
      tangential = std::copysign(limit, tangential);
      contact.sliding = true;
    }
    contact.force[t] = tangential;
  }
  return contact;
}

Point RigidPile::pushed_out(const Point& x) const {
  const bool bore = spec_.inner_radius > 0.0;
  const double above_tip = x.y() - tip_;
  const double from_inner = bore ? x.x() - spec_.inner_radius : std::numeric_limits<double>::infinity();
  const double from_outer = spec_.outer_radius - x.x();
  if (!(above_tip > 0.0 && from_inner > 0.0 && from_outer > 0.0)) return x;
  Point out = x;
  if (above_tip <= from_inner && above_tip <= from_outer) out.y() = tip_;
  else if (from_inner <= from_outer) out.x() = spec_.inner_radius;
  else out.x() = spec_.outer_radius;
  return out;
}

PileForces RigidPile::forces_on_pile(std::span<const NodeContact> contacts) {
  PileForces forces;
  for (const NodeContact& c : contacts) {
    // The pile's force on the node is the node's on the pile, reversed.
    const double upward = -c.force.y();
    switch (c.face) {
      case PileFace::annulus: forces.annulus += upward; break;
      case PileFace::inner_shaft: forces.inner_shaft += upward; break;
      case PileFace::outer_shaft: forces.outer_shaft += upward; break;
      case PileFace::none: break;
    }
  }
  return forces;
}

}  // namespace dfc::continuum
