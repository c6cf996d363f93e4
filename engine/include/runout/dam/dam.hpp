#pragma once
// The depth-averaged model (DAM): the slide as a chain of 1D Lagrangian
// elements along the rigid base, a fast second opinion next to the MPM
// (docs/dam.md has the equations, their discretisation and sources).
//
// Nodes 0..N sit on the base at along-base coordinates s_i (x on a planar
// base, arc length on a polyline) and move with their layer-averaged
// velocity v_i. Element e lies between nodes e and e + 1 and keeps its
// volume V_e (area per unit width) for ever, so mass is conserved exactly;
// its thickness is h_e = V_e / (s_{e+1} - s_e). Per node, per unit width:
//
//   M_i dv_i/dt = sum_e m_e g_t,e / 2            gravity along the local slope
//               + N_{i-1} - N_i                  longitudinal thrust
//               - sum_e tau_e l_e / 2 sign(v_i)  basal resistance
//
//   N_e = rho g_n,e h_e^2 / 2 - h_e q_e   (earth_pressure Rankine; q_e = 0: Hydrostatic)
//
// q_e the layer's longitudinal deviator sigma_x - sigma_z (tension
// positive), elastic with the incompressible plane-strain modulus 4 G and
// bounded by the Rankine limits |q| <= 2 su, su at the layer's plastic
// strain and plastic shear rate (a backward-Euler viscoplastic return;
// docs/dam.md, "Longitudinal stress"). tau_e comes from the strength law
// of strength.hpp at the element's accumulated basal shear strain xi_e and
// its shear strain rate estimate (scene.dam, docs/dam.md "Shear strain rate"):
//   Linear: a linear velocity profile from rest at the base, 2 |v| / h;
//   Plug:   the basal rate of a Herschel-Bulkley plug flow whose rheology is
//           the strength law: sheared layer f h with f = 1 - tau_y / tau_b;
//   Band:   the same layer, never thinner than the clay's band thickness
//           t_s, its base softening with the layer's mean shear strain.
// Ambient water, where the scene asks for it, adds drag on the upper surface
// and on an advancing face and the added mass of the water moved along.
#include <optional>
#include <vector>

#include "runout/mpm/base.hpp"
#include "runout/scene/polygon.hpp"
#include "runout/scene/scene.hpp"
#include "runout/mpm/strength.hpp"
#include "runout/run/memory_estimate.hpp"

namespace runout {

// The limiting shear stress on the base of an element: the strength law
// (no-slip: failure in the layer at its base), capped by the interface's
// own limit (frictional tau, Coulomb mu sigma_n; infinite for no-slip).
struct BasalLaw {
  InterfaceKind interface = InterfaceKind::NoSlip;
  double tau = 0;           // Frictional
  double mu = 0;            // Coulomb
  StrengthParams strength;

  double interface_limit(double normal_stress) const;
};

// The layer sheared under a rigid plug at the base of a layer of
// depth-averaged speed `speed` and thickness h whose rheology is the
// strength law su(xi, gamma_dot) = tau_y + A (gamma_dot / gamma_dot_ref)^n,
// with the basal stress capped at `cap` by the interface (docs/dam.md,
// "Shear strain rate"): as thick as steady plug flow makes it, but never
// thinner than `band` (nor thicker than h).
struct ShearLayer {
  double thickness = 0.0;   // d_s [m]
  double basal_rate = 0.0;  // at the base, where the stress is: the rate of su [1/s]
  double mean_rate = 0.0;   // the plug's speed over d_s: the layer's mean shear rate [1/s]
};
ShearLayer sheared_layer(const StrengthParams& p, double xi, double speed, double h, double cap,
                         double band);

// The basal rate of the steady plug flow alone (band 0). Needs a rate term
// (eta > 0): without one the sheared layer has no thickness.
double plug_flow_shear_rate(const StrengthParams& p, double xi, double speed, double h,
                            double cap);

// Thickness of the polygon above the base point at s, measured along the
// base normal: the length of the normal ray from the base inside the polygon.
double thickness_along_normal(const Polygon& polygon, const BaseView& base, double s);

// The layer's softening variable advanced by one step's plastic strains
// (engineering, per element): without a band thickness (band = 0) by each
// element's own; with the clay's t_s = band, on bands one layer thickness
// apart (docs/dam.md, "Longitudinal softening"): by the plastic strain
// averaged over the elements within h / 2 of the element, times h /
// (sqrt(2) t_s). Nodes s (elements + 1), element volumes (area per unit
// width: h = volume / length).
void soften_layer(const std::vector<double>& s, const std::vector<double>& volume,
                  const std::vector<double>& plastic, double band, std::vector<double>& xi);

class DamSolver {
 public:
  // The slide is the first body of the scene; scene.dam sets the elements
  // and the shear rate estimate. Throws SceneError when the scene has no
  // [base] (the model runs along one) or the body is empty somewhere along it.
  // checked: the run's memory estimate, already passed by require_memory
  // (empty: the solver checks it itself).
  explicit DamSolver(const Scene& scene, const std::optional<MemoryEstimate>& checked = {});

