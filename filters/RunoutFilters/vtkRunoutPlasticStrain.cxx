#include "vtkRunoutPlasticStrain.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "FrameArrays.h"
#include "runout/analysis/plastic_strain.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

using namespace runout::analysis;
using namespace runout::filters;

vtkStandardNewMacro(vtkRunoutPlasticStrain);

namespace
{
// Used when neither GridSpacing nor the frame's particle_spacing is known.
constexpr double FallbackGridSpacing = 0.5;
// A grid spacing far too small for the slide, or particles scattered far
// apart, would exhaust the memory: about 60 bytes a node (four projected
// arrays, their VTK copies and the coverage), so 1e7 nodes (a 5 km slide
// on a 0.5 m grid 1 km high) take 0.6 GB. Refused beyond.
constexpr double MaximumGridNodes = 1e7;

// Why the frame's points, strains or ids cannot be used, or "". Ids are
// cast to 64-bit integers, so they must lie within their range.
std::string FrameProblem(vtkPointSet* frame, vtkDataArray* xi, vtkDataArray* ids)
{
  std::string problem = points_problem(frame);
  if (problem.empty())
  {
    problem = point_array_problem(frame, xi, xi->GetName() ? xi->GetName() : "", 1);
  }
  if (problem.empty())
  {
    problem = point_array_problem(frame, ids, "particle_id", 1, 9.2e18);
  }
  return problem;
}

struct NamedField
{
  const char* Name;
  const std::vector<double>* Values;
};

// The image of the particles' fields projected on `grid`, with
// `coverage`. No active scalars: ParaView colours a new display by them,
// with the range of the frame shown at Apply, and at t = 0 (where it opens
// a series) xi is 0 everywhere: the grid's outline got a colour map from 0
// to 1e-38 and its scalar bar, both kept as the time changed.
void FillGrid(vtkImageData* image, const std::vector<Vec2>& points,
  const std::vector<NamedField>& fields, const GridSpec& grid, double radius)
{
  std::vector<const std::vector<double>*> values;
  for (const NamedField& field : fields)
  {
    values.push_back(field.Values);
  }
  const GridProjection projection = project_to_grid(points, values, grid, radius);

  image->SetOrigin(grid.origin.x, grid.origin.y, 0.0);
  image->SetSpacing(grid.spacing, grid.spacing, grid.spacing);
  image->SetDimensions(grid.nx, grid.ny, grid.nx > 0 ? 1 : 0);
  for (size_t f = 0; f < fields.size(); ++f)
  {
    image->GetPointData()->AddArray(make_double_array(fields[f].Name, projection.fields[f]));
  }
  vtkNew<vtkUnsignedCharArray> coverage;
  coverage->SetName("coverage");
  coverage->SetNumberOfTuples(static_cast<vtkIdType>(projection.coverage.size()));
  std::copy(projection.coverage.begin(), projection.coverage.end(), coverage->GetPointer(0));
  image->GetPointData()->AddArray(coverage);
}
}

// xi by particle id of the frames seen last, keyed on their time, and the
// input's time steps.
struct vtkRunoutPlasticStrain::vtkInternals
{
  std::vector<double> TimeSteps;
  std::map<double, StrainById> Cache;
  std::string CachedArray;          // the strain array the cache holds
  vtkMTimeType CachedUpstream = 0;  // the upstream pipeline the cache came from
  bool FetchingPrevious = false;    // this execution delivers the previous step only
  double PreviousStep = 0.0;

  // The survey of a time series: the union of its frames' bounding boxes,
  // read once (every step in turn, CONTINUE_EXECUTING), so that the Strain
  // Grid has one extent for every frame, declared in RequestInformation. A
  // grid that followed each frame's particles would change its extent with
  // the time, which ParaView's image representations cannot follow (they
  // keep the extent of the first frame, and report every other as outside
  // it).
  bool Surveying = false;
  size_t SurveyIndex = 0;
  bool Surveyed = false;
  vtkMTimeType SurveyedUpstream = 0;
  bool HasBox = false;
  Vec2 Low, High;
  double SurveySpacing = 0.0;  // particle_spacing of the series
  double RequestedTime = 0.0;  // the step the survey was started for

