// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenEXRReader.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkDataObject.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfTileDescription.h>
#include <ImfVecAttribute.h>
#include <ImfVersion.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkOpenEXRReader);

namespace
{
/// Scanlines read per OpenEXR call: the granularity of progress and abort.
constexpr int RowsPerBlock = 64;

/// What the header says about the image, checked before anything is allocated.
struct ImageLayout
{
  Imath::Box2i Window;
  int Width = 0;
  int Height = 0;
  /// All of R, G and B exist: they form `Radiance`.
  bool HasColor = false;
  /// The channels that become arrays of their own (all but R, G, B when HasColor).
  std::vector<std::string> OtherChannels;
  /// The channel `Z` (OpenEXR's depth) becomes the array `Depth`, the renderer's name: the
  /// file has `Z` and no channel `Depth` (files written before `Z` have `Depth`, read as is).
  bool ZAsDepth = false;
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
};

/// Throws std::runtime_error for an empty data window or one beyond `maximumPixels`.
void CheckWindowSize(long long width, long long height, vtkIdType maximumPixels)
{
  if (width <= 0 || height <= 0)
  {
    throw std::runtime_error("the data window is empty");
  }
  // width > M / height is width * height > M for positive integers, without the product,
  // which overflows for two 2^32-wide extents of a crafted header.
  if (width > maximumPixels / height)
  {
    std::ostringstream problem;
    problem << "the data window (" << width << " x " << height << " pixels) exceeds the limit of "
            << maximumPixels << " pixels (MaximumPixels)";
    throw std::runtime_error(problem.str());
  }
}

std::int32_t LittleEndian32(const unsigned char* bytes)
{
  return static_cast<std::int32_t>(
    bytes[0] | (bytes[1] << 8) | (bytes[2] << 16) | (static_cast<std::uint32_t>(bytes[3]) << 24));
}

/// The bytes OpenEXR 3.1 reads for a value of a fixed-size attribute type; 0 for the others.
int FixedAttributeSize(const std::string& type)
{
  static const std::map<std::string, int> sizes = { { "box2i", 16 },
    { "box2f", 16 },
    { "chromaticities", 32 },
    { "compression", 1 },
    { "deepImageState", 1 },
    { "double", 8 },
    { "envmap", 1 },
    { "float", 4 },
    { "int", 4 },
    { "keycode", 28 },
    { "lineOrder", 1 },
    { "m33f", 36 },
    { "m33d", 72 },
    { "m44f", 64 },
    { "m44d", 128 },
    { "rational", 8 },
    { "tiledesc", 9 },
    { "timecode", 8 },
    { "v2i", 8 },
    { "v2f", 8 },
    { "v2d", 16 },
    { "v3i", 12 },
    { "v3f", 12 },
    { "v3d", 24 } };
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

/// Reads a NUL-terminated attribute or type name; false where the file stops first or the
/// name is longer than OpenEXR allows.
bool ReadName(std::istream& in, std::string& name)
{
  constexpr std::size_t MaximumNameLength = 256; // with the "long names" flag; 32 without
  name.clear();
  char c = 0;
  while (in.get(c) && c != '\0')
  {
    if (name.size() == MaximumNameLength)
    {
      return false;
    }
    name.push_back(c);
  }
  return static_cast<bool>(in);
}

[[noreturn]] void ThrowCorruptAttribute(const std::string& name,
  const std::string& type,
  const std::string& problem)
{
  throw std::runtime_error(
    "corrupt header: the attribute '" + name + "' (" + type + ") " + problem);
}

/// The bytes OpenEXR 3.1 consumes for the value of a `type` attribute that starts at
/// `valueStart` (read from `in`, `left` bytes before the file's end), in `holds`: -1 where it
/// reads exactly the declared size. False where the file stops inside the value (left to
/// OpenEXR's own message).
bool ValueBytes(std::istream& in,
  const std::string& type,
  std::streamoff valueStart,
  std::int64_t left,
  std::int64_t& holds)
{
  holds = FixedAttributeSize(type);
  if (holds == 0 && type == "chlist")
  {
    // Channels (name, 16 bytes) up to an empty name.
    std::string channel;
    while (ReadName(in, channel) && !channel.empty() && in.seekg(16, std::ios::cur))
    {
    }
    if (!in)
    {
      return false;
    }
    holds = static_cast<std::int64_t>(in.tellg() - valueStart);
  }
  else if (holds == 0 && type == "preview")
  {
    unsigned char dimensions[8];
    if (!in.read(reinterpret_cast<char*>(dimensions), 8))
    {
      return false;
    }
    const std::uint64_t width = static_cast<std::uint32_t>(LittleEndian32(dimensions));
    const std::uint64_t height = static_cast<std::uint32_t>(LittleEndian32(dimensions + 4));
    // 4 bytes per pixel; a product beyond the file cannot match (and must not wrap).
    holds = width != 0 && height > static_cast<std::uint64_t>(left) / width
      ? left + 1
      : static_cast<std::int64_t>(8 + 4 * width * height);
  }
  else if (holds == 0)
  {
    holds = -1;
  }
  return true;
}

/// Reads a dataWindow value (min.x, min.y, max.x, max.y) and checks it against
/// `maximumPixels`; false where the file stops inside it. An inverted window is left to
/// OpenEXR's message.
bool CheckDataWindowValue(std::istream& in, vtkIdType maximumPixels)
{
  unsigned char box[16];
  if (!in.read(reinterpret_cast<char*>(box), 16))
  {
    return false;
  }
  const long long width = static_cast<long long>(LittleEndian32(box + 8)) - LittleEndian32(box) + 1;
  const long long height =
    static_cast<long long>(LittleEndian32(box + 12)) - LittleEndian32(box + 4) + 1;
  if (width > 0 && height > 0)
  {
    CheckWindowSize(width, height, maximumPixels);
  }
  return true;
}

/**
 * Walks the attributes of the header(s) that follow the magic number and version field as
 * OpenEXR 3.1 reads them, and throws std::runtime_error for one whose declared size exceeds
 * the rest of the file or differs from what its value holds (a channel list, a fixed-size
 * value, a preview image). OpenEXR allocates and fills what a string, opaque or preview
 * attribute declares before reading it, and reads a channel list or a fixed-size value by its
 * content, not its declared size (after a wrong one it reads the next attribute from the wrong
 * place): 610- and 918-byte files found by FuzzOpenEXRReader made every InputFile cost 1.7 GB
 * and seconds (Testing/Data/bad/fuzz/exr_attribute_size_beyond_file.exr,
 * exr_channel_list_shorter_than_declared.exr). In a valid file every declared size is exact.
 * Anything else wrong with the header (a name that does not end, a file that stops) is left to
 * OpenEXR's own message. The first header's data window is checked against `maximumPixels`
 * here too: OpenEXR's InputFile allocates line buffers as wide as the window before the reader
 * sees the header.
 */
void CheckAttributeSizes(std::istream& in,
  std::streamoff fileSize,
  bool multiPart,
  vtkIdType maximumPixels)
{
  std::string name;
  std::string type;
  bool firstHeader = true;
  while (ReadName(in, name))
  {
    if (name.empty()) // the end of a header
    {
      if (!multiPart || in.peek() == 0 || in.peek() == EOF) // no more headers
      {
        return;
      }
      firstHeader = false;
      continue;
    }
    unsigned char size[4];
    if (!ReadName(in, type) || !in.read(reinterpret_cast<char*>(size), 4))
    {
      return;
    }
    const std::int64_t declared = LittleEndian32(size);
    const std::streamoff valueStart = in.tellg();
    const std::int64_t left = fileSize - static_cast<std::int64_t>(valueStart);
    if (declared < 0 || declared > left)
    {
      ThrowCorruptAttribute(name,
        type,
        "claims " + std::to_string(declared) + " bytes, more than the " + std::to_string(left) +
          " left in the file");
    }
    // What OpenEXR will consume for this value; -1 where it reads exactly the declared size.
    std::int64_t holds = 0;
    if (!ValueBytes(in, type, valueStart, left, holds))
    {
      return;
    }
    if (holds >= 0 && holds != declared)
    {
      ThrowCorruptAttribute(name,
        type,
        "declares " + std::to_string(declared) + " bytes but its value holds " +
          std::to_string(holds));
    }
    in.seekg(valueStart);
    if (firstHeader && name == "dataWindow" && type == "box2i" &&
      CheckDataWindowValue(in, maximumPixels))
    {
      continue;
    }
    in.seekg(declared, std::ios::cur);
  }
}

/// Throws std::runtime_error unless the file exists, is not empty, starts with the EXR
/// magic number, no header attribute claims more bytes than the file has and the data window
/// is within `maximumPixels`: these cases get plainer messages than OpenEXR's, and before
/// OpenEXR allocates anything.
void CheckFileStart(const std::string& fileName, vtkIdType maximumPixels)
{
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    throw std::runtime_error("cannot open the file (missing or unreadable)");
  }
  char magic[4] = { 0, 0, 0, 0 };
  in.read(magic, 4);
  if (in.gcount() == 0)
  {
    throw std::runtime_error("the file is empty");
  }
  if (in.gcount() < 4 || !Imf::isImfMagic(magic))
  {
    throw std::runtime_error(
      "not an OpenEXR file (it does not start with the magic number 76 2f 31 01)");
  }
  unsigned char version[4];
  if (in.read(reinterpret_cast<char*>(version), 4))
  {
    in.seekg(0, std::ios::end);
    const std::streamoff fileSize = in.tellg();
    in.seekg(8);
    const bool multiPart = (version[1] & 0x10) != 0; // the multi-part flag
    CheckAttributeSizes(in, fileSize, multiPart, maximumPixels);
  }
}

/// Reads the layout from a header; throws std::runtime_error for what this reader refuses.
ImageLayout ReadLayout(const Imf::Header& header, vtkIdType maximumPixels)
{
  ImageLayout layout;
  layout.Window = header.dataWindow();
  const Imath::Box2i& window = layout.Window;
  const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
  const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
  CheckWindowSize(width, height, maximumPixels);
  layout.Width = static_cast<int>(width);
  layout.Height = static_cast<int>(height);
  if (header.hasTileDescription())
  {
    // OpenEXR reads a tiled file through a buffer of whole tiles: a tile far larger than the
    // image (a damaged tile description) would allocate gigabytes for a few pixels.
    const Imf::TileDescription& tile = header.tileDescription();
    const long long tileWidth = std::max<long long>(width, 1024);
    const long long tileHeight = std::max<long long>(height, 1024);
    if (tile.xSize > tileWidth || tile.ySize > tileHeight)
    {
      throw std::runtime_error("its tiles of " + std::to_string(tile.xSize) + " x " +
        std::to_string(tile.ySize) + " pixels are larger than the image (" + std::to_string(width) +
        " x " + std::to_string(height) + ") and 1024 x 1024");
    }
  }

  const Imf::ChannelList& channels = header.channels();
  if (channels.begin() == channels.end())
  {
    throw std::runtime_error("the file has no channels");
  }
  layout.HasColor =
    channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
  for (auto it = channels.begin(); it != channels.end(); ++it)
  {
    const std::string name = it.name();
    if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
    {
      throw std::runtime_error(
        "the channel '" + name + "' is sub-sampled; only full-resolution channels are supported");
    }
    if (!(layout.HasColor && (name == "R" || name == "G" || name == "B")))
    {
      layout.OtherChannels.push_back(name);
    }
  }

  layout.ZAsDepth =
    channels.findChannel("Z") && !channels.findChannel(vtkSphericalCoverArrayNames::Depth);

  // The writer's geometry attributes; absent in files from other tools.
  if (const auto* origin = header.findTypedAttribute<Imf::V3dAttribute>("vtkOrigin"))
  {
    const Imath::V3d& o = origin->value();
    if (std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z))
    {
      layout.Origin[0] = o.x;
      layout.Origin[1] = o.y;
      layout.Origin[2] = o.z;
    }
  }
  if (const auto* spacing = header.findTypedAttribute<Imf::V3dAttribute>("vtkSpacing"))
  {
    const Imath::V3d& s = spacing->value();
    if (std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z))
    {
      layout.Spacing[0] = s.x;
      layout.Spacing[1] = s.y;
      layout.Spacing[2] = s.z;
    }
  }
  return layout;
}

