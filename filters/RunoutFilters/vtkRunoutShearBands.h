/**
 * @class   vtkRunoutShearBands
 * @brief   Shear bands of a Runout particle frame: skeletons and a table.
 *
 * Input: a point set with the cumulative plastic shear strain xi (input
 * array 0, default the point array `plastic_shear_strain`) and the particle
 * spacing (the `particle_spacing` field data, or ParticleSpacing). The
 * `base_points` field data, when present, gives the base the dips are
 * measured against; else the x axis.
 *
 * The particles whose xi is above the threshold (ThresholdMode: Absolute,
 * RelativeToReference or Percentile) are linked into bands: two particles
 * at most LinkingFactor particle spacings apart are linked, and a band
 * takes a linked particle only when the particle's local orientation is
 * within MaximumAngle of the band's, so bands that meet come out separate.
 * Bands of fewer than MinimumParticles particles are dropped.
 * docs/filters.md, "Shear bands", gives the definitions.
 *
 * Output port 0: a vtkPolyData with one polyline per band (its skeleton,
 * the mean positions of its particles in bins along its principal axis).
 * Output port 1: a vtkTable with one row per band. Both carry, per band
 * (ordered by centroid_s, rear to front): band_id, centroid_x, centroid_y,
 * centroid_s, dip (degrees, positive when the band descends towards the
 * base in the direction of increasing s), length, thickness, mean_strain,
 * peak_strain, particle_count.
 *
 * Without the xi array, or without any particle spacing, the filter reports
 * an error naming it and both outputs are empty; a frame without bands
 * gives an empty table with every column.
 */
#ifndef vtkRunoutShearBands_h
#define vtkRunoutShearBands_h

#include "RunoutFiltersModule.h"  // for export macro
#include "vtkPolyDataAlgorithm.h"

namespace runout
{
namespace filters
{
struct BandFrame;
}
}

class RUNOUTFILTERS_EXPORT vtkRunoutShearBands : public vtkPolyDataAlgorithm
{
public:
  static vtkRunoutShearBands* New();
  vtkTypeMacro(vtkRunoutShearBands, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ThresholdModes
  {
    ABSOLUTE = 0,
    RELATIVE_TO_REFERENCE = 1,
    PERCENTILE = 2
  };

  ///@{
  /**
   * How the strain threshold is set: ABSOLUTE (Threshold), RELATIVE_TO_REFERENCE
   * (RelativeThreshold x ReferenceStrain) or PERCENTILE (the Percentile-th
   * percentile of the frame's xi; the default). A particle is in a band when
   * its xi is strictly above the threshold.
   */
  vtkSetClampMacro(ThresholdMode, int, ABSOLUTE, PERCENTILE);
  vtkGetMacro(ThresholdMode, int);
  void SetThresholdModeToAbsolute() { this->SetThresholdMode(ABSOLUTE); }
  void SetThresholdModeToRelativeToReference() { this->SetThresholdMode(RELATIVE_TO_REFERENCE); }
  void SetThresholdModeToPercentile() { this->SetThresholdMode(PERCENTILE); }
  ///@}

  ///@{
  /**
   * The strain threshold of ABSOLUTE mode. Default 1.
   */
  vtkSetMacro(Threshold, double);
  vtkGetMacro(Threshold, double);
  ///@}

  ///@{
  /**
   * RELATIVE_TO_REFERENCE mode: threshold = RelativeThreshold x
   * ReferenceStrain (e.g. the material's xi95). Defaults 1 and 1.
   */
  vtkSetMacro(RelativeThreshold, double);
  vtkGetMacro(RelativeThreshold, double);
  vtkSetMacro(ReferenceStrain, double);
  vtkGetMacro(ReferenceStrain, double);
  ///@}

  ///@{
  /**
   * PERCENTILE mode: the percentile of xi over the frame's particles
   * (nearest rank). Default 90: the top tenth of the particles.
   */
  vtkSetClampMacro(Percentile, double, 0.0, 100.0);
  vtkGetMacro(Percentile, double);
  ///@}

  ///@{
  /**
   * Particle spacing h in the frame's length unit. 0 (the default): the
   * frame's `particle_spacing` field data.
   */
  vtkSetClampMacro(ParticleSpacing, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ParticleSpacing, double);
  ///@}

  ///@{
  /**
   * Linking distance in particle spacings. Default 1.5: a lattice
   * particle's side and diagonal neighbours, not the next ones.
   */
  vtkSetClampMacro(LinkingFactor, double, 0.1, VTK_DOUBLE_MAX);
  vtkGetMacro(LinkingFactor, double);
  ///@}

  ///@{
  /**
   * Radius, in particle spacings, of the neighbourhood whose principal axis
   * is a particle's local orientation. Default 6: larger than a band's
   * thickness, so the axis follows the band.
   */
  vtkSetClampMacro(OrientationRadius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(OrientationRadius, double);
  ///@}

  ///@{
  /**
   * Largest angle in degrees between a particle's local orientation and a
   * band's mean orientation for the band to take the particle. Default 30;
   * 90 links on distance alone.
   */
  vtkSetClampMacro(MaximumAngle, double, 0.0, 90.0);
  vtkGetMacro(MaximumAngle, double);
  ///@}

  ///@{
  /**
   * Fewest particles of a band; smaller clusters are dropped. Default 10.
   */
  vtkSetClampMacro(MinimumParticles, int, 1, VTK_INT_MAX);
  vtkGetMacro(MinimumParticles, int);
  ///@}

protected:
  vtkRunoutShearBands();
  ~vtkRunoutShearBands() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /**
   * Reads the input frame and finds its bands with this filter's
   * parameters. False, after an error naming what is missing, when the input
   * lacks the strain array or a particle spacing.
   */
  bool FindBands(vtkInformationVector** inputVector, runout::filters::BandFrame& frame);

  // Defaults: those of runout::analysis::BandParameters (shear_bands.hpp).
  int ThresholdMode;
  double Threshold;
  double RelativeThreshold;
  double ReferenceStrain;
  double Percentile;
  double ParticleSpacing = 0.0;
  double LinkingFactor;
  double OrientationRadius;
  double MaximumAngle;
  int MinimumParticles;

private:
  vtkRunoutShearBands(const vtkRunoutShearBands&) = delete;
  void operator=(const vtkRunoutShearBands&) = delete;
};

#endif
