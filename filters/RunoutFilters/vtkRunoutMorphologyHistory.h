/**
 * @class   vtkRunoutMorphologyHistory
 * @brief   Time history of a Runout particle series' morphology: one table
 *          row per time step.
 *
 * Input: a Runout particle frame series (the run's .pvd through
 * vtkPVDReader, or any time-aware source of such frames). The filter has
 * the pipeline update every time step of the input's TIME_STEPS in turn
 * (REQUEST_UPDATE_EXTENT with CONTINUE_EXECUTING, as
 * vtkExtractDataArraysOverTime does) and appends one row per step, the
 * columns of vtkRunoutMorphology's table: `Time`, `toe`, `rear`, `length`,
 * `max_thickness`, `runout`, `toe_velocity`, ... and `mechanism`. ParaView
 * opens output port 1, the lengths alone (`Time`, `toe (m)`, `rear (m)`,
 * `runout (m)`, `length (m)`, `max_thickness (m)`), as a line chart
 * against `Time`; port 0 is the whole table. An input without time steps
 * gives the one row of its current data. The output is not temporal.
 *
 * The point arrays read are input arrays 0 (velocity), 1 (mass) and 2
 * (initial position), the engine's `velocity`, `mass` and
 * `initial_position` by default.
 *
 * Each row's `mechanism` is classed with the travel up to its time (the
 * late stretch of morphology_rules.hpp), as `runout analyse` classes it.
 *
 * A frame without points is skipped with a warning; a frame with
 * points but without one of the arrays vtkRunoutMorphology needs stops the
 * iteration with an error naming the array, and the output is empty.
 */
#ifndef vtkRunoutMorphologyHistory_h
#define vtkRunoutMorphologyHistory_h

#include "RunoutFiltersModule.h"  // for export macro
#include "vtkTableAlgorithm.h"
#include "vtkNew.h"               // for vtkNew

class RUNOUTFILTERS_EXPORT vtkRunoutMorphologyHistory : public vtkTableAlgorithm
{
public:
  static vtkRunoutMorphologyHistory* New();
  vtkTypeMacro(vtkRunoutMorphologyHistory, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkRunoutMorphologyHistory();
  ~vtkRunoutMorphologyHistory() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkRunoutMorphologyHistory(const vtkRunoutMorphologyHistory&) = delete;
  void operator=(const vtkRunoutMorphologyHistory&) = delete;

  // Moves on to the next time step, or, after the last, delivers the tables.
  int NextTimeStep(vtkInformation* request, vtkInformationVector* outputVector);

  int NumberOfTimeSteps = 0;
  int CurrentTimeIndex = 0;
  vtkNew<vtkTable> History;  // the rows gathered so far
};

#endif
