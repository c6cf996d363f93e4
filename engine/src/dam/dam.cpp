// The depth-averaged model: set-up from the scene and one explicit step
// (dam.hpp; derivations in docs/dam.md).
#include "runout/dam/dam.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "runout/scene/materials.hpp"
#include "runout/run/memory_estimate.hpp"
#include "runout/measure/morphology.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/simulation.hpp"
#include "runout/mpm/stages.hpp"

namespace runout {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Artificial viscosity coefficients (von Neumann & Richtmyer 1950, J. Appl.
// Phys. 21; the linear term as in Wilkins 1980, J. Comput. Phys. 36): a
// Lagrangian scheme without it rings behind every shock, and a fast slide
// running into its own slow front makes one.
constexpr double kQuadraticViscosity = 1.0;
constexpr double kLinearViscosity = 0.2;

// Elements per greatest thickness of the layer, at least (default_elements).
constexpr double kElementsPerThickness = 8.0;

// Elements of the cell's length, but none shorter than an eighth of the
// layer's greatest thickness H: a depth-averaged layer represents nothing
// shorter than its thickness, and the explicit step follows the element
// length, so N elements cost as N^2. From H / 8 to the cell (60 times
// finer on the reference scenes) the five scenes' runouts move by at most
// 2.5 % (docs/dam.md, "Elements"). H is sampled at the cell's elements.
int default_elements(const Polygon& polygon, const BaseView& base, double lo, double hi,
                     double cell) {
  const int fine = std::max(2, static_cast<int>(std::lround((hi - lo) / cell)));
  double thickest = 0.0;
  for (int e = 0; e < fine; ++e)
    thickest = std::max(thickest,
                        thickness_along_normal(polygon, base, lo + (hi - lo) * (e + 0.5) / fine));
  const double length = std::max(cell, thickest / kElementsPerThickness);
  return std::max(2, static_cast<int>(std::lround((hi - lo) / length)));
}

BasalLaw basal_law(const Scene& scene, const MaterialSpec& m) {
  BasalLaw law;
  law.interface = scene.base.interface;
  law.tau = scene.base.shear_strength;
  law.mu = scene.base.friction;
  law.strength = strength_params(m);
  return law;
}

// The plug-flow relations in x = ln f, f = h_s / h the sheared fraction
// (docs/dam.md, "Shear strain rate"): a Herschel-Bulkley layer of rheology
// tau = tau_y + A (gamma_dot / gamma_dot_ref)^n, steady on its base, shears
// below the depth where tau(z) = tau_b (1 - z / h) falls to tau_y, so
// tau_b = tau_y / (1 - f); integrating its velocity profile twice gives
//   gamma_dot_b = (n + 1) v / (n f h (1 - c f)),   c = n / (2 n + 1).
// The flow's f is the root of
//   phi(x) = ln(tau_b - tau_y) - ln(A (gamma_dot_b / gamma_dot_ref)^n)
//          = ln(tau_y / A) + (1 + n) x - ln(1 - e^x) + n ln(1 - c e^x) - n ln k,
// k = (n + 1) v / (n h gamma_dot_ref), increasing in x from -inf to +inf at 0.
struct PlugFlow {
  double n, c, constant;  // constant = ln(tau_y / A) - n ln k

  double phi(double x) const {
    const double f = std::exp(x);
    return constant + (1.0 + n) * x - std::log1p(-f) + n * std::log1p(-c * f);
  }
  double slope(double x) const {
    const double f = std::exp(x);
    return (1.0 + n) + f / (1.0 - f) - n * c * f / (1.0 - c * f);
  }
  // Newton's method from the small-f estimate phi = constant + (1 + n) x
  // + O(f), kept inside the bracket (lo, hi) where phi changes sign
  // (bisection whenever a step leaves it): phi is steep near f = 1, so
  // Newton alone is not safe there. Only a step from phi <= 0, which has set
  // a finite lo, can leave the bracket: from phi > 0 Newton moves left.
  double root() const {
    double x = std::min(-constant / (1.0 + n), -1e-3), lo = -kInfinity, hi = 0.0;
    for (int k = 0; k < 100; ++k) {
      const double value = phi(x);
      (value > 0.0 ? hi : lo) = x;
      const double next = x - value / slope(x);
      if (std::abs(next - x) <= 1e-13 * std::max(1.0, std::abs(x))) return next;
      x = next > lo && next < hi ? next : 0.5 * (lo + hi);
    }
    return x;
  }
};

// Steady plug flow at speed v and thickness h, for a rheology with a rate
// term (A > 0).
PlugFlow plug_flow(const StrengthParams& p, double tau_y, double A, double speed, double h) {
  const double n = p.rate_exponent;
  const double k = (n + 1.0) * speed / (n * h * p.reference_rate);
  return {n, n / (2.0 * n + 1.0), std::log(tau_y / A) - n * std::log(k)};
}

// The sheared fraction of the layer: the plug flow's, or the band's t_s / h
// where that is thicker (and never more than the whole layer). phi grows
// with f, so phi(t_s / h) >= 0 says the plug flow's root lies below the
// band without finding it: one evaluation instead of Newton's iterations.
double sheared_fraction(const StrengthParams& p, double tau_y, double A, double speed, double h,
                        double band) {
  const double floor = std::min(1.0, band / h);
  if (!(A > 0.0)) return floor;
  const PlugFlow flow = plug_flow(p, tau_y, A, speed, h);
  if (floor > 0.0 && flow.phi(std::log(floor)) >= 0.0) return floor;
  return std::exp(flow.root());
}

// The velocity profile across a sheared layer of thickness d under a plug
// moving at u_p, as BING and BingClaw write it (Imran, Harff & Parker 2001,
// Comput. Geosci. 27; Kim, Lovholt, Issler & Forsberg 2019, J. Geophys.
// Res. Oceans 124): u(z) = u_p (1 - (1 - z / d)^(1 + 1/n)) for a
// Herschel-Bulkley clay of exponent n, so the basal rate is
// (1 + 1/n) u_p / d and the layer's depth average u_p (n + 1) / (2 n + 1),
// which makes the whole layer's v = u_p (1 - c d / h), c = n / (2 n + 1).
// Without a rate term the rheology sets no profile inside the band, and
// it shears uniformly, as the MPM's regularised band does (strength.md):
// the limit n -> infinity, factor 1 and c = 1/2.
struct ShearProfile {
  double factor, c;
};

ShearProfile shear_profile(double A, double n) {
  if (!(A > 0.0)) return {1.0, 0.5};
  return {(n + 1.0) / n, n / (2.0 * n + 1.0)};
}

// The engineering plastic shear strain dgamma of one step of a viscoplastic
// layer whose strength depends on its *plastic* shear rate dgamma / dt
// (docs/dam.md, "Longitudinal stress"). Backward Euler: the returned stress
// is 2 su at the step's own plastic rate, |q_trial| - 2 G dgamma =
// 2 su(xi, dgamma / dt), the consistency form of rate-dependent plasticity
// (Wang, Sluys & de Borst 1997, Int. J. Numer. Meth. Eng. 40; the implicit
// return of viscoplasticity, Simo & Hughes 1998, Computational Inelasticity).
// With su = tau_y + A (gamma_dot / gamma_dot_ref)^n (both strength forms at
// a fixed xi, as in plug_flow_shear_rate) and excess = |q_trial| - 2 tau_y > 0:
//   2 G y + k y^n = excess,    k = 2 A / (gamma_dot_ref dt)^n,    y = dgamma.
// In u = ln y, F(u) = ln(2 G e^u + k e^(n u)) - ln(excess) is increasing and
// convex (a log-sum-exp of affine functions), so Newton's method from a
// point where F >= 0 converges monotonically from above; the smaller of the
// two one-term roots is such a point. With n <= F' <= 1 and F'' <= 1/4 its
// error after a step of du is at most (1 / (8 n)) du^2, so a step below 1e-9
// leaves y to round-off (two or three iterations). Without a rate term
// (A = 0) it is the rate-independent return excess / (2 G).
double viscoplastic_increment(const StrengthParams& p, double xi, double excess,
                              double two_g, double dt) {
  const double tau_y = strength(p, xi, 0.0);
  const double A = strength(p, xi, p.reference_rate) - tau_y;
  if (!(A > 0.0)) return excess / two_g;
  const double n = p.rate_exponent;
  const double k = 2.0 * A / std::pow(p.reference_rate * dt, n);
  const double target = std::log(excess);
  double u = std::min(std::log(excess / two_g), (target - std::log(k)) / n);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double elastic = two_g * std::exp(u), viscous = k * std::exp(n * u);
    const double next = u - (std::log(elastic + viscous) - target) * (elastic + viscous) /
                                (elastic + n * viscous);
    if (!(std::abs(next - u) > 1e-9)) return std::exp(next);
    u = next;
  }
  return std::exp(u);
}

}  // namespace

