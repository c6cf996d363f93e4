// Scene files: the default scene, every class of error (with the key and the
// line it is reported at), the resolved-scene round trip, the polygon
// helpers and particle seeding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "runout/scene/polygon.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/seeding.hpp"

namespace runout {
namespace {

constexpr double kPi = 3.14159265358979323846;

Scene default_scene() {
  return parse_scene(default_scene_toml(), "default.toml");
}

// Every key sits on a known line, so error cases can replace a line and
// name the line the error must point at.
const char* const kMinimal =
    "[scene]\n"                      //  1
    "name = \"mini\"\n"              //  2
    "\n"                             //  3
    "[grid]\n"                       //  4
    "cell_size = 0.5\n"              //  5
    "min = [0.0, 0.0]\n"             //  6
    "max = [10.0, 5.0]\n"            //  7
    "ppc = 2\n"                      //  8
    "\n"                             //  9
    "[time]\n"                       // 10
    "end = 1.0\n"                    // 11
    "output_interval = 0.1\n"        // 12
    "\n"                             // 13
    "[[material]]\n"                 // 14
    "name = \"clay\"\n"              // 15
    "density = 600.0\n"              // 16
    "youngs_modulus = 1.0e5\n"       // 17
    "poisson_ratio = 0.3\n"          // 18
    "\n"                             // 19
    "[[body]]\n"                     // 20
    "name = \"block\"\n"             // 21
    "material = \"clay\"\n"          // 22
    "type = \"rectangle\"\n"         // 23
    "min = [1.0, 0.0]\n"             // 24
    "max = [3.0, 2.0]\n";            // 25

// kMinimal with lines first..last (1-based) replaced by `text`.
std::string replace_lines(int first, int last, const std::string& text) {
  std::istringstream in(kMinimal);
  std::string out, line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (n < first || n > last)
      out += line + "\n";
    else if (n == first)
      out += text + "\n";
  }
  return out;
}

TEST(SceneParser, DefaultSceneParses) {
  const Scene s = default_scene();
  EXPECT_EQ(s.name, "default");
  EXPECT_DOUBLE_EQ(s.grid.cell_size, 0.4);
  EXPECT_EQ(s.grid.min, Eigen::Vector2d(-30.0, 0.0));
  EXPECT_EQ(s.grid.max, Eigen::Vector2d(400.0, 10.0));
  EXPECT_EQ(s.grid.shape, ShapeKind::Gimp);
  EXPECT_EQ(s.grid.ppc, 2);
  EXPECT_EQ(s.boundary.bottom, BoundaryKind::Free);  // the base is the bottom
  EXPECT_EQ(s.boundary.top, BoundaryKind::Free);
  EXPECT_EQ(s.base.kind, BaseKind::Planar);
  EXPECT_EQ(s.base.interface, InterfaceKind::Frictional);
  EXPECT_DOUBLE_EQ(s.base.shear_strength, 1000.0);
  EXPECT_DOUBLE_EQ(s.time.end, 60.0);
  EXPECT_DOUBLE_EQ(s.time.output_interval, 1.0);
  EXPECT_DOUBLE_EQ(s.time.rest_fraction, 1e-3);
  EXPECT_DOUBLE_EQ(s.gravity.slope_angle_deg, 5.0);
  const double theta = 5.0 * kPi / 180.0;
  EXPECT_NEAR(s.gravity.vector.x(), 9.81 * std::sin(theta), 1e-12);
  EXPECT_NEAR(s.gravity.vector.y(), -9.81 * std::cos(theta), 1e-12);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "clay");
  EXPECT_DOUBLE_EQ(s.materials[0].density, 600.0);
  EXPECT_DOUBLE_EQ(s.materials[0].youngs_modulus, 250.0e3);
  EXPECT_DOUBLE_EQ(s.materials[0].poisson_ratio, 0.49);
  EXPECT_EQ(s.materials[0].model, MaterialModel::Tresca);
  EXPECT_DOUBLE_EQ(s.materials[0].su0, 2500.0);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].material, 0);
  ASSERT_EQ(s.bodies[0].polygon.size(), 4u);
  // 48.66 m base, 5 m high, 30-degree faces: top 31.34 m, area 200 m2 (to
  // the 4 digits SCENES.md gives).
  EXPECT_NEAR(signed_area(s.bodies[0].polygon), 200.0, 0.01);
  EXPECT_TRUE(s.output.compress);
  EXPECT_TRUE(s.overrides.empty());
}

TEST(SceneParser, OptionalTablesTakeDefaults) {
  const Scene s = parse_scene(kMinimal, "mini.toml");
  const Scene defaults;
  EXPECT_EQ(s.boundary.left, BoundaryKind::Slip);
  EXPECT_EQ(s.boundary.right, BoundaryKind::Slip);
  EXPECT_EQ(s.boundary.bottom, BoundaryKind::Fixed);
  EXPECT_EQ(s.boundary.top, BoundaryKind::Free);
  EXPECT_EQ(s.gravity.vector, Eigen::Vector2d(0.0, -9.81));
  EXPECT_EQ(s.gravity.slope_angle_deg, 0.0);
  EXPECT_EQ(s.solver.flip, defaults.solver.flip);
  EXPECT_EQ(s.solver.mass_threshold, defaults.solver.mass_threshold);
  EXPECT_EQ(s.solver.damping, defaults.solver.damping);
  EXPECT_EQ(s.time.courant, 0.2);
  EXPECT_EQ(s.grid.shape, ShapeKind::Gimp);
  EXPECT_EQ(s.materials[0].model, MaterialModel::Elastic);
  EXPECT_EQ(s.bodies[0].velocity, Eigen::Vector2d::Zero());
  EXPECT_TRUE(s.output.compress);
  EXPECT_EQ(s.description, "");
}

TEST(SceneParser, ClockwiseOutlineIsStoredCounterClockwise) {
  const Scene s = parse_scene(
      replace_lines(23, 25, "type = \"polygon\"\n"
                            "vertices = [[1.0, 1.0], [1.0, 3.0], [3.0, 3.0], [3.0, 1.0]]"),
      "cw.toml");
  EXPECT_DOUBLE_EQ(signed_area(s.bodies[0].polygon), 4.0);
}

