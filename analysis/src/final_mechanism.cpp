#include "runout/analysis/final_mechanism.hpp"

#include <filesystem>
#include <stdexcept>

#include "runout/analysis/run_analysis.hpp"
#include "runout/study/study.hpp"
#include "runout/output/vtu_writer.hpp"

namespace runout::analysis {

namespace {

// The run's travel from its history.csv beside the index (the same toe and
// length as the frames', at every history time), ending with the last
// frame's; only the frame's when there is no readable history.
std::vector<TravelSample> travel_to(const std::string& pvd_path, const FrameMorphology& last,
                                    double last_time) {
  std::vector<TravelSample> travel;
  const auto history_path = std::filesystem::path(pvd_path).parent_path() / "history.csv";
  try {
    const study::History h = study::read_history(history_path.string());
    for (std::size_t k = 0; k < h.time.size() && h.time[k] < last_time; ++k)
      travel.push_back({h.runout[k], h.length[k]});
  } catch (const std::runtime_error&) {
    travel.clear();
  }
  travel.push_back({last.runout, last.now.length});
  return travel;
}

}  // namespace

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
    classify_by_travel(frame.morphology,
                       travel_to(pvd_path, frame.morphology, entries.back().first));
    return mechanism_name(frame.morphology.mechanism);
  } catch (const std::exception& e) {  // the index, the manifest or the frame unreadable
    why = e.what();
    return "";
  }
}

}  // namespace runout::analysis
