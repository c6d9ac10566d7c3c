// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenEXRWriter.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkArrayDispatch.h>
#include <vtkDataArray.h>
#include <vtkDataArrayRange.h>
#include <vtkErrorCode.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfVecAttribute.h>
#include <half.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <random>
#include <set>
#include <sstream>

vtkStandardNewMacro(vtkOpenEXRWriter);

namespace
{
/// Rows of scanlines written per OpenEXR call: the granularity of progress and abort.
constexpr int RowsPerBlock = 64;

/// One EXR channel and the component of the VTK array it is taken from.
struct ChannelSource
{
  std::string Channel;
  vtkDataArray* Array;
  int Component;
  Imf::PixelType Type;
  /// The renderer's `Depth` written as OpenEXR's `Z`: its "no surface" marker (negative, -1)
  /// becomes +infinity, OpenEXR's depth of a pixel that sees nothing.
  bool DepthToZ = false;
};

/// OpenEXR's name of the depth channel (the distance from the viewer).
constexpr const char* ZChannel = "Z";

/// Copies one component of a float or double array into a plane of floats in EXR scanline
/// order (rows flipped: VTK's y points up, EXR's down). float -> float is a copy, so the
/// file holds the array's bits (denormals, infinities, NaN payloads included).
struct CopyComponentFlipped
{
  template<typename ArrayT>
  void operator()(ArrayT* array, int component, int width, int height, float* plane) const
  {
    const auto tuples = vtk::DataArrayTupleRange(array);
    for (int j = 0; j < height; ++j)
    {
      float* row = plane + static_cast<std::size_t>(height - 1 - j) * width;
      const vtkIdType first = static_cast<vtkIdType>(j) * width;
      for (int i = 0; i < width; ++i)
      {
        row[i] = static_cast<float>(tuples[first + i][component]);
      }
    }
  }
};

/// A name next to `fileName` (same folder, so the final rename is atomic) that no other
/// writer picks: the file name plus a random suffix.
std::string TemporaryName(const std::string& fileName)
{
  std::random_device entropy;
  std::ostringstream name;
  name << fileName << ".tmp" << std::hex << entropy() << entropy();
  return name.str();
}

/// Removes `path` if it exists, ignoring errors (used to clean up after a failure).
void RemoveQuietly(const std::string& path)
{
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

/// The problem with the input image for an EXR file (empty when there is none): an empty
/// extent, or a 3-D one (a file holds one XY slice).
std::string ImageProblem(const int extent[6])
{
  if (extent[0] > extent[1] || extent[2] > extent[3] || extent[4] > extent[5])
  {
    return "the input image is empty";
  }
  if (extent[4] != extent[5])
  {
    std::ostringstream problem;
    problem << "the input image is 3-D (z extent " << extent[4] << ".." << extent[5]
            << "); an EXR file holds one XY slice";
    return problem.str();
  }
  return std::string();
}

/// Adds the channels of the point array `name` (`role` in messages): R, G, B of a 3-component
/// colour array (in `colorType`), or one FLOAT channel named after a 1-component array. Returns
/// the problem (empty when there is none): a missing array, the wrong number of components, a
/// type other than float or double, or a channel written twice.
std::string AddArrayChannels(vtkPointData* pointData,
  const std::string& name,
  int components,
  const char* role,
  Imf::PixelType colorType,
  std::vector<ChannelSource>& channels,
  std::set<std::string>& channelNames)
{
  vtkDataArray* array = pointData->GetArray(name.c_str());
  std::ostringstream problem;
  if (name.empty())
  {
    problem << "an empty array name was given as " << role;
  }
  else if (!array)
  {
    problem << "the input has no point array '" << name << "' (" << role << ")";
  }
  else if (array->GetNumberOfComponents() != components)
  {
    problem << "the point array '" << name << "' (" << role << ") has "
            << array->GetNumberOfComponents() << " components, not " << components;
  }
  else if (array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE)
  {
    problem << "the point array '" << name << "' (" << role << ") holds "
            << array->GetDataTypeAsString() << " values, not float or double";
  }
  if (!problem.str().empty())
  {
    return problem.str();
  }
  if (components == 3)
  {
    const char* rgb[3] = { "R", "G", "B" };
    for (int c = 0; c < 3; ++c)
    {
      channels.push_back({ rgb[c], array, c, colorType });
      channelNames.insert(rgb[c]);
    }
    return std::string();
  }
  const bool depth = name == vtkSphericalCoverArrayNames::Depth;
  const std::string channel = depth ? ZChannel : name;
  if (!channelNames.insert(channel).second)
  {
    return "the channel '" + channel + "' is written twice";
  }
  channels.push_back({ channel, array, 0, Imf::FLOAT, depth });
  return std::string();
}

/// The channels: R, G, B from the colour array, then the extra single-component arrays.
/// Returns the first problem (empty when there is none).
std::string CollectChannels(vtkPointData* pointData,
  const std::string& colorArrayName,
  const std::vector<std::string>& channelArrays,
  Imf::PixelType colorType,
  std::vector<ChannelSource>& channels)
{
  std::set<std::string> channelNames;
  std::string problem = AddArrayChannels(
    pointData, colorArrayName, 3, "colour array", colorType, channels, channelNames);
  for (std::size_t a = 0; problem.empty() && a < channelArrays.size(); ++a)
  {
    problem = AddArrayChannels(
      pointData, channelArrays[a], 1, "extra channel", colorType, channels, channelNames);
  }
  return problem;
}

/// Planes of floats in EXR order, one per channel; HALF channels get a rounded copy instead
/// (OpenEXR's output file does not convert between the frame buffer's and the file's pixel
/// types). Throws std::bad_alloc when memory runs out.
void CopyPlanes(const std::vector<ChannelSource>& channels,
  int width,
  int height,
  std::vector<std::vector<float>>& planes,
  std::vector<std::vector<Imath::half>>& halfPlanes)
{
  for (std::size_t k = 0; k < channels.size(); ++k)
  {
    planes[k].resize(static_cast<std::size_t>(width) * height);
    if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>::Execute(channels[k].Array,
          CopyComponentFlipped{},
          channels[k].Component,
          width,
          height,
          planes[k].data()))
    {
      CopyComponentFlipped{}(
        channels[k].Array, channels[k].Component, width, height, planes[k].data());
    }
    if (channels[k].DepthToZ)
    {
      for (float& z : planes[k])
      {
        if (z < 0.0f)
        {
          z = std::numeric_limits<float>::infinity();
        }
      }
    }
    if (channels[k].Type == Imf::HALF)
    {
      halfPlanes[k].assign(planes[k].begin(), planes[k].end());
      std::vector<float>().swap(planes[k]);
    }
  }
}

/// The file's header: the image's extent as data window (EXR's y grows downwards, so
/// scanline y holds VTK row ymin + ymax - y), the compression, the vtkOrigin and vtkSpacing
/// attributes and the channels.
Imf::Header MakeHeader(vtkImageData* input,
  const int extent[6],
  int compression,
  const std::vector<ChannelSource>& channels)
{
  const Imath::Box2i window(Imath::V2i(extent[0], extent[2]), Imath::V2i(extent[1], extent[3]));
  Imf::Header header(window, window);
  header.compression() = static_cast<Imf::Compression>(compression);
  double origin[3];
  double spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  // The slice's z index moves into the origin: the file has no z extent.
  const double sliceZ = origin[2] + extent[4] * spacing[2];
  header.insert("vtkOrigin", Imf::V3dAttribute(Imath::V3d(origin[0], origin[1], sliceZ)));
  header.insert("vtkSpacing", Imf::V3dAttribute(Imath::V3d(spacing[0], spacing[1], spacing[2])));
  for (const ChannelSource& channel : channels)
  {
    header.channels().insert(channel.Channel, Imf::Channel(channel.Type));
  }
  return header;
}

/// The frame buffer OpenEXR reads the planes from, over the header's data window.
Imf::FrameBuffer MakeFrameBuffer(const Imath::Box2i& window,
  const std::vector<ChannelSource>& channels,
  std::vector<std::vector<float>>& planes,
  std::vector<std::vector<Imath::half>>& halfPlanes)
{
  Imf::FrameBuffer frameBuffer;
  for (std::size_t k = 0; k < channels.size(); ++k)
  {
    frameBuffer.insert(channels[k].Channel,
      channels[k].Type == Imf::HALF ? Imf::Slice::Make(Imf::HALF, halfPlanes[k].data(), window)
                                    : Imf::Slice::Make(Imf::FLOAT, planes[k].data(), window));
  }
  return frameBuffer;
}

/// Writes the scanlines to `path`, RowsPerBlock at a time with the writer's progress, until
/// all are written or the writer is aborted. Throws what OpenEXR throws.
void WriteScanlines(vtkAlgorithm* writer,
  const std::string& path,
  const Imf::Header& header,
  const Imf::FrameBuffer& frameBuffer,
  int height)
{
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frameBuffer);
  for (int written = 0; written < height;)
  {
    if (writer->GetAbortExecute())
    {
      break;
    }
    const int rows = std::min(RowsPerBlock, height - written);
    file.writePixels(rows);
    written += rows;
    writer->UpdateProgress(static_cast<double>(written) / height);
  }
}
}

