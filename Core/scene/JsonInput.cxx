// SPDX-License-Identifier: BSD-3-Clause
#include "scene/JsonInput.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace sphcover
{
namespace
{

std::string FormatNumber(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string EscapePointerToken(const std::string& key)
{
  // RFC 6901: '~' -> "~0", '/' -> "~1".
  std::string out;
  for (char c : key)
  {
    if (c == '~')
    {
      out += "~0";
    }
    else if (c == '/')
    {
      out += "~1";
    }
    else
    {
      out += c;
    }
  }
  return Excerpt(out); // a key may be megabytes long; the message names its start
}

/// nlohmann/json's DOM builder, told not to throw, remembering where and why parsing failed:
/// the byte offset and the JSON pointer of the value being read (nlohmann's exceptions lose
/// both for a number overflow such as 1e999, which is a non-finite number to us). It also
/// stops at what JSON allows but a scene must not have (Problem, at ErrorPointer): a repeated
/// key (nlohmann would keep the last silently), a NUL character in a key or string (it would
/// cut a file name short when the path reaches the C library), nesting beyond MaxJsonDepth.
class LocatingDomParser : public nlohmann::detail::json_sax_dom_parser<Json>
{
  using Base = nlohmann::detail::json_sax_dom_parser<Json>;

public:
  explicit LocatingDomParser(Json& root)
    : Base(root, false)
  {
  }

  bool null() { return this->Value(Base::null()); }
  bool boolean(bool value) { return this->Value(Base::boolean(value)); }
  bool number_integer(Json::number_integer_t value)
  {
    return this->Value(Base::number_integer(value));
  }
  bool number_unsigned(Json::number_unsigned_t value)
  {
    return this->Value(Base::number_unsigned(value));
  }
  bool number_float(Json::number_float_t value, const Json::string_t& text)
  {
    return this->Value(Base::number_float(value, text));
  }
  bool string(Json::string_t& value)
  {
    if (value.find('\0') != std::string::npos)
    {
      return this->Stop("NUL character (\\u0000) in a string");
    }
    return this->Value(Base::string(value));
  }
  bool binary(Json::binary_t& value) { return this->Value(Base::binary(value)); }
  bool start_object(std::size_t size)
  {
    if (this->Path.size() >= MaxJsonDepth)
    {
      return this->Stop("nested deeper than " + std::to_string(MaxJsonDepth) + " levels");
    }
    this->Path.push_back({ false, 0, std::string(), {} });
    return Base::start_object(size);
  }
  bool key(Json::string_t& name)
  {
    Level& level = this->Path.back();
    level.Key = name;
    if (name.find('\0') != std::string::npos)
    {
      return this->Stop("NUL character (\\u0000) in a key");
    }
    if (!level.Keys.insert(name).second)
    {
      return this->Stop("duplicate key " + Quote(name));
    }
    return Base::key(name);
  }
  bool end_object()
  {
    this->Path.pop_back();
    return this->Value(Base::end_object());
  }
  bool start_array(std::size_t size)
  {
    if (this->Path.size() >= MaxJsonDepth)
    {
      return this->Stop("nested deeper than " + std::to_string(MaxJsonDepth) + " levels");
    }
    this->Path.push_back({ true, 0, std::string(), {} });
    return Base::start_array(size);
  }
  bool end_array()
  {
    this->Path.pop_back();
    return this->Value(Base::end_array());
  }

  template<class Exception>
  bool parse_error(std::size_t position, const std::string&, const Exception& error)
  {
    this->Failed = true;
    this->ErrorPosition = position;
    this->ErrorMessage = error.what();
    this->ErrorId = error.id;
    this->ErrorPointer = this->Pointer();
    return false;
  }

  bool Failed = false;
  size_t ErrorPosition = 0;
  std::string ErrorMessage;
  std::string ErrorPointer;
  int ErrorId = 0;
  std::string Problem; // set when the callbacks stopped a syntactically valid document

private:
  struct Level
  {
    bool IsArray;
    size_t Count;               // elements read so far (arrays)
    std::string Key;            // the current key (objects)
    std::set<std::string> Keys; // the keys read so far (objects)
  };

  /// The JSON pointer of the value being read.
  std::string Pointer() const
  {
    std::string pointer;
    for (const Level& level : this->Path)
    {
      pointer += level.IsArray ? Child("", level.Count) : Child("", level.Key);
    }
    return pointer;
  }

  /// Ends the parse (a callback returning false) with `problem` at the current value.
  bool Stop(const std::string& problem)
  {
    this->Failed = true;
    this->ErrorPointer = this->Pointer();
    this->Problem = problem;
    return false;
  }

  /// A complete value was read: the enclosing array moves on to its next element.
  bool Value(bool result)
  {
    if (!this->Path.empty() && this->Path.back().IsArray)
    {
      ++this->Path.back().Count;
    }
    return result;
  }

  std::vector<Level> Path;
};

/// "line L, column C" of the character before byte `offset` of `text` (nlohmann reports the
/// byte offset just past the error; users want line and column).
std::string LineAndColumn(const std::string& text, size_t offset)
{
  const size_t end = std::min(offset == 0 ? size_t{ 0 } : offset - 1, text.size());
  size_t line = 1;
  size_t column = 1;
  for (size_t k = 0; k < end; ++k)
  {
    if (text[k] == '\n')
    {
      ++line;
      column = 1;
    }
    else
    {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

/// nlohmann's message of a syntax error without what the location says already, the token it
/// stopped in quoted short.
std::string SyntaxErrorDetail(const std::string& message)
{
  // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: ".
  std::string detail = message;
  const size_t bracket = detail.find("] ");
  if (detail.compare(0, 16, "[json.exception.") == 0 && bracket != std::string::npos)
  {
    detail = detail.substr(bracket + 2);
  }
  const size_t colon = detail.find(": ");
  if (detail.compare(0, 14, "parse error at") == 0 && colon != std::string::npos)
  {
    detail = detail.substr(colon + 2);
  }
  // nlohmann quotes the whole token it stopped in ("...; last read: '<token>'", maybe
  // followed by "; expected ..."), which may be a megabyte-long string.
  const std::string lastRead = "last read: '";
  const size_t quoted = detail.find(lastRead);
  if (quoted != std::string::npos)
  {
    const size_t begin = quoted + lastRead.size();
    size_t end = detail.find("'; expected", begin);
    end = end != std::string::npos ? end : detail.rfind('\'');
    if (end != std::string::npos && end >= begin)
    {
      detail = detail.substr(0, quoted) + "last read: " + Quote(detail.substr(begin, end - begin)) +
        detail.substr(end + 1);
    }
  }
  return detail;
}

} // namespace

std::string TooLarge(const std::string& what, double value, double limit)
{
  return what + " too large: " + FormatNumber(value) + " (the limit is " + FormatNumber(limit) +
    " in magnitude)";
}

std::string Child(const std::string& pointer, const std::string& key)
{
  return pointer + "/" + EscapePointerToken(key);
}

std::string Child(const std::string& pointer, size_t index)
{
  return pointer + "/" + std::to_string(index);
}

Json ParseJsonDocument(const std::string& text, const std::string& path)
{
  Json root;
  LocatingDomParser dom(root);
  if (Json::sax_parse(text, &dom) && !dom.Failed)
  {
    return root;
  }
  if (!dom.Problem.empty())
  {
    throw InputError(
      path, dom.ErrorPointer.empty() ? std::string("/") : dom.ErrorPointer, dom.Problem);
  }
  const std::string position = LineAndColumn(text, dom.ErrorPosition);
  const std::string detail = SyntaxErrorDetail(dom.ErrorMessage);
  if (dom.ErrorId == 406) // a number too large for a double, such as 1e999
  {
    throw InputError(
      path, dom.ErrorPointer, "not a finite number (" + detail + ", " + position + ")");
  }
  throw InputError(path,
    position,
    "JSON syntax error: " + detail +
      (dom.ErrorPointer.empty() ? "" : " (in " + dom.ErrorPointer + ")"));
}

bool ParseJsonValue(const std::string& text, Json& value)
{
  Json parsed;
  LocatingDomParser dom(parsed);
  if (!Json::sax_parse(text, &dom) || dom.Failed)
  {
    return false;
  }
  value = std::move(parsed);
  return true;
}

void JsonInput::Fail(const std::string& pointer, const std::string& problem) const
{
  throw InputError(this->Source, pointer.empty() ? std::string("/") : pointer, problem);
}

void JsonInput::ExpectObject(const Json& j, const std::string& pointer) const
{
  if (!j.is_object())
  {
    this->Fail(pointer, "expected an object");
  }
}

void JsonInput::CheckKeys(const Json& j,
  const std::string& pointer,
  const std::vector<const char*>& allowed) const
{
  for (auto it = j.begin(); it != j.end(); ++it)
  {
    if (std::none_of(
          allowed.begin(), allowed.end(), [&](const char* key) { return it.key() == key; }))
    {
      this->Fail(Child(pointer, it.key()), "unknown key " + Quote(it.key()));
    }
  }
}

const Json& JsonInput::Require(const Json& j, const std::string& pointer, const char* key) const
{
  auto it = j.find(key);
  if (it == j.end())
  {
    this->Fail(pointer, std::string("missing key '") + key + "'");
  }
  return *it;
}

double JsonInput::Number(const Json& j, const std::string& pointer) const
{
  if (!j.is_number())
  {
    this->Fail(pointer, "expected a number");
  }
  const double value = j.get<double>();
  if (!std::isfinite(value))
  {
    this->Fail(pointer, "not a finite number");
  }
  return value;
}

long long JsonInput::Integer(const Json& j, const std::string& pointer) const
{
  if (j.is_number_unsigned() && j.get<unsigned long long>() > (1ull << 62))
  {
    this->Fail(pointer, "integer out of range");
  }
  if (!j.is_number_integer())
  {
    this->Fail(pointer, "expected an integer");
  }
  return j.get<long long>();
}

int JsonInput::PositiveInteger(const Json& j, const std::string& pointer, long long limit) const
{
  const long long value = this->Integer(j, pointer);
  if (value < 1 || value > limit)
  {
    this->Fail(pointer,
      "must be a positive integer (at most " + std::to_string(limit) + "), got " +
        std::to_string(value));
  }
  return static_cast<int>(value);
}

bool JsonInput::Boolean(const Json& j, const std::string& pointer) const
{
  if (!j.is_boolean())
  {
    this->Fail(pointer, "expected a boolean");
  }
  return j.get<bool>();
}

std::string JsonInput::String(const Json& j, const std::string& pointer) const
{
  if (!j.is_string())
  {
    this->Fail(pointer, "expected a string");
  }
  return j.get<std::string>();
}

double JsonInput::Bounded(const Json& j,
  const std::string& pointer,
  double limit,
  const char* what) const
{
  const double value = this->Number(j, pointer);
  if (std::fabs(value) > limit)
  {
    this->Fail(pointer, TooLarge(what, value, limit));
  }
  return value;
}

glm::dvec3 JsonInput::Vec3(const Json& j, const std::string& pointer) const
{
  if (!j.is_array() || j.size() != 3)
  {
    this->Fail(pointer, "expected an array of 3 numbers");
  }
  glm::dvec3 v;
  for (size_t k = 0; k < 3; ++k)
  {
    v[static_cast<int>(k)] = this->Number(j[k], Child(pointer, k));
  }
  return v;
}

glm::dvec3 JsonInput::Bands(const Json& j, const std::string& pointer, double lo, double hi) const
{
  const glm::dvec3 v = this->Vec3(j, pointer);
  for (int k = 0; k < 3; ++k)
  {
    if (v[k] < lo || v[k] > hi)
    {
      std::ostringstream problem;
      problem << "must be in [" << lo << ", " << hi << "], got " << v[k];
      this->Fail(Child(pointer, static_cast<size_t>(k)), problem.str());
    }
  }
  return v;
}

} // namespace sphcover
