#pragma once
// Ends a run once the slide's bulk motion has stayed below fraction x its
// peak for `duration` seconds (scene time.rest_*). The bulk motion is the
// largest of the toe's speed along the base, the speed of the main body's
// mass-weighted mean velocity (momentum / mass), and the speed of the
// blocks (morphology.hpp's block_speed: each block's mean motion, so a block
// that has broken away and runs on keeps the run going after the main body
// has stopped), measured as energies (the speeds squared), so rest_fraction
// keeps its meaning of a kinetic-energy share. Not the total kinetic
// energy: grid-scale noise next to a no-slip base carries 1 to 3 % of the
// peak energy in a slide that has stopped (docs/convergence.md, "At rest")
// but no mean momentum, and these mean speeds average it out.
#include <algorithm>

namespace runout {

class RestDetector {
 public:
  // peak and since: where a checkpointed detector stood.
  RestDetector(double fraction, double duration, double peak = 0.0, double since = -1.0)
      : fraction_(fraction), duration_(duration), peak_(peak), since_(since) {}
  double peak() const { return peak_; }
  double since() const { return since_; }
  bool at_rest(double time, double toe_speed, double mean_speed, double block_speed) {
    if (fraction_ <= 0.0) return false;
    const double bulk = std::max({toe_speed * toe_speed, mean_speed * mean_speed,
                                  block_speed * block_speed});
    peak_ = std::max(peak_, bulk);
    if (peak_ <= 0.0 || bulk >= fraction_ * peak_) {
      since_ = -1.0;
      return false;
    }
    if (since_ < 0.0) since_ = time;
    return time - since_ >= duration_;
  }

 private:
  double fraction_, duration_;
  double peak_, since_;
};

}  // namespace runout
