// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer harness of vtkOpenEXRReader (the real VTK reader, through the pipeline): the bytes
// are written to a temporary .exr file, then CanReadFile and Update run on it. The reader must
// never throw nor crash: a bad file is one error (silenced here) and an empty output; a good one
// is an image whose arrays all have one tuple per point. OpenEXR itself is Debian's library,
// not instrumented: libFuzzer's coverage sees the reader's branches only, ASan sees OpenEXR's
// memory errors only where they pass through intercepted calls (memcpy, malloc, ...).
#include "FuzzTemporaryFolder.h"
#include "vtkOpenEXRReader.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>

#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  vtkObject::GlobalWarningDisplayOff(); // errors are expected; printing them costs the fuzzer
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const std::string file = (FuzzTemporaryFolder::Get() / "fuzz.exr").string();
  FuzzTemporaryFolder::WriteBytes(file, data, size);

  vtkNew<vtkOpenEXRReader> reader;
  // 512 x 512 at most: a mutated header claiming the default limit (2^28 pixels, GBs of
  // arrays) would make every such input cost seconds. What a tiny file can make the reader
  // allocate under the default limit is a finding of its own (Testing/Data/bad/fuzz/).
  reader->SetMaximumPixels(1 << 18);
  (void)reader->CanReadFile(file.c_str());
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  const vtkIdType points = image->GetNumberOfPoints();
  vtkPointData* pointData = image->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    if (!array || array->GetNumberOfTuples() != points)
    {
      std::abort(); // an array that does not fit the image
    }
    // Read values across the whole array: a short one would show as a heap overflow.
    double sum = 0;
    const vtkIdType values = array->GetNumberOfValues();
    for (vtkIdType k = 0; k < values; k += 1 + values / 4096)
    {
      sum += array->GetComponent(
        k / array->GetNumberOfComponents(), static_cast<int>(k % array->GetNumberOfComponents()));
    }
    (void)sum;
  }
  return 0;
}