double BasalLaw::interface_limit(double normal_stress) const {
  switch (interface) {
    case InterfaceKind::Frictional: return tau;
    case InterfaceKind::Coulomb: return mu * normal_stress;
    case InterfaceKind::NoSlip: break;
  }
  return kInfinity;
}

ShearLayer sheared_layer(const StrengthParams& p, double xi, double speed, double h, double cap,
                         double band) {
  const double tau_y = strength(p, xi, 0.0);
  // At rest, or sliding on an interface weaker than the clay: no shear in it.
  if (speed == 0.0 || cap <= tau_y) return {};
  // su(xi, gamma_dot) - tau_y = A (gamma_dot / gamma_dot_ref)^n in both
  // strength forms (strength.hpp): A is the rate term at the reference rate
  // (exactly 0 without one, not the round-off of su(xi, ref) - tau_y).
  const double A = p.eta > 0.0 ? strength(p, xi, p.reference_rate) - tau_y : 0.0;
  const double n = p.rate_exponent;
  // The band: a layer that the rheology would make thinner than t_s shears
  // over t_s, the clay's physical band thickness (as the MPM's band does).
  const double f = sheared_fraction(p, tau_y, A, speed, h, band);
  const ShearProfile profile = shear_profile(A, n);
  const double plug_speed = speed / (1.0 - profile.c * f);
  double rate = profile.factor * plug_speed / (f * h);
  // The interface slips at cap: the clay above it shears at the rate where
  // its strength reaches cap, if that is less.
  if (A > 0.0 && std::isfinite(cap))
    rate = std::min(rate, p.reference_rate * std::pow((cap - tau_y) / A, 1.0 / n));
  return {f * h, rate, rate / profile.factor};
}

