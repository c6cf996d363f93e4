// `runout study` and `runout check --budget`: the arithmetic on synthetic
// data of known answer (interpolation, errors, observed order, Pareto
// front, the rigid-block reference, the cost model), then the commands end
// to end on the verification block.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "cli_runner.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/study/study.hpp"
#include "scene_builders.hpp"

using namespace runout;
using namespace runout::study;
namespace fs = std::filesystem;

namespace {

const std::string kBlockScene =
    std::string(RUNOUT_SOURCE_DIR) + "/scenes/verification_sliding_block.toml";

// A history of a toe that runs out as s = t^2 with velocity 2t, its length
// 10 + t: columns in the engine's order, with others in between.
std::string synthetic_history() {
  std::string csv = "time,step,dt,toe,toe_velocity,runout,rear,length,max_thickness\n";
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.5 * k;
    std::ostringstream row;
    row << t << "," << 10 * k << ",0.05,0," << 2 * t << "," << t * t << ",0," << 10 + t << ",1\n";
    csv += row.str();
  }
  return csv;
}

}  // namespace

TEST(Study, InterpolatesBetweenRowsAndHoldsOnlyARunAtRest) {
  const std::vector<double> t{0, 1, 2}, v{0, 10, 30};
  EXPECT_DOUBLE_EQ(value_at(t, v, 0.25, false), 2.5);
  EXPECT_DOUBLE_EQ(value_at(t, v, 1.5, false), 20.0);
  EXPECT_DOUBLE_EQ(value_at(t, v, 2.0, false), 30.0);
  EXPECT_DOUBLE_EQ(value_at(t, v, -1.0, false), 0.0);
  EXPECT_TRUE(std::isnan(value_at(t, v, 2.5, false)));  // the run never got there
  EXPECT_DOUBLE_EQ(value_at(t, v, 2.5, true), 30.0);    // it stopped at rest
  EXPECT_TRUE(std::isnan(value_at({}, {}, 1.0, true)));
}

TEST(Study, MetricsOfASyntheticHistory) {
  const History h = parse_history(synthetic_history(), "synthetic");
  ASSERT_EQ(h.time.size(), 11u);
  const Metrics m = run_metrics(h, {1.0, 1.25, 4.0}, false);
  EXPECT_DOUBLE_EQ(m.runout_at[0], 1.0);
  // Between rows 1.0 and 1.5 (s = 1, 2.25): linear, not the parabola.
  EXPECT_DOUBLE_EQ(m.runout_at[1], 1.625);
  EXPECT_DOUBLE_EQ(m.runout_at[2], 16.0);
  EXPECT_DOUBLE_EQ(m.runout_end, 25.0);
  EXPECT_DOUBLE_EQ(m.peak_toe_velocity, 10.0);
  EXPECT_DOUBLE_EQ(m.final_length, 15.0);
}

TEST(Study, HistoryErrorsNameTheColumnOrTheLine) {
  try {
    parse_history("time,step,toe_velocity,length\n0,0,0,0\n", "h.csv");
    FAIL() << "no runout column";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("h.csv: no column 'runout'"), std::string::npos);
  }
  try {
    parse_history("time,step,toe_velocity,runout,length\n0,0,0,0,0\n1,2,x,4,5\n", "h.csv");
    FAIL() << "a bad number";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("h.csv:3: 'x'"), std::string::npos);
  }
}

TEST(Study, RelativeErrorsAgainstAReference) {
  EXPECT_DOUBLE_EQ(relative_error(9.0, 10.0), 0.1);
  EXPECT_DOUBLE_EQ(relative_error(11.0, -10.0), 2.1);
  EXPECT_TRUE(std::isnan(relative_error(1.0, 0.0)));
  EXPECT_TRUE(std::isnan(relative_error(NAN, 1.0)));
  Metrics run{{2.0}, 9.0, 3.0, 12.0}, ref{{4.0}, 10.0, 2.0, 12.0};
  const std::vector<double> e = metric_errors(run, ref);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_DOUBLE_EQ(e[0], 0.5);
  EXPECT_DOUBLE_EQ(e[1], 0.1);
  EXPECT_DOUBLE_EQ(e[2], 0.5);
  EXPECT_DOUBLE_EQ(e[3], 0.0);
}