TEST(SceneParser, GridMaxIsSnappedUpToANode) {
  const Scene s = parse_scene(replace_lines(7, 7, "max = [9.8, 4.6]"), "snap.toml");
  EXPECT_DOUBLE_EQ(s.grid.max.x(), 10.0);
  EXPECT_DOUBLE_EQ(s.grid.max.y(), 5.0);
}

TEST(SceneParser, GravityVectorAndIntegerForFloat) {
  const Scene s = parse_scene(replace_lines(13, 13, "[gravity]\nvector = [1, -9]\n"),
                              "g.toml");
  EXPECT_EQ(s.gravity.vector, Eigen::Vector2d(1.0, -9.0));
  EXPECT_EQ(s.gravity.slope_angle_deg, 0.0);
}

// kMinimal's material as Tresca, with only the required key: the strength
// defaults (no softening, no rate effect) fill in the rest.
const char* const kTrescaClay =
    "poisson_ratio = 0.3\n"
    "model = \"tresca\"\n"
    "su0 = 2500";

TEST(SceneParser, TrescaMaterialTakesDefaults) {
  const Scene s = parse_scene(replace_lines(18, 18, kTrescaClay), "tresca.toml");
  const MaterialSpec& m = s.materials[0];
  const MaterialSpec defaults;
  EXPECT_EQ(m.model, MaterialModel::Tresca);
  EXPECT_EQ(m.su0, 2500.0);
  EXPECT_EQ(m.sensitivity, 1.0);
  EXPECT_EQ(m.xi95, defaults.xi95);
  EXPECT_EQ(m.eta, 0.0);
  EXPECT_EQ(m.rate_exponent, 0.1);
  EXPECT_EQ(m.reference_rate, 1.0);
  EXPECT_EQ(m.strength_form, StrengthForm::Multiplicative);
  EXPECT_EQ(m.band_thickness, 0.0);  // local softening
  EXPECT_EQ(m.nonlocal_length, 0.0);
  EXPECT_EQ(m.youngs_modulus, 1.0e5);
}

TEST(SceneParser, TrescaMaterialEveryKey) {
  const Scene s = parse_scene(
      replace_lines(18, 18, std::string(kTrescaClay) +
                                "\nsensitivity = 40\nxi95 = 45\neta = 0.0167\n"
                                "rate_exponent = 0.5\nreference_rate = 0.01\n"
                                "strength_form = \"additive\"\nband_thickness = 0.3\n"
                                "nonlocal_length = 1.5"),
      "tresca.toml");
  const MaterialSpec& m = s.materials[0];
  EXPECT_EQ(m.band_thickness, 0.3);
  EXPECT_EQ(m.nonlocal_length, 1.5);
  EXPECT_EQ(m.sensitivity, 40.0);
  EXPECT_EQ(m.xi95, 45.0);
  EXPECT_EQ(m.eta, 0.0167);
  EXPECT_EQ(m.rate_exponent, 0.5);
  EXPECT_EQ(m.reference_rate, 0.01);
  EXPECT_EQ(m.strength_form, StrengthForm::Additive);
}

TEST(SceneParser, RestDetectionIsOffByDefault) {
  const Scene defaults = parse_scene(kMinimal, "mini.toml");
  EXPECT_EQ(defaults.time.rest_fraction, 0.0);
  EXPECT_EQ(defaults.time.rest_duration, 1.0);
  const Scene s = parse_scene(
      replace_lines(12, 12, "output_interval = 0.1\nrest_fraction = 0.01\nrest_duration = 2.5"),
      "rest.toml");
  EXPECT_EQ(s.time.rest_fraction, 0.01);
  EXPECT_EQ(s.time.rest_duration, 2.5);
}

// kMinimal with a [base] table after the body (its first line is 27).
std::string with_base(const std::string& base_lines) {
  return replace_lines(25, 25, "max = [3.0, 2.0]\n\n[base]\n" + base_lines);
}

// A name is any printable text: letters of any script pass, while controls
// and formatting characters (tests/bad_scenes/scene_name_with_*) do not.
TEST(SceneParser, NameMayHoldAnyPrintableLetters) {
  const Scene s = parse_scene(replace_lines(2, 2, "name = \"Storegga_\u00f8st_\u6ed1\u5761\""),
                              "utf8.toml");
  EXPECT_EQ(s.name, "Storegga_\u00f8st_\u6ed1\u5761");
}

TEST(SceneParser, PlanarBaseFreesTheBottom) {
  const Scene s = parse_scene(with_base("kind = \"planar\""), "planar.toml");
  EXPECT_EQ(s.base.kind, BaseKind::Planar);
  EXPECT_EQ(s.base.interface, InterfaceKind::NoSlip);
  EXPECT_TRUE(s.base.points.empty());
  // kMinimal has no [boundary]: the bottom's default (fixed) gives way to the base.
  EXPECT_EQ(s.boundary.bottom, BoundaryKind::Free);
  EXPECT_EQ(parse_scene(kMinimal, "mini.toml").base.kind, BaseKind::None);
}

TEST(SceneParser, PolylineBaseWithFriction) {
  const Scene s = parse_scene(
      with_base("kind = \"polyline\"\npoints = [[0, 3], [4, 1.5], [10, 1]]\n"
                "interface = \"frictional\"\nshear_strength = 1000") +
          "\n[boundary]\nbottom = \"free\"\n",
      "polyline.toml");
  EXPECT_EQ(s.base.kind, BaseKind::Polyline);
  ASSERT_EQ(s.base.points.size(), 3u);
  EXPECT_EQ(s.base.points[1], Eigen::Vector2d(4.0, 1.5));
  EXPECT_EQ(s.base.interface, InterfaceKind::Frictional);
  EXPECT_EQ(s.base.shear_strength, 1000.0);
  EXPECT_EQ(s.boundary.bottom, BoundaryKind::Free);

  const Scene coulomb = parse_scene(
      with_base("kind = \"planar\"\ninterface = \"coulomb\"\nfriction = 0.3"), "mu.toml");
  EXPECT_EQ(coulomb.base.interface, InterfaceKind::Coulomb);
  EXPECT_EQ(coulomb.base.friction, 0.3);
}

