/**
 * @class   vtkRunoutRunoutDistance
 * @brief   Toe, rear, length and runout of one Runout particle frame.
 *
 * Input: a point set with the 3-component point array `initial_position`,
 * as the engine writes every frame. Output: a one-row table with the
 * columns `time`, `toe_x` (largest x of the points), `rear_x` (smallest x),
 * `length` (toe_x - rear_x) and `runout` (toe_x minus the largest x of
 * `initial_position`). x is the engine's run frame: down the base for a
 * planar slope. Applied to a time series in ParaView, "Plot Data Over Time"
 * of this table gives the runout history.
 *
 * `time` is the data time step of the input, else its `TimeValue` field
 * data, else NaN. Without `initial_position` the filter reports an error
 * and outputs an empty table; with no points it outputs an empty table.
 */
#ifndef vtkRunoutRunoutDistance_h
#define vtkRunoutRunoutDistance_h

#include "RunoutFiltersModule.h"  // for export macro
#include "vtkTableAlgorithm.h"

class RUNOUTFILTERS_EXPORT vtkRunoutRunoutDistance : public vtkTableAlgorithm
{
public:
  static vtkRunoutRunoutDistance* New();
  vtkTypeMacro(vtkRunoutRunoutDistance, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkRunoutRunoutDistance() = default;
  ~vtkRunoutRunoutDistance() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkRunoutRunoutDistance(const vtkRunoutRunoutDistance&) = delete;
  void operator=(const vtkRunoutRunoutDistance&) = delete;
};

#endif
