// The depth-averaged model (docs/dam.md): the rigid-block acceleration, the
// plastic arrest profile, exact mass conservation, convergence with the
// number of elements, the shear strain rate estimates, and a CLI run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

#include "runout/dam.hpp"
#include "runout/polygon.hpp"
#include "runout/scene_parser.hpp"
#include "cli_runner.hpp"
#include "scene_builders.hpp"

namespace fs = std::filesystem;
using namespace runout;

namespace {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

// A rectangular layer (length x thickness) from x = 0 on a planar base
// inclined at slope_deg (slope frame), frictional interface tau, a Tresca
// material too strong to fail so that tau alone acts at the base.
Scene layer_scene(double length, double thickness, double slope_deg, double density,
                  double tau) {
  Scene s = fixtures::block_scene({0.0, 0.0}, {length, thickness}, {-10.0, 0.0},
                                  {10.0 * length, 4.0 * thickness}, 0.1, 2, density, 1e6, 0.3);
  const double a = slope_deg * kPi / 180.0;
  s.gravity.vector = {kG * std::sin(a), -kG * std::cos(a)};
  s.base.kind = BaseKind::Planar;
  s.base.interface = InterfaceKind::Frictional;
  s.base.shear_strength = tau;
  s.materials[0].model = MaterialModel::Tresca;
  s.materials[0].su0 = 1e12;
  return s;
}

Scene with_elements(Scene s, int n, ShearRateEstimate rate = ShearRateEstimate::Linear) {
  s.method = Method::Dam;
  s.dam.elements = n;
  s.dam.shear_rate = rate;
  return s;
}

double total_volume(const DamSolver& dam) {
  double v = 0.0;
  for (int e = 0; e < dam.elements(); ++e) v += dam.thickness(e) * dam.length(e);
  return v;
}

// Runs until every node has been at rest for a whole second (the resistance
// stops nodes exactly), or until t_max.
void run_to_rest(DamSolver& dam, double t_max) {
  int still = 0;
  while (dam.time() < t_max && still < 10) {
    dam.advance_to(dam.time() + 0.1);
    const bool moving = std::any_of(dam.v().begin(), dam.v().end(), [](double v) { return v != 0.0; });
    still = moving ? 0 : still + 1;
  }
  ASSERT_LT(dam.time(), t_max) << "did not come to rest";
}

TEST(Dam, UniformSlabAcceleratesAtTheRigidBlockRate) {
  // a = g sin(theta) - tau / (rho h): away from the ends, which spread, the
  // layer is a rigid block until the end waves (speed sqrt(g h)) arrive.
  const double rho = 2000.0, h = 1.0, tau = 1000.0, theta = 10.0;
  DamSolver dam(with_elements(layer_scene(400.0, h, theta, rho, tau), 400));
  dam.advance_to(1.0);
  const double expected = kG * std::sin(theta * kPi / 180.0) - tau / (rho * h);
  const double a = dam.v()[200] / dam.time();
  EXPECT_NEAR(a, expected, 0.01 * expected);
}

// A symmetric mound on [0, 2 a]: h = sqrt(2 tau (a - |x - a|) / (rho g)),
// the limit profile of a plastic mass of basal strength tau.
Polygon mound(double a, double tau, double rho, int points) {
  Polygon p{{0.0, 0.0}, {2.0 * a, 0.0}};
  for (int k = points - 1; k > 0; --k) {
    const double x = 2.0 * a * k / points;
    p.emplace_back(x, std::sqrt(2.0 * tau * (a - std::abs(x - a)) / (rho * kG)));
  }
  return p;
}

TEST(Dam, PlasticMassArrestsOnTheLimitProfile) {
  // At rest on a flat base the pressure gradient is held by tau_y:
  // d/dx (rho g h^2 / 2) = -tau_y, so h = sqrt(2 tau_y (x_f - x) / (rho g)).
  // The mass starts as the limit mound of a 5 % stronger base, so that it
  // spreads slowly and arrests with little overshoot: a dam break (a
  // rectangle) ends flatter than the limit (statically admissible but below
  // it), having spent its kinetic energy against the base. From a 30 %
  // stronger mound the final profile is already 12 % below the limit.
  const double rho = 1000.0, tau = 500.0, a = 10.0;
  Scene s = layer_scene(2.0 * a, 2.0, 0.0, rho, tau);
  s.bodies[0].polygon = mound(a, 1.05 * tau, rho, 400);
  DamSolver dam(with_elements(s, 400));
  run_to_rest(dam, 200.0);
  const double x_f = dam.s().back(), centre = a;  // symmetric spreading
  int compared = 0;
  for (int e = 0; e < dam.elements(); ++e) {
    const double x = dam.mid(e);
    if (x < centre + 0.1 * (x_f - centre) || x > x_f - 0.1 * (x_f - centre)) continue;
    const double expected = std::sqrt(2.0 * tau * (x_f - x) / (rho * kG));
    EXPECT_NEAR(dam.thickness(e), expected, 0.05 * expected) << "at x = " << x;
    ++compared;
  }
  EXPECT_GT(compared, 50);
}

TEST(Dam, MassIsConservedToRoundOff) {
  Scene s = layer_scene(20.0, 2.0, 5.0, 1000.0, 300.0);
  DamSolver dam(with_elements(s, 200));
  const double area = 20.0 * 2.0;
  EXPECT_NEAR(total_volume(dam), area, 1e-12 * area);
  run_to_rest(dam, 200.0);
  EXPECT_GT(dam.s().back(), 30.0);  // it moved
  EXPECT_NEAR(total_volume(dam), area, 1e-12 * area);
}

TEST(Dam, RunoutConvergesAsElementsDouble) {
  double runout[3];
  for (int k = 0; k < 3; ++k) {
    DamSolver dam(with_elements(layer_scene(20.0, 2.0, 0.0, 1000.0, 500.0), 25 << k));
    run_to_rest(dam, 200.0);
    runout[k] = dam.s().back() - 20.0;
  }
  const double coarse = std::abs(runout[1] - runout[0]), fine = std::abs(runout[2] - runout[1]);
  EXPECT_LT(fine, 0.7 * coarse) << runout[0] << " " << runout[1] << " " << runout[2];
}

TEST(Dam, MassAtRestBelowItsStrengthStaysAtRest) {
  // Driving stress rho g h sin(theta) = 1.7 kPa, far below su0: the static
  // check holds every node exactly where it is.
  Scene s = layer_scene(20.0, 1.0, 10.0, 1000.0, 1e12);
  s.materials[0].su0 = 1e6;
  DamSolver dam(with_elements(s, 100));
  dam.advance_to(1.0);
  for (double v : dam.v()) EXPECT_EQ(v, 0.0);
  EXPECT_EQ(dam.s().back(), 20.0);
}

TEST(Dam, ShearRateEstimates) {
  // Linear profile: 2 |v| / h. Plug: f = 1 - tau_y / tau_d of the layer
  // sheared, |v| / (f h (1 - f / 2)); the same frictional tau is tau_y.
  const double rho = 2000.0, h = 1.0, tau = 1000.0, theta = 20.0;
  const double tau_d = rho * kG * h * std::sin(theta * kPi / 180.0);
  for (ShearRateEstimate rate : {ShearRateEstimate::Linear, ShearRateEstimate::Plug}) {
    DamSolver dam(with_elements(layer_scene(400.0, h, theta, rho, tau), 400, rate));
    dam.advance_to(1.0);
    const double v = dam.v()[200];  // the rate of the last step used this speed
    dam.step(1e-6);
    const double f = 1.0 - tau / tau_d;
    const double expected =
        rate == ShearRateEstimate::Linear ? 2.0 * v / h : v / (f * h * (1.0 - 0.5 * f));
    EXPECT_NEAR(dam.gamma_dot()[200], expected, 1e-6 * expected);
  }
}

TEST(Dam, InitialStateFollowsThePolygonOnAPolylineBase) {
  // The escarpment: a 12 m (vertical) layer on the 13.75-degree slope; the
  // sampled thickness profile holds the polygon's area.
  const Scene s = load_scene_file(RUNOUT_SOURCE_DIR "/scenes/escarpment.toml");
  const DamSolver dam(s);
  const double area = 116.8 * 12.0;
  EXPECT_NEAR(total_volume(dam), area, 0.002 * area);
  const double normal_thickness = 12.0 * std::cos(13.75 * kPi / 180.0);
  EXPECT_NEAR(dam.thickness(dam.elements() / 2), normal_thickness, 1e-6 * normal_thickness);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Dam, ElasticBodyIsRefused) {
  Scene s = with_elements(layer_scene(10.0, 1.0, 5.0, 1700.0, 1e3), 10);
  s.materials[0].model = MaterialModel::Elastic;
  try {
    DamSolver dam(s);
    FAIL() << "an elastic body was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("needs model = \"tresca\""), std::string::npos)
        << e.what();
  }
}

