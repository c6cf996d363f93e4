#include "runout/analysis/final_mechanism.hpp"

#include <filesystem>
#include <stdexcept>

#include "runout/analysis/run_analysis.hpp"
#include "runout/vtu_writer.hpp"

namespace runout::analysis {

std::string final_mechanism(const std::string& pvd_path, std::string& why) {
  try {
    const PvdIndex::Entries entries = read_pvd_entries(pvd_path);
    if (entries.empty()) {
      why = "the index lists no frame";
      return "";
    }
    const FrameManifest manifest(pvd_path);
    std::string bytes;
    why = read_listed_frame(std::filesystem::path(pvd_path).parent_path().string(),
                            entries.back().second, &manifest, bytes);
    if (!why.empty()) return "";
    FrameAnalysis frame;
    why = analyse_frame(parse_vtu_frame(bytes), AnalysisParameters{}, frame);
    if (!why.empty()) return "";
    return mechanism_name(frame.morphology.mechanism);
  } catch (const std::exception& e) {  // the index, the manifest or the frame unreadable
    why = e.what();
    return "";
  }
}

}  // namespace runout::analysis