// A scene that is wrong in one way, and what the error must say.
struct ErrorCase {
  const char* name;
  int first_line, last_line;  // replaced lines of kMinimal
  std::string replacement;
  int line;                   // where the error must point
  const char* key;
  const char* what;           // part of the message after the key
};

std::ostream& operator<<(std::ostream& os, const ErrorCase& c) { return os << c.name; }

class SceneErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(SceneErrors, NameKeyAndLine) {
  const ErrorCase& c = GetParam();
  const std::string text = replace_lines(c.first_line, c.last_line, c.replacement);
  try {
    parse_scene(text, "bad.toml");
    FAIL() << "no error for:\n" << text;
  } catch (const SceneError& e) {
    const std::string message = e.what();
    const std::string where = "bad.toml:" + std::to_string(c.line) + ": " + c.key + ": ";
    EXPECT_EQ(message.rfind(where, 0), 0u) << message;
    EXPECT_NE(message.find(c.what), std::string::npos) << message;
    EXPECT_EQ(e.line(), c.line) << message;
  }
}

const char* const kSelfIntersecting =
    "type = \"polygon\"\n"
    "vertices = [[1.0, 1.0], [3.0, 3.0], [3.0, 1.0], [1.0, 3.0]]";
const char* const kFlatTrapezoid =
    "type = \"trapezoid\"\n"
    "base_start = [1.0, 0.0]\n"
    "base_length = 2.0\n"
    "height = 2.0\n"
    "rear_angle = 30.0\n"
    "front_angle = 30.0";
const char* const kSecondClay =
    "[[material]]\n"
    "name = \"clay\"\n"
    "density = 1.0\n"
    "youngs_modulus = 1.0\n"
    "poisson_ratio = 0.2\n";

