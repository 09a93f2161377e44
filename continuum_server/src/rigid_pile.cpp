#include "dfc/continuum/rigid_pile.hpp"

#include <cassert>
#include <cmath>

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
  // A node on a face stays there to round-off: 1e-9 of the pile's radius is
  // far above the round-off of coordinates and far below any element size.
  const double tolerance = 1e-9 * spec_.outer_radius;
  if (x.y() <= tip_ + tolerance) return PileFace::annulus;
  if (spec_.inner_radius > 0.0 && x.x() <= spec_.inner_radius + tolerance) return PileFace::inner_shaft;
  if (x.x() >= spec_.outer_radius - tolerance) return PileFace::outer_shaft;
  // Already inside (a node that crossed a corner): the face of least penetration.
  const double next_tip = tip_ - spec_.velocity;
  PileFace face = PileFace::annulus;
  double least = end.y() - next_tip;
  if (spec_.inner_radius > 0.0 && end.x() - spec_.inner_radius < least) {
    least = end.x() - spec_.inner_radius;
    face = PileFace::inner_shaft;
  }
  if (spec_.outer_radius - end.x() < least) face = PileFace::outer_shaft;
  return face;
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
