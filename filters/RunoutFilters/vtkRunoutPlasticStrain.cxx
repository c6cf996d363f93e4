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
#include "StrainAlgorithms.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

using namespace runout::filters;

vtkStandardNewMacro(vtkRunoutPlasticStrain);

namespace
{
// Used when neither GridSpacing nor the frame's particle_spacing is known.
constexpr double FallbackGridSpacing = 0.5;
// A grid spacing far too small for the slide would exhaust the memory
// (four arrays per node): refused beyond this many nodes.
constexpr double MaximumGridNodes = 1e8;

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

// The image of the particles' fields projected on the grid of `spacing`
// over them, with `coverage`; the first field is the active scalars.
void FillGrid(vtkImageData* image, const std::vector<Vec2>& points,
  const std::vector<NamedField>& fields, double spacing, double radius)
{
  std::vector<const std::vector<double>*> values;
  for (const NamedField& field : fields)
  {
    values.push_back(field.Values);
  }
  const GridSpec grid = grid_covering(points, spacing);
  const GridProjection projection = project_to_grid(points, values, grid, radius);

  image->SetOrigin(grid.origin.x, grid.origin.y, 0.0);
  image->SetSpacing(spacing, spacing, spacing);
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
  image->GetPointData()->SetActiveScalars(fields.front().Name);
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
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  auto& steps = this->Internals->TimeSteps;
  steps.clear();
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
  {
    const double* values = inInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    steps.assign(values, values + inInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutPlasticStrain::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto& internals = *this->Internals;
  internals.FetchingPrevious = false;

  // The cached strains are stale once another strain array is selected, or,
  // for a time series, once anything upstream changes (another file, an
  // array computed upstream). Not for frames given one at a time without
  // time steps: each of them is an upstream change.
  auto* upstream = vtkDemandDrivenPipeline::SafeDownCast(this->GetInputExecutive(0, 0));
  const vtkMTimeType upstreamTime =
    upstream && !internals.TimeSteps.empty() ? upstream->GetPipelineMTime() : 0;
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
  const double previous =
    internals.PreviousTime(outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()));
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
  const double spacing = this->GridSpacing > 0
    ? this->GridSpacing
    : (particleSpacing > 0 ? 2 * particleSpacing : FallbackGridSpacing);
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
  const double nodes = input->GetNumberOfPoints() == 0
    ? 0.0
    : ((bounds[1] - bounds[0]) / spacing + 2) * ((bounds[3] - bounds[2]) / spacing + 2);
  if (!(nodes <= MaximumGridNodes) || !std::isfinite(spacing))
  {
    vtkErrorMacro("GridSpacing " << spacing << " gives a grid of " << nodes
                                 << " nodes over the particles: too many. No grid output.");
    return 1;
  }
  // The radius reaches at least two particle spacings, so that a fine grid
  // has no uncovered node inside the slide.
  vtkImageData* image = vtkImageData::GetData(outputVector, 1);
  FillGrid(image, positions_of(input),
    { { xiArray->GetName(), &xi }, { "plastic_strain_increment", &increment },
      { "normalised_plastic_strain", &normalised } },
    spacing, 2 * std::max(spacing, particleSpacing));
  // The grid's extent follows the particles, so it is known only now, not
  // in RequestInformation: without it as the whole extent, ParaView's image
  // representations (which slice and extract within the whole extent) show
  // nothing.
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