  // The grid spacing: the property, else twice the particle spacing.
  static double Spacing(double gridSpacing, double particleSpacing)
  {
    return gridSpacing > 0 ? gridSpacing
                           : (particleSpacing > 0 ? 2 * particleSpacing : FallbackGridSpacing);
  }

  // Whether the series coming from the upstream pipeline `upstream` has
  // been surveyed.
  bool SurveyDone(vtkMTimeType upstream) const
  {
    return this->Surveyed && this->SurveyedUpstream == upstream;
  }

  // Whether it has a grid: surveyed, with points in some frame.
  bool HasSeriesGrid(vtkMTimeType upstream) const
  {
    return !this->TimeSteps.empty() && this->SurveyDone(upstream) && this->HasBox;
  }

  // The grid over every frame of the series.
  GridSpec SeriesGrid(double gridSpacing) const
  {
    return grid_covering({ this->Low, this->High }, Spacing(gridSpacing, this->SurveySpacing));
  }

  // Adds one surveyed frame: its box, its spacing, and its strains when
  // they are the ones the requested step needs next.
  void Survey(vtkPointSet* frame, vtkDataArray* xi, vtkDataArray* ids, bool valid)
  {
    if (points_problem(frame).empty() && frame->GetNumberOfPoints() > 0)
    {
      double bounds[6];
      frame->GetBounds(bounds);
      const Vec2 low{ bounds[0], bounds[2] }, high{ bounds[1], bounds[3] };
      this->Low = this->HasBox ? Vec2{ std::min(this->Low.x, low.x), std::min(this->Low.y, low.y) }
                               : low;
      this->High = this->HasBox
        ? Vec2{ std::max(this->High.x, high.x), std::max(this->High.y, high.y) }
        : high;
      this->HasBox = true;
    }
    if (!(this->SurveySpacing > 0))
    {
      this->SurveySpacing = particle_spacing_of(frame);
    }
    const double time = this->TimeSteps[this->SurveyIndex];
    const double previous = this->PreviousTime(this->RequestedTime);
    if (time == previous)
    {
      this->Cache[time] = valid ? strain_by_id(ids_of(ids), component_of(xi)) : StrainById();
    }
    if (++this->SurveyIndex == this->TimeSteps.size())
    {
      this->Surveying = false;
      this->Surveyed = true;
    }
  }

  // The time step before `time` (as delivered by a reader: the largest step
  // <= time), or with no time steps the largest cached time before it; NaN
  // when none.
  double PreviousTime(double time) const
  {
    const double none = std::nan("");
    if (std::isnan(time))
    {
      return none;
    }
    if (!this->TimeSteps.empty())
    {
      auto at = std::upper_bound(this->TimeSteps.begin(), this->TimeSteps.end(), time);
      return at - this->TimeSteps.begin() >= 2 ? *(at - 2) : none;
    }
    auto after = this->Cache.lower_bound(time);
    return after == this->Cache.begin() ? none : std::prev(after)->first;
  }

  // The cached strains of the frame before `time`, or nullptr.
  const StrainById* Previous(double time) const
  {
    // (NaN compares equivalent to every key of a map: never look it up.)
    const double previous = this->PreviousTime(time);
    const auto at = std::isnan(previous) ? this->Cache.end() : this->Cache.find(previous);
    return at == this->Cache.end() ? nullptr : &at->second;
  }

  // Caches the strains of the frame at `time`, keeping only what the next
  // frame forward needs (this one) and what this one needed, so that
  // stepping back and forth costs no extra update.
  void Keep(double time, StrainById strains)
  {
    if (std::isnan(time))
    {
      return;
    }
    const double previous = this->PreviousTime(time);
    this->Cache[time] = std::move(strains);
    for (auto entry = this->Cache.begin(); entry != this->Cache.end();)
    {
      const bool keep = entry->first == time || entry->first == previous;
      entry = keep ? std::next(entry) : this->Cache.erase(entry);
    }
  }
};