INSTANTIATE_TEST_SUITE_P(
    SceneParser, SceneErrors,
    ::testing::Values(
        ErrorCase{"Syntax", 5, 5, "cell_size = = 0.5", 5, "syntax error", ""},
        ErrorCase{"UnknownTopLevelTable", 13, 13, "[gird]\nx = 1\n", 13, "gird", "unknown key"},
        ErrorCase{"UnknownTopLevelKey", 1, 1, "verbose = true\n[scene]", 1, "verbose", "unknown key"},
        ErrorCase{"UnknownNestedKey", 5, 5, "cellsize = 0.5", 5, "grid.cellsize", "unknown key"},
        ErrorCase{"UnknownMethod", 3, 3, "method = \"sph\"", 3, "scene.method",
                  "must be one of \"mpm\", \"dam\" (got \"sph\")"},
        ErrorCase{"UnknownShearRate", 13, 13, "[dam]\nshear_rate = \"cubic\"", 14,
                  "dam.shear_rate", "must be one of \"linear\", \"plug\", \"band\""},
        // The band's thickness is the clay's: a slide without one has none.
        ErrorCase{"BandWithoutBandThickness", 13, 13, "[dam]\nshear_rate = \"band\"", 14,
                  "dam.shear_rate", "\"band\" needs band_thickness in the material"},
        ErrorCase{"NegativeSkinFriction", 13, 13, "[dam]\nskin_friction = -0.01", 14,
                  "dam.skin_friction", "must be >= 0 (got -0.01)"},
        ErrorCase{"NegativePressureDrag", 13, 13, "[dam]\npressure_drag = -1", 14,
                  "dam.pressure_drag", "must be >= 0 (got -1)"},
        ErrorCase{"AddedMassNotANumber", 13, 13, "[dam]\nadded_mass = \"some\"", 14,
                  "dam.added_mass", "expected a number, got string"},
        ErrorCase{"NoWater", 13, 13, "[dam]\nwater_density = 0", 14, "dam.water_density",
                  "must be > 0 (got 0)"},
        ErrorCase{"UnknownWaterKey", 13, 13, "[dam]\nform_drag = 1", 14, "dam.form_drag",
                  "unknown key"},
        ErrorCase{"NegativeElements", 13, 13, "[dam]\nelements = -1", 14, "dam.elements",
                  "must be >= 0 (got -1)"},
        ErrorCase{"UnknownEarthPressure", 13, 13, "[dam]\nearth_pressure = \"coulomb\"", 14,
                  "dam.earth_pressure",
                  "must be one of \"rankine\", \"hydrostatic\" (got \"coulomb\")"},
        // The fixed fraction is gone: the plug estimate's sheared layer
        // follows from the rheology (docs/dam.md).
        ErrorCase{"RetiredShearLayerKey", 13, 13, "[dam]\nmin_shear_layer = 0.1", 14,
                  "dam.min_shear_layer", "unknown key"},
        ErrorCase{"UnknownBodyKey", 25, 25, "colour = \"red\"", 25, "body[0].colour", "unknown key"},
        ErrorCase{"KeyOfAnotherBodyType", 25, 25, "max = [3.0, 2.0]\nheight = 1.0", 26,
                  "body[0].height", "unknown key"},
        ErrorCase{"StringForNumber", 16, 16, "density = \"heavy\"", 16, "material[0].density",
                  "expected a number, got string"},
        ErrorCase{"FloatForInteger", 8, 8, "ppc = 2.5", 8, "grid.ppc",
                  "expected an integer, got float"},
        ErrorCase{"NotAPoint", 6, 6, "min = [0.0, 0.0, 1.0]", 6, "grid.min",
                  "expected an array of 2 numbers"},
        ErrorCase{"SingleMaterialTable", 14, 14, "[material]", 14, "material",
                  "expected an array of tables ([[material]]), got table"},
        ErrorCase{"MissingKey", 5, 5, "", 4, "grid.cell_size", "missing required key"},
        ErrorCase{"MissingTable", 10, 12, "", 1, "time", "missing required key"},
        ErrorCase{"NonPositiveCellSize", 5, 5, "cell_size = -0.1", 5, "grid.cell_size",
                  "must be > 0 (got -0.1)"},
        ErrorCase{"NotFinite", 5, 5, "cell_size = inf", 5, "grid.cell_size",
                  "must be a finite number"},
        ErrorCase{"PpcBelowOne", 8, 8, "ppc = 0", 8, "grid.ppc", "must be in [1, 16] (got 0)"},
        ErrorCase{"PpcAbove16", 8, 8, "ppc = 17", 8, "grid.ppc", "must be in [1, 16] (got 17)"},
        ErrorCase{"NonPositiveDensity", 16, 16, "density = 0", 16, "material[0].density",
                  "must be in (0, 100000] (got 0)"},
        ErrorCase{"IncompressiblePoisson", 18, 18, "poisson_ratio = 0.5", 18,
                  "material[0].poisson_ratio", "must be in (-1, 0.5) (got 0.5)"},
        ErrorCase{"GridMaxNotAboveMin", 7, 7, "max = [10.0, 0.0]", 7, "grid.max",
                  "must be greater than grid.min"},
        ErrorCase{"OutputAfterEnd", 12, 12, "output_interval = 2.0", 12,
                  "time.output_interval", "must be <= time.end"},
        ErrorCase{"CourantAboveTheStableLimit", 12, 12, "output_interval = 0.1\ncourant = 0.6", 13,
                  "time.courant", "must be <= 0.25 with shape gimp and transfer flip (got 0.6)"},
        ErrorCase{"UnknownTransfer", 12, 12, "output_interval = 0.1\n[solver]\ntransfer = \"fmpm\"",
                  14, "solver.transfer", "fmpm"},
        ErrorCase{"NegativeGravityRamp", 12, 12, "output_interval = 0.1\n[gravity]\nramp = -1.0",
                  14, "gravity.ramp", ">= 0"},
        ErrorCase{"CourantZero", 12, 12, "output_interval = 0.1\ncourant = 0", 13, "time.courant",
                  "must be in (0, 1]"},
        ErrorCase{"UnknownBoundaryKind", 13, 13, "[boundary]\nleft = \"open\"\n", 14,
                  "boundary.left", "must be one of \"free\", \"slip\", \"fixed\""},
        ErrorCase{"UnknownBodyType", 23, 23, "type = \"circle\"", 23, "body[0].type",
                  "must be one of \"rectangle\", \"trapezoid\", \"polygon\""},
        ErrorCase{"SelfIntersectingPolygon", 23, 25, kSelfIntersecting, 23, "body[0].polygon",
                  "self-intersecting polygon"},
        ErrorCase{"TooFewVertices", 23, 25, "type = \"polygon\"\nvertices = [[1, 1], [2, 2]]", 24,
                  "body[0].vertices", "at least 3 vertices"},
        ErrorCase{"PolygonOutsideGrid", 25, 25, "max = [3.0, 6.0]", 23, "body[0].polygon",
                  "outside the grid"},
        ErrorCase{"UnknownMaterial", 22, 22, "material = \"sand\"", 22, "body[0].material",
                  "unknown material \"sand\""},
        ErrorCase{"DuplicateMaterial", 19, 19, kSecondClay, 20, "material[1].name",
                  "duplicate material name \"clay\""},
        ErrorCase{"SlopeAndVector", 13, 13, "[gravity]\nslope_angle = 5.0\nvector = [0.0, -9.81]\n",
                  14, "gravity.slope_angle", "cannot be combined with gravity.vector"},
        ErrorCase{"SlopeAngleVertical", 13, 13, "[gravity]\nslope_angle = 90\n", 14,
                  "gravity.slope_angle", "must be in (-90, 90)"},
        ErrorCase{"TrapezoidWithoutTop", 23, 25, kFlatTrapezoid, 25, "body[0].base_length",
                  "must be > 0"},
        ErrorCase{"NoBodies", 20, 25, "", 1, "body", "missing required key"},
        ErrorCase{"RestFractionOne", 12, 12, "output_interval = 0.1\nrest_fraction = 1", 13,
                  "time.rest_fraction", "must be in [0, 1) (got 1)"},
        ErrorCase{"RestDurationZero", 12, 12, "output_interval = 0.1\nrest_duration = 0", 13,
                  "time.rest_duration", "must be > 0 (got 0)"},
        ErrorCase{"UnknownModel", 18, 18, "poisson_ratio = 0.3\nmodel = \"mohr\"", 19,
                  "material[0].model", "must be one of \"elastic\", \"tresca\""},
        ErrorCase{"TrescaKeyOnElastic", 18, 18, "poisson_ratio = 0.3\nsu0 = 2500", 19,
                  "material[0].su0", "unknown key"},
        ErrorCase{"TrescaWithoutSu0", 18, 18, "poisson_ratio = 0.3\nmodel = \"tresca\"", 14,
                  "material[0].su0", "missing required key"},
        ErrorCase{"Su0Zero", 18, 18, "poisson_ratio = 0.3\nmodel = \"tresca\"\nsu0 = 0", 20,
                  "material[0].su0", "must be > 0 (got 0)"},
        ErrorCase{"SensitivityBelowOne", 18, 18, std::string(kTrescaClay) + "\nsensitivity = 0.5",
                  21, "material[0].sensitivity", "must be >= 1 (got 0.5)"},
        ErrorCase{"SofteningWithoutXi95", 18, 18, std::string(kTrescaClay) + "\nsensitivity = 40",
                  14, "material[0].xi95", "missing required key"},
        ErrorCase{"Xi95Zero", 18, 18, std::string(kTrescaClay) + "\nxi95 = 0", 21,
                  "material[0].xi95", "must be > 0 (got 0)"},
        ErrorCase{"NonlocalLengthZero", 18, 18,
                  std::string(kTrescaClay) + "\nband_thickness = 0.1\nnonlocal_length = 0", 22,
                  "material[0].nonlocal_length", "must be > 0 (got 0)"},
        ErrorCase{"NonlocalLengthWithoutBandThickness", 18, 18,
                  std::string(kTrescaClay) + "\nnonlocal_length = 1", 21,
                  "material[0].nonlocal_length", "band_thickness"},
        ErrorCase{"BandThicknessNegative", 18, 18,
                  std::string(kTrescaClay) + "\nband_thickness = -0.1", 21,
                  "material[0].band_thickness", "must be > 0 (got -0.1)"},
        ErrorCase{"NonlocalLengthOnElastic", 18, 18, "poisson_ratio = 0.3\nnonlocal_length = 1", 19,
                  "material[0].nonlocal_length", "unknown key"},
        ErrorCase{"NegativeEta", 18, 18, std::string(kTrescaClay) + "\neta = -0.1", 21,
                  "material[0].eta", "must be >= 0 (got -0.1)"},
        ErrorCase{"RateExponentAboveOne", 18, 18,
                  std::string(kTrescaClay) + "\nrate_exponent = 1.5", 21, "material[0].rate_exponent", "must be in (0, 1] (got 1.5)"},
        ErrorCase{"ReferenceRateZero", 18, 18, std::string(kTrescaClay) + "\nreference_rate = 0",
                  21, "material[0].reference_rate", "must be > 0 (got 0)"},
        ErrorCase{"BadStrengthForm", 18, 18,
                  std::string(kTrescaClay) + "\nstrength_form = \"product\"", 21,
                  "material[0].strength_form",
                  "must be one of \"additive\", \"multiplicative\" (got \"product\")"},
        ErrorCase{"BaseWithoutKind", 25, 25, "max = [3.0, 2.0]\n[base]\ninterface = \"no_slip\"",
                  26, "base.kind", "missing required key"},
        ErrorCase{"UnknownBaseKind", 25, 25, "max = [3.0, 2.0]\n[base]\nkind = \"curved\"", 27,
                  "base.kind", "must be one of \"planar\", \"polyline\""},
        ErrorCase{"PointsOnPlanarBase", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"planar\"\npoints = [[0, 0], [1, 0]]", 28,
                  "base.points", "unknown key"},
        ErrorCase{"PolylineWithoutPoints", 25, 25, "max = [3.0, 2.0]\n[base]\nkind = \"polyline\"",
                  26, "base.points", "missing required key"},
        ErrorCase{"PolylineOnePoint", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"polyline\"\npoints = [[0, 0]]", 28,
                  "base.points", "expected at least 2 points (got 1)"},
        ErrorCase{"PolylineXNotIncreasing", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"polyline\"\n"
                  "points = [[0, 1], [4, 0.5], [4, 0]]",
                  28, "base.points",
                  "x must increase strictly along the line: point 2 (4, 0) follows x = 4"},
        ErrorCase{"PolylineSegmentWithoutLength", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"polyline\"\n"
                  "points = [[0, 1], [1e-320, 1], [4, 0]]",
                  28, "base.points",
                  "point 1 (1e-320, 1) is too close to point 0 for the segment between them to "
                  "have a length"},
        ErrorCase{"PolylineOutsideGrid", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"polyline\"\npoints = [[0, 1], [12, 0]]", 28,
                  "base.points", "point 1 (12, 0) lies outside the grid's x range [0, 10]"},
        ErrorCase{"FrictionalWithoutTau", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"planar\"\ninterface = \"frictional\"", 26,
                  "base.shear_strength", "missing required key"},
        ErrorCase{"TauOnNoSlip", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"planar\"\nshear_strength = 1000", 28,
                  "base.shear_strength", "unknown key"},
        ErrorCase{"FrictionOnFrictional", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"planar\"\ninterface = \"frictional\"\n"
                  "shear_strength = 1000\nfriction = 0.3",
                  30, "base.friction", "unknown key"},
        ErrorCase{"CoulombFrictionZero", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"planar\"\ninterface = \"coulomb\"\n"
                  "friction = 0",
                  29, "base.friction", "must be > 0 (got 0)"},
        ErrorCase{"BaseAndFixedBottom", 13, 13,
                  "[boundary]\nbottom = \"fixed\"\n[base]\nkind = \"planar\"\n", 14,
                  "boundary.bottom",
                  "must be \"free\" when [base] is given: the base is the bottom"},
        ErrorCase{"PeriodicOnOneSide", 13, 13, "[boundary]\nleft = \"periodic\"\n", 14,
                  "boundary.left", "needs the other side periodic too"},
        ErrorCase{"PeriodicTop", 13, 13,
                  "[boundary]\nleft = \"periodic\"\nright = \"periodic\"\ntop = \"periodic\"\n",
                  16, "boundary.top", "is for left and right only"},
        ErrorCase{"PeriodicOnAPolyline", 25, 25,
                  "max = [3.0, 2.0]\n[base]\nkind = \"polyline\"\npoints = [[0, 1], [10, 0]]\n"
                  "[boundary]\nleft = \"periodic\"\nright = \"periodic\"",
                  30, "boundary.left", "needs a planar base or none"}),
    [](const ::testing::TestParamInfo<ErrorCase>& info) { return std::string(info.param.name); });

