// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ByteBuffer.h
 * @brief Raw values in a byte buffer, for what one process sends another: the cover's row
 * blocks (RowBlockBytes.h) and the exchanges of work shared among ranks (RankShare.h). Values
 * are trivially copyable and written in the machine's own layout (the ranks of one solve run
 * one build of the program); an array is its count (uint64) then its values.
 */
#ifndef SPHCOVER_BYTEBUFFER_H
#define SPHCOVER_BYTEBUFFER_H

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace sphcover
{

/// Appends raw values to a buffer.
class ByteWriter
{
public:
  explicit ByteWriter(std::vector<char>& bytes)
    : Bytes(bytes)
  {
  }
  template<typename T>
  void Values(const T* values, std::size_t count)
  {
    static_assert(std::is_trivially_copyable<T>::value, "raw bytes only");
    const char* raw = reinterpret_cast<const char*>(values);
    this->Bytes.insert(this->Bytes.end(), raw, raw + count * sizeof(T));
  }
  template<typename T>
  void Value(const T& value)
  {
    this->Values(&value, 1);
  }
  template<typename T>
  void Array(const std::vector<T>& values)
  {
    this->Value(static_cast<uint64_t>(values.size()));
    this->Values(values.data(), values.size());
  }

private:
  std::vector<char>& Bytes;
};

/// Reads raw values from a buffer; false once a value would run past its end.
class ByteReader
{
public:
  ByteReader(const char* bytes, std::size_t size)
    : Next(bytes)
    , Left(size)
  {
  }
  explicit ByteReader(const std::vector<char>& bytes)
    : ByteReader(bytes.data(), bytes.size())
  {
  }
  template<typename T>
  bool Values(T* values, std::size_t count)
  {
    static_assert(std::is_trivially_copyable<T>::value, "raw bytes only");
    if (count > this->Left / sizeof(T))
    {
      return false;
    }
    if (count > 0) // an empty vector's data() may be null, which memcpy must not get
    {
      std::memcpy(values, this->Next, count * sizeof(T));
    }
    this->Next += count * sizeof(T);
    this->Left -= count * sizeof(T);
    return true;
  }
  template<typename T>
  bool Value(T& value)
  {
    return this->Values(&value, 1);
  }
  template<typename T>
  bool Array(std::vector<T>& values)
  {
    uint64_t count = 0;
    if (!this->Value(count) || count > this->Left / sizeof(T))
    {
      return false;
    }
    values.resize(static_cast<std::size_t>(count));
    return this->Values(values.data(), values.size());
  }
  bool AtEnd() const { return this->Left == 0; }

private:
  const char* Next;
  std::size_t Left;
};

} // namespace sphcover

#endif