/// A float array of `tuples` x `components` values, allocated here so that a failed
/// allocation is an error (std::runtime_error) rather than VTK's: vtkFloatArray reports it and
/// goes on with no buffer, where OpenEXR then writes the pixels (a crash on a small file whose
/// header claims a large image, on a machine or under a limit with less memory than that).
vtkSmartPointer<vtkFloatArray> NewFloatArray(const std::string& name,
  int components,
  vtkIdType tuples)
{
  const std::size_t values = static_cast<std::size_t>(components) * tuples;
  float* buffer = static_cast<float*>(std::malloc(values * sizeof(float)));
  if (!buffer)
  {
    std::ostringstream problem;
    problem << "not enough memory for the channel '" << name << "' ("
            << (values * sizeof(float) + (1 << 20) - 1) / (1 << 20) << " MiB)";
    throw std::runtime_error(problem.str());
  }
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(components);
  array->SetArray(buffer, static_cast<vtkIdType>(values), 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  return array;
}

/// Allocates the arrays the channels are read into (`radiance` from R, G, B when the layout
/// has colour, one array per other channel) and returns the frame buffer over them: OpenEXR
/// writes straight into the arrays (converting half and uint to float) in EXR scanline order;
/// the rows are flipped afterwards.
Imf::FrameBuffer NewArraysFrameBuffer(const ImageLayout& layout,
  vtkIdType pixels,
  vtkSmartPointer<vtkFloatArray>& radiance,
  std::vector<vtkSmartPointer<vtkFloatArray>>& others)
{
  Imf::FrameBuffer frameBuffer;
  if (layout.HasColor)
  {
    radiance = NewFloatArray("Radiance", 3, pixels);
    const char* rgb[3] = { "R", "G", "B" };
    for (int c = 0; c < 3; ++c)
    {
      frameBuffer.insert(rgb[c],
        Imf::Slice::Make(Imf::FLOAT,
          radiance->GetPointer(c),
          layout.Window,
          3 * sizeof(float),
          3 * sizeof(float) * layout.Width));
    }
  }
  for (const std::string& name : layout.OtherChannels)
  {
    const bool depth = layout.ZAsDepth && name == "Z";
    vtkSmartPointer<vtkFloatArray> array =
      NewFloatArray(depth ? vtkSphericalCoverArrayNames::Depth : name, 1, pixels);
    frameBuffer.insert(name, Imf::Slice::Make(Imf::FLOAT, array->GetPointer(0), layout.Window));
    others.push_back(array);
  }
  return frameBuffer;
}

/// Reverses the order of the rows of an array of `height` rows of `rowValues` floats.
void FlipRows(float* values, int height, std::size_t rowValues)
{
  for (int j = 0; j < height / 2; ++j)
  {
    float* top = values + j * rowValues;
    float* bottom = values + (height - 1 - j) * rowValues;
    std::swap_ranges(top, top + rowValues, bottom);
  }
}
}