TEST(SceneParser, MissingFileHasNoLine) {
  const std::string path = "/nonexistent/runout/scene.toml";
  try {
    load_scene_file(path);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 0);
    // Then the system's reason (strerror).
    EXPECT_EQ(std::string(e.what()).rfind("cannot open scene file '" + path + "': ", 0), 0u)
        << e.what();
  }
}

TEST(SceneParser, LoadedFileIsNamedInMessages) {
  const std::string path = ::testing::TempDir() + "runout_bad_scene.toml";
  std::ofstream(path) << replace_lines(5, 5, "cell_size = 0");
  try {
    load_scene_file(path);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":5: grid.cell_size: ", 0), 0u) << e.what();
  }
  std::remove(path.c_str());
}

// Exact equality on purpose: the resolved scene must reproduce every bit.
void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.grid.cell_size, b.grid.cell_size);
  EXPECT_EQ(a.grid.min, b.grid.min);
  EXPECT_EQ(a.grid.max, b.grid.max);
  EXPECT_EQ(a.grid.shape, b.grid.shape);
  EXPECT_EQ(a.grid.domain, b.grid.domain);
  EXPECT_EQ(a.grid.ppc, b.grid.ppc);
  EXPECT_EQ(a.boundary.left, b.boundary.left);
  EXPECT_EQ(a.boundary.right, b.boundary.right);
  EXPECT_EQ(a.boundary.bottom, b.boundary.bottom);
  EXPECT_EQ(a.boundary.top, b.boundary.top);
  EXPECT_EQ(a.time.end, b.time.end);
  EXPECT_EQ(a.time.output_interval, b.time.output_interval);
  EXPECT_EQ(a.time.courant, b.time.courant);
  EXPECT_EQ(a.time.rest_fraction, b.time.rest_fraction);
  EXPECT_EQ(a.time.rest_duration, b.time.rest_duration);
  EXPECT_EQ(a.gravity.vector, b.gravity.vector);
  EXPECT_EQ(a.gravity.slope_angle_deg, b.gravity.slope_angle_deg);
  EXPECT_EQ(a.gravity.ramp, b.gravity.ramp);
  EXPECT_EQ(a.solver.transfer, b.solver.transfer);
  EXPECT_EQ(a.solver.flip, b.solver.flip);
  EXPECT_EQ(a.solver.pic_cells, b.solver.pic_cells);
  EXPECT_EQ(a.solver.mass_threshold, b.solver.mass_threshold);
  EXPECT_EQ(a.solver.damping, b.solver.damping);
  EXPECT_EQ(a.solver.volumetric_smoothing, b.solver.volumetric_smoothing);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].model, b.materials[i].model);
    EXPECT_EQ(a.materials[i].density, b.materials[i].density);
    EXPECT_EQ(a.materials[i].youngs_modulus, b.materials[i].youngs_modulus);
    EXPECT_EQ(a.materials[i].poisson_ratio, b.materials[i].poisson_ratio);
    EXPECT_EQ(a.materials[i].su0, b.materials[i].su0);
    EXPECT_EQ(a.materials[i].sensitivity, b.materials[i].sensitivity);
    EXPECT_EQ(a.materials[i].xi95, b.materials[i].xi95);
    EXPECT_EQ(a.materials[i].eta, b.materials[i].eta);
    EXPECT_EQ(a.materials[i].rate_exponent, b.materials[i].rate_exponent);
    EXPECT_EQ(a.materials[i].reference_rate, b.materials[i].reference_rate);
    EXPECT_EQ(a.materials[i].strength_form, b.materials[i].strength_form);
    EXPECT_EQ(a.materials[i].band_thickness, b.materials[i].band_thickness);
    EXPECT_EQ(a.materials[i].nonlocal_length, b.materials[i].nonlocal_length);
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].name, b.bodies[i].name);
    EXPECT_EQ(a.bodies[i].material, b.bodies[i].material);
    EXPECT_EQ(a.bodies[i].polygon, b.bodies[i].polygon);
    EXPECT_EQ(a.bodies[i].velocity, b.bodies[i].velocity);
  }
  EXPECT_EQ(a.base.kind, b.base.kind);
  EXPECT_EQ(a.base.points, b.base.points);
  EXPECT_EQ(a.base.interface, b.base.interface);
  EXPECT_EQ(a.base.shear_strength, b.base.shear_strength);
  EXPECT_EQ(a.base.friction, b.base.friction);
  EXPECT_EQ(a.base.clay_band, b.base.clay_band);
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.dam.shear_rate, b.dam.shear_rate);
  EXPECT_EQ(a.dam.elements, b.dam.elements);
  EXPECT_EQ(a.dam.earth_pressure, b.dam.earth_pressure);
  EXPECT_EQ(a.dam.water_density, b.dam.water_density);
  EXPECT_EQ(a.dam.skin_friction, b.dam.skin_friction);
  EXPECT_EQ(a.dam.pressure_drag, b.dam.pressure_drag);
  EXPECT_EQ(a.dam.added_mass, b.dam.added_mass);
  EXPECT_EQ(a.output.compress, b.output.compress);
  EXPECT_EQ(a.overrides, b.overrides);
}

