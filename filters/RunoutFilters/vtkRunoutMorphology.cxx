#include "vtkRunoutMorphology.h"

#include "FrameArrays.h"
#include "MorphologyFrame.h"

#include "vtkCellArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <vector>

vtkStandardNewMacro(vtkRunoutMorphology);

namespace
{
// The profile as a polyline through the upper surface of its bins.
void FillProfile(const runout::Profile& profile, vtkPolyData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(profile.bins.size());
  if (n == 0)
  {
    return;
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> line;
  line->InsertNextCell(n);
  std::vector<double> s, thickness, velocity;
  std::vector<int> particles;
  for (vtkIdType k = 0; k < n; ++k)
  {
    const runout::ProfileBin& bin = profile.bins[k];
    points->InsertNextPoint(bin.x_surface, bin.y_surface, 0.0);
    line->InsertCellPoint(k);
    s.push_back(bin.s);
    thickness.push_back(bin.thickness);
    velocity.push_back(bin.velocity_s);
    particles.push_back(bin.particles);
  }
  output->SetPoints(points);
  output->SetLines(line);
  vtkPointData* data = output->GetPointData();
  data->AddArray(runout::filters::make_double_array("s", s));
  data->AddArray(runout::filters::make_double_array("thickness", thickness));
  data->AddArray(runout::filters::make_double_array("velocity_s", velocity));
  data->AddArray(runout::filters::make_int_array("particles", particles));
  data->SetActiveScalars("thickness");
}
}

//------------------------------------------------------------------------------
vtkRunoutMorphology::vtkRunoutMorphology()
  : BinSpacings(runout::analysis::kProfileBinSpacings)
{
  this->SetNumberOfOutputPorts(2);
  runout::filters::select_morphology_arrays(this);
}

//------------------------------------------------------------------------------
vtkTable* vtkRunoutMorphology::GetTableOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkRunoutMorphology::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutMorphology::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkRunoutMorphology::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* profile = vtkPolyData::GetData(outputVector, 0);
  vtkTable* table = vtkTable::GetData(outputVector, 1);

  runout::analysis::FrameMorphology morphology;
  const std::string error =
    runout::filters::measure_point_set(input, this->BinSpacings, morphology,
      runout::filters::selected_morphology_arrays(this));
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 1;
  }
  if (input->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro("The input has no points: an empty profile and an undetermined row.");
  }
  FillProfile(morphology.profile, profile);
  runout::filters::add_morphology_columns(table);
  runout::filters::append_morphology_row(
    table, runout::filters::frame_time_of(input), morphology);
  return 1;
}

//------------------------------------------------------------------------------
void vtkRunoutMorphology::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BinSpacings: " << this->BinSpacings << "\n";
}
