#include "vtkRunoutMorphologyHistory.h"

#include "FrameArrays.h"
#include "MorphologyFrame.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTable.h"

#include <utility>
#include <vector>

vtkStandardNewMacro(vtkRunoutMorphologyHistory);

namespace
{
// The lengths of output port 1, under the names the chart shows, with their
// unit: a line chart plots every numeric column of the table it is given,
// and the full table's counts (particles: thousands) and ratios would
// flatten the lengths.
const std::pair<const char*, const char*> LengthColumns[] = { { "Time", "Time" },
  { "toe", "toe (m)" }, { "rear", "rear (m)" }, { "runout", "runout (m)" },
  { "length", "length (m)" }, { "max_thickness", "max_thickness (m)" } };

void AddLengthColumns(vtkTable* history, vtkTable* lengths)
{
  for (const auto& [name, label] : LengthColumns)
  {
    vtkNew<vtkDoubleArray> column;
    column->DeepCopy(history->GetColumnByName(name));
    column->SetName(label);
    lengths->AddColumn(column);
  }
}
}

//------------------------------------------------------------------------------
vtkRunoutMorphologyHistory::vtkRunoutMorphologyHistory()
{
  this->SetNumberOfOutputPorts(2);
  runout::filters::select_morphology_arrays(this);
}

//------------------------------------------------------------------------------
int vtkRunoutMorphologyHistory::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutMorphologyHistory::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  this->NumberOfTimeSteps = inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS())
    ? inInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS())
    : 0;
  // The tables span every time step: they have no time of their own, so
  // that a change of the view's time does not run the whole series again.
  for (int port = 0; port < this->GetNumberOfOutputPorts(); ++port)
  {
    vtkInformation* outInfo = outputVector->GetInformationObject(port);
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutMorphologyHistory::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (this->NumberOfTimeSteps > 0)
  {
    const double* steps = inInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    inInfo->Set(
      vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), steps[this->CurrentTimeIndex]);
  }
  return 1;
}

namespace
{
// The runout and length of the rows gathered so far, then the frame's own:
// the travel the mechanism class reads (morphology_rules.hpp).
std::vector<runout::analysis::TravelSample> TravelWith(
  vtkTable* history, const runout::analysis::FrameMorphology& frame)
{
  std::vector<runout::analysis::TravelSample> travel;
  vtkDataArray* runout = vtkDataArray::SafeDownCast(history->GetColumnByName("runout"));
  vtkDataArray* length = vtkDataArray::SafeDownCast(history->GetColumnByName("length"));
  for (vtkIdType row = 0; runout && length && row < history->GetNumberOfRows(); ++row)
  {
    travel.push_back({ runout->GetComponent(row, 0), length->GetComponent(row, 0) });
  }
  travel.push_back({ frame.runout, frame.now.length });
  return travel;
}
}

//------------------------------------------------------------------------------
int vtkRunoutMorphologyHistory::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);

  if (this->CurrentTimeIndex == 0)
  {
    this->History->Initialize();
    runout::filters::add_morphology_columns(this->History);
    if (this->NumberOfTimeSteps > 1)
    {
      request->Set(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING(), 1);
    }
  }

  // The history has no profile to show: any bin width does.
  runout::analysis::FrameMorphology morphology;
  // The engine never writes a frame without particles: in a series, one is
  // a frame that could not be read (a file the index lists is missing or
  // unreadable). It is skipped, so one lost frame costs one row.
  if (input->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro(<< "Time step " << this->CurrentTimeIndex
                    << ": the frame has no points (a file the index lists missing or "
                       "unreadable?); skipped.");
    return this->NextTimeStep(request, outputVector);
  }
  const std::string error = runout::filters::measure_point_set(input,
    runout::kMainBodyBinSpacings, morphology, runout::filters::selected_morphology_arrays(this));
  if (!error.empty())
  {
    vtkErrorMacro(<< "Time step " << this->CurrentTimeIndex << ": " << error);
    request->Remove(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING());
    this->CurrentTimeIndex = 0;
    this->History->Initialize();
    return 1;
  }
  runout::analysis::classify_by_travel(morphology, TravelWith(this->History, morphology));
  runout::filters::append_morphology_row(
    this->History, runout::filters::frame_time_of(input), morphology);
  return this->NextTimeStep(request, outputVector);
}

//------------------------------------------------------------------------------
int vtkRunoutMorphologyHistory::NextTimeStep(
  vtkInformation* request, vtkInformationVector* outputVector)
{
  if (++this->CurrentTimeIndex < this->NumberOfTimeSteps)
  {
    return 1;
  }
  request->Remove(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING());
  this->CurrentTimeIndex = 0;
  vtkTable::GetData(outputVector)->ShallowCopy(this->History);
  // Built apart and copied in whole, as the History: the output the pipeline
  // hands over carries the field data of an input frame (its TimeValue
  // among it), which a table of every frame must not.
  vtkNew<vtkTable> lengths;
  AddLengthColumns(this->History, lengths);
  vtkTable::GetData(outputVector, 1)->ShallowCopy(lengths);
  return 1;
}

//------------------------------------------------------------------------------
void vtkRunoutMorphologyHistory::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfTimeSteps: " << this->NumberOfTimeSteps << "\n";
}
