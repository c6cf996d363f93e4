#include "budget_check.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "exit_codes.hpp"
#include "runout/dam/dam.hpp"
#include "runout/run/device_info.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/simulation.hpp"
#include "runout/study/study.hpp"

namespace runout {
namespace {

// Wall time of the calibration: long enough to average over many steps,
// short enough that a check stays a check.
constexpr double kCalibrationSeconds = 0.3;
// The calibration cell: the scene's own, or coarser, with this many cells
// across the slide's mean thickness at most.
constexpr double kCalibrationCells = 8.0;

struct Calibration {
  study::CostModel model;
  int size = 0;        // particles or elements at the calibration cell
  double steps = 0;    // steps of the whole run at the calibration cell
  double step_seconds = 0;
};

// seconds_per_step for kCalibrationSeconds, scaled to the whole run: end /
// dt steps, dt the CFL step of the start (the step falls a little as the
// slide speeds up, and a run that comes to rest ends sooner).
template <class Model>
Calibration calibrate(Model& model, int size, double cell, double end, int dimension) {
  Calibration c;
  c.size = size;
  c.step_seconds = seconds_per_step(model, kCalibrationSeconds);
  c.steps = end / model.stable_dt();
  c.model = {cell, c.step_seconds * c.steps, dimension};
  return c;
}

void print_calibration(const char* method, const char* unit, const Calibration& c) {
  std::printf("# calibration: %s at h = %.3g m: %d %s, %.3g ms per step, %.3g steps "
              "-> %.3g s for the whole run\n",
              method, c.model.cell, c.size, unit, 1e3 * c.step_seconds, c.steps, c.model.seconds);
}

// The finest cell in the budget and what it costs.
double print_estimate(const char* label, const char* unit, const Calibration& c, double budget) {
  const double h = study::finest_cell_for_budget(c.model, budget);
  const double ratio = c.model.cell / h;
  std::printf("%s finest cell %.3g m (about %.3g %s, %.3g steps, %.3g s)\n", label, h,
              c.size * std::pow(ratio, c.model.dimension), unit, c.steps * ratio,
              study::estimated_seconds(c.model, h));
  return h;
}

// The DAM's elements within the budget: the scene's (by default the cell's,
// none shorter than an eighth of the layer's thickness, dam.cpp), or fewer where
// the budget does not afford it; a run costs as N^2 (the step follows the
// element length).
int print_dam_estimate(const Calibration& c, double budget) {
  const double affordable = c.size * std::sqrt(budget / c.model.seconds);
  const int n = std::max(2, static_cast<int>(std::min<double>(c.size, affordable)));
  const double ratio = static_cast<double>(n) / c.size;
  std::printf("dam cpu:  %d elements (%s; about %.3g steps, %.3g s)\n", n,
              n == c.size ? "the scene's" : "fewer than the scene's, for the budget",
              c.steps * ratio, c.model.seconds * ratio * ratio);
  return n;
}

}  // namespace

int budget_check(const Scene& scene, double budget) {
  const study::SlideSize size = study::slide_size(scene);
  const double cell = std::max(scene.grid.cell_size, size.mean_thickness / kCalibrationCells);
  std::printf("# budget: %.3g s for %s to t = %.4g s, %d OpenMP thread(s) on this machine\n",
              budget, scene.name.c_str(), scene.time.end, omp_get_max_threads());
  std::printf("# slide: %.3g m long, %.3g m mean thickness\n", size.length, size.mean_thickness);

  Scene mpm = scene;
  mpm.method = Method::Mpm;
  mpm.overrides.clear();
  apply_overrides(mpm, cell, std::nullopt);
  Simulation sim(mpm);
  const Calibration mpm_cal =
      calibrate(sim, sim.particles().size(), cell, scene.time.end, 2);
  print_calibration("mpm", "particles", mpm_cal);

  std::optional<Calibration> dam_cal;
  std::string dam_why;
  // The DAM as `runout run --method dam` would run the scene: its elements
  // do not follow a finer cell (dam.cpp), so it is calibrated at its own.
  Scene dam = scene;
  dam.method = Method::Dam;
  try {
    DamSolver solver(dam);
    dam_cal = calibrate(solver, solver.elements(), scene.grid.cell_size, scene.time.end, 1);
    print_calibration("dam", "elements", *dam_cal);
  } catch (const SceneError& e) {
    dam_why = e.what();
  } catch (const NumericalFailure& e) {
    dam_why = std::string("its calibration failed: ") + e.what();
  }

  const double h_mpm = print_estimate("mpm cpu: ", "particles", mpm_cal, budget);
  std::string why;
  if (cuda_devices(why).empty())
    std::printf("mpm cuda: not available here (%s)\n", why.c_str());
  else
    std::printf("mpm cuda: a device is present; this check calibrates the CPU only\n");
  int dam_elements = 0;
  if (dam_cal)
    dam_elements = print_dam_estimate(*dam_cal, budget);
  else
    std::printf("dam cpu:  cannot run this scene: %s\n", dam_why.c_str());

  const study::MethodChoice choice = study::choose_method(h_mpm, dam_cal.has_value(), size);
  if (choice.method == Method::Mpm)
    std::printf("pick: mpm cpu at h = %.3g m: %s\n", h_mpm, choice.reason.c_str());
  else
    std::printf("pick: dam cpu with %d elements (--elements %d): %s\n", dam_elements,
                dam_elements, choice.reason.c_str());
  return cli::kOk;
}

}  // namespace runout
