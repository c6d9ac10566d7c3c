// SPDX-License-Identifier: BSD-3-Clause
#include "scene/MeshFileCheck.h"

#include "scene/InputError.h"
#include "scene/InputFile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

namespace sphcover
{
namespace
{

[[noreturn]] void Fail(const std::string& path, const std::string& location, const std::string& p)
{
  throw InputError(path, location, p);
}

std::string Line(int line)
{
  return "line " + std::to_string(line);
}

/// A count in a header: digits only, at most MaxMeshElements.
std::uint64_t Count(const std::string& path,
  int line,
  const std::string& what,
  const std::string& token)
{
  char* end = nullptr;
  const unsigned long long value = std::strtoull(token.c_str(), &end, 10);
  if (token.empty() || !std::isdigit(static_cast<unsigned char>(token[0])) || *end != '\0')
  {
    Fail(path, Line(line), "expected a count for " + what + ", got " + Quote(token));
  }
  if (value > MaxMeshElements)
  {
    Fail(path,
      Line(line),
      what + " declares " + token + " entries (the limit is " + std::to_string(MaxMeshElements) +
        ")");
  }
  return value;
}

/// OBJ: every face index names an existing vertex ("f 1 2 3", "f 1/1 2/2 3/3", relative "-1").
void CheckObj(const std::string& path, const std::string& text)
{
  std::uint64_t vertices = 0;
  {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
    {
      vertices += line.compare(0, 2, "v ") == 0 || line.compare(0, 2, "v\t") == 0;
    }
  }
  if (vertices > MaxMeshElements)
  {
    Fail(path, "", "more than " + std::to_string(MaxMeshElements) + " vertices");
  }
  std::istringstream in(text);
  std::string line;
  std::uint64_t seen = 0; // vertices defined so far: what a relative index counts back from
  for (int number = 1; std::getline(in, line); ++number)
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    seen += keyword == "v";
    if (keyword != "f")
    {
      continue;
    }
    std::string corner;
    while (words >> corner)
    {
      char* end = nullptr;
      const long long index = std::strtoll(corner.c_str(), &end, 10);
      if (end == corner.c_str())
      {
        continue; // not a number: VTK's own message is clear
      }
      const bool valid =
        index > 0 ? std::uint64_t(index) <= vertices : index < 0 && std::uint64_t(-index) <= seen;
      if (!valid)
      {
        Fail(path,
          Line(number),
          "face refers to vertex " + std::to_string(index) + ", but the file has " +
            std::to_string(vertices) + " vertices");
      }
    }
  }
}

/// PLY: the header's counts fit the file, the data is complete, and every vertex index of a
/// face names an existing vertex.
class PlyCheck
{
public:
  PlyCheck(const std::string& path, const std::string& text)
    : Path(path)
    , Text(text)
  {
  }

  void Run()
  {
    this->ReadHeader();
    std::uint64_t vertices = 0;
    for (const Element& element : this->Elements)
    {
      vertices = element.Name == "vertex" ? element.Count : vertices;
    }
    for (const Element& element : this->Elements)
    {
      const bool isFace = element.Name == "face";
      for (std::uint64_t n = 0; n < element.Count; ++n)
      {
        for (const Property& property : element.Properties)
        {
          const std::string where = "element '" + element.Name + "' " + std::to_string(n + 1);
          if (property.CountType.empty())
          {
            this->Value(property.Type, where);
            continue;
          }
          const double size = this->Value(property.CountType, where);
          if (!(size >= 0.0) || size != std::floor(size))
          {
            Fail(this->Path, where, "list length is not a count: " + std::to_string(size));
          }
          const bool indices =
            isFace && (property.Name == "vertex_indices" || property.Name == "vertex_index");
          for (double k = 0; k < size; ++k)
          {
            const double index = this->Value(property.Type, where);
            if (indices && !(index >= 0.0 && index < double(vertices)))
            {
              std::ostringstream problem;
              problem << "face refers to vertex " << index << ", but the file has " << vertices
                      << " vertices (numbered from 0)";
              Fail(this->Path, "face " + std::to_string(n + 1), problem.str());
            }
          }
        }
      }
    }
  }

private:
  struct Property
  {
    std::string CountType; // empty unless a list
    std::string Type;
    std::string Name;
  };
  struct Element
  {
    std::string Name;
    std::uint64_t Count;
    std::vector<Property> Properties;
  };

  static int SizeOf(const std::string& type)
  {
    static const char* const one[] = { "char", "uchar", "int8", "uint8" };
    static const char* const two[] = { "short", "ushort", "int16", "uint16" };
    static const char* const four[] = { "int", "uint", "float", "int32", "uint32", "float32" };
    static const char* const eight[] = { "double", "float64" };
    auto in = [&](const auto& names)
    { return std::find(std::begin(names), std::end(names), type) != std::end(names); };
    return in(one) ? 1 : in(two) ? 2 : in(four) ? 4 : in(eight) ? 8 : 0;
  }

  std::string Type(int line, const std::string& token) const
  {
    if (SizeOf(token) == 0)
    {
      Fail(this->Path, Line(line), "unknown property type " + Quote(token));
    }
    return token;
  }

