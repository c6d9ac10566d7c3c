// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file JsonInput.h
 * @brief Reading user JSON (the scene files, the command line's --set values) into typed values,
 * each failure one InputError naming the source, the RFC 6901 JSON pointer and the problem.
 *
 * Core-internal: it exposes nlohmann/json, which Core links privately, so only Core's .cxx files
 * include it. ParseJsonDocument turns text into a document (syntax errors located by line and
 * column, stricter than JSON where a scene must be: no duplicate keys, no NUL characters, at most
 * MaxJsonDepth levels); JsonInput reads values out of it, each at its pointer. The schema of what
 * the values mean is the scene loader's (SceneLoader.cxx, SettingsOverride.cxx).
 */
#ifndef SPHCOVER_JSONINPUT_H
#define SPHCOVER_JSONINPUT_H

#include "scene/InputError.h"

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace sphcover
{
using Json = nlohmann::json;

/// Deepest nesting of arrays and objects accepted; a scene needs 5. Without a limit a file of
/// a million '[' is a million-level document (and a 2 MB pointer in the message).
constexpr std::size_t MaxJsonDepth = 64;

/// The JSON pointer of member `key` (escaped as RFC 6901 says, cut short when long) or element
/// `index` of the value at `pointer`.
std::string Child(const std::string& pointer, const std::string& key);
std::string Child(const std::string& pointer, std::size_t index);

/// "<what> too large: <value> (the limit is <limit> in magnitude)".
std::string TooLarge(const std::string& what, double value, double limit);

/// The document in `text`. Throws InputError(path, location, problem): a syntax error at its
/// line and column, a number beyond double (1e999) or a stricter-than-JSON rule at its pointer.
Json ParseJsonDocument(const std::string& text, const std::string& path);

/// Whether `text` is one JSON value by the rules of ParseJsonDocument; if so, stores it.
bool ParseJsonValue(const std::string& text, Json& value);

/// Typed, located access to a JSON document from `source` (a file name, or "--set"): every
/// accessor takes the value and its pointer, and throws InputError(source, pointer, problem).
class JsonInput
{
public:
  explicit JsonInput(std::string source)
    : Source(std::move(source))
  {
  }

  /// Throws InputError(source, pointer, problem); the root's pointer "" is written "/".
  [[noreturn]] void Fail(const std::string& pointer, const std::string& problem) const;

  void ExpectObject(const Json& j, const std::string& pointer) const;
  /// Fails at the first key of object `j` that is not in `allowed`.
  void CheckKeys(const Json& j,
    const std::string& pointer,
    const std::vector<const char*>& allowed) const;
  /// Member `key` of object `j`, which must exist.
  const Json& Require(const Json& j, const std::string& pointer, const char* key) const;
  /// A finite number.
  double Number(const Json& j, const std::string& pointer) const;
  /// Integers are written without fraction or exponent (FORMAT.md): 32, not 32.0.
  long long Integer(const Json& j, const std::string& pointer) const;
  /// An integer in [1, limit].
  int PositiveInteger(const Json& j, const std::string& pointer, long long limit) const;
  bool Boolean(const Json& j, const std::string& pointer) const;
  std::string String(const Json& j, const std::string& pointer) const;
  /// A finite number of magnitude at most `limit`; beyond it, "<what> too large".
  double Bounded(const Json& j, const std::string& pointer, double limit, const char* what) const;
  /// An array of 3 finite numbers.
  glm::dvec3 Vec3(const Json& j, const std::string& pointer) const;
  /// Per-band values in [lo, hi].
  glm::dvec3 Bands(const Json& j, const std::string& pointer, double lo, double hi) const;

  /// Problems inside a file the document refers to are reported at the entry that names it,
  /// followed by the file's own location: "room.scene: /surfaces/3/file: pot.bpt: line 7: ...".
  template<typename Read>
  auto Included(const std::string& pointer, Read&& read) const -> decltype(read())
  {
    try
    {
      return read();
    }
    catch (const InputError& e)
    {
      this->Fail(pointer, e.what());
    }
  }

protected:
  const std::string Source;
};

} // namespace sphcover

#endif
