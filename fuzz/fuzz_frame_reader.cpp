// libFuzzer target: arbitrary bytes as a particle frame, read by the
// engine's own reader (runout/output/vtu_reader.hpp) and, when it reads, analysed
// as `runout analyse` analyses a frame (docs/fuzzing.md). A VtuReadError,
// or a frame analyse_frame refuses, is the expected answer to bad input;
// a crash, another exception or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "runout/analysis/run_analysis.hpp"
#include "runout/output/vtu_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  runout::VtuFrame frame;
  try {
    frame = runout::parse_vtu_frame(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const runout::VtuReadError&) {
    return 0;
  }
  runout::analysis::FrameAnalysis analysis;
  runout::analysis::analyse_frame(frame, runout::analysis::AnalysisParameters(), analysis);
  return 0;
}
