// `runout analyse` gives the numbers of the VTK filters: a short real run
// analysed by the CLI, then opened with vtkPVDReader (as ParaView opens it)
// and put through Runout Shear Bands, Runout Horsts And Grabens, Runout
// Morphology and Runout Morphology History with their defaults; every cell
// of every table of every frame must be the same, to the last digit (the
// CSV's 17 digits read back as the filter's double). And the CLI's defaults
// are the filters'.
#include <gtest/gtest.h>

#include <vtkAbstractArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPVDReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_table.hpp"
#include "filter_fixtures.hpp"
#include "runout/analysis/horst_graben.hpp"
#include "runout/analysis/morphology_rules.hpp"
#include "runout/analysis/shear_bands.hpp"
#include "vtkRunoutHorstGraben.h"
#include "vtkRunoutMorphology.h"
#include "vtkRunoutMorphologyHistory.h"
#include "vtkRunoutShearBands.h"

namespace fs = std::filesystem;
using runout::cli_runner::Result;
using runout::cli_runner::run_cli;
using runout::csv_table::read_table;
using runout::csv_table::Table;
using runout::filter_fixtures::ErrorCounter;

namespace {

// A coarse run to t = 4 s (five frames, bands in four of them, blocks),
// analysed by the CLI once for every test.
class AnalyseAgainstFilters : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    run_ = new runout::cli_runner::CoarseRun("runout_analyse_filters", 4);
    const Result analyse = run_cli("analyse " + run_->dir().string());
    ASSERT_EQ(analyse.code, 0) << analyse.output;
  }
  static void TearDownTestSuite() { delete run_; }

  static fs::path analysis(const std::string& file) { return run_->dir() / "analysis" / file; }
  static std::string pvd() { return run_->pvd().string(); }
  // The frames' times, as the CLI read them from the index.
  static std::vector<double> times() {
    const Table morphology = read_table(analysis("morphology.csv"));
    std::vector<double> t;
    for (std::size_t k = 0; k < morphology.rows.size(); ++k) t.push_back(morphology.number(k, "Time"));
    return t;
  }

  static runout::cli_runner::CoarseRun* run_;
};
runout::cli_runner::CoarseRun* AnalyseAgainstFilters::run_ = nullptr;

std::string numbered(const char* stem, std::size_t k) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu.csv", stem, k);
  return name;
}

// The CSV cell as the double it was written from ("nan" for NaN).
double number(const std::string& cell) { return std::strtod(cell.c_str(), nullptr); }

void expect_same(double csv, double filter, const std::string& where) {
  if (std::isnan(filter))
    EXPECT_TRUE(std::isnan(csv)) << where << ": " << csv << ", the filter NaN";
  else
    EXPECT_EQ(csv, filter) << where;
}

// Every column of `table` (in order) and every cell equal to the CSV's,
// which may hold `extra` columns first (frame).
void expect_table(vtkTable* table, const Table& csv, std::size_t extra = 0) {
  ASSERT_EQ(static_cast<std::size_t>(table->GetNumberOfColumns()) + extra, csv.header.size());
  ASSERT_EQ(static_cast<std::size_t>(table->GetNumberOfRows()), csv.rows.size());
  for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c) {
    vtkAbstractArray* column = table->GetColumn(c);
    const std::string name = column->GetName();
    EXPECT_EQ(csv.header[c + extra], name);
    for (vtkIdType row = 0; row < table->GetNumberOfRows(); ++row) {
      const std::string cell = csv.rows[row][c + extra];
      const std::string where = name + " row " + std::to_string(row);
      if (auto* text = vtkStringArray::SafeDownCast(column))
        EXPECT_EQ(cell, text->GetValue(row)) << where;
      else
        expect_same(number(cell), column->GetVariantValue(row).ToDouble(), where);
    }
  }
}

}  // namespace

TEST_F(AnalyseAgainstFilters, BandsAndBlocksOfEveryFrame) {
  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(pvd().c_str());
  vtkNew<vtkRunoutShearBands> bands;
  vtkNew<vtkRunoutHorstGraben> blocks;
  vtkNew<ErrorCounter> errors;
  for (vtkAlgorithm* filter : {static_cast<vtkAlgorithm*>(bands), static_cast<vtkAlgorithm*>(blocks)}) {
    filter->SetInputConnection(reader->GetOutputPort());
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
  }
  const std::vector<double> t = times();
  ASSERT_EQ(t.size(), 5u);
  int band_rows = 0, block_rows = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    bands->UpdateTimeStep(t[k]);
    blocks->UpdateTimeStep(t[k]);
    auto* band_table = vtkTable::SafeDownCast(bands->GetOutputDataObject(1));
    auto* block_table = vtkTable::SafeDownCast(blocks->GetOutputDataObject(1));
    expect_table(band_table, read_table(analysis(numbered("bands", k))));
    expect_table(block_table, read_table(analysis(numbered("blocks", k))));
    band_rows += static_cast<int>(band_table->GetNumberOfRows());
    block_rows += static_cast<int>(block_table->GetNumberOfRows());
  }
  EXPECT_EQ(errors->errors, 0) << errors->last;
  // Not a comparison of empty tables.
  EXPECT_GT(band_rows, 3);
  EXPECT_GT(block_rows, 3);
}

