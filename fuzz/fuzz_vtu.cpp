// libFuzzer target: arbitrary bytes as a .vtu particle frame, read by
// VTK's vtkXMLUnstructuredGridReader and passed through each Runout filter
// (docs/fuzzing.md). A filter may report an error and give empty output;
// a crash, an exception or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include <vtkAlgorithm.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "vtkRunoutHorstGraben.h"
#include "vtkRunoutMorphology.h"
#include "vtkRunoutPlasticStrain.h"
#include "vtkRunoutShearBands.h"

namespace {

// True when every DataArray of the XML is ASCII and of a type VTK knows.
// This target found two bugs in ParaView 5.11's own reader, which it then
// steps around so that the fuzzing goes on into the filters: a null
// dereference in vtkXMLReader::ReadXMLInformation for a field-data
// DataArray of an unknown type, and binary arrays whose (zlib) headers it
// trusts for the size of an allocation (allocation-size-too-big). The
// filters see the same arrays whichever the encoding, and ASCII numbers
// are what mutations turn into NaNs, infinities and wrong counts.
bool ascii_arrays_of_known_types(vtkXMLDataElement* element) {
  if (std::string(element->GetName()) == "DataArray") {
    int type = 0;
    const char* format = element->GetAttribute("format");
    if (!element->GetWordTypeAttribute("type", type) || !format || std::string(format) != "ascii")
      return false;
  }
  for (int i = 0; i < element->GetNumberOfNestedElements(); ++i)
    if (!ascii_arrays_of_known_types(element->GetNestedElement(i))) return false;
  return true;
}

bool readable_by_vtk(const std::string& xml) {
  std::istringstream stream(xml);
  vtkNew<vtkXMLDataParser> parser;
  parser->SetStream(&stream);
  return parser->Parse() && parser->GetRootElement() &&
         ascii_arrays_of_known_types(parser->GetRootElement());
}

void run_filter(vtkAlgorithm* filter, vtkUnstructuredGrid* frame) {
  filter->SetInputDataObject(frame);
  filter->Update();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Errors are the expected answer to most inputs; printing them would
  // only slow the fuzzer down.
  vtkObject::GlobalWarningDisplayOff();
  const std::string xml(reinterpret_cast<const char*>(data), size);
  if (!readable_by_vtk(xml)) return 0;
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->ReadFromInputStringOn();
  reader->SetInputString(xml);
  reader->Update();
  vtkUnstructuredGrid* frame = reader->GetOutput();
  if (!frame) return 0;
  vtkNew<vtkRunoutPlasticStrain> strain;
  run_filter(strain, frame);
  vtkNew<vtkRunoutShearBands> bands;
  run_filter(bands, frame);
  vtkNew<vtkRunoutHorstGraben> blocks;
  run_filter(blocks, frame);
  vtkNew<vtkRunoutMorphology> morphology;
  run_filter(morphology, frame);
  return 0;
}
