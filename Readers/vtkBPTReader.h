// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkBPTReader
 * @brief Reads a Bezier patch text file (.bpt) on its own: one surface per patch.
 *
 * The .bpt format: the number of patches, then for each patch a line "du dv" and
 * (du+1)(dv+1) control points "x y z", u fastest. Any whitespace (tabs, CR LF) and C number
 * syntax (exponent notation) are accepted. The output is that of vtkPatchSceneReader
 * (Documentation/Pipeline.md#reader
 * ), every patch with the material "default" (white diffuse, reflectance 0.8) and all
 * patches named after the file.
 */
#ifndef vtkBPTReader_h
#define vtkBPTReader_h

#include "SphericalCoverReadersModule.h" // for export macro
#include "vtkPatchSceneReader.h"

class SPHERICALCOVERREADERS_EXPORT vtkBPTReader : public vtkPatchSceneReader
{
public:
  static vtkBPTReader* New();
  vtkTypeMacro(vtkBPTReader, vtkPatchSceneReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkBPTReader();
  ~vtkBPTReader() override;

  sphcover::Scene LoadFile(const std::string& fileName) override;

private:
  vtkBPTReader(const vtkBPTReader&) = delete;
  void operator=(const vtkBPTReader&) = delete;
};

#endif