TEST(SceneWriter, DefaultSceneRoundTrips) {
  const Scene original = default_scene();
  expect_same_scene(parse_scene(to_toml(original), "resolved.toml"), original);
}

TEST(SceneWriter, EveryNonDefaultValueRoundTrips) {
  Scene s = parse_scene(
      "[scene]\nname = \"odd \\\"one\\\"\"\ndescription = \"tab\\there\\nnewline\"\n"
      "[grid]\ncell_size = 0.1\nmin = [-1.3, 0.7]\nmax = [7.77, 3.33]\n"
      "shape = \"linear\"\ndomain = \"fixed\"\nppc = 3\n"
      "[boundary]\nleft = \"free\"\nright = \"fixed\"\nbottom = \"free\"\ntop = \"fixed\"\n"
      "[time]\nend = 3\noutput_interval = 0.1\ncourant = 0.25\nrest_fraction = 0.003\n"
      "rest_duration = 0.7\n"
      "[gravity]\nmagnitude = 9.80665\nslope_angle = -13.75\nramp = 0.75\n"
      "[solver]\ntransfer = \"pic_flip\"\nflip = 0.5\npic_cells = 12.5\nmass_threshold = 1e-7\n"
      "damping = 0.1\n"
      "[[material]]\nname = \"a\"\ndensity = 525\nyoungs_modulus = 1.5e6\npoisson_ratio = -0.2\n"
      "model = \"tresca\"\nsu0 = 15e3\nsensitivity = 40\nxi95 = 45\neta = 0.0167\n"
      "rate_exponent = 0.5\nreference_rate = 0.3\nstrength_form = \"additive\"\n"
      "band_thickness = 0.03\nnonlocal_length = 0.07\n"
      "[[material]]\nname = \"b\"\ndensity = 2000.5\nyoungs_modulus = 3e7\npoisson_ratio = 0.1\n"
      "[[body]]\nname = \"t\"\nmaterial = \"b\"\ntype = \"trapezoid\"\n"
      "base_start = [0.1, 0.8]\nbase_length = 5.3\nheight = 1.1\n"
      "rear_angle = 100.0\nfront_angle = 33.3\nvelocity = [0.25, -1e-3]\n"
      "[[body]]\nname = \"p\"\nmaterial = \"a\"\ntype = \"polygon\"\n"
      "vertices = [[6, 1], [7, 1], [6.5, 2.9]]\n"
      "[base]\nkind = \"polyline\"\npoints = [[-1.3, 0.75], [2.1, 0.71], [7.77, 0.7]]\n"
      "interface = \"coulomb\"\nfriction = 0.35\n"
      "[output]\ncompress = false\n",
      "odd.toml");
  apply_overrides(s, 0.13, 4);
  expect_same_scene(parse_scene(to_toml(s), "resolved.toml"), s);
}