TEST_F(AnalyseAgainstFilters, MorphologyHistoryIsTheMorphologyTable) {
  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(pvd().c_str());
  vtkNew<vtkRunoutMorphologyHistory> history;
  vtkNew<ErrorCounter> errors;
  history->AddObserver(vtkCommand::ErrorEvent, errors);
  history->SetInputConnection(reader->GetOutputPort());
  history->Update();
  EXPECT_EQ(errors->errors, 0) << errors->last;
  const Table csv = read_table(analysis("morphology.csv"));
  ASSERT_EQ(csv.header.front(), "frame");
  expect_table(history->GetOutput(), csv, 1);
}

TEST_F(AnalyseAgainstFilters, ProfileOfEveryFrame) {
  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(pvd().c_str());
  vtkNew<vtkRunoutMorphology> morphology;
  morphology->SetInputConnection(reader->GetOutputPort());
  const std::vector<double> t = times();
  for (std::size_t k = 0; k < t.size(); ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    morphology->UpdateTimeStep(t[k]);
    vtkPolyData* profile = morphology->GetOutput();
    const Table csv = read_table(analysis(numbered("profile", k)));
    ASSERT_EQ(static_cast<std::size_t>(profile->GetNumberOfPoints()), csv.rows.size());
    ASSERT_GT(csv.rows.size(), 10u);
    for (vtkIdType i = 0; i < profile->GetNumberOfPoints(); ++i) {
      double xyz[3];
      profile->GetPoint(i, xyz);
      const std::string row = " row " + std::to_string(i);
      expect_same(csv.number(i, "x_surface"), xyz[0], "x_surface" + row);
      expect_same(csv.number(i, "y_surface"), xyz[1], "y_surface" + row);
      for (const char* name : {"s", "thickness", "velocity_s", "particles"})
        expect_same(csv.number(i, name), profile->GetPointData()->GetArray(name)->GetTuple1(i),
                    name + row);
    }
    // The one-row table is the history's row of the frame, but for the
    // class from the travel, which one frame alone cannot see (NaN late
    // stretch, the frame-only rule: docs/filters.md, "Mechanism class").
    const Table rows = read_table(analysis("morphology.csv"));
    vtkTable* table = morphology->GetTableOutput();
    for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c) {
      vtkAbstractArray* column = table->GetColumn(c);
      const std::string name = column->GetName();
      if (name == "late_stretch")
        EXPECT_TRUE(std::isnan(column->GetVariantValue(0).ToDouble()));
      else if (name == "mechanism" || name == "mechanism_id")
        continue;
      else if (auto* text = vtkStringArray::SafeDownCast(column))
        EXPECT_EQ(rows.cell(k, column->GetName()), text->GetValue(0));
      else
        expect_same(rows.number(k, column->GetName()), column->GetVariantValue(0).ToDouble(),
                    column->GetName());
    }
  }
}

// The CLI analyses with the filters' defaults: the same structs behind
// both, and the profile bins' default and range.
TEST(AnalyseDefaults, AreTheFilters) {
  const runout::analysis::BandParameters band;
  vtkNew<vtkRunoutShearBands> bands;
  EXPECT_EQ(bands->GetThresholdMode(), static_cast<int>(band.threshold.mode));
  EXPECT_EQ(bands->GetThreshold(), band.threshold.absolute);
  EXPECT_EQ(bands->GetRelativeThreshold(), band.threshold.relative);
  EXPECT_EQ(bands->GetReferenceStrain(), band.threshold.reference);
  EXPECT_EQ(bands->GetPercentile(), band.threshold.percentile);
  EXPECT_EQ(bands->GetParticleSpacing(), 0.0);  // the frame's particle_spacing, as the CLI
  EXPECT_EQ(bands->GetLinkingFactor(), band.linking_factor);
  EXPECT_EQ(bands->GetOrientationRadius(), band.orientation_radius);
  EXPECT_EQ(bands->GetMaximumAngle(), band.max_angle);
  EXPECT_EQ(bands->GetMinimumParticles(), band.min_particles);
  const runout::analysis::BlockParameters block;
  vtkNew<vtkRunoutHorstGraben> blocks;
  EXPECT_EQ(blocks->GetDipTolerance(), block.dip_tolerance);
  EXPECT_EQ(blocks->GetSurfaceGap(), block.surface_gap);
  vtkNew<vtkRunoutMorphology> morphology;
  EXPECT_EQ(morphology->GetBinSpacings(), runout::analysis::kProfileBinSpacings);
  EXPECT_EQ(morphology->GetBinSpacingsMinValue(), runout::analysis::kMinProfileBinSpacings);
  EXPECT_EQ(morphology->GetBinSpacingsMaxValue(), runout::analysis::kMaxProfileBinSpacings);
}
