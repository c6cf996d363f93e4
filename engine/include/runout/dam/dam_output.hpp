#pragma once
// What a depth-averaged run writes, in the MPM layout (docs/output.md):
// the history row, the per-frame polyline (.vtp) and the thickness profile.
#include <string>
#include <vector>

#include "runout/dam/dam.hpp"
#include "runout/output/history.hpp"
#include "runout/measure/morphology.hpp"

namespace runout {

// initial_toe: the front node's s at t = 0, for the runout column.
HistoryRow dam_history_row(const DamSolver& dam, double initial_toe);

// VTK XML PolyData: one point per element on the base at its mid-point, one
// polyline through them; point data thickness, velocity, strength,
// shear_strain_rate, plastic_shear_strain (xi_b) and s; field data
// TimeValue and base_points (base_xy: x0, y0, x1, y1, ...). Written
// atomically with the arrays inline binary (vtk_xml.hpp).
void write_dam_vtp(const std::string& path, const DamSolver& dam,
                   const std::vector<double>& base_xy, bool compress);

// The elements as the bins of a thickness profile (one element a bin, its
// surface at the mid-point), for write_profile_csv.
Profile dam_profile(const DamSolver& dam);

}  // namespace runout
