// libFuzzer target: arbitrary bytes as a .vtu particle frame, read by
// VTK's vtkXMLUnstructuredGridReader and passed through each Runout filter
// (docs/fuzzing.md). A filter may report an error and give empty output;
// a crash, an exception or a sanitizer report is a bug.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
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
// This target found four bugs in ParaView 5.11's own reader, which it then
// steps around so that the fuzzing goes on into the filters: a null
// dereference in vtkXMLReader::ReadXMLInformation for a field-data
// DataArray of an unknown type, and binary arrays whose (zlib) headers it
// trusts for the size of an allocation (allocation-size-too-big). The
// filters see the same arrays whichever the encoding, and ASCII numbers
// are what mutations turn into NaNs, infinities and wrong counts.
// A third: it sizes the connectivity by the last cell offset, so an offset
// of 3e11 is a 2.5 TB allocation; no offset may exceed what the input could
// list (an ASCII connectivity entry takes two bytes at least).
bool offsets_within(vtkXMLDataElement* element, const std::string& xml) {
  const char* name = element->GetAttribute("Name");
  if (!name || std::string(name) != "offsets") return true;
  // The parser keeps no character data of a DataArray, only where the
  // element starts: its values follow the end of the start tag.
  const std::size_t start = xml.find('>', static_cast<std::size_t>(element->GetXMLByteIndex()));
  if (start == std::string::npos) return false;
  std::istringstream values(xml.substr(start + 1, xml.find('<', start) - start - 1));
  double offset = 0;
  while (values >> offset)
    if (!(offset <= static_cast<double>(xml.size()))) return false;
  return true;
}

// And a fourth: it trusts the counts it is given (a NumberOfComponents of
// 3777...7 ran a loop over the components for longer than the fuzzer's
// 20 s timeout). No count of an ASCII file can exceed its size in bytes.
bool counts_within(vtkXMLDataElement* element, std::size_t input_size) {
  for (int i = 0; i < element->GetNumberOfAttributes(); ++i) {
    if (std::string(element->GetAttributeName(i)).rfind("NumberOf", 0) != 0) continue;
    const double count = std::strtod(element->GetAttributeValue(i), nullptr);
    if (!(count >= 0 && count <= static_cast<double>(input_size))) return false;
  }
  return true;
}

bool ascii_arrays_of_known_types(vtkXMLDataElement* element, const std::string& xml) {
  if (!counts_within(element, xml.size())) return false;
  if (std::string(element->GetName()) == "DataArray") {
    int type = 0;
    const char* format = element->GetAttribute("format");
    if (!element->GetWordTypeAttribute("type", type) || !format || std::string(format) != "ascii")
      return false;
    if (!offsets_within(element, xml)) return false;
  }
  for (int i = 0; i < element->GetNumberOfNestedElements(); ++i)
    if (!ascii_arrays_of_known_types(element->GetNestedElement(i), xml)) return false;
  return true;
}

// A fifth, of the same kind: CreateArray builds a string for every
// component of every array, so 150 arrays of 9000 components each took
// 2.9 s and 420 MB here and a CI machine five times slower past the
// timeout; and it sizes an array by components times tuples.
// An ASCII file lists every value of every array, so the values all its
// arrays claim (components times tuples, a tuple at least for an empty
// array) cannot exceed the input's size either. Tuples are the array's
// NumberOfTuples, or its piece's points or cells.
double count_of(vtkXMLDataElement* element, const char* name, double absent) {
  const char* value = element->GetAttribute(name);
  return value ? std::strtod(value, nullptr) : absent;
}

struct Budget {
  double left;
  double points = 0;
  double cells = 0;
};

bool values_within(vtkXMLDataElement* element, const char* parent, Budget& budget) {
  const std::string name = element->GetName();
  if (name == "Piece") {
    budget.points = count_of(element, "NumberOfPoints", 0);
    budget.cells = count_of(element, "NumberOfCells", 0);
  }
  if (name == "DataArray") {
    const bool of_cells = parent && (std::string(parent) == "CellData" || std::string(parent) == "Cells");
    const double tuples = count_of(element, "NumberOfTuples", of_cells ? budget.cells : budget.points);
    budget.left -= count_of(element, "NumberOfComponents", 1) * std::max(tuples, 1.0);
    if (!(budget.left >= 0)) return false;
  }
  for (int i = 0; i < element->GetNumberOfNestedElements(); ++i)
    if (!values_within(element->GetNestedElement(i), element->GetName(), budget)) return false;
  return true;
}

bool readable_by_vtk(const std::string& xml) {
  std::istringstream stream(xml);
  vtkNew<vtkXMLDataParser> parser;
  parser->SetStream(&stream);
  if (!parser->Parse() || !parser->GetRootElement()) return false;
  Budget budget{static_cast<double>(xml.size())};
  return ascii_arrays_of_known_types(parser->GetRootElement(), xml) &&
         values_within(parser->GetRootElement(), nullptr, budget);
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
