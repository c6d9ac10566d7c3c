// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkOpenEXRWriter
 * @brief Writes a 2-D vtkImageData as an OpenEXR file: a 3-component point array as the
 * channels R, G, B (32-bit float, or half) plus optional single-component arrays as extra
 * channels (Documentation/Pipeline.md#rendering: the HDR image of the rendered radiance, paper
 * §5.3).
 *
 * Radiance is a physical quantity spanning orders of magnitude (emitters next to dark
 * corners), so it is stored in floating point, not tone-mapped: OpenEXR is the standard
 * container for such images and any compositing or viewing tool reads it.
 *
 * Layout of the file:
 * - channels `R`, `G`, `B` from the array named by ColorArrayName (default `Radiance`), each
 *   component one channel; float or double arrays (double is rounded to float);
 * - one extra channel per name given to AddChannelArray(), named like the array, except the
 *   renderer's depth: the array `Depth` (vtkSphericalCoverArrayNames::Depth, the distance
 *   from the eye along the camera ray, -1 where no surface is seen) is written as the channel
 *   `Z`, OpenEXR's name for the depth (distance from the viewer), with +infinity where no
 *   surface is seen (every negative value: the renderer's only negative depth is -1), so that
 *   compositing tools read it as depth; vtkOpenEXRReader reads `Z` back as `Depth` with -1.
 *   Extra channels are always 32-bit float, whatever PixelType says (depth needs float
 *   precision);
 * - data window = display window = the image's x and y extent (non-zero origins kept);
 * - rows flipped so that the image is upright in EXR viewers: VTK's row j (y up) is EXR's
 *   scanline y = ymin + ymax - j (y down);
 * - the image's origin and spacing as the custom attributes `vtkOrigin` and `vtkSpacing`
 *   (v3d), which vtkOpenEXRReader restores (other tools ignore them); the z index of the
 *   slice is folded into the z of the origin.
 *
 * Writing is atomic: the file is written under a temporary name in the same folder and
 * renamed on success, so a failed write (no input, missing or unsuitable array, unwritable
 * folder) leaves no file and no partial file. Failures are reported by vtkErrorMacro, an
 * error code (GetErrorCode()) and a zero return of Write().
 */
#ifndef vtkOpenEXRWriter_h
#define vtkOpenEXRWriter_h

#include "SphericalCoverReadersModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for std::string
#include <vector> // for std::vector

class vtkImageData;

class SPHERICALCOVERREADERS_EXPORT vtkOpenEXRWriter : public vtkWriter
{
public:
  static vtkOpenEXRWriter* New();
  vtkTypeMacro(vtkOpenEXRWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Precision of the R, G, B channels in the file.
  enum PixelTypes
  {
    Half = 0, ///< 16-bit float: 11 significant bits, largest finite value 65504
    Float = 1 ///< 32-bit float: the array's float values bit for bit
  };

  /// OpenEXR's compression methods (the values of Imf::Compression). The first five are
  /// lossless; PXR24 rounds float channels to 24 bits; B44, B44A, DWAA and DWAB are lossy.
  enum Compressions
  {
    NoCompression = 0,
    RLECompression = 1,
    ZIPSCompression = 2, ///< zlib, one scanline per block
    ZIPCompression = 3,  ///< zlib, 16 scanlines per block
    PIZCompression = 4,
    PXR24Compression = 5,
    B44Compression = 6,
    B44ACompression = 7,
    DWAACompression = 8,
    DWABCompression = 9
  };

  ///@{
  /// The file to write (.exr). Default is empty.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The 3-component point array (float or double) written as R, G, B. Default is "Radiance".
  vtkSetStdStringFromCharMacro(ColorArrayName);
  vtkGetCharFromStdStringMacro(ColorArrayName);
  ///@}

  ///@{
  /// Extra single-component point arrays (float or double), each written as a 32-bit float
  /// channel named like the array (`Depth` as `Z`, see above). Default: none.
  void AddChannelArray(const char* arrayName);
  void RemoveAllChannelArrays();
  int GetNumberOfChannelArrays() const;
  const char* GetChannelArray(int index) const;
  ///@}

  ///@{
  /// Precision of R, G, B: Half (0) or Float (1). Default is Float.
  vtkSetClampMacro(PixelType, int, Half, Float);
  vtkGetMacro(PixelType, int);
  void SetPixelTypeToHalf() { this->SetPixelType(Half); }
  void SetPixelTypeToFloat() { this->SetPixelType(Float); }
  ///@}

  ///@{
  /// Compression method, one of Compressions. Default is ZIP (3, lossless).
  vtkSetClampMacro(Compression, int, NoCompression, DWABCompression);
  vtkGetMacro(Compression, int);
  ///@}

  vtkImageData* GetInput();

protected:
  vtkOpenEXRWriter();
  ~vtkOpenEXRWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  std::string ColorArrayName;
  std::vector<std::string> ChannelArrays;
  int PixelType;
  int Compression;

private:
  vtkOpenEXRWriter(const vtkOpenEXRWriter&) = delete;
  void operator=(const vtkOpenEXRWriter&) = delete;
};

#endif
