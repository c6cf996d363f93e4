/**
 * @class   vtkRunoutPlasticStrain
 * @brief   Plastic strain increment, normalised strain and a gridded strain
 *          field of a Runout particle frame.
 *
 * Input: a point set with the cumulative plastic shear strain xi (input
 * array 0, default the point array `plastic_shear_strain`) and the point
 * array `particle_id`, as the engine writes every frame.
 *
 * Output port 0: the particles with two more point arrays:
 * - `plastic_strain_increment`: xi minus xi of the same particle (same
 *   `particle_id`) in the previous frame; 0 on the first frame, for a
 *   particle the previous frame lacks, and when there is no previous frame.
 *   The previous frame is the time step before the input's in the input's
 *   TIME_STEPS: the filter keeps xi by particle id of the last frames it saw,
 *   keyed on their time, and when the one it needs is missing (the first
 *   frame shown, a jump back in time) it has the pipeline update the
 *   previous step first (CONTINUE_EXECUTING), so the increment does not
 *   depend on the order in which frames are visited. Selecting another
 *   strain array, or a change upstream of a time series, empties the cache.
 *   An input without time steps (frames given one at a time) uses the
 *   cached frame with the largest time (TimeValue) before its own.
 * - `normalised_plastic_strain`: xi / Xi95 when Xi95 > 0, else xi divided by
 *   the largest xi of the frame (0 when that is 0).
 *
 * Output port 1: a vtkImageData (one node thick in z) over the particles'
 * bounding box with the node spacing GridSpacing (for a time series, the
 * box of every frame together: the first update reads each time step once
 * to find it, so that the grid's whole extent, the same for every frame, is
 * known in RequestInformation), holding the kernel-weighted
 * projections of xi (under its input name), of the increment and of the
 * normalised strain, and `coverage` (1 where a particle is within the kernel
 * radius, else 0 with all values 0). The kernel is w = 1 - (r / R)^2 with
 * R = 2 max(GridSpacing, particle spacing), normalised, so that a uniform
 * field projects exactly.
 *
 * Without the xi array or `particle_id` the filter reports an error naming
 * the array and both outputs are empty.
 */
#ifndef vtkRunoutPlasticStrain_h
#define vtkRunoutPlasticStrain_h

#include "RunoutFiltersModule.h"  // for export macro
#include "vtkPassInputTypeAlgorithm.h"

#include <memory>  // for std::unique_ptr

class vtkImageData;

class RUNOUTFILTERS_EXPORT vtkRunoutPlasticStrain : public vtkPassInputTypeAlgorithm
{
public:
  static vtkRunoutPlasticStrain* New();
  vtkTypeMacro(vtkRunoutPlasticStrain, vtkPassInputTypeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * xi95 of the material (the plastic shear strain at 95 % of the
   * remoulding) that `normalised_plastic_strain` divides xi by. 0 (the
   * default): divide by the largest xi of the frame.
   */
  vtkSetClampMacro(Xi95, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Xi95, double);
  ///@}

  ///@{
  /**
   * Node spacing of the gridded field (output port 1), in the frame's
   * length unit. 0 (the default): twice the frame's `particle_spacing`
   * field data, or 0.5 without it.
   */
  vtkSetClampMacro(GridSpacing, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(GridSpacing, double);
  ///@}

  /**
   * The gridded field (output port 1).
   */
  vtkImageData* GetGridOutput();

protected:
  vtkRunoutPlasticStrain();
  ~vtkRunoutPlasticStrain() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double Xi95 = 0.0;
  double GridSpacing = 0.0;

private:
  // The upstream pipeline's modification time for a time series, 0 for
  // frames without time steps.
  vtkMTimeType UpstreamTime();

  vtkRunoutPlasticStrain(const vtkRunoutPlasticStrain&) = delete;
  void operator=(const vtkRunoutPlasticStrain&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
