// The engine's frames and index read back by ParaView's own VTK: every array
// present with its component count and every value as written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <vtkCell.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPVDReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "runout/output/vtu_writer.hpp"

namespace fs = std::filesystem;
using namespace runout;

namespace {

// Values with full 53-bit mantissas, both signs, and magnitudes from 1e-3
// to 1e5, so that any truncation or reordering shows.
Particles random_particles(int n) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto value = [&](double scale) { return scale * u(rng); };
  Particles p;
  p.resize(n);
  for (int i = 0; i < n; ++i) {
    p.x[i] = value(100); p.y[i] = value(10); p.x0[i] = value(100); p.y0[i] = value(10);
    p.vx[i] = value(5); p.vy[i] = value(5);
    p.sxx[i] = value(1e5); p.syy[i] = value(1e5); p.szz[i] = value(1e5); p.sxy[i] = value(1e4);
    p.mass[i] = 1 + std::abs(value(10)); p.vol[i] = std::abs(value(1e-2)); p.vol0[i] = std::abs(value(1e-2));
    p.xi[i] = std::abs(value(2)); p.gamma_dot[i] = std::abs(value(1e-3)); p.su[i] = std::abs(value(1.5e4));
    p.band_xi[i] = std::abs(value(40));
    p.body[i] = i % 4 - 1; p.material[i] = i % 3; p.id[i] = (std::int64_t{1} << 40) + 7 * i;
  }
  return p;
}

// What a point array must hold for particle i.
struct Expected {
  const char* name;
  int components;
  std::function<std::vector<double>(const Particles&, int)> tuple;
  bool exact;  // stored values: bit for bit; derived invariants: to rounding
};

std::vector<Expected> expected_arrays() {
  using V = std::vector<double>;
  return {
      {"velocity", 3, [](const Particles& p, int i) { return V{p.vx[i], p.vy[i], 0}; }, true},
      {"displacement", 3, [](const Particles& p, int i) { return V{p.x[i] - p.x0[i], p.y[i] - p.y0[i], 0}; }, true},
      {"stress", 6, [](const Particles& p, int i) { return V{p.sxx[i], p.syy[i], p.szz[i], p.sxy[i], 0, 0}; }, true},
      {"mean_stress", 1, [](const Particles& p, int i) { return V{(p.sxx[i] + p.syy[i] + p.szz[i]) / 3}; }, false},
      // Independent form of sqrt(3 J2) for the plane-strain tensor.
      {"von_mises_stress", 1, [](const Particles& p, int i) {
         const double a = p.sxx[i] - p.syy[i], b = p.syy[i] - p.szz[i], c = p.szz[i] - p.sxx[i];
         return V{std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * p.sxy[i] * p.sxy[i])};
       }, false},
      {"max_shear_stress", 1, [](const Particles& p, int i) {
         return V{std::sqrt(0.25 * (p.sxx[i] - p.syy[i]) * (p.sxx[i] - p.syy[i]) + p.sxy[i] * p.sxy[i])};
       }, false},
      {"plastic_shear_strain", 1, [](const Particles& p, int i) { return V{p.xi[i]}; }, true},
      {"shear_strain_rate", 1, [](const Particles& p, int i) { return V{p.gamma_dot[i]}; }, true},
      {"strength", 1, [](const Particles& p, int i) { return V{p.su[i]}; }, true},
      {"mass", 1, [](const Particles& p, int i) { return V{p.mass[i]}; }, true},
      {"volume", 1, [](const Particles& p, int i) { return V{p.vol[i]}; }, true},
      {"initial_volume", 1, [](const Particles& p, int i) { return V{p.vol0[i]}; }, true},
      {"initial_position", 3, [](const Particles& p, int i) { return V{p.x0[i], p.y0[i], 0}; }, true},
      {"body_id", 1, [](const Particles& p, int i) { return V{double(p.body[i])}; }, true},
      {"material_id", 1, [](const Particles& p, int i) { return V{double(p.material[i])}; }, true},
      {"particle_id", 1, [](const Particles& p, int i) { return V{double(p.id[i])}; }, true},
  };
}