TEST(Study, ObservedOrderOfAKnownPowerLaw) {
  const std::vector<double> h{0.8, 0.4, 0.2, 0.1};
  for (double p : {1.0, 1.7, 2.0}) {
    std::vector<double> e;
    for (double x : h) e.push_back(0.3 * std::pow(x, p));
    EXPECT_NEAR(observed_order(h, e), p, 1e-12);
  }
  // A zero error (the reference itself) and a NaN take no part.
  EXPECT_NEAR(observed_order({0.8, 0.4, 0.2, 0.1}, {0.64, 0.16, NAN, 0.0}), 2.0, 1e-12);
  EXPECT_TRUE(std::isnan(observed_order({0.4}, {0.1})));
  EXPECT_TRUE(std::isnan(observed_order({0.4, 0.4}, {0.1, 0.2})));
}

TEST(Study, ParetoFrontOfAKnownSet) {
  //                              0    1    2    3    4    5    6
  const std::vector<double> cost{1.0, 2.0, 3.0, 4.0, 2.5, 5.0, NAN};
  const std::vector<double> err{0.5, 0.6, 0.2, 0.2, 0.3, 0.05, 0.0};
  // 1 is beaten by 0, 3 by 2 (same error, dearer), 6 has no cost.
  EXPECT_EQ(pareto_front(cost, err), (std::vector<int>{0, 4, 2, 5}));
  EXPECT_TRUE(pareto_front({}, {}).empty());
}

TEST(Study, RigidBlockAccelerationForEachInterface) {
  const double g = 9.81, theta = 10.0 * M_PI / 180.0, rho = 600.0, H = 2.0;
  Scene s = fixtures::block_scene({2, 0}, {12, H}, {0, 0}, {60, 6}, 0.25, 2, rho, 2e6, 0.3);
  s.gravity.vector = {g * std::sin(theta), -g * std::cos(theta)};
  s.base.kind = BaseKind::Planar;
  s.base.interface = InterfaceKind::Frictional;
  s.base.shear_strength = 1000.0;
  RigidBlock b = rigid_block(s);
  EXPECT_NEAR(b.acceleration, g * std::sin(theta) - 1000.0 / (rho * H), 1e-12);
  EXPECT_DOUBLE_EQ(b.length, 10.0);
  const Metrics m = rigid_block_metrics(b, {2.0, 9.0}, 4.0);
  EXPECT_NEAR(m.runout_at[0], 0.5 * b.acceleration * 4.0, 1e-12);
  EXPECT_TRUE(std::isnan(m.runout_at[1]));  // after the end of the run
  EXPECT_NEAR(m.runout_end, 0.5 * b.acceleration * 16.0, 1e-12);
  EXPECT_NEAR(m.peak_toe_velocity, 4.0 * b.acceleration, 1e-12);

  s.base.interface = InterfaceKind::Coulomb;
  s.base.friction = 0.1;
  EXPECT_NEAR(rigid_block(s).acceleration, g * (std::sin(theta) - 0.1 * std::cos(theta)), 1e-12);
  s.base.friction = 0.5;  // above tan(10 deg): held
  EXPECT_EQ(rigid_block(s).acceleration, 0.0);
  s.base.interface = InterfaceKind::NoSlip;
  EXPECT_EQ(rigid_block(s).acceleration, 0.0);
  s.base.kind = BaseKind::None;
  EXPECT_THROW(rigid_block(s), SceneError);
}

TEST(Study, CostModelScalesWithTheCellPowerOfItsDimensionPlusOne) {
  const CostModel mpm{0.5, 10.0, 2}, dam{0.5, 10.0, 1};
  // Half the cell: 4x the particles and 2x the steps (MPM); 2x and 2x (DAM).
  EXPECT_NEAR(estimated_seconds(mpm, 0.25), 80.0, 1e-12);
  EXPECT_NEAR(estimated_seconds(dam, 0.25), 40.0, 1e-12);
  EXPECT_NEAR(finest_cell_for_budget(mpm, 80.0), 0.25, 1e-12);
  EXPECT_NEAR(finest_cell_for_budget(dam, 40.0), 0.25, 1e-12);
  EXPECT_NEAR(estimated_seconds(mpm, finest_cell_for_budget(mpm, 37.0)), 37.0, 1e-9);
}

TEST(Study, SlideSizeOfTheCaseTrapezoid) {
  const Scene s = load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/case3_block_sliding.toml");
  const SlideSize z = slide_size(s);
  EXPECT_NEAR(z.length, 48.66, 1e-9);
  EXPECT_NEAR(z.mean_thickness, 200.0 / 48.66, 0.01);  // SCENES.md: area about 200 m2
}