double plug_flow_shear_rate(const StrengthParams& p, double xi, double speed, double h,
                            double cap) {
  return sheared_layer(p, xi, speed, h, cap, 0.0).basal_rate;
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

// Without a band thickness, each element's own strain (the local law).
// With the clay's t_s, the layer yields on bands through its thickness h,
// about one per h along it (the horsts and grabens of a spreading slide,
// the scarps of a retrogressive one): a plastic strain dgamma
// (engineering, twice the longitudinal strain) stretches or shortens the
// layer by dgamma / 2 per unit length, which 45-degree bands h apart take
// as a slip of sqrt(2) (dgamma / 2) h each, so a band remoulds by dgamma h
// / (sqrt(2) t_s), xi = delta / t_s as in the MPM's band and the base's
// (crack-band scaling, Bazant & Oh 1983, with the band spacing as the
// zone's width). The strain is first averaged over the length h around
// the element, so that a softening zone is never shorter than the band
// spacing and the answer does not move with the elements.
void soften_layer(const std::vector<double>& s, const std::vector<double>& volume,
                  const std::vector<double>& plastic, double band, std::vector<double>& xi) {
  const int n = static_cast<int>(volume.size());
  if (!(band > 0.0)) {
    for (int e = 0; e < n; ++e) xi[e] += plastic[e];
    return;
  }
  const auto length = [&](int e) { return s[e + 1] - s[e]; };
  const auto mid = [&](int e) { return 0.5 * (s[e] + s[e + 1]); };
  for (int e = 0; e < n; ++e) {
    const double h = volume[e] / length(e), reach = 0.5 * h, c = mid(e);
    double sum = plastic[e] * length(e), covered = length(e);
    for (int k = e - 1; k >= 0 && c - mid(k) <= reach; --k) {
      sum += plastic[k] * length(k);
      covered += length(k);
    }
    for (int k = e + 1; k < n && mid(k) - c <= reach; ++k) {
      sum += plastic[k] * length(k);
      covered += length(k);
    }
    xi[e] += (sum / covered) * h / (std::sqrt(2.0) * band);
  }
}

DamSolver::DamSolver(const Scene& scene, const std::optional<MemoryEstimate>& checked)
    : base_(scene.base, scene.grid.min.y()),
      gravity_(scene.gravity.vector),
      gravity_ramp_(scene.gravity.ramp),
      options_(scene.dam),
      courant_(scene.time.courant) {
  if (scene.base.kind == BaseKind::None)
    throw SceneError("the depth-averaged method runs along a [base]; the scene has none", 0);
  if (scene.boundary.left == BoundaryKind::Periodic)
    throw SceneError("the depth-averaged method has no periodic boundaries (boundary.left, "
                     "boundary.right); run the scene with the MPM", 0);
  if (!checked) require_memory(scene, Method::Dam);
  const BodySpec& body = scene.bodies.front();
  const MaterialSpec& material = scene.materials[body.material];
  // The layer resists through the strength law, at its base and in its
  // longitudinal stress (docs/dam.md): an elastic body has none and would
  // spread like a fluid, which answers nothing.
  if (material.model != MaterialModel::Tresca)
    throw SceneError("material " + material.name +
                         ": the depth-averaged method needs model = \"tresca\" (an elastic body "
                         "has no strength to resist spreading)",
                     0);
  density_ = material.density;
  law_ = basal_law(scene, material);
  // A rate-independent clay has no sheared layer in plug flow: it fails on
  // a slip surface of no thickness, where the rate (and so the softening)
  // would be infinite.
  if (options_.shear_rate == ShearRateEstimate::Plug && !(material.eta > 0.0))
    throw SceneError("material " + material.name +
                         ": dam.shear_rate = \"plug\" needs a rate-dependent strength (eta > 0); "
                         "without one the plug flow has no sheared layer (use \"linear\")",
                     0);
  // The band is the length that the layer's thickness takes where the
  // rheology gives none: without t_s it would be the plug estimate.
  band_ = material.band_thickness;
  if (options_.shear_rate == ShearRateEstimate::Band && !(band_ > 0.0))
    throw SceneError("material " + material.name +
                         ": dam.shear_rate = \"band\" needs band_thickness, the thickness of the "
                         "clay's shear band",
                     0);
  // The water accelerated with the slide (added mass, C_m times the
  // displaced water) adds to the inertia of every part of it alike.
  inertia_ = 1.0 + options_.added_mass * options_.water_density / density_;
  // Undrained, so incompressible: in plane strain sigma_x - sigma_z grows at
  // 2 G (eps_x - eps_z) = 4 G eps_x. K = 1 is the layer without stiffness
  // (and so without strength): its deviator stays 0.
  const double shear_modulus = material.youngs_modulus / (2.0 * (1.0 + material.poisson_ratio));
  modulus_ = options_.earth_pressure == EarthPressure::Rankine ? 4.0 * shear_modulus : 0.0;

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
                    : default_elements(body.polygon, b, lo, hi, scene.grid.cell_size);
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
  q_.assign(n, 0.0);  // stress-free start: the hydrostatic thrust, as at K = 1
  layer_xi_.assign(n, 0.0);
  opened_.assign(n, 0.0);
}

DamSolver::Slope DamSolver::slope_at(double s) const {
  const BaseFrame f = base_frame_at(base_.view(), s);
  return {gravity_.x() * f.tx + gravity_.y() * f.ty, -(gravity_.x() * f.nx + gravity_.y() * f.ny)};
}

double DamSolver::stable_dt() const {
  // Long shallow-water waves travel at sqrt(g_n h) relative to the flow
  // (e.g. Savage & Hutter 1989, J. Fluid Mech. 199); with the layer's
  // stiffness the thrust N = rho g_n h^2 / 2 - h q stiffens by 4 G h per unit
  // strain, so the elastic wave speed is sqrt(g_n h + 4 G / rho). The
  // element length over the fastest signal speed, times the Courant number;
  // slopes_ hold the whole of gravity, the most a ramp gives.
  double dt = kInfinity;
  for (int e = 0; e < elements(); ++e) {
    // The viscosity adds its own signal speed (Wilkins 1980): 2 c2 |dv| + c1 c.
    const double gh = std::max(0.0, slopes_[e].g_n) * thickness(e);
    const double wave = std::sqrt(gh + modulus_ / density_);
    const double jump = std::max(0.0, v_[e] - v_[e + 1]);
    const double c = wave + kLinearViscosity * std::sqrt(gh) + 2.0 * kQuadraticViscosity * jump +
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
  const double h = thickness(e), c = std::sqrt(std::max(0.0, g_n(e)) * h);
  return density_ * h * (kQuadraticViscosity * dv * dv - kLinearViscosity * c * dv);
}

double DamSolver::thrust(int e) const {
  const double h = thickness(e);
  return 0.5 * density_ * g_n(e) * h * h - h * q_[e];
}

// Gravity along the slope plus the thrust gradient, per node [N/m]:
// -dN/ds integrated over the node's share of the layer is the jump of the
// element thrusts across it; outside the slide N = 0.
std::vector<double> DamSolver::driving_forces() const {
  std::vector<double> drive(s_.size(), 0.0);
  for (int e = 0; e < elements(); ++e) {
    const double weight = 0.5 * density_ * volume_[e] * gravity_scale_ * slopes_[e].g_t;
    const double push = thrust(e) + viscous_force(e);
    drive[e] += weight - push;
    drive[e + 1] += weight + push;
  }
  return drive;
}

// The linear and plug estimates soften the base at their basal rate; the
// band at the layer's mean rate, the plug's displacement over d_s, so that
// a band of t_s remoulds after the displacement xi95 t_s, as the MPM's
// regularised band does (docs/dam.md, "Shear strain rate").
ShearLayer DamSolver::basal_shear(int e, double cap) const {
  const double speed = std::abs(element_velocity(e)), h = thickness(e);
  switch (options_.shear_rate) {
    case ShearRateEstimate::Linear: return {h, 2.0 * speed / h, 2.0 * speed / h};
    case ShearRateEstimate::Plug: {
      const ShearLayer layer = sheared_layer(law_.strength, xi_[e], speed, h, cap, 0.0);
      return {layer.thickness, layer.basal_rate, layer.basal_rate};
    }
    case ShearRateEstimate::Band: break;
  }
  return sheared_layer(law_.strength, xi_[e], speed, h, cap, band_);
}

// The basal resistance of every element at its current rate: the clay's
// strength, capped by the interface. The softening variable xi_b advances
// only where the clay fails at its base: on an interface weaker than the
// clay the layer slides on it, and its base is not sheared plastically (as
// in the MPM, where slip at the interface is no plastic strain).
void DamSolver::update_basal_state(double dt) {
  for (int e = 0; e < elements(); ++e) {
    const double cap = law_.interface_limit(density_ * g_n(e) * thickness(e));
    const ShearLayer layer = basal_shear(e, cap);
    gamma_dot_[e] = layer.basal_rate;
    const double su = strength(law_.strength, xi_[e], gamma_dot_[e]);
    tau_[e] = std::min(su, cap);
    if (opened_[e] > 0.0) {  // only where the clay has a band thickness
      // The share of the element's base under its grabens' floors: an
      // element of intact length l0 pulled plastically by opened * l0 has
      // opened / (1 + opened) of its length open, filled by clay remoulded
      // on the layer's bands, which the base carries at that clay's
      // strength (as the MPM's basal band does where the slide's own
      // bands reach it, docs/strength.md, "The basal band").
      const double share = opened_[e] / (1.0 + opened_[e]);
      const double fill = std::min(strength(law_.strength, layer_xi_[e], gamma_dot_[e]), cap);
      tau_[e] = (1.0 - share) * tau_[e] + share * fill;
    }
    if (su <= cap) xi_[e] += layer.mean_rate * dt;
  }
}

// Hydrodynamic drag of the ambient water (De Blasio, Engvik, Harbitz &
// Elverhoi 2004, J. Geophys. Res. 109; as in BingClaw, Kim et al. 2019),
// opposing the motion, in N/m. Skin friction 0.5 rho_w C_F v|v| acts on
// each node's share of the upper surface.
double DamSolver::skin_friction(std::size_t node) const {
  double surface = 0.0;
  if (node > 0) surface += 0.5 * length(static_cast<int>(node) - 1);
  if (node + 1 < s_.size()) surface += 0.5 * length(static_cast<int>(node));
  return 0.5 * options_.water_density * options_.skin_friction * v_[node] * v_[node] * surface;
}

// Pressure (form) drag 0.5 rho_w C_P v|v| on the frontal area, the part of
// the surface that faces the water a node moves into: per node the drop of
// the surface across it in its direction of motion (the depth-averaged
// |dh/ds| where it faces the flow), so an advancing end contributes its
// whole face and a receding one, in its wake, nothing. It is the slide's
// drag as a whole, as the block models write it, and it decelerates every
// part of the slide alike: the layer's passive strength, 2 su per unit
// thickness, cannot take the stagnation pressure as a load on its face
// nodes (in case 1, 0.5 rho_w v^2 = 6.9 kPa > 2 su = 5 kPa at 3.7 m/s):
// applied there it piled the front into a 0.64 m head of 4 mm elements
// within 6 s and cut the step 20-fold (docs/dam.md, "Ambient water").
double DamSolver::form_drag_deceleration() const {
  if (options_.pressure_drag == 0.0) return 0.0;
  double force = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double behind = i > 0 ? thickness(static_cast<int>(i) - 1) : 0.0;
    const double ahead = i + 1 < s_.size() ? thickness(static_cast<int>(i)) : 0.0;
    const double facing = std::max(0.0, v_[i] > 0.0 ? behind - ahead : ahead - behind);
    force += 0.5 * options_.water_density * options_.pressure_drag * v_[i] * v_[i] * facing;
    mass += node_mass_[i];
  }
  return force / mass;
}

// Driving forces first, then the resistance (the base's and the water's
// drag), which opposes the motion and can at most bring a node to rest
// within the step: a node at rest stays at rest while its driving force is
// below its share of the basal strength.
void DamSolver::update_velocities(const std::vector<double>& drive, double dt) {
  std::vector<double> resist(s_.size(), 0.0);
  for (int e = 0; e < elements(); ++e) {
    const double force = 0.5 * tau_[e] * length(e);
    resist[e] += force;
    resist[e + 1] += force;
  }
  const double form_drag = form_drag_deceleration();
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double water = skin_friction(i) + form_drag * node_mass_[i];
    const double inertia = inertia_ * node_mass_[i];
    const double trial = v_[i] + dt * drive[i] / inertia;
    const double stop = dt * (resist[i] + water) / inertia;
    v_[i] = std::abs(trial) <= stop ? 0.0 : trial - std::copysign(stop, trial);
  }
}

