/**
 * @class   vtkRunoutSeriesReader
 * @brief   Reads a Runout run's .pvd series, checking every frame against
 *          the run's manifest before VTK parses it.
 *
 * The engine writes beside its index `<name>.pvd` a manifest
 * `<name>.pvd.manifest` with each frame's size and CRC-32, recorded as the
 * frame was written (docs/output.md). This reader offers the index's times
 * as TIME_STEPS, as vtkPVDReader does; for the requested time it takes the
 * last frame at or before it (a frame stored a rounding error after the
 * time asked counts as at it), and reads the file with
 * vtkXMLUnstructuredGridReader only when its size and CRC-32 match the
 * manifest. A frame that is missing, not in the manifest, of another size
 * or checksum, or that VTK cannot read, gives a warning naming the file and
 * why, and an empty output: a damaged byte never reaches VTK's parser
 * (one changed base64 character in a compression header made VTK 5.11's
 * reader abort the whole ParaView), and Runout Morphology History skips
 * that step and keeps the others. A run without a manifest (older than the
 * manifest) is read unchecked, with one warning saying so. Without a file
 * name it offers no time steps and reports nothing until it is run.
 */
#ifndef vtkRunoutSeriesReader_h
#define vtkRunoutSeriesReader_h

#include "RunoutFiltersModule.h"  // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <cstddef> // for std::size_t
#include <string>  // for std::string
#include <utility> // for std::pair
#include <vector>  // for std::vector

class RUNOUTFILTERS_EXPORT vtkRunoutSeriesReader : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkRunoutSeriesReader* New();
  vtkTypeMacro(vtkRunoutSeriesReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The run's .pvd index; its manifest is the same name with `.manifest`.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

protected:
  vtkRunoutSeriesReader();
  ~vtkRunoutSeriesReader() override;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkRunoutSeriesReader(const vtkRunoutSeriesReader&) = delete;
  void operator=(const vtkRunoutSeriesReader&) = delete;

  // The entry of Frames shown at `time`: the last at or before it, up to
  // TimeTolerance.
  std::size_t FrameAt(double time) const;
  // How far after `time` frame k + 1 may lie and still be the one shown.
  double TimeTolerance(std::size_t k) const;
  // Says once per index that its run has no manifest to check against.
  void WarnNoManifest();

  char* FileName = nullptr;
  std::vector<std::pair<double, std::string>> Frames;  // time, file: the index's finite times
  std::string WarnedNoManifestFor;  // the index whose missing manifest was reported
};

#endif
