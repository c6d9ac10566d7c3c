// SPDX-License-Identifier: BSD-3-Clause
// vtkOpenEXRWriter -> vtkOpenEXRReader (Documentation/Pipeline.md#rendering):
// - float data round-trips bit for bit (random bit patterns over the whole float range:
//   denormals, -0, the largest finite values, infinities, a NaN) for every lossless
//   compression, with a non-zero extent origin, origin and spacing, and extra channels;
//   a double extra channel comes back as the double rounded to float;
// - the image is upright in the file: OpenEXR itself (not our reader) finds VTK's top-left
//   pixel at the data window's first scanline, and the header has the data window = extent;
// - half pixels: R, G, B within half precision (relative 2^-11 for normal half values) and
//   actually rounded, while the extra channel stays 32-bit exact;
// - a double colour array is written as its values rounded to float;
// - the renderer's Depth is OpenEXR's Z: the array `Depth` is written as the channel `Z` (no
//   channel `Depth`) with +infinity where it is -1 and its values elsewhere, and read back as
//   the array `Depth` (no `Z`) with -1 there (an array Z next to Depth: TestOpenEXRBadInput).
#include "TestFailures.h"
#include "vtkOpenEXRReader.h"
#include "vtkOpenEXRWriter.h"

#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{
using TestFailures::Check;

float FromBits(std::uint32_t bits)
{
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint32_t ToBits(float value)
{
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

/// Random float bit patterns (every exponent equally likely, so denormals and huge values
/// are frequent) with the special values placed at fixed pixels.
void FillRandomBits(vtkFloatArray* array, std::mt19937& random)
{
  const vtkIdType count = array->GetNumberOfValues();
  for (vtkIdType k = 0; k < count; ++k)
  {
    array->SetValue(k, FromBits(static_cast<std::uint32_t>(random())));
  }
  const float special[] = { std::numeric_limits<float>::denorm_min(),
    -0.0f,
    std::numeric_limits<float>::max(),
    -std::numeric_limits<float>::max(),
    std::numeric_limits<float>::infinity(),
    -std::numeric_limits<float>::infinity(),
    std::numeric_limits<float>::min(),
    FromBits(0x007fffffu),
    1.0f,
    std::numeric_limits<float>::quiet_NaN() };
  for (std::size_t k = 0; k < sizeof special / sizeof special[0] && vtkIdType(k) < count; ++k)
  {
    array->SetValue(static_cast<vtkIdType>(k * 7), special[k]);
  }
}

bool SameBits(vtkDataArray* a, vtkDataArray* b)
{
  auto* fa = vtkFloatArray::SafeDownCast(a);
  auto* fb = vtkFloatArray::SafeDownCast(b);
  return fa && fb && fa->GetNumberOfValues() == fb->GetNumberOfValues() &&
    fa->GetNumberOfComponents() == fb->GetNumberOfComponents() &&
    std::memcmp(fa->GetPointer(0), fb->GetPointer(0), sizeof(float) * fa->GetNumberOfValues()) == 0;
}

/// A 37 x 23 image with extent origin (-5, 7), slice z = 0, Radiance (float, 3), Mask
/// (float), Weight (double).
vtkSmartPointer<vtkImageData> MakeImage(std::mt19937& random)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(-5, 31, 7, 29, 0, 0);
  image->SetOrigin(0.25, -3.5, 2.0);
  image->SetSpacing(0.5, 0.125, 1.0);
  const vtkIdType pixels = image->GetNumberOfPoints();
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(pixels);
  FillRandomBits(radiance, random);
  vtkNew<vtkFloatArray> depth;
  depth->SetName("Mask");
  depth->SetNumberOfTuples(pixels);
  FillRandomBits(depth, random);
  vtkNew<vtkDoubleArray> weight;
  weight->SetName("Weight");
  weight->SetNumberOfTuples(pixels);
  std::uniform_real_distribution<double> uniform(-1e3, 1e3);
  for (vtkIdType k = 0; k < pixels; ++k)
  {
    weight->SetValue(k, uniform(random));
  }
  image->GetPointData()->AddArray(radiance);
  image->GetPointData()->AddArray(depth);
  image->GetPointData()->AddArray(weight);
  return image;
}

vtkImageData* Read(vtkOpenEXRReader* reader, const std::string& file)
{
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}
}

