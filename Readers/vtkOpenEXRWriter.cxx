// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenEXRWriter.h"

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
};

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
  if (extent[0] > extent[1] || extent[2] > extent[3] || extent[4] > extent[5])
  {
    fail(vtkErrorCode::UserError, "the input image is empty");
    return;
  }
  if (extent[4] != extent[5])
  {
    std::ostringstream problem;
    problem << "the input image is 3-D (z extent " << extent[4] << ".." << extent[5]
            << "); an EXR file holds one XY slice";
    fail(vtkErrorCode::UserError, problem.str());
    return;
  }
  const int width = extent[1] - extent[0] + 1;
  const int height = extent[3] - extent[2] + 1;

  // The channels: R, G, B from the colour array, then the extra single-component arrays.
  std::vector<ChannelSource> channels;
  std::set<std::string> channelNames;
  auto addArray = [&](const std::string& name, int components, const char* role) -> bool
  {
    vtkDataArray* array = input->GetPointData()->GetArray(name.c_str());
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
      fail(vtkErrorCode::UserError, problem.str());
      return false;
    }
    if (components == 3)
    {
      const Imf::PixelType type = this->PixelType == Half ? Imf::HALF : Imf::FLOAT;
      const char* rgb[3] = { "R", "G", "B" };
      for (int c = 0; c < 3; ++c)
      {
        channels.push_back({ rgb[c], array, c, type });
        channelNames.insert(rgb[c]);
      }
      return true;
    }
    if (!channelNames.insert(name).second)
    {
      fail(vtkErrorCode::UserError, "the channel '" + name + "' is written twice");
      return false;
    }
    channels.push_back({ name, array, 0, Imf::FLOAT });
    return true;
  };
  if (!addArray(this->ColorArrayName, 3, "colour array"))
  {
    return;
  }
  for (const std::string& name : this->ChannelArrays)
  {
    if (!addArray(name, 1, "extra channel"))
    {
      return;
    }
  }

  // Planes of floats in EXR order; HALF channels get a rounded copy (OpenEXR's output file
  // does not convert between the frame buffer's and the file's pixel types).
  std::vector<std::vector<float>> planes(channels.size());
  std::vector<std::vector<Imath::half>> halfPlanes(channels.size());
  try
  {
    for (std::size_t k = 0; k < channels.size(); ++k)
    {
      planes[k].resize(static_cast<std::size_t>(width) * height);
      if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>::Execute(
            channels[k].Array,
            CopyComponentFlipped{},
            channels[k].Component,
            width,
            height,
            planes[k].data()))
      {
        CopyComponentFlipped{}(
          channels[k].Array, channels[k].Component, width, height, planes[k].data());
      }
      if (channels[k].Type == Imf::HALF)
      {
        halfPlanes[k].assign(planes[k].begin(), planes[k].end());
        std::vector<float>().swap(planes[k]);
      }
    }
  }
  catch (const std::bad_alloc&)
  {
    fail(vtkErrorCode::OutOfDiskSpaceError,
      "not enough memory for a " + std::to_string(width) + " x " + std::to_string(height) +
        " image");
    return;
  }

  // EXR's y grows downwards; the data window keeps the image's extent (so non-zero extent
  // origins survive) and scanline y holds VTK row ymin + ymax - y.
  const Imath::Box2i window(Imath::V2i(extent[0], extent[2]), Imath::V2i(extent[1], extent[3]));
  Imf::Header header(window, window);
  header.compression() = static_cast<Imf::Compression>(this->Compression);
  double origin[3];
  double spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  // The slice's z index moves into the origin: the file has no z extent.
  const double sliceZ = origin[2] + extent[4] * spacing[2];
  header.insert("vtkOrigin", Imf::V3dAttribute(Imath::V3d(origin[0], origin[1], sliceZ)));
  header.insert("vtkSpacing", Imf::V3dAttribute(Imath::V3d(spacing[0], spacing[1], spacing[2])));
  Imf::FrameBuffer frameBuffer;
  for (std::size_t k = 0; k < channels.size(); ++k)
  {
    header.channels().insert(channels[k].Channel, Imf::Channel(channels[k].Type));
    frameBuffer.insert(channels[k].Channel,
      channels[k].Type == Imf::HALF ? Imf::Slice::Make(Imf::HALF, halfPlanes[k].data(), window)
                                    : Imf::Slice::Make(Imf::FLOAT, planes[k].data(), window));
  }

  const std::string temporary = TemporaryName(this->FileName);
  try
  {
    {
      Imf::OutputFile file(temporary.c_str(), header);
      file.setFrameBuffer(frameBuffer);
      for (int written = 0; written < height;)
      {
        if (this->GetAbortExecute())
        {
          break;
        }
        const int rows = std::min(RowsPerBlock, height - written);
        file.writePixels(rows);
        written += rows;
        this->UpdateProgress(static_cast<double>(written) / height);
      }
    }
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
