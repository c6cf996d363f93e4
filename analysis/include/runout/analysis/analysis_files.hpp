#pragma once
// The files `runout analyse` writes (docs/analyse.md): per analysed frame
// NNNNN (its place in the index, as in frame_NNNNN.vtu) the tables of the
// filters, and for the run one row per frame and a JSON summary of it all.
//
//   morphology.csv      frame, Time, then the morphology columns
//                       (result_columns.hpp), one row per analysed frame
//   bands_NNNNN.csv     "# time = T", then band_id and the band columns
//   blocks_NNNNN.csv    "# time = T", then block_id and the block columns
//   profile_NNNNN.csv   the profile in the bins of --bin-spacings, in the
//                       engine's profile format (runout/measure/morphology.hpp)
//   analysis.json       the parameters, every analysed frame with its
//                       morphology, bands (with skeletons) and blocks (with
//                       outlines), and the skipped frames with the reason
#include <string>

#include "runout/analysis/run_analysis.hpp"
#include "runout/output/checkpoint.hpp"

namespace runout::analysis {

using runout::kAnalysisFolder;  // checkpoint.hpp: a new run clears it

// Writes `run` into `dir` (created when missing), each file atomically,
// after removing what an earlier analysis left there (its files only, so a
// run analysed again keeps no frame it has since lost). Throws
// std::runtime_error naming what cannot be written.
void write_analysis(const std::string& dir, const RunAnalysis& run,
                    const AnalysisParameters& parameters);

}  // namespace runout::analysis