  void ReadHeader()
  {
    size_t position = 0;
    for (int line = 1;; ++line)
    {
      const size_t end = this->Text.find('\n', position);
      if (end == std::string::npos)
      {
        Fail(this->Path, Line(line), "no 'end_header' line (not a PLY file?)");
      }
      std::string text = this->Text.substr(position, end - position);
      position = end + 1;
      if (!text.empty() && text.back() == '\r')
      {
        text.pop_back();
      }
      std::istringstream words(text);
      std::vector<std::string> w;
      for (std::string word; words >> word;)
      {
        w.push_back(word);
      }
      if (line == 1)
      {
        if (w.size() != 1 || w[0] != "ply")
        {
          Fail(this->Path, Line(1), "expected 'ply' (not a PLY file?)");
        }
      }
      else if (w.empty() || w[0] == "comment" || w[0] == "obj_info")
      {
      }
      else if (w[0] == "format" && w.size() == 3)
      {
        this->Binary = w[1] != "ascii";
        this->BigEndian = w[1] == "binary_big_endian";
        if (this->Binary && !this->BigEndian && w[1] != "binary_little_endian")
        {
          Fail(this->Path, Line(line), "unknown PLY format " + Quote(w[1]));
        }
      }
      else if (w[0] == "element" && w.size() == 3)
      {
        const std::uint64_t count = Count(this->Path, line, "element " + Quote(w[1]), w[2]);
        // Every entry takes at least one byte, in any encoding.
        if (count > this->Text.size())
        {
          Fail(this->Path,
            Line(line),
            "element " + Quote(w[1]) + " declares " + w[2] + " entries, more than the file's " +
              std::to_string(this->Text.size()) + " bytes can hold");
        }
        this->Elements.push_back({ w[1], count, {} });
      }
      else if (w[0] == "property" && !this->Elements.empty() &&
        ((w.size() == 3 && w[1] != "list") || (w.size() == 5 && w[1] == "list")))
      {
        const bool list = w[1] == "list";
        this->Elements.back().Properties.push_back(
          { list ? this->Type(line, w[2]) : "", this->Type(line, list ? w[3] : w[1]), w.back() });
      }
      else if (w[0] == "end_header" && w.size() == 1)
      {
        this->Position = position;
        return;
      }
      else
      {
        Fail(this->Path, Line(line), "unexpected header line " + Quote(text));
      }
    }
  }

  /// The next value of `type`; the data ending first is a truncated file.
  double Value(const std::string& type, const std::string& where)
  {
    if (this->Binary)
    {
      const size_t size = static_cast<size_t>(SizeOf(type));
      if (this->Text.size() - this->Position < size)
      {
        Fail(this->Path, where, "unexpected end of data (a truncated file?)");
      }
      unsigned char bytes[8];
      std::memcpy(bytes, this->Text.data() + this->Position, size);
      this->Position += size;
      if (this->BigEndian)
      {
        std::reverse(bytes, bytes + size);
      }
      return Decode(type, bytes);
    }
    const size_t begin = this->Text.find_first_not_of(" \t\r\n", this->Position);
    if (begin == std::string::npos)
    {
      Fail(this->Path, where, "unexpected end of data (a truncated file?)");
    }
    size_t end = this->Text.find_first_of(" \t\r\n", begin);
    end = end == std::string::npos ? this->Text.size() : end;
    const std::string token = this->Text.substr(begin, end - begin);
    this->Position = end;
    char* stop = nullptr;
    const double value = std::strtod(token.c_str(), &stop);
    if (stop != token.c_str() + token.size())
    {
      Fail(this->Path, where, "expected a number, got " + Quote(token));
    }
    return value;
  }

  /// A little-endian value of `type` as a double.
  static double Decode(const std::string& type, const unsigned char* bytes)
  {
    const bool isSigned = type[0] != 'u';
    const bool isFloat = type.compare(0, 5, "float") == 0 || type == "double";
    const int size = SizeOf(type);
    std::uint64_t bits = 0;
    for (int k = size - 1; k >= 0; --k)
    {
      bits = (bits << 8) | bytes[k];
    }
    if (isFloat)
    {
      if (size == 4)
      {
        float f;
        const auto b32 = static_cast<std::uint32_t>(bits);
        std::memcpy(&f, &b32, 4);
        return f;
      }
      double d;
      std::memcpy(&d, &bits, 8);
      return d;
    }
    if (isSigned && size < 8 && (bits >> (8 * size - 1)) != 0)
    {
      return double(bits) - std::ldexp(1.0, 8 * size); // two's complement
    }
    return isSigned ? double(static_cast<std::int64_t>(bits)) : double(bits);
  }

  const std::string& Path;
  const std::string& Text;
  bool Binary = false;
  bool BigEndian = false;
  size_t Position = 0;
  std::vector<Element> Elements;
};

/// VTP: no declared count beyond MaxMeshElements (the XML reader allocates it up front).
void CheckVtp(const std::string& path, const std::string& text)
{
  for (const char* attribute : { "NumberOfPoints=\"",
         "NumberOfVerts=\"",
         "NumberOfLines=\"",
         "NumberOfStrips=\"",
         "NumberOfPolys=\"",
         "NumberOfTuples=\"" })
  {
    const size_t length = std::strlen(attribute);
    for (size_t at = text.find(attribute); at != std::string::npos;
         at = text.find(attribute, at + length))
    {
      const size_t end = text.find('"', at + length);
      const std::string value =
        text.substr(at + length, end == std::string::npos ? 0 : end - at - length);
      const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
      Count(path, line, std::string(attribute, length - 2), value);
    }
  }
}

} // namespace

void CheckMeshFile(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  if (ext != "obj" && ext != "ply" && ext != "vtp")
  {
    CheckInputFile(path);
    return;
  }
  const std::string text = ReadInputFile(path);
  if (ext == "obj")
  {
    CheckObj(path, text);
  }
  else if (ext == "ply")
  {
    PlyCheck(path, text).Run();
  }
  else
  {
    CheckVtp(path, text);
  }
}

} // namespace sphcover
