#include "vtkRunoutRunoutDistance.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkTable.h"

vtkStandardNewMacro(vtkRunoutRunoutDistance);

namespace
{
struct RunoutMeasures
{
  double ToeX;
  double RearX;
  double Length;
  double Runout;
};

// Extent along x of the current and initial positions (n > 0 points).
RunoutMeasures MeasureRunout(vtkDataArray* positions, vtkDataArray* initialPositions)
{
  double now[2];
  double before[2];
  positions->GetRange(now, 0);
  initialPositions->GetRange(before, 0);
  return { now[1], now[0], now[1] - now[0], now[1] - before[1] };
}

// A frame read through a time-aware reader carries its time step; a frame
// built or read otherwise still has the engine's TimeValue.
double FrameTime(vtkDataObject* frame)
{
  vtkInformation* info = frame->GetInformation();
  if (info->Has(vtkDataObject::DATA_TIME_STEP()))
  {
    return info->Get(vtkDataObject::DATA_TIME_STEP());
  }
  vtkDataArray* timeValue = frame->GetFieldData()->GetArray("TimeValue");
  return timeValue && timeValue->GetNumberOfTuples() > 0 ? timeValue->GetComponent(0, 0)
                                                         : vtkMath::Nan();
}

void AddColumn(vtkTable* table, const char* name, double value)
{
  vtkNew<vtkDoubleArray> column;
  column->SetName(name);
  column->InsertNextValue(value);
  table->AddColumn(column);
}
}

//------------------------------------------------------------------------------
int vtkRunoutRunoutDistance::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutRunoutDistance::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkTable* output = vtkTable::GetData(outputVector);

  vtkDataArray* initial = input->GetPointData()->GetArray("initial_position");
  if (!initial || initial->GetNumberOfComponents() != 3)
  {
    vtkErrorMacro("The input has no 3-component point array \"initial_position\": "
                  "not a Runout particle frame.");
    return 1;
  }
  if (input->GetNumberOfPoints() == 0)
  {
    return 1;
  }

  const RunoutMeasures m = MeasureRunout(input->GetPoints()->GetData(), initial);
  AddColumn(output, "time", FrameTime(input));
  AddColumn(output, "toe_x", m.ToeX);
  AddColumn(output, "rear_x", m.RearX);
  AddColumn(output, "length", m.Length);
  AddColumn(output, "runout", m.Runout);
  return 1;
}

//------------------------------------------------------------------------------
void vtkRunoutRunoutDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