  void step(double dt);          // throws NumericalFailure
  void advance_to(double t);     // stable steps, the last one landing on t
  double stable_dt() const;      // CFL: courant l_e / (wave speed + |v| + viscous speed)

  int elements() const { return static_cast<int>(volume_.size()); }
  double time() const { return time_; }
  long steps() const { return steps_; }
  double last_dt() const { return last_dt_; }
  double density() const { return density_; }
  BaseView base() const { return base_.view(); }

  // Nodes.
  const std::vector<double>& s() const { return s_; }
  const std::vector<double>& v() const { return v_; }
  const std::vector<double>& node_mass() const { return node_mass_; }
  // Elements: constant volume; the last step's basal state.
  const std::vector<double>& volume() const { return volume_; }
  const std::vector<double>& xi() const { return xi_; }
  const std::vector<double>& gamma_dot() const { return gamma_dot_; }
  const std::vector<double>& tau() const { return tau_; }
  // Elements: the layer's longitudinal deviator q [Pa] (tension positive)
  // and its softening variable: its accumulated plastic shear strain (2
  // |plastic longitudinal strain|), or, where the clay has a band thickness
  // t_s, the displacement of its bands over t_s (soften_layer).
  const std::vector<double>& deviator() const { return q_; }
  const std::vector<double>& layer_xi() const { return layer_xi_; }
  // Elements: the layer's accumulated plastic extension (longitudinal
  // strain), where the clay has a band thickness: its grabens' opening,
  // whose floors carry the base ("Basal resistance" in docs/dam.md).
  const std::vector<double>& opened() const { return opened_; }
  double thrust(int e) const;  // N_e without the artificial viscosity [N/m]
  double length(int e) const { return s_[e + 1] - s_[e]; }
  double thickness(int e) const { return volume_[e] / length(e); }
  double mid(int e) const { return 0.5 * (s_[e] + s_[e + 1]); }
  double element_velocity(int e) const { return 0.5 * (v_[e] + v_[e + 1]); }
  double basal_shear_force() const;  // sum tau_e l_e [N/m]

 private:
  struct Slope {
    double g_t, g_n;  // gravity along the base tangent and into the base
  };
  Slope slope_at(double s) const;                     // the whole of gravity
  double g_n(int e) const { return gravity_scale_ * slopes_[e].g_n; }  // this step's
  double viscous_force(int e) const;
  std::vector<double> driving_forces() const;
  ShearLayer basal_shear(int e, double cap) const;
  double skin_friction(std::size_t node) const;  // [N/m]
  double form_drag_deceleration() const;          // [m/s2], the same for every node
  void update_basal_state(double dt);
  void update_velocities(const std::vector<double>& drive, double dt);
  void update_layer_stress(double dt);
  void move_nodes(double dt);

  Base base_;
  Eigen::Vector2d gravity_;
  double gravity_ramp_ = 0, gravity_scale_ = 1;  // scene.gravity.ramp, gravity_factor
  BasalLaw law_;
  DamSpec options_;
  double density_ = 0, courant_ = 0;
  double modulus_ = 0;  // 4 G: the layer's deviator per unit longitudinal strain
  double band_ = 0;     // t_s of the slide's clay [m], 0 where it has none
  double inertia_ = 1;  // 1 + C_m rho_w / rho: the added mass of the water moved along
  std::vector<double> s_, v_, node_mass_;
  std::vector<double> volume_, xi_, gamma_dot_, tau_;
  std::vector<double> q_, layer_xi_, opened_;
  std::vector<double> layer_plastic_;  // this step's plastic strain per element (scratch)
  std::vector<Slope> slopes_;  // at each element's mid-point, for the current nodes
  double time_ = 0, last_dt_ = 0;
  long steps_ = 0;
};

}  // namespace runout