TEST(Study, MethodChoiceFollowsTheResolutionOfTheThickness) {
  const SlideSize long_thin{120.0, 4.0}, short_thick{10.0, 4.0};
  EXPECT_EQ(choose_method(0.2, true, long_thin).method, Method::Mpm);   // 20 cells
  EXPECT_EQ(choose_method(1.0, true, long_thin).method, Method::Dam);   // 4 cells
  EXPECT_EQ(choose_method(1.0, false, long_thin).method, Method::Mpm);  // DAM cannot run it
  const MethodChoice c = choose_method(1.0, true, short_thick);
  EXPECT_EQ(c.method, Method::Mpm);
  EXPECT_NE(c.reason.find("under-resolved"), std::string::npos);
  // A sensitive clay, long and thin all the same: not the DAM.
  const MethodChoice s = choose_method(1.0, true, SlideSize{120.0, 4.0, 40.0});
  EXPECT_EQ(s.method, Method::Mpm);
  EXPECT_NE(s.reason.find("sensitive clay (St = 40)"), std::string::npos) << s.reason;
  EXPECT_EQ(choose_method(1.0, true, SlideSize{120.0, 4.0, 3.9}).method, Method::Dam);
}

// The escarpment (St = 40): its sensitivity is the slide's.
TEST(Study, SlideSizeCarriesTheClaysSensitivity) {
  const Scene s = load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/escarpment.toml");
  EXPECT_EQ(slide_size(s).sensitivity, 40.0);
}

// ---- the commands ----

namespace {

using Table = std::vector<std::map<std::string, std::string>>;

// study.csv as rows of column name -> text (the study quotes no cell here).
Table read_csv(const fs::path& path, std::vector<std::string>& header) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) header.push_back(c);
  Table rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
    rows.push_back(row);
  }
  return rows;
}

// The verification block as a strong Tresca clay (su0 far above the
// block's weight per area, so it stays elastic) that the depth-averaged
// model can run too.
std::string strong_clay_block() {
  const fs::path path = fs::temp_directory_path() / "runout_test_study_clay_block.toml";
  std::ofstream(path) << R"([scene]
name = "clay_block"
[grid]
cell_size = 0.5
min = [0.0, 0.0]
max = [200.0, 6.0]
ppc = 1
[base]
kind = "planar"
interface = "frictional"
shear_strength = 1000.0
[time]
end = 2.0
output_interval = 0.5
[gravity]
magnitude = 9.81
slope_angle = 10.0
[[material]]
name = "clay"
model = "tresca"
density = 600.0
youngs_modulus = 2.0e6
poisson_ratio = 0.3
su0 = 1.0e5
[[body]]
name = "block"
material = "clay"
type = "rectangle"
min = [2.0, 0.0]
max = [12.0, 2.0]
)";
  return path.string();
}

}  // namespace