// The layer's deviator q from this step's longitudinal strain, an elastic
// predictor and a return to the Rankine limits |q| <= 2 su (Tresca in plane
// strain: (sigma_1 - sigma_3) / 2 <= su, with x and z principal). The
// strength is the clay's own law at the layer's plastic strain and plastic
// rate: with eps_z = -eps_x the engineering plastic shear strain is twice
// the plastic longitudinal strain, dgamma = (|q_trial| - |q|) / (2 G), and
// its rate dgamma / dt (strength.md's gamma_dot for D_xx = -D_zz, of the
// plastic part). The layer yields when the trial leaves the rate-free
// limit 2 su(xi, 0); viscoplastic_increment then finds the plastic
// strain at which the stress is 2 su at its own rate.
//
// The rate is the plastic one, not the total 2 |dv/ds| of the step: the
// elastic layer rings, and with n = 0.1 even a weak ringing raised its
// limit (in case 3, elements below the limit had 2 |dv/ds| of 0.15 to
// 0.5 1/s on average, so su = 2.3 to 2.5 su0, while those yielding flowed at
// 0.004 to 0.04 1/s), by an amount that depended on where the steps
// sampled the ringing: case 3's runout at 60 s was 376.3, 337.9, 274.5 and
// 284.3 m at Courant 0.3, 0.2, 0.1 and 0.05 (docs/dam.md, "Longitudinal
// stress").
void DamSolver::update_layer_stress(double dt) {
  const double two_g = 0.5 * modulus_;
  layer_plastic_.assign(elements(), 0.0);
  for (int e = 0; e < elements(); ++e) {
    const double strain_rate = (v_[e + 1] - v_[e]) / length(e);
    const double trial = q_[e] + modulus_ * strain_rate * dt;
    const double limit = 2.0 * strength(law_.strength, layer_xi_[e], 0.0);
    if (std::abs(trial) <= limit) {
      q_[e] = trial;
      continue;
    }
    const double dgamma = viscoplastic_increment(law_.strength, layer_xi_[e],
                                                 std::abs(trial) - limit, two_g, dt);
    q_[e] = std::copysign(2.0 * strength(law_.strength, layer_xi_[e], dgamma / dt), trial);
    layer_plastic_[e] = dgamma;
    if (band_ > 0.0 && trial > 0.0) opened_[e] += 0.5 * dgamma;  // pulled: its grabens open
  }
  soften_layer(s_, volume_, layer_plastic_, band_, layer_xi_);
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
  gravity_scale_ = gravity_factor(time_ + 0.5 * dt, gravity_ramp_);  // as the MPM step
  const std::vector<double> drive = driving_forces();
  update_basal_state(dt);
  update_velocities(drive, dt);
  update_layer_stress(dt);
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