// The other interface, a planar base, and defaults of a Tresca material.
TEST(SceneWriter, PlanarBaseAndTrescaDefaultsRoundTrip) {
  const Scene s = parse_scene(
      replace_lines(18, 25, std::string(kTrescaClay) +
                                "\n[[body]]\nname = \"block\"\nmaterial = \"clay\"\n"
                                "type = \"rectangle\"\nmin = [1.0, 0.0]\nmax = [3.0, 2.0]\n"
                                "[base]\nkind = \"planar\"\ninterface = \"frictional\"\n"
                                "shear_strength = 1e3\nclay_band = true"),
      "planar.toml");
  ASSERT_EQ(s.base.kind, BaseKind::Planar);
  ASSERT_TRUE(s.base.clay_band);
  expect_same_scene(parse_scene(to_toml(s), "resolved.toml"), s);
}

// The depth-averaged model's keys: the method in [scene], the [dam] table.
TEST(SceneWriter, DepthAveragedKeysRoundTrip) {
  Scene s = parse_scene(replace_lines(3, 3, "method = \"dam\"") +
                            "[dam]\nshear_rate = \"plug\"\nearth_pressure = \"hydrostatic\"\nelements = 120\n"
                            "water_density = 1030.5\nskin_friction = 0.0125\npressure_drag = 0.75\n"
                            "added_mass = 0.125\n",
                        "dam.toml");
  EXPECT_EQ(s.method, Method::Dam);
  EXPECT_EQ(s.dam.shear_rate, ShearRateEstimate::Plug);
  EXPECT_EQ(s.dam.elements, 120);
  EXPECT_EQ(s.dam.earth_pressure, EarthPressure::Hydrostatic);
  EXPECT_EQ(s.dam.water_density, 1030.5);
  EXPECT_EQ(s.dam.skin_friction, 0.0125);
  EXPECT_EQ(s.dam.pressure_drag, 0.75);
  EXPECT_EQ(s.dam.added_mass, 0.125);
  expect_same_scene(parse_scene(to_toml(s), "resolved.toml"), s);
  const Scene defaults = parse_scene(kMinimal, "mini.toml");
  EXPECT_EQ(defaults.method, Method::Mpm);
  EXPECT_EQ(defaults.dam.shear_rate, ShearRateEstimate::Linear);
  EXPECT_EQ(defaults.dam.elements, 0);
  EXPECT_EQ(defaults.dam.earth_pressure, EarthPressure::Rankine);
  // The ambient water is off unless asked for.
  EXPECT_EQ(defaults.dam.water_density, 1025.0);
  EXPECT_EQ(defaults.dam.skin_friction, 0.0);
  EXPECT_EQ(defaults.dam.pressure_drag, 0.0);
  EXPECT_EQ(defaults.dam.added_mass, 0.0);
}

// The band is the default shear rate where the slide's clay has a band
// thickness; linear and plug stay selectable, and the choice round-trips.
TEST(SceneWriter, BandIsTheDefaultWithABandThickness) {
  const std::string clay = replace_lines(18, 18, std::string(kTrescaClay) + "\nband_thickness = 0.2");
  const Scene band = parse_scene(clay, "band.toml");
  EXPECT_EQ(band.dam.shear_rate, ShearRateEstimate::Band);
  expect_same_scene(parse_scene(to_toml(band), "resolved.toml"), band);
  const Scene linear = parse_scene(clay + "\n[dam]\nshear_rate = \"linear\"\n", "linear.toml");
  EXPECT_EQ(linear.dam.shear_rate, ShearRateEstimate::Linear);
  expect_same_scene(parse_scene(to_toml(linear), "resolved.toml"), linear);
  EXPECT_EQ(parse_scene(replace_lines(18, 18, kTrescaClay), "local.toml").dam.shear_rate,
            ShearRateEstimate::Linear);
}

TEST(SceneWriter, MethodOverridesAreRecordedAndChecked) {
  Scene s = default_scene();
  apply_method_overrides(s, std::string("dam"), std::string("plug"), 40);
  EXPECT_EQ(s.method, Method::Dam);
  EXPECT_EQ(s.dam.shear_rate, ShearRateEstimate::Plug);
  EXPECT_EQ(s.dam.elements, 40);
  EXPECT_EQ(s.overrides, (std::vector<std::string>{"scene.method = \"dam\"",
                                                   "dam.shear_rate = \"plug\"",
                                                   "dam.elements = 40"}));
  expect_same_scene(parse_scene(to_toml(s), "resolved.toml"), s);
  EXPECT_THROW(apply_method_overrides(s, std::string("fem"), std::nullopt, std::nullopt),
               SceneError);
  EXPECT_THROW(apply_method_overrides(s, std::nullopt, std::nullopt, -2), SceneError);
}

TEST(SceneWriter, OverridesAreRecordedAndChecked) {
  Scene s = default_scene();
  apply_overrides(s, 0.4, 3, 7.5);
  EXPECT_EQ(s.grid.cell_size, 0.4);
  EXPECT_EQ(s.grid.ppc, 3);
  EXPECT_EQ(s.time.end, 7.5);
  EXPECT_EQ(s.overrides, (std::vector<std::string>{"grid.cell_size = 0.4", "grid.ppc = 3",
                                                   "time.end = 7.5"}));
  // The old max need not lie on a node of the new grid, so it must have moved to one.
  const double cells = (s.grid.max.x() - s.grid.min.x()) / s.grid.cell_size;
  EXPECT_NEAR(cells, std::round(cells), 1e-9);

  struct Bad {
    std::optional<double> cell;
    std::optional<int> ppc;
    std::optional<double> end;
    std::string flag;
  };
  // An end before the first output interval would leave no frame to write.
  for (const Bad& bad : {Bad{0.0, {}, {}, "--cell"}, Bad{-1.0, {}, {}, "--cell"},
                         Bad{{}, 0, {}, "--ppc"}, Bad{{}, 17, {}, "--ppc"},
                         Bad{{}, {}, 0.5 * s.time.output_interval, "--end"}}) {
    try {
      apply_overrides(s, bad.cell, bad.ppc, bad.end);
      FAIL() << "no error for " << bad.flag;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.line(), 0);
      EXPECT_EQ(std::string(e.what()).rfind(bad.flag + ": must be", 0), 0u) << e.what();
    }
  }
}