TEST(StudyCommand, MatrixRowsSkipsAndErrorsAgainstTheRigidBlock) {
  using cli_runner::run_cli;
  const fs::path out = fs::temp_directory_path() / "runout_test_study";
  fs::remove_all(out);
  const cli_runner::Result r =
      run_cli("study " + strong_clay_block() +
              " --cells 1,0.5 --ppc 1 --method mpm,dam --backend cpu,cuda --end 1.5 --times 1 --reference analytic-block --jobs 2 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::vector<std::string> header;
  const Table rows = read_csv(out / "study.csv", header);
  for (const char* c : {"method", "backend", "shape", "cell", "ppc", "particles", "steps", "wall_s",
                        "particle_steps_per_s", "peak_memory_mib", "runout_t1", "runout_end",
                        "peak_toe_velocity", "final_length", "err_runout_t1", "err_runout_end",
                        "err_peak_toe_velocity", "err_final_length", "reference"})
    EXPECT_NE(std::find(header.begin(), header.end(), c), header.end()) << c;
  // 2 cells x (mpm cpu, mpm cuda, dam cpu, dam cuda): the DAM takes no shape
  // or ppc, and runs on the CPU only.
  ASSERT_EQ(rows.size(), 8u);
  int ran = 0;
  for (const auto& row : rows) {
    const bool cuda = row.at("backend") == "cuda";
    if (cuda && row.at("method") == "dam") {
      EXPECT_EQ(row.at("status"), "skipped");
      EXPECT_NE(row.at("note").find("CPU only"), std::string::npos);
      continue;
    }
    if (cuda && row.at("status") == "skipped") {  // a build or machine without CUDA
      EXPECT_NE(row.at("note").find("no CUDA device"), std::string::npos);
      continue;
    }
    ++ran;
    EXPECT_EQ(row.at("status"), "ok") << row.at("id") << ": " << row.at("note");
    EXPECT_EQ(row.at("reference"), "analytic-block");
    const double mem = std::stod(row.at("peak_memory_mib"));
    EXPECT_TRUE(std::isfinite(mem) && mem > 0.0) << row.at("id");
    EXPECT_GT(std::stol(row.at("steps")), 0);
    EXPECT_EQ(std::stod(row.at("end_time")), 1.5);
    // The study's arithmetic on the CSV itself: err = |s - s_exact| / s_exact
    // with s_exact = a t^2 / 2 at t = 1.5 s.
    const double a = 9.81 * std::sin(10.0 * M_PI / 180.0) - 1000.0 / (600.0 * 2.0);
    const double exact = 0.5 * a * 1.5 * 1.5;
    const double err = std::abs(std::stod(row.at("runout_end")) - exact) / exact;
    EXPECT_NEAR(std::stod(row.at("err_runout_end")), err, 1e-5 * (1.0 + err));
    if (row.at("method") == "mpm") {
      EXPECT_EQ(row.at("shape"), "gimp");
      EXPECT_EQ(row.at("ppc"), "1");
    } else {
      EXPECT_EQ(row.at("shape"), "");
      EXPECT_EQ(row.at("ppc"), "");
    }
  }
  EXPECT_GE(ran, 4);  // mpm and dam on the CPU at both cells
  EXPECT_TRUE(fs::exists(out / "runs" / "mpm_cpu_gimp_h0.5_ppc1" / "history.csv"));
}

TEST(StudyCommand, FinestRunIsTheReferenceAndTheDomainLengthIsAColumn) {
  using cli_runner::run_cli;
  const fs::path out = fs::temp_directory_path() / "runout_test_study_finest";
  fs::remove_all(out);
  const cli_runner::Result r = run_cli("study " + kBlockScene +
                                       " --cells 1,0.5 --ppc 1 --end 1 --domain-x-max 30,60 --out " +
                                       out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::vector<std::string> header;
  const Table rows = read_csv(out / "study.csv", header);
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) {
    const std::string x = row.at("domain_x_max");
    EXPECT_TRUE(x == "30" || x == "60") << x;
    EXPECT_EQ(row.at("reference"), "mpm_cpu_gimp_h0.5_ppc1_x" + x);
    if (row.at("cell") == "0.5") {
      EXPECT_EQ(std::stod(row.at("err_runout_end")), 0.0);
    }
  }
}

TEST(StudyCommand, BudgetCheckEstimatesEachMethodAndPicksOne) {
  const cli_runner::Result r =
      cli_runner::run_cli("check " + kBlockScene + " --budget 5");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* line :
       {"# calibration: mpm at h = ", "mpm cpu:  finest cell ", "mpm cuda: ",
        "dam cpu:  cannot run this scene: material stiff: the depth-averaged method needs "
        "model = \"tresca\"",
        "pick: "})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
}

