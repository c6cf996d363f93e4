#pragma once
// `runout analyse`: the shear bands, blocks and morphology of every frame of
// a run, read from the engine's own frames (runout/output/vtu_reader.hpp) and
// measured with the algorithms and defaults of the VTK filters, which read
// the same arrays (FrameArrays, MorphologyFrame), so the numbers are the
// filters' (docs/analyse.md).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "runout/analysis/horst_graben.hpp"
#include "runout/analysis/morphology_rules.hpp"
#include "runout/analysis/shear_bands.hpp"
#include "runout/output/vtu_reader.hpp"

namespace runout::analysis {

// The settings, defaulted as the filters' properties are; the spacings of
// bands and blocks are each frame's particle_spacing.
struct AnalysisParameters {
  double bin_spacings = kProfileBinSpacings;  // profile bins, in particle spacings
  BandParameters bands;
  BlockParameters blocks;
};

struct FrameAnalysis {
  std::size_t index = 0;  // the frame's place in the index: NNNNN of frame_NNNNN.vtu
  std::string file;       // as the index lists it
  double time = 0;        // the index's timestep; the frame's TimeValue when it has none
  FrameMorphology morphology;
  std::vector<ShearBand> bands;
  std::vector<SlideBlock> blocks;
};

// Measures `frame` into `out` (all but index, file and time): its
// morphology (vtkRunoutMorphology with bin_spacings), its bands
// (vtkRunoutShearBands) and its blocks (vtkRunoutHorstGraben). "" or why it
// cannot be, naming the array or field that is missing or unusable.
std::string analyse_frame(const VtuFrame& frame, const AnalysisParameters& parameters,
                          FrameAnalysis& out);

struct SkippedFrame {
  std::size_t index = 0;
  std::string file;
  std::string reason;
};

struct RunAnalysis {
  std::string index_file;       // the .pvd's name
  bool manifest_checked = true; // false: it had no readable manifest
  std::vector<FrameAnalysis> frames;
  std::vector<SkippedFrame> skipped;
};

// Every frame the .pvd at pvd_path lists, in order. A frame that does not
// match the index's manifest, cannot be read (vtu_reader.hpp's refusals
// included) or cannot be analysed is skipped, and `warn` told
// "FILE: why; skipped"; without a manifest, `warn` is told so once and the
// frames are read unchecked. Throws std::runtime_error when the index
// cannot be read.
RunAnalysis analyse_run(const std::string& pvd_path, const AnalysisParameters& parameters,
                        const std::function<void(const std::string&)>& warn);

}  // namespace runout::analysis
