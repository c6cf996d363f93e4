// The depth-averaged model: set-up from the scene and one explicit step
// (dam.hpp; derivations in docs/dam.md).
#include "runout/dam.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "runout/materials.hpp"
#include "runout/memory_estimate.hpp"
#include "runout/morphology.hpp"
#include "runout/scene_parser.hpp"
#include "runout/simulation.hpp"

namespace runout {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Artificial viscosity coefficients (von Neumann & Richtmyer 1950, J. Appl.
// Phys. 21; the linear term as in Wilkins 1980, J. Comput. Phys. 36): a
// Lagrangian scheme without it rings behind every shock, and a fast slide
// running into its own slow front makes one.
constexpr double kQuadraticViscosity = 1.0;
constexpr double kLinearViscosity = 0.2;

BasalLaw basal_law(const Scene& scene, const MaterialSpec& m) {
  BasalLaw law;
  law.interface = scene.base.interface;
  law.tau = scene.base.shear_strength;
  law.mu = scene.base.friction;
  law.strength = strength_params(m);
  return law;
}

// The shear strain rate at the base of an element (docs/dam.md, "Shear
// strain rate"). speed = |v|, h the thickness; tau_y the element's basal
// resistance at rest rate (the Bingham yield stress) and tau_d its driving
// stress, both for the Plug estimate.
double shear_rate(const DamSpec& o, double speed, double h, double tau_y, double tau_d) {
  if (o.shear_rate == ShearRateEstimate::Linear) return 2.0 * speed / h;
  // Depth below which the stress, growing linearly with depth to tau_d at
  // the base, exceeds tau_y: the sheared layer h_s = f h under the plug.
  const double f = tau_d > 0.0 ? std::clamp(1.0 - tau_y / tau_d, o.min_shear_layer, 1.0)
                               : o.min_shear_layer;
  return speed / (f * h * (1.0 - 0.5 * f));
}

}  // namespace

double BasalLaw::resistance(double xi, double gamma_dot, double normal_stress) const {
  const double su = runout::strength(strength, xi, gamma_dot);
  switch (interface) {
    case InterfaceKind::Frictional: return std::min(tau, su);
    case InterfaceKind::Coulomb: return std::min(mu * normal_stress, su);
    case InterfaceKind::NoSlip: break;
  }
  return su;
}

double thickness_along_normal(const Polygon& polygon, const BaseView& base, double s) {
  const BaseFrame f = base_frame_at(base, s);
  const Eigen::Vector2d origin(f.x, f.y), normal(f.nx, f.ny);
  // Where the ray origin + lambda normal crosses each edge (parallel edges
  // never cross it), then the inside part of each stretch between crossings.
  std::vector<double> crossings{0.0};
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d a = polygon[k], edge = polygon[(k + 1) % n] - a;
    const double det = normal.x() * -edge.y() + normal.y() * edge.x();
    if (std::abs(det) < 1e-14 * edge.norm()) continue;
    const Eigen::Vector2d r = a - origin;
    const double lambda = (r.x() * -edge.y() + r.y() * edge.x()) / det;
    const double mu = (normal.x() * r.y() - normal.y() * r.x()) / det;
    if (lambda > 0.0 && mu >= 0.0 && mu <= 1.0) crossings.push_back(lambda);
  }
  std::sort(crossings.begin(), crossings.end());
  double inside = 0.0;
  for (std::size_t k = 0; k + 1 < crossings.size(); ++k) {
    const double mid = 0.5 * (crossings[k] + crossings[k + 1]);
    if (contains(polygon, origin + mid * normal)) inside += crossings[k + 1] - crossings[k];
  }
  return inside;
}