TEST(StudyCommand, SlopeAngleIsADimensionWithItsOwnReference) {
  using cli_runner::run_cli;
  const fs::path out = fs::temp_directory_path() / "runout_test_study_slope";
  fs::remove_all(out);
  const cli_runner::Result r =
      run_cli("study " + strong_clay_block() + " --cells 1,0.5 --ppc 1 --method mpm,dam"
              " --slope-angle 10,20 --jobs 2 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::vector<std::string> header;
  const Table rows = read_csv(out / "study.csv", header);
  EXPECT_NE(std::find(header.begin(), header.end(), "slope_angle"), header.end());
  ASSERT_EQ(rows.size(), 8u);  // 2 angles x 2 cells x (mpm, dam)
  std::map<std::string, std::map<std::string, std::string>> by_id;
  for (const auto& row : rows) by_id[row.at("id")] = row;
  for (const std::string angle : {"10", "20"}) {
    // The study's copy of the scene is on the slope: gravity tilted, its
    // magnitude kept, so the rigid block's a = g sin(theta) - tau / (rho H).
    const Scene s = load_scene_file((out / ("scene_a" + angle + ".toml")).string());
    const double theta = std::stod(angle) * M_PI / 180.0;
    EXPECT_DOUBLE_EQ(s.gravity.slope_angle_deg, std::stod(angle));
    EXPECT_NEAR(s.gravity.vector.x(), 9.81 * std::sin(theta), 1e-12);
    EXPECT_NEAR(s.gravity.vector.y(), -9.81 * std::cos(theta), 1e-12);
    const double a = 9.81 * std::sin(theta) - 1000.0 / (600.0 * 2.0);
    EXPECT_NEAR(rigid_block(s).acceleration, a, 1e-12);

    const std::string ref = "mpm_cpu_gimp_h0.5_ppc1_a" + angle;
    ASSERT_TRUE(by_id.count(ref)) << ref;
    const double ref_runout = std::stod(by_id.at(ref).at("runout_end"));
    // The block slides as the rigid block does, within the 2-4 % start-up
    // offset the verification study measures (docs/study.md).
    EXPECT_NEAR(ref_runout, 0.5 * a * 2.0 * 2.0, 0.05 * 0.5 * a * 2.0 * 2.0) << angle;
    for (const std::string id : {"mpm_cpu_gimp_h1_ppc1_a", "dam_cpu_h1_a", "dam_cpu_h0.5_a"}) {
      const auto& row = by_id.at(id + angle);
      EXPECT_EQ(row.at("status"), "ok") << row.at("id") << ": " << row.at("note");
      EXPECT_EQ(row.at("slope_angle"), angle);
      // Measured against the finest MPM run at its own angle, not the other.
      EXPECT_EQ(row.at("reference"), ref);
      const double runout = std::stod(row.at("runout_end"));
      // Both from CSV cells of 6 significant digits.
      const double err = std::abs(runout - ref_runout) / ref_runout;
      EXPECT_NEAR(std::stod(row.at("err_runout_end")), err, 1e-5 * (1.0 + err));
    }
  }
}

TEST(StudyCommand, TheRigidBlockReferenceIsOnEachSlope) {
  const fs::path out = fs::temp_directory_path() / "runout_test_study_slope_block";
  fs::remove_all(out);
  const cli_runner::Result r = cli_runner::run_cli(
      "study " + strong_clay_block() + " --cells 0.5 --ppc 1 --slope-angle 10,20"
      " --reference analytic-block --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::vector<std::string> header;
  const Table rows = read_csv(out / "study.csv", header);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    // s(2 s) = a t^2 / 2 with a = g sin(theta) - tau / (rho H) of the row's slope.
    const double theta = std::stod(row.at("slope_angle")) * M_PI / 180.0;
    const double exact = 0.5 * (9.81 * std::sin(theta) - 1000.0 / (600.0 * 2.0)) * 4.0;
    const double err = std::abs(std::stod(row.at("runout_end")) - exact) / exact;
    EXPECT_EQ(row.at("reference"), "analytic-block");
    EXPECT_NEAR(std::stod(row.at("err_runout_end")), err, 1e-5 * (1.0 + err)) << row.at("id");
    EXPECT_LT(err, 0.05) << row.at("id");  // the verification study's 2-4 % offset
  }
}

TEST(StudyCommand, SlopeAngleIsRefusedOnAPolylineBase) {
  const fs::path out = fs::temp_directory_path() / "runout_test_study_slope_polyline";
  fs::remove_all(out);
  const cli_runner::Result r = cli_runner::run_cli(
      "study " + std::string(RUNOUT_SOURCE_DIR) + "/scenes/escarpment.toml --slope-angle 5 --out " +
      out.string());
  EXPECT_EQ(r.code, 65) << r.output;
  EXPECT_NE(r.output.find("--slope-angle: the scene's [base] is a polyline"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out / "study.csv"));
}

// ---- scene settings, samples, resuming and collecting ----

namespace {

std::string text_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(StudyCommand, SetSweepsASceneKeyAndAResumedStudyRerunsNothing) {
  using cli_runner::run_cli;
  const fs::path out = fs::temp_directory_path() / "runout_test_study_set";
  fs::remove_all(out);
  const std::string args = "study " + strong_clay_block() +
                           " --cells 1 --ppc 1 --set base.shear_strength=600,1200 --end 1.5"
                           " --times 1 --jobs 2 --out " + out.string();
  const cli_runner::Result r = run_cli(args);
  ASSERT_EQ(r.code, 0) << r.output;
  std::vector<std::string> header;
  const Table rows = read_csv(out / "study.csv", header);
  ASSERT_EQ(rows.size(), 2u);
  std::map<std::string, double> runout;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("note");
    // The row's scene is written and holds the row's value.
    const Scene s = load_scene_file((out / row.at("scene")).string());
    EXPECT_EQ(s.base.shear_strength, std::stod(row.at("base.shear_strength")));
    runout[row.at("base.shear_strength")] = std::stod(row.at("runout_end"));
    // Each point is its own reference: no error against the other value.
    EXPECT_EQ(row.at("reference"), row.at("id"));
  }
  // The weaker interface lets the block go further: a = g sin 10 - tau / (rho H).
  EXPECT_GT(runout.at("600"), runout.at("1200"));
  // The mechanism rule: the block kept its shape; at 600 Pa it moved more
  // than a tenth of its length (1.9 m of 10 m), at 1200 Pa less (0.8 m).
  EXPECT_EQ(rows[0].at("mechanism"), "block sliding");
  EXPECT_EQ(rows[1].at("mechanism"), "undetermined");
  const std::string csv = text_of(out / "study.csv");

  // Again: every run is done, none is run, the CSV is the same.
  const auto summary_time = fs::last_write_time(out / "runs" / rows[0].at("id") / "summary.json");
  const cli_runner::Result again = run_cli(args);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("2 done before, 0 to run"), std::string::npos) << again.output;
  EXPECT_EQ(fs::last_write_time(out / "runs" / rows[0].at("id") / "summary.json"), summary_time);
  EXPECT_EQ(text_of(out / "study.csv"), csv);

  // --collect gathers the same CSV from the folder alone; a run whose
  // summary is gone is a row that says so.
  const cli_runner::Result collected = run_cli("study --collect " + out.string());
  ASSERT_EQ(collected.code, 0) << collected.output;
  EXPECT_EQ(text_of(out / "study.csv"), csv);
  fs::remove(out / "runs" / rows[1].at("id") / "summary.json");
  EXPECT_EQ(run_cli("study --collect " + out.string()).code, 70);
  std::vector<std::string> after_header;
  const Table after = read_csv(out / "study.csv", after_header);
  EXPECT_EQ(after[1].at("status"), "error");
  EXPECT_NE(after[1].at("note").find("no finished summary.json"), std::string::npos);
}

