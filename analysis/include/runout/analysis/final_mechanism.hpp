#pragma once
// The mechanism class of a run's last frame, by the rule of `runout
// analyse` and the Runout Morphology filter (morphology_rules.hpp), for
// the run's summary.json.
#include <string>

namespace runout::analysis {

// mechanism_name() of the last frame the index at pvd_path lists, checked
// against its manifest. Empty, with `why` set, when there is no frame or
// it cannot be read or measured (a depth-averaged run's frames carry no
// particles to classify).
std::string final_mechanism(const std::string& pvd_path, std::string& why);

}  // namespace runout::analysis