const Polygon kUnitSquare = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

TEST(Polygon, SignedAreaFollowsOrientation) {
  EXPECT_DOUBLE_EQ(signed_area(kUnitSquare), 1.0);
  EXPECT_DOUBLE_EQ(signed_area(Polygon(kUnitSquare.rbegin(), kUnitSquare.rend())), -1.0);
  EXPECT_DOUBLE_EQ(signed_area({{0, 0}, {4, 0}, {0, 3}}), 6.0);
}

TEST(Polygon, SimpleAndSelfIntersecting) {
  EXPECT_TRUE(is_simple(kUnitSquare));
  EXPECT_TRUE(is_simple({{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}}));  // concave
  EXPECT_FALSE(is_simple({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));         // bow-tie
  EXPECT_FALSE(is_simple({{0, 0}, {1, 0}, {1, 0}, {0, 1}}));         // repeated vertex
  EXPECT_FALSE(is_simple({{0, 0}, {2, 0}, {1, 0}}));                 // folds back
  EXPECT_FALSE(is_simple({{0, 0}, {1, 0}}));
}

TEST(Polygon, Contains) {
  EXPECT_TRUE(contains(kUnitSquare, {0.5, 0.5}));
  EXPECT_FALSE(contains(kUnitSquare, {1.5, 0.5}));
  EXPECT_FALSE(contains(kUnitSquare, {0.5, -0.1}));
  const Polygon notch = {{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}};
  EXPECT_TRUE(contains(notch, {0.5, 1.2}));
  EXPECT_FALSE(contains(notch, {1.0, 1.5}));
}

TEST(Seeding, AlignedRectangleFillsWholeCells) {
  for (const int ppc : {1, 2, 4}) {
    Scene s = parse_scene(kMinimal, "mini.toml");  // 2 m x 2 m block, h = 0.5
    s.grid.ppc = ppc;
    s.bodies[0].velocity = {0.5, -0.25};
    const Particles p = seed_particles(s);
    ASSERT_EQ(p.size(), 16 * ppc * ppc);
    const double total_mass = std::accumulate(p.mass.begin(), p.mass.end(), 0.0);
    EXPECT_NEAR(total_mass / (600.0 * 4.0), 1.0, 1e-12);
    for (int i = 0; i < p.size(); ++i) {
      EXPECT_TRUE(p.x[i] > 1.0 && p.x[i] < 3.0 && p.y[i] > 0.0 && p.y[i] < 2.0);
      EXPECT_EQ(p.id[i], i);
      EXPECT_EQ(p.x0[i], p.x[i]);
      EXPECT_EQ(p.vx[i], 0.5);
      EXPECT_EQ(p.vy[i], -0.25);
      EXPECT_EQ(p.vol0[i], 0.25 / (ppc * ppc));
      EXPECT_EQ(p.vol[i], p.vol0[i]);
    }
  }
}

TEST(Seeding, TrapezoidVolumeWithinOneCellRow) {
  const Scene s = default_scene();
  const Particles p = seed_particles(s);
  const double volume = std::accumulate(p.vol0.begin(), p.vol0.end(), 0.0);
  const double exact = signed_area(s.bodies[0].polygon);
  EXPECT_LT(std::abs(volume - exact), 48.66 * s.grid.cell_size);
  for (int i = 0; i < p.size(); ++i) {
    ASSERT_TRUE(contains(s.bodies[0].polygon, {p.x[i], p.y[i]}));
    ASSERT_EQ(p.id[i], i);
    ASSERT_EQ(p.body[i], 0);
    ASSERT_EQ(p.material[i], 0);
  }
}

// The lattice seeds a layer to the last sub-cell centre inside it: a
// block 2.9 m high at spacing 0.5 m is seeded 6 rows, 3 m, high (at 0.8 m
// the reference slides' 5 m were 4.8 m). Its particles carry the block's
// own mass, rho A, so its weight and basal stresses are the block's; a
// second block the lattice fills exactly keeps rho v per particle, bit
// for bit.
TEST(Seeding, EachBodyCarriesTheMassOfItsArea) {
  Scene s = parse_scene(
      replace_lines(25, 25, "max = [3.0, 2.9]\n\n[[body]]\nname = \"second\"\nmaterial = \"clay\"\n"
                            "type = \"rectangle\"\nmin = [5.0, 0.0]\nmax = [6.0, 1.0]"),
      "two.toml");
  s.grid.ppc = 1;
  const Particles p = seed_particles(s);
  double mass[2] = {0.0, 0.0}, volume = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    mass[p.body[i]] += p.mass[i];
    if (p.body[i] == 0) volume += p.vol[i];
    if (p.body[i] == 1) {
      EXPECT_EQ(p.mass[i], 600.0 * 0.25);
    }
  }
  EXPECT_NEAR(volume, 2.0 * 3.0, 1e-12);  // 4 columns of 6 rows of 0.25 m2
  EXPECT_NEAR(mass[0] / (600.0 * 2.0 * 2.9), 1.0, 1e-12);
  EXPECT_NEAR(mass[1] / (600.0 * 1.0 * 1.0), 1.0, 1e-12);
}

TEST(Seeding, IdsRunThroughEveryBody) {
  const Scene s = parse_scene(
      replace_lines(25, 25, "max = [3.0, 2.0]\n\n[[body]]\nname = \"second\"\nmaterial = \"clay\"\n"
                            "type = \"rectangle\"\nmin = [5.0, 0.0]\nmax = [6.0, 1.0]"),
      "two.toml");
  const Particles p = seed_particles(s);
  ASSERT_EQ(p.size(), 16 * 4 + 4 * 4);
  for (int i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.id[i], i);
    EXPECT_EQ(p.body[i], i < 64 ? 0 : 1);
  }
}

}  // namespace
}  // namespace runout
