#pragma once
// The resolved description of a run: what the scene file says, with every
// default filled in. The parser (scene_parser.hpp) builds it; the solver
// only reads it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "runout/scene/kinds.hpp"

namespace runout {

struct GridSpec {
  double cell_size = 0.0;                 // h [m]
  Eigen::Vector2d min{0.0, 0.0};          // domain corner; a grid node lies here
  Eigen::Vector2d max{0.0, 0.0};          // opposite corner (snapped up to a node)
  ShapeKind shape = ShapeKind::Gimp;
  DomainKind domain = DomainKind::Deforming;  // GIMP particle domains follow F
  int ppc = 2;                            // particles per cell per direction
};

struct BoundarySpec {
  BoundaryKind left = BoundaryKind::Slip;
  BoundaryKind right = BoundaryKind::Slip;
  BoundaryKind bottom = BoundaryKind::Fixed;
  BoundaryKind top = BoundaryKind::Free;
};

struct TimeSpec {
  double end = 1.0;              // [s]
  double output_interval = 0.1;  // [s]
  double courant = 0.2;
  // The run also ends at rest: the kinetic energy of the slide's bulk
  // motion (the larger of its toe's speed and its mean velocity's, squared)
  // below rest_fraction of its peak for rest_duration seconds.
  // rest_fraction = 0 switches it off.
  double rest_fraction = 0.0;
  double rest_duration = 1.0;    // [s]
};

struct GravitySpec {
  // Gravity in the frame of the run. For a planar slope the run is in the
  // slope frame (x down the base), so vector = g (sin theta, -cos theta).
  Eigen::Vector2d vector{0.0, -9.81};
  double slope_angle_deg = 0.0;  // 0 unless the scene gives a slope
  double ramp = 0.0;             // [s] gravity rises over this time (gravity_factor); 0: at once
};

struct SolverSpec {
  TransferKind transfer = TransferKind::Flip;
  double flip = 0.99;             // PIC/FLIP blend (transfer "pic_flip"): 1 pure FLIP, 0 pure PIC
  // Transfer "flip": a PIC share that damps at the rate 1 / T, with T the
  // time a P-wave takes to cross pic_cells cells (flip_share); 0, the
  // default: pure FLIP, as Uintah, CB-Geo and Anura3D run.
  double pic_cells = 0.0;
  // XPIC(m) (Hammerquist and Nairn 2017, musl_stages.hpp): every step with
  // transfer "xpic"; with "flip", one XPIC step each time a P-wave crosses
  // xpic_cells cells (0: never), a noise filter on a schedule of physical
  // time, as NairnMPM runs it (periodicCFL), so that what it removes per
  // second does not change with the Courant number. On by default for
  // "flip" (the parser sets 0 for the other transfers): without it a
  // stopped slide on a no-slip base keeps 13 % of its peak kinetic energy
  // in FLIP noise next to the base, and gains more (coarse case 2: 15.9 kJ
  // at 12 s, 23.4 kJ at 60 s, of a 117 kJ peak; docs/convergence.md).
  int xpic_order = 5;
  double xpic_cells = 40.0;
  double mass_threshold = 1e-9;   // nodes lighter than this fraction of a full cell's mass are not accelerated
  double damping = 0.0;           // Cundall local non-viscous damping coefficient, 0..1
  bool volumetric_smoothing = true;  // cell-averaged volumetric strain rate (anti-locking)
};

struct MaterialSpec {
  std::string name;
  MaterialModel model = MaterialModel::Elastic;
  double density = 0.0;          // [kg/m3]
  double youngs_modulus = 0.0;   // [Pa]
  double poisson_ratio = 0.0;
  // Tresca only (SCENES.md, "Strength of the slide"):
  double su0 = 0.0;              // intact undrained strength [Pa]
  double sensitivity = 1.0;      // St >= 1; d_rem = 1 / St
  double xi95 = 1.0;             // plastic shear strain at 95 % remoulding
  double eta = 0.0;              // viscosity coefficient; 0: no rate effect
  double rate_exponent = 0.1;    // n
  double reference_rate = 1.0;   // gamma_dot_ref [1/s]
  StrengthForm strength_form = StrengthForm::Multiplicative;
  // Regularised softening (docs/strength.md, nonlocal.hpp): > 0, the
  // thickness t_s [m] of the clay's physical shear band, so that a band
  // remoulds after the displacement xi95 t_s; 0: local softening (mesh
  // dependent). nonlocal_length: the averaging length l [m], a numerical
  // choice the answer does not depend on; 0: kRegularisationCells cells.
  double band_thickness = 0.0;
  double nonlocal_length = 0.0;
};

struct BodySpec {
  std::string name;
  int material = 0;                        // index into Scene::materials
  std::vector<Eigen::Vector2d> polygon;    // counter-clockwise, simple
  Eigen::Vector2d velocity{0.0, 0.0};      // initial velocity [m/s]
};

// The rigid base the slide runs on. Planar: the grid's bottom line (a
// planar-slope scene runs in the slope frame), normal +y. Polyline: a
// bathymetry in the run's frame, points ordered in the direction of travel,
// the slide above it (on the left of the direction of travel).
struct BaseSpec {
  BaseKind kind = BaseKind::None;  // None: the bottom boundary condition alone
  std::vector<Eigen::Vector2d> points;  // Polyline only
  InterfaceKind interface = InterfaceKind::NoSlip;
  double shear_strength = 0.0;     // tau [Pa], Frictional
  double friction = 0.0;           // mu, Coulomb
  // The clay fails along the base in a band of its band_thickness t_s,
  // thinner than any cell: the base's nodes slip at the strength of the
  // clay there, which softens with the slip over t_s (docs/strength.md,
  // "The basal band"). No-slip and frictional interfaces only.
  bool clay_band = false;
};

// The depth-integrated longitudinal stress of the depth-averaged model
// (docs/dam.md, "Longitudinal stress"). Rankine: the hydrostatic thrust
// minus h times the layer's deviator, elastic up to the active (-2 su) and
// passive (+2 su) limits; Hydrostatic: earth-pressure coefficient K = 1,
// no strength inside the layer.
enum class EarthPressure { Rankine, Hydrostatic };

// The depth-averaged model (docs/dam.md); read by it alone.
struct DamSpec {
  // Linear: 2 |v| / h; Plug: the basal rate of a Herschel-Bulkley plug flow
  // with the strength law as its rheology (its sheared layer follows from it);
  // Band: the same sheared layer, never thinner than the clay's band
  // thickness t_s (the parser's default where the slide's material has one).
  ShearRateEstimate shear_rate = ShearRateEstimate::Linear;
  EarthPressure earth_pressure = EarthPressure::Rankine;
  int elements = 0;              // 0: the body's initial length over grid.cell_size, in
                                 // elements no shorter than an eighth of its greatest thickness
  // Ambient water (docs/dam.md, "Ambient water"); each coefficient 0: off.
  double water_density = 1025.0;  // rho_w [kg/m3], sea water
  double skin_friction = 0.0;     // C_F: drag 0.5 rho_w C_F v|v| on the upper surface
  double pressure_drag = 0.0;     // C_P: drag 0.5 rho_w C_P v|v| h on an advancing face
  double added_mass = 0.0;        // C_m: inertia of C_m rho_w per unit volume of slide
};

struct OutputSpec {
  bool compress = true;  // zlib inside the inline base64 arrays
};

struct Scene {
  std::string name;
  std::string description;
  Method method = Method::Mpm;
  GridSpec grid;
  BoundarySpec boundary;
  TimeSpec time;
  GravitySpec gravity;
  SolverSpec solver;
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  BaseSpec base;
  DamSpec dam;
  OutputSpec output;
  // Command-line overrides applied after parsing, as "key = value" lines, so
  // the resolved scene written beside the frames says how it was run.
  std::vector<std::string> overrides;
};

}  // namespace runout
