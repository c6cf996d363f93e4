/**
 * @class   vtkRunoutMorphology
 * @brief   Thickness and surface profile, toe, rear, length, runout and
 *          mechanism class of one Runout particle frame.
 *
 * Input: a point set with the point arrays `velocity`, `mass` and
 * `initial_position` and the field data `base_points` and
 * `particle_spacing`, as the engine writes every frame (docs/output.md).
 * Every length is measured along the base by the engine's own
 * measure_slide and slide_profile (docs/morphology.md), so the numbers are
 * those of the run's history.csv.
 *
 * Output port 0: the profile along the base, a polyline through the upper
 * surface (x_surface, y_surface, 0) of every bin, rear to front, with the
 * point arrays `s` (bin centre along the base), `thickness`, `velocity_s`
 * (mass-weighted velocity along the base) and `particles`. The bins are
 * BinSpacings particle spacings wide.
 *
 * Output port 1: a one-row table of the frame: `Time`, `toe`, `rear`,
 * `length`, `max_thickness`, `runout`, `toe_velocity`, the centroid
 * (`centroid_x`, `centroid_y`, `centroid_s`, `centroid_velocity`),
 * `outside_mass`, `initial_toe`, `length_ratio` (L / L0), `thickness_ratio`
 * (Hmax / H0), `particles`, `troughs`, `initial_troughs`, `mechanism_id` and
 * `mechanism` (docs/filters.md, "Runout morphology"). The initial values
 * (toe, L0, H0) are those of the particles' `initial_position`, the t = 0
 * configuration, so one frame is enough: the runout is relative to the
 * first frame of the run without reading it.
 *
 * The point arrays read are input arrays 0 (velocity), 1 (mass) and 2
 * (initial position), the engine's names by default.
 *
 * A frame without points gives an empty profile and a row with `particles`
 * 0, NaN lengths and `undetermined`. A frame with points but without one
 * of the arrays: an error naming it, both outputs empty.
 */
#ifndef vtkRunoutMorphology_h
#define vtkRunoutMorphology_h

#include "RunoutFiltersModule.h"  // for export macro
#include "vtkPolyDataAlgorithm.h"

class vtkTable;

class RUNOUTFILTERS_EXPORT vtkRunoutMorphology : public vtkPolyDataAlgorithm
{
public:
  static vtkRunoutMorphology* New();
  vtkTypeMacro(vtkRunoutMorphology, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Width of the profile's bins along the base, in particle spacings (the
   * frame's `particle_spacing`). Default 2 (runout::analysis::
   * kProfileBinSpacings, as `runout analyse`): narrower bins show the gaps
   * between particle columns as dips of the profile. The range is
   * kMinProfileBinSpacings to kMaxProfileBinSpacings.
   */
  vtkSetClampMacro(BinSpacings, double, 0.25, 1000.0);
  vtkGetMacro(BinSpacings, double);
  ///@}

  /**
   * The one-row table (output port 1).
   */
  vtkTable* GetTableOutput();

protected:
  vtkRunoutMorphology();
  ~vtkRunoutMorphology() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double BinSpacings;

private:
  vtkRunoutMorphology(const vtkRunoutMorphology&) = delete;
  void operator=(const vtkRunoutMorphology&) = delete;
};

#endif
