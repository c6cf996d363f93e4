#include "vtkRunoutHorstGraben.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "FrameArrays.h"
#include "HorstGraben.h"
#include "ShearBands.h"

using namespace runout::filters;

vtkStandardNewMacro(vtkRunoutHorstGraben);

//------------------------------------------------------------------------------
vtkRunoutHorstGraben::vtkRunoutHorstGraben()
{
  const BlockParameters defaults;
  this->DipTolerance = defaults.dip_tolerance;
  this->SurfaceGap = defaults.surface_gap;
}

//------------------------------------------------------------------------------
int vtkRunoutHorstGraben::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataArray* displacementArray =
    vtkPointSet::GetData(inputVector[0])->GetPointData()->GetArray("displacement");
  if (!displacementArray)
  {
    vtkErrorMacro("The input has no point array \"displacement\": not a Runout particle frame.");
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

  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> outlines;
  const size_t n = blocks.size();
  vtkNew<vtkStringArray> type;
  type->SetName("type");
  type->SetNumberOfValues(static_cast<vtkIdType>(n));
  std::vector<int> id(n), code(n), leftBand(n), rightBand(n), count(n);
  std::vector<double> start(n), end(n), width(n), top(n), relief(n), leftDip(n), rightDip(n),
    displacement(n);
  for (size_t b = 0; b < n; ++b)
  {
    const SlideBlock& block = blocks[b];
    outlines->InsertNextCell(static_cast<vtkIdType>(block.outline.size()));
    for (const Vec2& p : block.outline)
    {
      outlines->InsertCellPoint(points->InsertNextPoint(p.x, p.y, 0.0));
    }
    id[b] = static_cast<int>(b);
    type->SetValue(static_cast<vtkIdType>(b), block_type_name(block.type));
    code[b] = static_cast<int>(block.type);
    start[b] = block.start_s;
    end[b] = block.end_s;
    width[b] = block.width;
    top[b] = block.top;
    relief[b] = block.relief;
    leftDip[b] = block.left_dip;
    rightDip[b] = block.right_dip;
    leftBand[b] = block.left_band;
    rightBand[b] = block.right_band;
    displacement[b] = block.displacement;
    count[b] = block.particles;
  }

  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->SetPoints(points);
  output->SetPolys(outlines);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  add_cell_column(output, table, make_int_array("block_id", id));
  add_cell_column(output, table, type);
  add_cell_column(output, table, make_int_array("type_code", code));
  add_cell_column(output, table, make_double_array("start_s", start));
  add_cell_column(output, table, make_double_array("end_s", end));
  add_cell_column(output, table, make_double_array("width", width));
  add_cell_column(output, table, make_double_array("top", top));
  add_cell_column(output, table, make_double_array("relief", relief));
  add_cell_column(output, table, make_double_array("left_dip", leftDip));
  add_cell_column(output, table, make_double_array("right_dip", rightDip));
  add_cell_column(output, table, make_int_array("left_band", leftBand));
  add_cell_column(output, table, make_int_array("right_band", rightBand));
  add_cell_column(output, table, make_double_array("displacement", displacement));
  add_cell_column(output, table, make_int_array("particle_count", count));
  return 1;
}

//------------------------------------------------------------------------------
void vtkRunoutHorstGraben::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DipTolerance: " << this->DipTolerance << "\n";
  os << indent << "SurfaceGap: " << this->SurfaceGap << "\n";
}
