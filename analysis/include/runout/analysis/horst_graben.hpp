#pragma once
// Horsts and grabens: the blocks of a frame between its shear bands, on
// plain arrays: the algorithm behind vtkRunoutHorstGraben and `runout
// analyse`. docs/filters.md, "Horsts and grabens", states the definitions.
#include <vector>

#include "runout/mpm/base.hpp"

#include "runout/analysis/shear_bands.hpp"
#include "runout/analysis/vec2.hpp"

namespace runout::analysis {

enum class BlockType { Block = 0, Horst = 1, Graben = 2 };

const char* block_type_name(BlockType type);

struct BlockParameters {
  double spacing = 0;        // particle spacing h (> 0)
  double dip_tolerance = 10; // degrees: a band dips when |dip| is in [tol, 90 - tol]
  double surface_gap = 3;    // in h: the most a band's top may lie below the upper surface
                             // and still bound blocks
  double outline_bin = 2;    // along-base bin width of the upper surface, in h: the surface
                             // bands must reach, and the profile the outlines follow
};

struct SlideBlock {
  BlockType type = BlockType::Block;
  int left_band = -1, right_band = -1;  // index into the bands, -1 where none
  double start_s = 0, end_s = 0;        // along-base extent of its particles (outer edges)
  double width = 0;                     // end_s - start_s
  double top = 0;                       // largest height above the base (outer edge)
  double relief = 0;                    // top minus the mean top of its neighbours; NaN alone
  double left_dip = 0, right_dip = 0;   // dips of the bounding bands; NaN where none
  double displacement = 0;              // mean |displacement| of its particles
  int particles = 0;
  // Closed polygon, counter-clockwise, run frame: the slide between its
  // bands, above the base and under the slide's upper surface (Runout
  // Morphology's profile, gaps between particle columns closed).
  std::vector<Vec2> outline;
};

// The blocks of the frame between consecutive boundary bands, rear to
// front. A boundary band is a band of `bands` that reaches the upper
// surface (within surface_gap) and is not parallel to the base (|dip| >=
// dip_tolerance); boundary bands are ordered by where they meet the
// surface. Without boundary bands there are no blocks. A block is a horst
// when its left band dips towards -s and its right band towards +s (they
// converge upwards), a graben when the reverse (they converge downwards),
// both dipping; else a plain block.
std::vector<SlideBlock> find_blocks(const std::vector<Vec2>& points,
                                    const std::vector<double>& displacement,
                                    const std::vector<ShearBand>& bands,
                                    const runout::BaseView& base,
                                    const BlockParameters& parameters);

}  // namespace runout::analysis