// optional_arrays: how many arrays the frame carries beyond the particle
// fields (rate_factor, when the frame is given the strength laws, and
// band_shear_strain, under the clay's basal band).
void expect_frame(vtkUnstructuredGrid* grid, const Particles& p, double time,
                  int optional_arrays = 0) {
  const int n = p.size();
  ASSERT_NE(grid, nullptr);
  ASSERT_EQ(grid->GetNumberOfPoints(), n);
  ASSERT_EQ(grid->GetNumberOfCells(), n);
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(grid->GetCellType(i), VTK_VERTEX);
    ASSERT_EQ(grid->GetCell(i)->GetPointId(0), i);
    double xyz[3];
    grid->GetPoint(i, xyz);
    ASSERT_EQ(xyz[0], p.x[i]);
    ASSERT_EQ(xyz[1], p.y[i]);
    ASSERT_EQ(xyz[2], 0.0);
  }

  vtkDataArray* time_value = grid->GetFieldData()->GetArray("TimeValue");
  ASSERT_NE(time_value, nullptr);
  ASSERT_EQ(time_value->GetNumberOfTuples(), 1);
  EXPECT_EQ(time_value->GetComponent(0, 0), time);

  const auto expected = expected_arrays();
  EXPECT_EQ(grid->GetPointData()->GetNumberOfArrays(),
            static_cast<int>(expected.size()) + optional_arrays);
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.name);
    vtkDataArray* a = grid->GetPointData()->GetArray(e.name);
    ASSERT_NE(a, nullptr);
    ASSERT_EQ(a->GetNumberOfComponents(), e.components);
    ASSERT_EQ(a->GetNumberOfTuples(), n);
    for (int i = 0; i < n; ++i) {
      const auto want = e.tuple(p, i);
      for (int c = 0; c < e.components; ++c) {
        if (e.exact) {
          ASSERT_EQ(a->GetComponent(i, c), want[c]) << "particle " << i << " component " << c;
        } else {
          ASSERT_NEAR(a->GetComponent(i, c), want[c], 1e-12 * (1 + std::abs(want[c])))
              << "particle " << i;
        }
      }
    }
  }
  // The element types the engine declares, as VTK reads them.
  EXPECT_EQ(std::string(grid->GetPointData()->GetArray("particle_id")->GetClassName()), "vtkTypeInt64Array");
  EXPECT_EQ(std::string(grid->GetPointData()->GetArray("body_id")->GetClassName()), "vtkTypeInt32Array");
  EXPECT_EQ(std::string(grid->GetPointData()->GetArray("mass")->GetClassName()), "vtkTypeFloat64Array");
}

class Readback : public ::testing::TestWithParam<std::tuple<int, bool>> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("runout_test_vtu_readback_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST_P(Readback, FrameReadsBackExactly) {
  const auto [n, compress] = GetParam();
  const Particles p = random_particles(n);
  const fs::path file = dir_ / "frame_00000.vtu";
  // Three materials (material ids are i % 3): no rate effect, and two rate laws.
  StrengthParams fast, slow;
  fast.eta = 1.0;
  fast.rate_exponent = 0.1;
  fast.reference_rate = 0.01;
  slow.eta = 0.0167;
  slow.rate_exponent = 0.5;
  const FrameInfo info{12.375, 0.125, {-5.0, 3.0, 0.0, 0.0, 40.0, -0.7},
                       {StrengthParams{}, fast, slow}, true};
  write_particles_vtu(file, p, info, compress);

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), 0);
  expect_frame(reader->GetOutput(), p, 12.375, 2);

  vtkDataArray* band = reader->GetOutput()->GetPointData()->GetArray("band_shear_strain");
  ASSERT_NE(band, nullptr);
  for (int i = 0; i < p.size(); ++i) EXPECT_EQ(band->GetTuple1(i), p.band_xi[i]);
  vtkDataArray* rate = reader->GetOutput()->GetPointData()->GetArray("rate_factor");
  ASSERT_NE(rate, nullptr);
  for (int i = 0; i < p.size(); ++i)
    EXPECT_EQ(rate->GetTuple1(i), rate_factor(info.strengths[p.material[i]], p.gamma_dot[i]));

  vtkFieldData* field = reader->GetOutput()->GetFieldData();
  vtkDataArray* spacing = field->GetArray("particle_spacing");
  ASSERT_NE(spacing, nullptr);
  EXPECT_EQ(spacing->GetTuple1(0), 0.125);
  vtkDataArray* base = field->GetArray("base_points");
  ASSERT_NE(base, nullptr);
  ASSERT_EQ(base->GetNumberOfTuples(), 3);
  ASSERT_EQ(base->GetNumberOfComponents(), 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(base->GetComponent(k, 0), info.base_xy[2 * k]);
    EXPECT_EQ(base->GetComponent(k, 1), info.base_xy[2 * k + 1]);
  }
}

// 300: one zlib block per array; 1500: several, the last partial; 4096:
// mass and the scalars fill exactly one block (last-block size 0); 0: empty.
INSTANTIATE_TEST_SUITE_P(SizesAndCompression, Readback,
                         ::testing::Combine(::testing::Values(300, 1500, 4096, 0),
                                            ::testing::Bool()));

TEST(ReadbackSeries, PvdReaderSeesEveryFrameAtItsTime) {
  const fs::path dir = fs::temp_directory_path() / ("runout_test_pvd_readback_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<double> times = {0.0, 0.1, 1.0 / 3.0};
  std::vector<Particles> frames;
  PvdIndex index((dir / "series.pvd").string());
  for (std::size_t k = 0; k < times.size(); ++k) {
    frames.push_back(random_particles(200 + 10 * static_cast<int>(k)));
    const std::string name = "frame_0000" + std::to_string(k) + ".vtu";
    write_particles_vtu(dir / name, frames.back(), FrameInfo{times[k], 0.0, {}, {}}, k % 2 == 0);
    index.add(times[k], name);
  }

  // vtkPVDReader is what ParaView opens a .pvd with.
  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(index.path().c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  const int steps = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  ASSERT_EQ(steps, static_cast<int>(times.size()));
  for (int k = 0; k < steps; ++k) {
    EXPECT_EQ(info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[k], times[k]);
    reader->UpdateTimeStep(times[k]);
    SCOPED_TRACE(k);
    expect_frame(vtkUnstructuredGrid::SafeDownCast(reader->GetOutputDataObject(0)), frames[k], times[k]);
  }
  fs::remove_all(dir);
}