TEST(DamCli, EscarpmentWritesHistoryAndPvd) {
  const fs::path dir = fs::temp_directory_path() / "runout_dam_cli";
  fs::remove_all(dir);
  const cli_runner::Result r = cli_runner::run_cli("run " RUNOUT_SOURCE_DIR "/scenes/escarpment.toml --method dam --cell 1.0 -q --out " +
                           dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string history = read_text(dir / "history.csv");
  EXPECT_EQ(history.rfind("time,step,dt,toe,toe_velocity,runout,rear,length,max_thickness,", 0), 0u);
  EXPECT_GT(std::count(history.begin(), history.end(), '\n'), 10);
  const std::string pvd = read_text(dir / "escarpment.pvd");
  EXPECT_NE(pvd.find("file=\"frame_00001.vtp\""), std::string::npos);
  const std::string vtp = read_text(dir / "frame_00001.vtp");
  for (const char* name : {"\"TimeValue\"", "\"base_points\"", "\"thickness\"", "\"velocity\"",
                           "\"strength\"", "\"shear_strain_rate\"", "\"plastic_shear_strain\"",
                           "NumberOfLines=\"1\""})
    EXPECT_NE(vtp.find(name), std::string::npos) << name;
  EXPECT_EQ(vtp.find("appended"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "scene.resolved.toml"));
  fs::remove_all(dir);
}

TEST(DamCli, SceneWithoutABaseIsRejected) {
  const fs::path dir = fs::temp_directory_path() / "runout_dam_cli_nobase";
  fs::remove_all(dir);
  const fs::path scene = fs::temp_directory_path() / "runout_dam_nobase.toml";
  std::ofstream(scene) << cli_runner::kSmallScene;  // it has no [base]
  const cli_runner::Result r = cli_runner::run_cli("run " + scene.string() + " --method dam -q --out " + dir.string());
  EXPECT_EQ(r.code, 65) << r.output;
  EXPECT_FALSE(fs::exists(dir));
  fs::remove(scene);
}

}  // namespace