int TestOpenEXRRoundTrip(int, char*[])
{
  const std::filesystem::path folder =
    std::filesystem::path(SPHCOVER_BINARY_DIR) / "Testing" / "Temporary" / "OpenEXRRoundTrip";
  std::filesystem::create_directories(folder);
  std::mt19937 random(20260611u);
  vtkSmartPointer<vtkImageData> image = MakeImage(random);
  auto* radiance = image->GetPointData()->GetArray("Radiance");
  auto* depth = image->GetPointData()->GetArray("Mask");
  auto* weight = vtkDoubleArray::SafeDownCast(image->GetPointData()->GetArray("Weight"));

  // Bit-exact round trip, every lossless compression.
  const int lossless[] = { vtkOpenEXRWriter::NoCompression,
    vtkOpenEXRWriter::RLECompression,
    vtkOpenEXRWriter::ZIPSCompression,
    vtkOpenEXRWriter::ZIPCompression,
    vtkOpenEXRWriter::PIZCompression };
  for (int compression : lossless)
  {
    const std::string what = "compression " + std::to_string(compression);
    const std::string file = (folder / ("float" + std::to_string(compression) + ".exr")).string();
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(file.c_str());
    writer->SetCompression(compression);
    writer->AddChannelArray("Mask");
    writer->AddChannelArray("Weight");
    Check(writer->Write() == 1, what + ": Write failed");

    vtkNew<vtkOpenEXRReader> reader;
    Check(reader->CanReadFile(file.c_str()) == 3, what + ": CanReadFile");
    vtkImageData* output = Read(reader, file);
    int extent[6];
    output->GetExtent(extent);
    Check(extent[0] == -5 && extent[1] == 31 && extent[2] == 7 && extent[3] == 29 &&
        extent[4] == 0 && extent[5] == 0,
      what + ": extent");
    double origin[3];
    double spacing[3];
    output->GetOrigin(origin);
    output->GetSpacing(spacing);
    Check(origin[0] == 0.25 && origin[1] == -3.5 && origin[2] == 2.0, what + ": origin");
    Check(spacing[0] == 0.5 && spacing[1] == 0.125 && spacing[2] == 1.0, what + ": spacing");
    Check(output->GetPointData()->GetNumberOfArrays() == 3, what + ": three arrays");
    Check(output->GetPointData()->GetScalars() &&
        std::string(output->GetPointData()->GetScalars()->GetName()) == "Radiance",
      what + ": Radiance is the active scalars");
    Check(SameBits(output->GetPointData()->GetArray("Radiance"), radiance),
      what + ": Radiance is not bit-exact");
    Check(
      SameBits(output->GetPointData()->GetArray("Mask"), depth), what + ": Mask is not bit-exact");
    auto* weightRead = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("Weight"));
    bool weightRounded =
      weightRead && weightRead->GetNumberOfValues() == weight->GetNumberOfValues();
    for (vtkIdType k = 0; weightRounded && k < weight->GetNumberOfValues(); ++k)
    {
      weightRounded =
        ToBits(weightRead->GetValue(k)) == ToBits(static_cast<float>(weight->GetValue(k)));
    }
    Check(weightRounded, what + ": Weight (double) is not its values rounded to float");
  }

  // Upright in the file, as OpenEXR itself reads it: scanline ymin (the top) is VTK's top row.
  {
    const std::string file = (folder / "float3.exr").string();
    Imf::InputFile exr(file.c_str());
    const Imath::Box2i window = exr.header().dataWindow();
    Check(window.min.x == -5 && window.max.x == 31 && window.min.y == 7 && window.max.y == 29,
      "data window != extent");
    Check(exr.header().displayWindow() == window, "display window != data window");
    Check(exr.header().channels().findChannel("R")->type == Imf::FLOAT, "R is not FLOAT");
    float top[37 * 3];
    Imf::FrameBuffer frameBuffer;
    const char* rgb[3] = { "R", "G", "B" };
    for (int c = 0; c < 3; ++c)
    {
      frameBuffer.insert(rgb[c],
        Imf::Slice::Make(Imf::FLOAT,
          top + c,
          Imath::Box2i(Imath::V2i(-5, 7), Imath::V2i(31, 7)),
          3 * sizeof(float),
          3 * sizeof(float) * 37));
    }
    exr.setFrameBuffer(frameBuffer);
    exr.readPixels(7);
    // VTK's top row is j = 22 (y index 29), tuples 22 * 37 ...
    Check(std::memcmp(
            top, static_cast<vtkFloatArray*>(radiance)->GetPointer(22 * 37 * 3), sizeof top) == 0,
      "the first scanline of the file is not VTK's top row (image not upright)");
  }

  // Half pixels: R, G, B rounded to half; the extra channel stays float.
  {
    vtkNew<vtkImageData> smooth;
    smooth->SetExtent(0, 63, 0, 47, 0, 0);
    vtkNew<vtkFloatArray> values;
    values->SetName("Radiance");
    values->SetNumberOfComponents(3);
    values->SetNumberOfTuples(smooth->GetNumberOfPoints());
    // Log-uniform over the normal half range [2^-14, 2^15].
    std::uniform_real_distribution<float> exponent(-14.0f, 15.0f);
    for (vtkIdType k = 0; k < values->GetNumberOfValues(); ++k)
    {
      values->SetValue(k, std::exp2(exponent(random)));
    }
    smooth->GetPointData()->AddArray(values);
    vtkNew<vtkFloatArray> smoothDepth;
    smoothDepth->SetName("Mask");
    smoothDepth->SetNumberOfTuples(smooth->GetNumberOfPoints());
    FillRandomBits(smoothDepth, random);
    smooth->GetPointData()->AddArray(smoothDepth);

    const std::string file = (folder / "half.exr").string();
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(smooth);
    writer->SetFileName(file.c_str());
    writer->SetPixelTypeToHalf();
    writer->AddChannelArray("Mask");
    Check(writer->Write() == 1, "half: Write failed");
    {
      Imf::InputFile exr(file.c_str());
      Check(exr.header().channels().findChannel("G")->type == Imf::HALF, "half: G is not HALF");
      Check(
        exr.header().channels().findChannel("Mask")->type == Imf::FLOAT, "half: Mask is not FLOAT");
    }
    vtkNew<vtkOpenEXRReader> reader;
    vtkImageData* output = Read(reader, file);
    auto* read = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("Radiance"));
    Check(read && read->GetNumberOfValues() == values->GetNumberOfValues(), "half: Radiance size");
    double worst = 0;
    vtkIdType rounded = 0;
    for (vtkIdType k = 0; read && k < values->GetNumberOfValues(); ++k)
    {
      const double exact = values->GetValue(k);
      worst = std::max(worst, std::abs(read->GetValue(k) - exact) / exact);
      rounded += read->GetValue(k) != values->GetValue(k) ? 1 : 0;
    }
    std::cout << "half: worst relative error " << worst << ", " << rounded << " of "
              << values->GetNumberOfValues() << " values changed by rounding\n";
    Check(worst <= std::exp2(-11.0), "half: error beyond half precision (2^-11 relative)");
    Check(rounded > values->GetNumberOfValues() / 2, "half: values were not rounded to half");
    Check(SameBits(output->GetPointData()->GetArray("Mask"), smoothDepth),
      "half: the Mask channel is not float-exact");
  }

  // A double colour array is written as float.
  {
    vtkNew<vtkImageData> doubles;
    doubles->SetExtent(0, 9, 0, 4, 0, 0);
    vtkNew<vtkDoubleArray> values;
    values->SetName("Colour");
    values->SetNumberOfComponents(3);
    values->SetNumberOfTuples(doubles->GetNumberOfPoints());
    std::uniform_real_distribution<double> uniform(0.0, 100.0);
    for (vtkIdType k = 0; k < values->GetNumberOfValues(); ++k)
    {
      values->SetValue(k, uniform(random));
    }
    doubles->GetPointData()->AddArray(values);
    const std::string file = (folder / "double.exr").string();
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(doubles);
    writer->SetFileName(file.c_str());
    writer->SetColorArrayName("Colour");
    Check(writer->Write() == 1, "double: Write failed");
    vtkNew<vtkOpenEXRReader> reader;
    auto* read =
      vtkFloatArray::SafeDownCast(Read(reader, file)->GetPointData()->GetArray("Radiance"));
    bool same = read && read->GetNumberOfValues() == values->GetNumberOfValues();
    for (vtkIdType k = 0; same && k < values->GetNumberOfValues(); ++k)
    {
      same = read->GetValue(k) == static_cast<float>(values->GetValue(k));
    }
    Check(same, "double: the colour is not the double values rounded to float");
  }

  // Depth as Z: OpenEXR's name for depth and its +infinity where nothing is seen.
  {
    vtkNew<vtkImageData> rendered;
    rendered->SetExtent(0, 7, 0, 5, 0, 0);
    const vtkIdType pixels = rendered->GetNumberOfPoints();
    vtkNew<vtkFloatArray> colour;
    colour->SetName("Radiance");
    colour->SetNumberOfComponents(3);
    colour->SetNumberOfTuples(pixels);
    colour->Fill(0.5);
    vtkNew<vtkFloatArray> depth;
    depth->SetName("Depth");
    depth->SetNumberOfTuples(pixels);
    std::uniform_real_distribution<float> distance(0.0f, 1e4f);
    for (vtkIdType k = 0; k < pixels; ++k)
    {
      // Every third pixel sees nothing (the renderer's -1), pixel 1 is at distance 0.
      depth->SetValue(k, k % 3 == 0 ? -1.0f : (k == 1 ? 0.0f : distance(random)));
    }
    rendered->GetPointData()->AddArray(colour);
    rendered->GetPointData()->AddArray(depth);
    const std::string file = (folder / "depth.exr").string();
    vtkNew<vtkOpenEXRWriter> writer;
    writer->SetInputData(rendered);
    writer->SetFileName(file.c_str());
    writer->AddChannelArray("Depth");
    Check(writer->Write() == 1, "depth: Write failed");
    {
      Imf::InputFile exr(file.c_str());
      const Imf::ChannelList& channels = exr.header().channels();
      Check(channels.findChannel("Z") && channels.findChannel("Z")->type == Imf::FLOAT,
        "depth: no FLOAT channel Z");
      Check(!channels.findChannel("Depth"), "depth: a channel Depth besides Z");
      std::vector<float> z(static_cast<std::size_t>(pixels));
      Imf::FrameBuffer frameBuffer;
      frameBuffer.insert("Z", Imf::Slice::Make(Imf::FLOAT, z.data(), exr.header().dataWindow()));
      exr.setFrameBuffer(frameBuffer);
      exr.readPixels(0, 5);
      bool right = true;
      for (int j = 0; j < 6; ++j)
      {
        for (int i = 0; i < 8; ++i)
        {
          const float written = depth->GetValue(j * 8 + i);
          const float inFile = z[static_cast<std::size_t>(5 - j) * 8 + i]; // rows flipped
          right = right &&
            (written < 0 ? inFile == std::numeric_limits<float>::infinity() : inFile == written);
        }
      }
      Check(right, "depth: Z is not the Depth with +infinity where nothing is seen");
    }
    vtkNew<vtkOpenEXRReader> reader;
    vtkImageData* output = Read(reader, file);
    Check(output->GetPointData()->GetArray("Z") == nullptr, "depth: the reader gave an array Z");
    Check(SameBits(output->GetPointData()->GetArray("Depth"), depth),
      "depth: Z did not read back as the Depth written (-1 where nothing is seen)");
  }
  return TestFailures::ExitCode();
}
