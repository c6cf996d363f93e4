/**
 * @class   vtkRunoutHorstGraben
 * @brief   Horsts, grabens and plain blocks between the shear bands of a
 *          Runout particle frame: outlines and a table.
 *
 * Input: as vtkRunoutShearBands, whose bands (with the same parameters)
 * bound the blocks, plus the 3-component point array of the displacement
 * (input array 1, default `displacement`).
 *
 * The bands that reach the slide's upper surface (within SurfaceGap
 * particle spacings) and are not parallel to the base (|dip| >=
 * DipTolerance), ordered by where they meet the surface, cut the slide
 * into blocks. A block is a horst when its rear band dips towards the rear
 * and its front band towards the front (the bands dip away from each
 * other, converging upwards: a raised wedge), a graben when the reverse
 * (converging downwards: a dropped wedge), a plain block otherwise (bands
 * dipping the same way, a band within DipTolerance of the base or of its
 * normal, an end block with one band). docs/filters.md, "Horsts and
 * grabens", gives the definitions.
 *
 * Output port 0: a vtkPolyData with one polygon per block (its particles'
 * outline in along-base bins). Output port 1: a vtkTable with one row per
 * block. Both carry, per block (rear to front): block_id, type ("horst",
 * "graben" or "block"), type_code (1, 2, 0), start_s, end_s, width, top,
 * relief, left_dip, right_dip, left_band, right_band (band_id of the band
 * outputs, -1 where none), displacement (mean |displacement| of its
 * particles), particle_count.
 *
 * Without the strain array, `displacement` or a particle spacing the filter
 * reports an error naming it and both outputs are empty; a frame without
 * boundary bands gives an empty table with every column.
 */
#ifndef vtkRunoutHorstGraben_h
#define vtkRunoutHorstGraben_h

#include "RunoutFiltersModule.h"  // for export macro
#include "vtkRunoutShearBands.h"

class RUNOUTFILTERS_EXPORT vtkRunoutHorstGraben : public vtkRunoutShearBands
{
public:
  static vtkRunoutHorstGraben* New();
  vtkTypeMacro(vtkRunoutHorstGraben, vtkRunoutShearBands);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Tolerance in degrees: a band within it of the base's direction does not
   * cut blocks, and a band dips (towards the rear or the front) when its
   * |dip| lies in [DipTolerance, 90 - DipTolerance]. Default 10.
   */
  vtkSetClampMacro(DipTolerance, double, 0.0, 45.0);
  vtkGetMacro(DipTolerance, double);
  ///@}

  ///@{
  /**
   * Largest depth, in particle spacings, of a band's top below the upper
   * surface for the band to cut blocks. Default 3.
   */
  vtkSetClampMacro(SurfaceGap, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SurfaceGap, double);
  ///@}

protected:
  vtkRunoutHorstGraben();
  ~vtkRunoutHorstGraben() override = default;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  // Defaults: those of runout::analysis::BlockParameters (horst_graben.hpp).
  double DipTolerance;
  double SurfaceGap;

private:
  vtkRunoutHorstGraben(const vtkRunoutHorstGraben&) = delete;
  void operator=(const vtkRunoutHorstGraben&) = delete;
};

#endif
