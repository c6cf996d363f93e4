#include "runout/analysis/result_columns.hpp"

#include <limits>

namespace runout::analysis {

namespace {

// A length or velocity of the morphology: NaN for a frame without
// particles, whose all-zero measures are no lengths.
Column<FrameMorphology> measure(const char* name, double (*value)(const FrameMorphology&)) {
  return {name, Column<FrameMorphology>::Double, [value](const FrameMorphology& m) {
            return m.now.particles == 0 ? std::numeric_limits<double>::quiet_NaN() : value(m);
          }};
}

Column<FrameMorphology> count(const char* name, int (*value)(const FrameMorphology&)) {
  return {name, Column<FrameMorphology>::Int,
          [value](const FrameMorphology& m) { return static_cast<double>(value(m)); }};
}

}  // namespace

const std::vector<Column<ShearBand>>& band_columns() {
  using C = Column<ShearBand>;
  static const std::vector<C> columns = {
      {"centroid_x", C::Double, [](const ShearBand& b) { return b.centroid.x; }},
      {"centroid_y", C::Double, [](const ShearBand& b) { return b.centroid.y; }},
      {"centroid_s", C::Double, [](const ShearBand& b) { return b.centroid_s; }},
      {"dip", C::Double, [](const ShearBand& b) { return b.dip; }},
      {"length", C::Double, [](const ShearBand& b) { return b.length; }},
      {"thickness", C::Double, [](const ShearBand& b) { return b.thickness; }},
      {"mean_strain", C::Double, [](const ShearBand& b) { return b.mean_strain; }},
      {"peak_strain", C::Double, [](const ShearBand& b) { return b.peak_strain; }},
      {"particle_count", C::Int,
       [](const ShearBand& b) { return static_cast<double>(b.particles.size()); }},
  };
  return columns;
}

const std::vector<Column<SlideBlock>>& block_columns() {
  using C = Column<SlideBlock>;
  static const std::vector<C> columns = {
      {"type", [](const SlideBlock& b) { return std::string(block_type_name(b.type)); }},
      {"type_code", C::Int, [](const SlideBlock& b) { return static_cast<double>(b.type); }},
      {"start_s", C::Double, [](const SlideBlock& b) { return b.start_s; }},
      {"end_s", C::Double, [](const SlideBlock& b) { return b.end_s; }},
      {"width", C::Double, [](const SlideBlock& b) { return b.width; }},
      {"top", C::Double, [](const SlideBlock& b) { return b.top; }},
      {"relief", C::Double, [](const SlideBlock& b) { return b.relief; }},
      {"left_dip", C::Double, [](const SlideBlock& b) { return b.left_dip; }},
      {"right_dip", C::Double, [](const SlideBlock& b) { return b.right_dip; }},
      {"left_band", C::Int, [](const SlideBlock& b) { return static_cast<double>(b.left_band); }},
      {"right_band", C::Int, [](const SlideBlock& b) { return static_cast<double>(b.right_band); }},
      {"displacement", C::Double, [](const SlideBlock& b) { return b.displacement; }},
      {"particle_count", C::Int, [](const SlideBlock& b) { return static_cast<double>(b.particles); }},
  };
  return columns;
}

const std::vector<Column<FrameMorphology>>& morphology_columns() {
  using M = FrameMorphology;
  static const std::vector<Column<M>> columns = {
      measure("toe", [](const M& m) { return m.now.toe_s; }),
      measure("rear", [](const M& m) { return m.now.rear_s; }),
      measure("length", [](const M& m) { return m.now.length; }),
      measure("max_thickness", [](const M& m) { return m.now.max_thickness; }),
      measure("runout", [](const M& m) { return m.runout; }),
      measure("toe_velocity", [](const M& m) { return m.now.toe_velocity; }),
      measure("centroid_x", [](const M& m) { return m.now.centroid_x; }),
      measure("centroid_y", [](const M& m) { return m.now.centroid_y; }),
      measure("centroid_s", [](const M& m) { return m.now.centroid_s; }),
      measure("centroid_velocity", [](const M& m) { return m.now.centroid_velocity_s; }),
      measure("outside_mass", [](const M& m) { return m.now.outside_mass; }),
      measure("initial_toe", [](const M& m) { return m.initial.toe_s; }),
      measure("length_ratio", [](const M& m) { return m.evidence.length_ratio; }),
      measure("thickness_ratio", [](const M& m) { return m.evidence.thickness_ratio; }),
      measure("late_stretch", [](const M& m) { return m.evidence.late_stretch; }),
      count("particles", [](const M& m) { return m.now.particles; }),
      // Troughs of the surface, not grabens: Runout Horsts And Grabens
      // calls a graben a block between shear bands, which this rule does
      // not see, and the two counts differ on the same frame.
      count("troughs", [](const M& m) { return m.evidence.grabens; }),
      count("initial_troughs", [](const M& m) { return m.evidence.initial_grabens; }),
      count("mechanism_id", [](const M& m) { return static_cast<int>(m.mechanism); }),
      {"mechanism", [](const M& m) { return std::string(mechanism_name(m.mechanism)); }},
  };
  return columns;
}

}  // namespace runout::analysis