vtkOpenEXRReader::vtkOpenEXRReader()
  : MaximumPixels(vtkIdType(1) << 28)
{
  this->SetNumberOfInputPorts(0);
}

vtkOpenEXRReader::~vtkOpenEXRReader() = default;

int vtkOpenEXRReader::CanReadFile(const char* fileName)
{
  if (!fileName)
  {
    return 0;
  }
  try
  {
    // Any window size: a file beyond MaximumPixels is still this reader's to refuse clearly.
    CheckFileStart(fileName, VTK_ID_MAX);
    Imf::InputFile file(fileName);
    return 3;
  }
  catch (...)
  {
    return 0;
  }
}

int vtkOpenEXRReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // An unreadable file is reported once, by RequestData: ParaView asks for the data even
  // after a failed information request, which would repeat the message. Here it only gets
  // an empty extent.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0, -1, 0, -1, 0, 0 };
  double origin[3] = { 0, 0, 0 };
  double spacing[3] = { 1, 1, 1 };
  try
  {
    if (!this->FileName.empty())
    {
      CheckFileStart(this->FileName, this->MaximumPixels);
      Imf::InputFile file(this->FileName.c_str());
      const ImageLayout layout = ReadLayout(file.header(), this->MaximumPixels);
      extent[0] = layout.Window.min.x;
      extent[1] = layout.Window.max.x;
      extent[2] = layout.Window.min.y;
      extent[3] = layout.Window.max.y;
      std::copy(layout.Origin, layout.Origin + 3, origin);
      std::copy(layout.Spacing, layout.Spacing + 3, spacing);
      if (layout.HasColor)
      {
        vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 3);
      }
    }
  }
  catch (...)
  {
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  return 1;
}

int vtkOpenEXRReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->Initialize();
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName set: cannot read an OpenEXR file.");
    return 0;
  }
  try
  {
    // Opened again: the file may have changed since RequestInformation.
    CheckFileStart(this->FileName, this->MaximumPixels);
    Imf::InputFile file(this->FileName.c_str());
    const ImageLayout layout = ReadLayout(file.header(), this->MaximumPixels);
    if (!file.isComplete())
    {
      throw std::runtime_error("the file is incomplete (truncated?): scanlines are missing");
    }
    const vtkIdType pixels = static_cast<vtkIdType>(layout.Width) * layout.Height;

    vtkSmartPointer<vtkFloatArray> radiance;
    std::vector<vtkSmartPointer<vtkFloatArray>> others;
    file.setFrameBuffer(NewArraysFrameBuffer(layout, pixels, radiance, others));
    for (int y = layout.Window.min.y; y <= layout.Window.max.y; y += RowsPerBlock)
    {
      if (this->GetAbortExecute())
      {
        output->Initialize();
        return 1;
      }
      file.readPixels(y, std::min(y + RowsPerBlock - 1, layout.Window.max.y));
      this->UpdateProgress(static_cast<double>(y - layout.Window.min.y + 1) / layout.Height);
    }

    output->SetExtent(
      layout.Window.min.x, layout.Window.max.x, layout.Window.min.y, layout.Window.max.y, 0, 0);
    output->SetOrigin(layout.Origin);
    output->SetSpacing(layout.Spacing);
    if (layout.HasColor)
    {
      FlipRows(radiance->GetPointer(0), layout.Height, 3 * static_cast<std::size_t>(layout.Width));
      output->GetPointData()->SetScalars(radiance);
    }
    for (vtkFloatArray* array : others)
    {
      FlipRows(array->GetPointer(0), layout.Height, layout.Width);
      if (layout.ZAsDepth && std::string(array->GetName()) == vtkSphericalCoverArrayNames::Depth)
      {
        // OpenEXR's +infinity (nothing seen) is the renderer's -1: the same image as the
        // Radiance Image filter gives, and finite ranges for colour maps.
        float* z = array->GetPointer(0);
        for (vtkIdType k = 0; k < pixels; ++k)
        {
          if (z[k] == std::numeric_limits<float>::infinity())
          {
            z[k] = -1.0f;
          }
        }
      }
      output->GetPointData()->AddArray(array);
    }
    return 1;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Cannot read OpenEXR file '" << this->FileName << "': " << e.what());
  }
  catch (...)
  {
    vtkErrorMacro(<< "Cannot read OpenEXR file '" << this->FileName << "': unknown error");
  }
  output->Initialize();
  return 0;
}

void vtkOpenEXRReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "MaximumPixels: " << this->MaximumPixels << "\n";
}