DamSolver::DamSolver(const Scene& scene)
    : base_(scene.base, scene.grid.min.y()),
      gravity_(scene.gravity.vector),
      options_(scene.dam),
      courant_(scene.time.courant) {
  if (scene.base.kind == BaseKind::None)
    throw SceneError("the depth-averaged method runs along a [base]; the scene has none", 0);
  require_memory(scene, Method::Dam);
  const BodySpec& body = scene.bodies.front();
  const MaterialSpec& material = scene.materials[body.material];
  // The layer's only resistance is the strength law at its base (docs/dam.md):
  // an elastic body would spread like a fluid, which answers nothing.
  if (material.model != MaterialModel::Tresca)
    throw SceneError("material " + material.name +
                         ": the depth-averaged method needs model = \"tresca\" (an elastic body "
                         "has no strength to resist spreading)",
                     0);
  density_ = material.density;
  law_ = basal_law(scene, material);

  // The body's extent along the base, split into equal elements.
  const BaseView b = base_.view();
  double lo = kInfinity, hi = -kInfinity;
  for (const Eigen::Vector2d& p : body.polygon) {
    const double s = locate_on_base(b, p.x(), p.y()).s;
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  const int n = options_.elements > 0
                    ? options_.elements
                    : std::max(2, static_cast<int>(std::lround((hi - lo) / scene.grid.cell_size)));
  for (int i = 0; i <= n; ++i) {
    s_.push_back(lo + (hi - lo) * i / n);
    const BaseFrame f = base_frame_at(b, s_.back());
    v_.push_back(body.velocity.x() * f.tx + body.velocity.y() * f.ty);
  }
  node_mass_.assign(n + 1, 0.0);
  for (int e = 0; e < n; ++e) {
    const double h = thickness_along_normal(body.polygon, b, mid(e));
    if (!(h > 0.0))
      throw SceneError("body " + body.name + " has no thickness above the base at s = " +
                           std::to_string(mid(e)) + ": the depth-averaged method needs one layer",
                       0);
    volume_.push_back(h * length(e));
    // Lumped: half of each element's mass on each of its nodes.
    node_mass_[e] += 0.5 * density_ * volume_[e];
    node_mass_[e + 1] += 0.5 * density_ * volume_[e];
  }
  for (int e = 0; e < n; ++e) slopes_.push_back(slope_at(mid(e)));
  xi_.assign(n, 0.0);
  gamma_dot_.assign(n, 0.0);
  tau_.assign(n, 0.0);
}

DamSolver::Slope DamSolver::slope_at(double s) const {
  const BaseFrame f = base_frame_at(base_.view(), s);
  return {gravity_.x() * f.tx + gravity_.y() * f.ty, -(gravity_.x() * f.nx + gravity_.y() * f.ny)};
}

double DamSolver::stable_dt() const {
  // Long shallow-water waves travel at sqrt(g_n h) relative to the flow
  // (e.g. Savage & Hutter 1989, J. Fluid Mech. 199); the element length over
  // the fastest signal speed, times the Courant number.
  double dt = kInfinity;
  for (int e = 0; e < elements(); ++e) {
    // The viscosity adds its own signal speed (Wilkins 1980): 2 c2 |dv| + c1 c.
    const double wave = std::sqrt(std::max(0.0, slopes_[e].g_n) * thickness(e));
    const double jump = std::max(0.0, v_[e] - v_[e + 1]);
    const double c = (1.0 + kLinearViscosity) * wave + 2.0 * kQuadraticViscosity * jump +
                     std::max(std::abs(v_[e]), std::abs(v_[e + 1]));
    if (c > 0.0) dt = std::min(dt, courant_ * length(e) / c);
  }
  return dt;
}

// The artificial viscous force of a compressing element [N/m], added to its
// pressure force: q h with q = rho (c2 dv^2 + c1 c |dv|), dv < 0 the
// velocity jump across it and c = sqrt(g_n h); zero in expansion.
double DamSolver::viscous_force(int e) const {
  const double dv = v_[e + 1] - v_[e];
  if (dv >= 0.0) return 0.0;
  const double h = thickness(e), c = std::sqrt(std::max(0.0, slopes_[e].g_n) * h);
  return density_ * h * (kQuadraticViscosity * dv * dv - kLinearViscosity * c * dv);
}

// Gravity along the slope plus the pressure gradient, per node [N/m]:
// -d/ds (rho g_n h^2 / 2) integrated over the node's share of the layer is
// the jump of the element pressure forces P across it; outside the slide P = 0.
std::vector<double> DamSolver::driving_forces() const {
  std::vector<double> drive(s_.size(), 0.0);
  for (int e = 0; e < elements(); ++e) {
    const double h = thickness(e);
    const double weight = 0.5 * density_ * volume_[e] * slopes_[e].g_t;
    const double pressure =
        0.5 * density_ * slopes_[e].g_n * h * h + viscous_force(e);
    drive[e] += weight - pressure;
    drive[e + 1] += weight + pressure;
  }
  return drive;
}

// The basal resistance of every element at its current rate, and the
// softening variable xi_b advanced by gamma_dot dt.
void DamSolver::update_basal_state(const std::vector<double>& drive, double dt) {
  for (int e = 0; e < elements(); ++e) {
    const double h = thickness(e);
    const double sigma_n = density_ * slopes_[e].g_n * h;
    double tau_y = 0.0, tau_d = 0.0;
    if (options_.shear_rate == ShearRateEstimate::Plug) {
      tau_y = law_.resistance(xi_[e], 0.0, sigma_n);
      // The element's share of its nodes' driving forces over its length.
      tau_d = std::abs(0.5 * (drive[e] + drive[e + 1])) / length(e);
    }
    gamma_dot_[e] = shear_rate(options_, std::abs(element_velocity(e)), h, tau_y, tau_d);
    tau_[e] = law_.resistance(xi_[e], gamma_dot_[e], sigma_n);
    xi_[e] += gamma_dot_[e] * dt;
  }
}

// Driving forces first, then the resistance, which opposes the motion and
// can at most bring a node to rest within the step: a node at rest stays at
// rest while its driving force is below its share of the basal strength.
void DamSolver::update_velocities(const std::vector<double>& drive, double dt) {
  std::vector<double> resist(s_.size(), 0.0);
  for (int e = 0; e < elements(); ++e) {
    const double force = 0.5 * tau_[e] * length(e);
    resist[e] += force;
    resist[e + 1] += force;
  }
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double trial = v_[i] + dt * drive[i] / node_mass_[i];
    const double stop = dt * resist[i] / node_mass_[i];
    v_[i] = std::abs(trial) <= stop ? 0.0 : trial - std::copysign(stop, trial);
  }
}

void DamSolver::move_nodes(double dt) {
  for (std::size_t i = 0; i < s_.size(); ++i) s_[i] += dt * v_[i];
  for (int e = 0; e < elements(); ++e) {
    if (!(length(e) > 0.0))
      throw NumericalFailure("depth-averaged element " + std::to_string(e) +
                             " inverted at t = " + std::to_string(time_) +
                             " s: the step is too large");
    slopes_[e] = slope_at(mid(e));
  }
}

void DamSolver::step(double dt) {
  const std::vector<double> drive = driving_forces();
  update_basal_state(drive, dt);
  update_velocities(drive, dt);
  move_nodes(dt);
  time_ += dt;
  last_dt_ = dt;
  ++steps_;
}

void DamSolver::advance_to(double t) {
  while (time_ < t) {
    const double dt = stable_dt();
    const bool last = t - time_ <= dt;
    step(last ? t - time_ : dt);
    if (last) time_ = t;  // exactly, whatever the rounding of the sum
  }
}

double DamSolver::basal_shear_force() const {
  double f = 0.0;
  for (int e = 0; e < elements(); ++e) f += tau_[e] * length(e);
  return f;
}

}  // namespace runout
