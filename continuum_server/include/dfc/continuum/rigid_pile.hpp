#pragma once
// The rigid open-ended pile of the continuum pile model (docs/continuum_pile.md
// §6): its axisymmetric section, a tube r_i ≤ r ≤ r_o above a flat annulus
// at z = tip (r_i = 0: a solid circular punch), moved down by a prescribed
// displacement per step, and the frictional contact of the soil's nodes
// against its three faces (annulus, inner shaft, outer shaft).
//
// The contact is kinematic (node-to-face, the predictor–corrector contact of
// explicit codes: Taylor & Flanagan 1989; Belytschko, Liu & Moran 2000
// §10.4): a node whose predicted position lies inside the pile is given the
// force that puts it on the face at the end of the step — the exact
// impenetrability a penalty would only approach, with no penalty stiffness
// to choose and no limit on the stable step. Tangentially the node sticks to
// the pile unless that needs more than Coulomb's μ|F_n|, when it slides with
// the tangential force μ|F_n| (Coulomb friction with a rigid–plastic slip
// rule, the limit of Monforte et al. 2019's elastic–plastic slip for a stiff
// interface). The faces are aligned with r and z, so the normal and the
// tangent are coordinate axes and the local damping (local_damping.hpp),
// which acts per component, is inverted exactly: in equilibrium the contact
// force is the node's reaction.
#include <array>
#include <span>

#include "dfc/continuum/axisymmetric_mesh.hpp"

namespace dfc::continuum {

enum class PileFace { none, annulus, inner_shaft, outer_shaft };

struct RigidPileSpec {
  double inner_radius = 0.003;  ///< r_i, m; 0: a solid punch (no inner shaft)
  double outer_radius = 0.004;  ///< r_o, m
  double tip = 0.0;             ///< z of the annulus at the start, m
  double velocity = 0.0;        ///< downward displacement per step, m (pseudo-time Δt = 1)
  double friction = 0.0;        ///< interface friction coefficient μ = tan δ
};

/// One soil node's state when its velocity is updated (axisymmetric_solver.cpp).
struct ContactNodeState {
  Point position;        ///< x after this step's move, m
  Point velocity;        ///< v of the previous half step, m per step
  Point trial_velocity;  ///< v of the next half step without contact
  Point force;           ///< unbalanced force without contact, N (ring total)
  double mass = 0.0;     ///< scaled nodal mass
  double damping = 0.0;  ///< local damping coefficient α
  std::array<bool, 2> prescribed{};  ///< velocity components held by a boundary condition
};

struct NodeContact {
  PileFace face = PileFace::none;
  Point force = Point::Zero();  ///< force of the pile ON the node, N (ring total)
  bool sliding = false;         ///< the tangential force is at μ|F_n|
};

/// The soil's resistance to the pile: the upward (+z) force ON the pile from
/// each face, N (−Σ F_z of the contact forces on the nodes of that face).
struct PileForces {
  double annulus = 0.0;
  double inner_shaft = 0.0;
  double outer_shaft = 0.0;
  [[nodiscard]] double total() const { return annulus + inner_shaft + outer_shaft; }
};

class RigidPile {
 public:
  explicit RigidPile(const RigidPileSpec& spec);

  /// Moves the pile by one step's displacement (the soil's nodes have just moved).
  void move();
  /// The downward displacement per step from now on (0 holds the pile).
  void set_velocity(double velocity) { spec_.velocity = velocity; }

  [[nodiscard]] const RigidPileSpec& spec() const { return spec_; }
  /// Current z of the annulus, m.
  [[nodiscard]] double tip() const { return tip_; }
  /// How far the pile has moved down since the start, m.
  [[nodiscard]] double penetration() const { return spec_.tip - tip_; }

  /// The contact of one node for the coming step (none if its predicted
  /// position stays outside the pile's position after the step).
  [[nodiscard]] NodeContact contact(const ContactNodeState& node) const;

  /// `x` if it is outside the pile (or on a face), else its projection on
  /// the face it penetrates least: for a node a remesh adds on a boundary
  /// edge that cuts a corner of the pile.
  [[nodiscard]] Point pushed_out(const Point& x) const;

  /// The faces' forces on the pile from the nodes' contacts.
  [[nodiscard]] static PileForces forces_on_pile(std::span<const NodeContact> contacts);

 private:
  /// Whether `x` lies inside or on the pile whose annulus is at `tip`.
  [[nodiscard]] bool inside(const Point& x, double tip) const;
  /// The face a node at `x` (outside the pile, at tip_) enters when its
  /// predicted position `end` is inside the pile after the step.
  [[nodiscard]] PileFace face_met(const Point& x, const Point& end) const;

  RigidPileSpec spec_;
  double tip_;
};

}  // namespace dfc::continuum