TEST(StudyCommand, AKeyTheSceneRefusesStopsTheStudyBeforeAnyRun) {
  const fs::path out = fs::temp_directory_path() / "runout_test_study_bad_key";
  fs::remove_all(out);
  for (const std::string& option :
       {std::string("--set material.clay.su0=2000,-1"), std::string("--set base.friction_angle=3"),
        std::string("--vary 'material.clay.su0=normal(2000,2000)' --sample 64"),
        std::string("--vary 'material.clay.su0=normal(2000,-1)' --sample 4")}) {
    const cli_runner::Result r = cli_runner::run_cli("study " + strong_clay_block() + " --cells 1 " +
                                                     option + " --out " + out.string());
    EXPECT_EQ(r.code, 65) << option << "\n" << r.output;
    const std::size_t from = option.find_first_not_of(" '", option.find(' '));
    const std::string key = option.substr(from, option.find('=') - from);
    EXPECT_NE(r.output.find(key), std::string::npos) << option << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << option;
  }
}

TEST(StudyCommand, SamplesFollowTheDistributionAndTheSeed) {
  using cli_runner::run_cli;
  const fs::path out = fs::temp_directory_path() / "runout_test_study_sample";
  fs::remove_all(out);
  const std::string args = "study " + strong_clay_block() +
                           " --cells 1 --ppc 1 --end 1 --vary 'base.shear_strength=uniform(400,1200)'"
                           " --sample 4 --seed 11 --jobs 2 --out ";
  ASSERT_EQ(run_cli(args + (out / "a").string()).code, 0);
  std::vector<std::string> header;
  const Table a = read_csv(out / "a" / "study.csv", header);
  ASSERT_EQ(a.size(), 4u);
  std::set<int> quarters;
  for (const auto& row : a) {
    const double tau = std::stod(row.at("base.shear_strength"));
    EXPECT_GT(tau, 400.0);
    EXPECT_LT(tau, 1200.0);
    quarters.insert(static_cast<int>((tau - 400.0) / 200.0));  // Latin hypercube: one per quarter
    EXPECT_EQ(row.at("status"), "ok") << row.at("note");
  }
  EXPECT_EQ(quarters.size(), 4u);
  // The same seed draws the same values (a fresh study, not a resumed one).
  ASSERT_EQ(run_cli(args + (out / "b").string()).code, 0);
  std::vector<std::string> b_header;
  const Table b = read_csv(out / "b" / "study.csv", b_header);
  for (std::size_t k = 0; k < a.size(); ++k)
    EXPECT_EQ(a[k].at("base.shear_strength"), b[k].at("base.shear_strength"));
}
