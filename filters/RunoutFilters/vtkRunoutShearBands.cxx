#include "vtkRunoutShearBands.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "FrameArrays.h"
#include "ShearBands.h"

using namespace runout::filters;

vtkStandardNewMacro(vtkRunoutShearBands);

//------------------------------------------------------------------------------
vtkRunoutShearBands::vtkRunoutShearBands()
{
  const BandParameters defaults;
  this->ThresholdMode = static_cast<int>(defaults.threshold.mode);
  this->Threshold = defaults.threshold.absolute;
  this->RelativeThreshold = defaults.threshold.relative;
  this->ReferenceStrain = defaults.threshold.reference;
  this->Percentile = defaults.threshold.percentile;
  this->LinkingFactor = defaults.linking_factor;
  this->OrientationRadius = defaults.orientation_radius;
  this->MaximumAngle = defaults.max_angle;
  this->MinimumParticles = defaults.min_particles;

  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "plastic_shear_strain");
}

//------------------------------------------------------------------------------
int vtkRunoutShearBands::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutShearBands::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
bool vtkRunoutShearBands::FindBands(vtkInformationVector** inputVector, BandFrame& frame)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkDataArray* xi = this->GetInputArrayToProcess(0, inputVector);
  if (!xi)
  {
    vtkErrorMacro("The input has no point array \"" << selected_array_name(this, 0)
                                                    << "\" (the plastic shear strain).");
    return false;
  }
  frame.spacing = this->ParticleSpacing > 0 ? this->ParticleSpacing : particle_spacing_of(input);
  if (frame.spacing <= 0)
  {
    vtkErrorMacro("The input has no field data \"particle_spacing\": set ParticleSpacing.");
    return false;
  }

  BandParameters parameters;
  parameters.threshold.mode = static_cast<runout::filters::ThresholdMode>(this->ThresholdMode);
  parameters.threshold.absolute = this->Threshold;
  parameters.threshold.relative = this->RelativeThreshold;
  parameters.threshold.reference = this->ReferenceStrain;
  parameters.threshold.percentile = this->Percentile;
  parameters.spacing = frame.spacing;
  parameters.linking_factor = this->LinkingFactor;
  parameters.orientation_radius = this->OrientationRadius;
  parameters.max_angle = this->MaximumAngle;
  parameters.min_particles = this->MinimumParticles;

  frame.points = positions_of(input);
  frame.xi = component_of(xi);
  frame.base = base_of(input);
  frame.bands = find_shear_bands(frame.points, frame.xi, frame.base.view(), parameters);
  return true;
}

//------------------------------------------------------------------------------
int vtkRunoutShearBands::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  BandFrame frame;
  if (!this->FindBands(inputVector, frame))
  {
    return 1;
  }

  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> skeletons;
  const size_t n = frame.bands.size();
  std::vector<int> id(n), count(n);
  std::vector<double> cx(n), cy(n), cs(n), dip(n), length(n), thickness(n), mean(n), peak(n);
  for (size_t b = 0; b < n; ++b)
  {
    const ShearBand& band = frame.bands[b];
    skeletons->InsertNextCell(static_cast<vtkIdType>(band.skeleton.size()));
    for (const Vec2& p : band.skeleton)
    {
      skeletons->InsertCellPoint(points->InsertNextPoint(p.x, p.y, 0.0));
    }
    id[b] = static_cast<int>(b);
    count[b] = static_cast<int>(band.particles.size());
    cx[b] = band.centroid.x;
    cy[b] = band.centroid.y;
    cs[b] = band.centroid_s;
    dip[b] = band.dip;
    length[b] = band.length;
    thickness[b] = band.thickness;
    mean[b] = band.mean_strain;
    peak[b] = band.peak_strain;
  }

  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->SetPoints(points);
  output->SetLines(skeletons);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  add_cell_column(output, table, make_int_array("band_id", id));
  add_cell_column(output, table, make_double_array("centroid_x", cx));
  add_cell_column(output, table, make_double_array("centroid_y", cy));
  add_cell_column(output, table, make_double_array("centroid_s", cs));
  add_cell_column(output, table, make_double_array("dip", dip));
  add_cell_column(output, table, make_double_array("length", length));
  add_cell_column(output, table, make_double_array("thickness", thickness));
  add_cell_column(output, table, make_double_array("mean_strain", mean));
  add_cell_column(output, table, make_double_array("peak_strain", peak));
  add_cell_column(output, table, make_int_array("particle_count", count));
  return 1;
}

//------------------------------------------------------------------------------
void vtkRunoutShearBands::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ThresholdMode: " << this->ThresholdMode << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "RelativeThreshold: " << this->RelativeThreshold << "\n";
  os << indent << "ReferenceStrain: " << this->ReferenceStrain << "\n";
  os << indent << "Percentile: " << this->Percentile << "\n";
  os << indent << "ParticleSpacing: " << this->ParticleSpacing << "\n";
  os << indent << "LinkingFactor: " << this->LinkingFactor << "\n";
  os << indent << "OrientationRadius: " << this->OrientationRadius << "\n";
  os << indent << "MaximumAngle: " << this->MaximumAngle << "\n";
  os << indent << "MinimumParticles: " << this->MinimumParticles << "\n";
}