vtkOpenEXRWriter::vtkOpenEXRWriter()
  : ColorArrayName("Radiance")
  , PixelType(Float)
  , Compression(ZIPCompression)
{
}

vtkOpenEXRWriter::~vtkOpenEXRWriter() = default;

void vtkOpenEXRWriter::AddChannelArray(const char* arrayName)
{
  this->ChannelArrays.emplace_back(arrayName ? arrayName : "");
  this->Modified();
}

void vtkOpenEXRWriter::RemoveAllChannelArrays()
{
  if (!this->ChannelArrays.empty())
  {
    this->ChannelArrays.clear();
    this->Modified();
  }
}

int vtkOpenEXRWriter::GetNumberOfChannelArrays() const
{
  return static_cast<int>(this->ChannelArrays.size());
}

const char* vtkOpenEXRWriter::GetChannelArray(int index) const
{
  if (index < 0 || index >= this->GetNumberOfChannelArrays())
  {
    return nullptr;
  }
  return this->ChannelArrays[index].c_str();
}

vtkImageData* vtkOpenEXRWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

int vtkOpenEXRWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

void vtkOpenEXRWriter::WriteData()
{
  // One message per failure, naming the file; the error code makes Write() return 0.
  auto fail = [this](unsigned long code, const std::string& problem)
  {
    vtkErrorMacro(<< "Cannot write OpenEXR file '" << this->FileName << "': " << problem);
    this->SetErrorCode(code);
  };
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName set: cannot write an OpenEXR file.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  vtkImageData* input = this->GetInput();
  if (!input)
  {
    fail(vtkErrorCode::UserError, "no input image");
    return;
  }
  int extent[6];
  input->GetExtent(extent);
  const std::string imageProblem = ImageProblem(extent);
  if (!imageProblem.empty())
  {
    fail(vtkErrorCode::UserError, imageProblem);
    return;
  }
  const int width = extent[1] - extent[0] + 1;
  const int height = extent[3] - extent[2] + 1;

  std::vector<ChannelSource> channels;
  const std::string channelProblem = CollectChannels(input->GetPointData(),
    this->ColorArrayName,
    this->ChannelArrays,
    this->PixelType == Half ? Imf::HALF : Imf::FLOAT,
    channels);
  if (!channelProblem.empty())
  {
    fail(vtkErrorCode::UserError, channelProblem);
    return;
  }

  std::vector<std::vector<float>> planes(channels.size());
  std::vector<std::vector<Imath::half>> halfPlanes(channels.size());
  try
  {
    CopyPlanes(channels, width, height, planes, halfPlanes);
  }
  catch (const std::bad_alloc&)
  {
    fail(vtkErrorCode::OutOfDiskSpaceError,
      "not enough memory for a " + std::to_string(width) + " x " + std::to_string(height) +
        " image");
    return;
  }
  const Imf::Header header = MakeHeader(input, extent, this->Compression, channels);
  const Imf::FrameBuffer frameBuffer =
    MakeFrameBuffer(header.dataWindow(), channels, planes, halfPlanes);

  const std::string temporary = TemporaryName(this->FileName);
  try
  {
    WriteScanlines(this, temporary, header, frameBuffer, height);
    if (this->GetAbortExecute())
    {
      // Aborted by the user: no message, but no file either and Write() returns 0.
      RemoveQuietly(temporary);
      this->SetErrorCode(vtkErrorCode::UserError);
      return;
    }
    std::filesystem::rename(temporary, this->FileName);
  }
  catch (const std::exception& e)
  {
    RemoveQuietly(temporary);
    fail(vtkErrorCode::CannotOpenFileError, e.what());
  }
  catch (...)
  {
    RemoveQuietly(temporary);
    fail(vtkErrorCode::UnknownError, "unknown error");
  }
}

void vtkOpenEXRWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "ColorArrayName: " << this->ColorArrayName << "\n";
  os << indent << "ChannelArrays:";
  for (const std::string& name : this->ChannelArrays)
  {
    os << " " << name;
  }
  os << "\n";
  os << indent << "PixelType: " << (this->PixelType == Half ? "Half" : "Float") << "\n";
  os << indent << "Compression: " << this->Compression << "\n";
}
