#include "vtkRunoutShearBands.h"

#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"

#include "FrameArrays.h"
#include "runout/analysis/result_columns.hpp"
#include "runout/analysis/shear_bands.hpp"

#include <cmath>
#include <string>

using namespace runout::analysis;
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
  if (!(frame.spacing > 0) || !std::isfinite(frame.spacing))
  {
    vtkErrorMacro("The input has no field data \"particle_spacing\": set ParticleSpacing.");
    return false;
  }
  std::string problem = points_problem(input);
  if (problem.empty())
  {
    problem = point_array_problem(input, xi, selected_array_name(this, 0), 1);
  }
  if (problem.empty())
  {
    problem = runout::analysis::extent_problem(positions_of(input), frame.spacing);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  if (input->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro("The input has no points: no bands.");
  }

  BandParameters parameters;
  parameters.threshold.mode = static_cast<runout::analysis::ThresholdMode>(this->ThresholdMode);
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

  write_items<ShearBand>(
    outputVector, frame.bands, &ShearBand::skeleton, false, kBandIdColumn, band_columns());
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
