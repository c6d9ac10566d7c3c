// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkOpenEXRReader
 * @brief Reads an OpenEXR image into a 2-D vtkImageData: R, G, B as the float point array
 * `Radiance` (3 components) and every other channel as a float array of its own name, except
 * OpenEXR's depth channel `Z`: it is read as the array `Depth` (the renderer's name,
 * vtkSphericalCoverArrayNames::Depth) with +infinity (nothing seen) as -1, the inverse of
 * vtkOpenEXRWriter, unless the file also has a channel `Depth` (then both keep their names).
 *
 * The inverse of vtkOpenEXRWriter (Documentation/Pipeline.md#rendering): the extent is the file's
 * data window, rows are flipped back (EXR scanline y is VTK row ymin + ymax - y) and the origin and
 * spacing come from the writer's `vtkOrigin` / `vtkSpacing` attributes (0 and 1 in files from other
 * tools), so a write/read round trip gives the identical image, bit for bit for float data.
 * Half and 32-bit unsigned channels are converted to float. `Radiance` is formed only when
 * all of R, G and B exist; otherwise each of them is an array of its own. `Radiance` is the
 * active scalars. Tiled and multi-part files are read (the first part); deep images and
 * sub-sampled channels are refused.
 *
 * A missing, empty, truncated, corrupt or non-EXR file, or one whose image does not fit in the
 * memory available, gives one error naming the file and the problem, a failed request and an
 * empty output (OpenEXR's exceptions are caught). The error comes from the data request; the
 * information request only reports an empty extent (ParaView requests the data even after a
 * failed information request: no second message).
 */
#ifndef vtkOpenEXRReader_h
#define vtkOpenEXRReader_h

#include "SphericalCoverReadersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string> // for std::string

class SPHERICALCOVERREADERS_EXPORT vtkOpenEXRReader : public vtkImageAlgorithm
{
public:
  static vtkOpenEXRReader* New();
  vtkTypeMacro(vtkOpenEXRReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .exr file to read. Default is empty.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /**
   * 3 if `fileName` starts with OpenEXR's magic number and its header reads, 0 otherwise
   * (vtkImageReader2's convention). Never throws, never reports an error.
   */
  int CanReadFile(const char* fileName);

  /// The file extension this reader handles: ".exr".
  const char* GetFileExtensions() { return ".exr"; }

  /// "OpenEXR".
  const char* GetDescriptiveName() { return "OpenEXR"; }

  /**
   * Largest data window accepted, in pixels (width x height); bigger windows are reported as
   * errors instead of exhausting memory on a corrupt header. Default is 2^28 (16384^2).
   */
  vtkSetClampMacro(MaximumPixels, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumPixels, vtkIdType);

protected:
  vtkOpenEXRReader();
  ~vtkOpenEXRReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  vtkIdType MaximumPixels;

private:
  vtkOpenEXRReader(const vtkOpenEXRReader&) = delete;
  void operator=(const vtkOpenEXRReader&) = delete;
};

#endif
