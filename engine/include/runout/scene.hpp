#pragma once
// The resolved description of a run: what the scene file says, with every
// default filled in. The parser (scene_parser.hpp) builds it; the solver
// only reads it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "runout/kinds.hpp"

namespace runout {

struct GridSpec {
  double cell_size = 0.0;                 // h [m]
  Eigen::Vector2d min{0.0, 0.0};          // domain corner; a grid node lies here
  Eigen::Vector2d max{0.0, 0.0};          // opposite corner (snapped up to a node)
  ShapeKind shape = ShapeKind::Gimp;
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
  double courant = 0.3;
};

struct GravitySpec {
  // Gravity in the frame of the run. For a planar slope the run is in the
  // slope frame (x down the base), so vector = g (sin theta, -cos theta).
  Eigen::Vector2d vector{0.0, -9.81};
  double slope_angle_deg = 0.0;  // 0 unless the scene gives a slope
};

struct SolverSpec {
  double flip = 0.99;             // PIC/FLIP blend: 1 pure FLIP, 0 pure PIC
  double mass_threshold = 1e-9;   // nodes lighter than this fraction of a full cell's mass are not accelerated
  double damping = 0.0;           // Cundall local non-viscous damping coefficient, 0..1
};

struct MaterialSpec {
  std::string name;
  MaterialModel model = MaterialModel::Elastic;
  double density = 0.0;          // [kg/m3]
  double youngs_modulus = 0.0;   // [Pa]
  double poisson_ratio = 0.0;
};

struct BodySpec {
  std::string name;
  int material = 0;                        // index into Scene::materials
  std::vector<Eigen::Vector2d> polygon;    // counter-clockwise, simple
  Eigen::Vector2d velocity{0.0, 0.0};      // initial velocity [m/s]
};

struct OutputSpec {
  bool compress = true;  // zlib inside the inline base64 arrays
};

struct Scene {
  std::string name;
  std::string description;
  GridSpec grid;
  BoundarySpec boundary;
  TimeSpec time;
  GravitySpec gravity;
  SolverSpec solver;
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  OutputSpec output;
  // Command-line overrides applied after parsing, as "key = value" lines, so
  // the resolved scene written beside the frames says how it was run.
  std::vector<std::string> overrides;
};

}  // namespace runout
