#include "vtkRunoutSeriesReader.h"

#include "vtkCommand.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"

#include "runout/output/vtu_writer.hpp"  // read_pvd_entries, FrameManifest

#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>

vtkStandardNewMacro(vtkRunoutSeriesReader);

namespace
{
// Counts the errors VTK's XML reader reports, and keeps the last, so that
// a frame it cannot parse is this reader's warning, not a second error.
class ParseErrors : public vtkCommand
{
public:
  static ParseErrors* New() { return new ParseErrors; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Last = data ? static_cast<const char*>(data) : "";
  }
  int Count = 0;
  std::string Last;
};

// The manifest of the index at `pvd` as it is on disk now; none for a run
// without one.
std::optional<runout::FrameManifest> ManifestOf(const char* pvd)
{
  try
  {
    return runout::FrameManifest(pvd);
  }
  catch (const std::exception&)
  {
    return std::nullopt;
  }
}
}

//------------------------------------------------------------------------------
vtkRunoutSeriesReader::vtkRunoutSeriesReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkRunoutSeriesReader::~vtkRunoutSeriesReader()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
int vtkRunoutSeriesReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  this->Frames.clear();
  if (!this->FileName || !*this->FileName)
  {
    // ParaView asks for the information as soon as the source is made,
    // before the user has picked a file: no file yet is not an error.
    return 1;
  }
  try
  {
    for (const auto& entry : runout::read_pvd_entries(this->FileName))
    {
      if (std::isfinite(entry.first))
      {
        this->Frames.push_back(entry);
      }
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< this->FileName << ": " << e.what());
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  if (this->Frames.empty())
  {
    vtkWarningMacro(<< this->FileName << " lists no frame with a time.");
    return 1;
  }
  std::vector<double> times;
  for (const auto& frame : this->Frames)
  {
    times.push_back(frame.first);
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
    static_cast<int>(times.size()));
  const double range[2] = { times.front(), times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

//------------------------------------------------------------------------------
int vtkRunoutSeriesReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outInfo);
  output->Initialize();
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No file: pick the run's .pvd index (File Name).");
    return 1;
  }
  if (this->Frames.empty())
  {
    return 1;
  }
  const double requested = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
    : this->Frames.front().first;
  const auto& [time, file] = this->Frames[this->FrameAt(requested)];
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), time);

  // Read at every frame: a run still writing adds to its manifest.
  const std::optional<runout::FrameManifest> manifest = ManifestOf(this->FileName);
  if (!manifest)
  {
    this->WarnNoManifest();
  }
  std::string bytes;
  std::string problem = runout::read_listed_frame(
    std::filesystem::path(this->FileName).parent_path().string(), file,
    manifest ? &*manifest : nullptr, bytes);
  if (problem.empty())
  {
    // VTK parses the very bytes the manifest vouched for, not the file again.
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    vtkNew<ParseErrors> errors;
    reader->AddObserver(vtkCommand::ErrorEvent, errors);
    reader->ReadFromInputStringOn();
    reader->SetInputString(bytes);
    reader->Update();
    if (errors->Count == 0)
    {
      output->ShallowCopy(reader->GetOutput());
      return 1;
    }
    problem = "VTK cannot read it (" + errors->Last + ")";
  }
  vtkWarningMacro(<< "Frame " << file << " (time " << time << "): " << problem
                  << "; skipped, the output is empty.");
  return 1;
}

//------------------------------------------------------------------------------
std::size_t vtkRunoutSeriesReader::FrameAt(double time) const
{
  std::size_t k = 0;
  while (k + 1 < this->Frames.size() && this->Frames[k + 1].first <= time + this->TimeTolerance(k))
  {
    ++k;
  }
  return k;
}

//------------------------------------------------------------------------------
double vtkRunoutSeriesReader::TimeTolerance(std::size_t k) const
{
  // The index stores the sum of the steps (27.700000000000003 for 27.7):
  // a time asked within a millionth of the interval of frame k + 1 is
  // that frame's, not the one before it.
  return 1e-6 * (this->Frames[k + 1].first - this->Frames[k].first);
}

//------------------------------------------------------------------------------
void vtkRunoutSeriesReader::WarnNoManifest()
{
  if (this->WarnedNoManifestFor != this->FileName)
  {
    this->WarnedNoManifestFor = this->FileName;
    vtkWarningMacro(<< "No manifest " << runout::manifest_path(this->FileName)
                    << ": the frames are read unchecked.");
  }
}

//------------------------------------------------------------------------------
void vtkRunoutSeriesReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Frames: " << this->Frames.size() << "\n";
}
