#include "vtkRunoutHorstGraben.h"

#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include "FrameArrays.h"
#include "runout/analysis/horst_graben.hpp"
#include "runout/analysis/result_columns.hpp"

#include <string>

using namespace runout::analysis;
using namespace runout::filters;

vtkStandardNewMacro(vtkRunoutHorstGraben);

//------------------------------------------------------------------------------
vtkRunoutHorstGraben::vtkRunoutHorstGraben()
{
  const BlockParameters defaults;
  this->DipTolerance = defaults.dip_tolerance;
  this->SurfaceGap = defaults.surface_gap;
  this->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "displacement");
}

//------------------------------------------------------------------------------
int vtkRunoutHorstGraben::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataArray* displacementArray = this->GetInputArrayToProcess(1, inputVector);
  if (!displacementArray)
  {
    vtkErrorMacro("The input has no point array \"" << selected_array_name(this, 1)
                                                    << "\" (the displacement): not a Runout "
                                                       "particle frame.");
    return 1;
  }
  const std::string problem = point_array_problem(
    vtkPointSet::GetData(inputVector[0]), displacementArray, selected_array_name(this, 1), 1);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 1;
  }
  BandFrame frame;
  if (!this->FindBands(inputVector, frame))
  {
    return 1;
  }

  BlockParameters parameters;
  parameters.spacing = frame.spacing;
  parameters.dip_tolerance = this->DipTolerance;
  parameters.surface_gap = this->SurfaceGap;
  const std::vector<SlideBlock> blocks = find_blocks(
    frame.points, magnitude_of(displacementArray), frame.bands, frame.base.view(), parameters);

  write_items<SlideBlock>(
    outputVector, blocks, &SlideBlock::outline, true, kBlockIdColumn, block_columns());
  return 1;
}

//------------------------------------------------------------------------------
void vtkRunoutHorstGraben::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DipTolerance: " << this->DipTolerance << "\n";
  os << indent << "SurfaceGap: " << this->SurfaceGap << "\n";
}