//------------------------------------------------------------------------------
vtkRunoutPlasticStrain::vtkRunoutPlasticStrain()
  : Internals(new vtkInternals)
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "plastic_shear_strain");
}

//------------------------------------------------------------------------------
vtkRunoutPlasticStrain::~vtkRunoutPlasticStrain() = default;

//------------------------------------------------------------------------------
vtkImageData* vtkRunoutPlasticStrain::GetGridOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkRunoutPlasticStrain::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutPlasticStrain::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkImageData");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkRunoutPlasticStrain::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Port 0 has the input's type; port 1 is the image of
  // FillOutputPortInformation, which the superclass would replace.
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0]);
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkDataObject* output = vtkDataObject::GetData(info);
  if (input && (!output || !output->IsA(input->GetClassName())))
  {
    vtkDataObject* fresh = input->NewInstance();
    info->Set(vtkDataObject::DATA_OBJECT(), fresh);
    fresh->FastDelete();
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutPlasticStrain::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  auto& internals = *this->Internals;
  internals.TimeSteps.clear();
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
  {
    const double* values = inInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    internals.TimeSteps.assign(
      values, values + inInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  }
  // The series' grid once it has been surveyed. Before (the first update of
  // a series) and for frames without time steps, only RequestData knows it.
  vtkInformation* gridInfo = outputVector->GetInformationObject(1);
  if (internals.HasSeriesGrid(this->UpstreamTime()))
  {
    const GridSpec grid = internals.SeriesGrid(this->GridSpacing);
    const int extent[6] = { 0, grid.nx - 1, 0, grid.ny - 1, 0, 0 };
    gridInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  }
  else
  {
    gridInfo->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  }
  return 1;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkRunoutPlasticStrain::UpstreamTime()
{
  // Not for frames given one at a time without time steps: each of them is
  // an upstream change.
  auto* upstream = vtkDemandDrivenPipeline::SafeDownCast(this->GetInputExecutive(0, 0));
  return upstream && !this->Internals->TimeSteps.empty() ? upstream->GetPipelineMTime() : 0;
}

//------------------------------------------------------------------------------
int vtkRunoutPlasticStrain::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto& internals = *this->Internals;
  internals.FetchingPrevious = false;

  // The cached strains are stale once another strain array is selected, or,
  // for a time series, once anything upstream changes (another file, an
  // array computed upstream).
  const vtkMTimeType upstreamTime = this->UpstreamTime();
  const std::string array = selected_array_name(this, 0);
  if (array != internals.CachedArray || upstreamTime != internals.CachedUpstream)
  {
    internals.Cache.clear();
    internals.CachedArray = array;
    internals.CachedUpstream = upstreamTime;
  }

  const int port = std::max(0, request->Get(vtkExecutive::FROM_OUTPUT_PORT()));
  vtkInformation* outInfo = outputVector->GetInformationObject(port);
  if (internals.TimeSteps.empty() ||
    !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    return 1;
  }
  const double requested = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (!internals.SurveyDone(upstreamTime))
  {
    if (!internals.Surveying)
    {
      internals.Surveying = true;
      internals.SurveyIndex = 0;
      internals.Surveyed = internals.HasBox = false;
      internals.SurveyedUpstream = upstreamTime;
      internals.SurveySpacing = 0.0;
      internals.RequestedTime = requested;
    }
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(),
      internals.TimeSteps[internals.SurveyIndex]);
    return 1;
  }
  const double previous = internals.PreviousTime(requested);
  if (!std::isnan(previous) && internals.Cache.count(previous) == 0)
  {
    internals.FetchingPrevious = true;
    internals.PreviousStep = previous;
    inputVector[0]->GetInformationObject(0)->Set(
      vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), previous);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutPlasticStrain::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  auto& internals = *this->Internals;

  vtkDataArray* xiArray = this->GetInputArrayToProcess(0, inputVector);
  vtkDataArray* idArray = input->GetPointData()->GetArray("particle_id");
  const std::string problem = xiArray && idArray ? FrameProblem(input, xiArray, idArray) : "";
  const bool valid = xiArray && idArray && problem.empty();
  if (internals.Surveying)
  {
    internals.Survey(input, xiArray, idArray, valid);
    request->Set(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING(), 1);
    return 1;
  }
  if (internals.FetchingPrevious)
  {
    // Cached even when invalid (as no strains), so that the next pass does
    // not ask for this step again.
    internals.Cache[internals.PreviousStep] =
      valid ? strain_by_id(ids_of(idArray), component_of(xiArray)) : StrainById();
    internals.FetchingPrevious = false;
    request->Set(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING(), 1);
    return 1;
  }
  request->Remove(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING());

  if (!xiArray)
  {
    vtkErrorMacro("The input has no point array \"" << selected_array_name(this, 0)
                                                    << "\" (the plastic shear strain).");
    return 1;
  }
  if (!idArray)
  {
    vtkErrorMacro("The input has no point array \"particle_id\": not a Runout particle frame.");
    return 1;
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 1;
  }
  if (input->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro("The input has no points: no strains and an empty grid.");
  }

  const double particleSpacing = particle_spacing_of(input);
  const bool series = internals.HasSeriesGrid(this->UpstreamTime());
  const double spacing = vtkInternals::Spacing(
    this->GridSpacing, series ? internals.SurveySpacing : particleSpacing);
  const std::string far = extent_problem(positions_of(input), spacing);
  if (!far.empty())
  {
    vtkErrorMacro(<< far);
    return 1;
  }

  const std::vector<double> xi = component_of(xiArray);
  const std::vector<std::int64_t> ids = ids_of(idArray);
  const double time = frame_time_of(input);
  const std::vector<double> increment = strain_increment(ids, xi, internals.Previous(time));
  const std::vector<double> normalised = normalised_strain(xi, this->Xi95);
  internals.Keep(time, strain_by_id(ids, xi));

  vtkPointSet* output = vtkPointSet::GetData(outputVector, 0);
  output->ShallowCopy(input);
  output->GetPointData()->AddArray(make_double_array("plastic_strain_increment", increment));
  output->GetPointData()->AddArray(make_double_array("normalised_plastic_strain", normalised));

  double bounds[6];
  input->GetBounds(bounds);
  const Vec2 low = series ? internals.Low : Vec2{ bounds[0], bounds[2] };
  const Vec2 high = series ? internals.High : Vec2{ bounds[1], bounds[3] };
  const double nodes = input->GetNumberOfPoints() == 0 && !series
    ? 0.0
    : ((high.x - low.x) / spacing + 2) * ((high.y - low.y) / spacing + 2);
  if (!(nodes <= MaximumGridNodes) || !std::isfinite(spacing))
  {
    vtkErrorMacro("GridSpacing " << spacing << " gives a grid of " << nodes
                                 << " nodes over the particles: too many. No grid output.");
    return 1;
  }
  // The radius reaches at least two particle spacings, so that a fine grid
  // has no uncovered node inside the slide.
  const GridSpec grid = input->GetNumberOfPoints() == 0 && !series
    ? GridSpec{ { 0, 0 }, spacing, 0, 0 }
    : grid_covering({ low, high }, spacing);
  vtkImageData* image = vtkImageData::GetData(outputVector, 1);
  FillGrid(image, positions_of(input),
    { { xiArray->GetName(), &xi }, { "plastic_strain_increment", &increment },
      { "normalised_plastic_strain", &normalised } },
    grid, 2 * std::max(grid.spacing, particleSpacing));
  // RequestInformation has declared this extent already, except on the
  // first update of a series (before its survey) and for frames without
  // time steps, whose grid only their own particles give; without it as
  // the whole extent, ParaView's image representations show nothing.
  outputVector->GetInformationObject(1)->Set(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), image->GetExtent(), 6);
  return 1;
}

//------------------------------------------------------------------------------
void vtkRunoutPlasticStrain::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Xi95: " << this->Xi95 << "\n";
  os << indent << "GridSpacing: " << this->GridSpacing << "\n";
}
