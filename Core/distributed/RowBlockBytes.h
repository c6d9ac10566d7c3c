// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RowBlockBytes.h
 * @brief A share of the spherical cover's rows (RowShares.h: the rows H_i of some
 * characteristic points, paper §3.3 / §4.3) as one byte buffer and back, so that the processes
 * of a distributed solve can exchange their rows (vtkSphericalCoverFilter and
 * vtkLightPropagationFilter under MPI) without Core knowing how they are sent.
 *
 * Layout: a tag and a version (uint32 each), the grid and fill (five int32 and the
 * UnoccludedKnown flag), the six culling counts (uint64), then every array of
 * SphericalCover::Arrays in declaration order as a uint64 length followed by its raw values. The
 * bytes are the host's: the processes of one job share their byte order and type sizes. A new
 * array of Arrays needs one line in Pack and one in Unpack (RowBlockBytes.cxx).
 */
#ifndef SPHCOVER_ROWBLOCKBYTES_H
#define SPHCOVER_ROWBLOCKBYTES_H

#include "cover/CandidateCulling.h"
#include "cover/SphericalCover.h"

#include <cstddef>
#include <string>
#include <vector>

namespace sphcover
{
/// The bytes of `block` and its culling counts.
std::vector<char> PackRowBlock(const SphericalCover::Arrays& block,
  const CullingStatistics& culling);

/**
 * Reads PackRowBlock's bytes into `block` and `culling`. Returns what is wrong ("" on success:
 * a wrong tag or version, or bytes missing or left over); the values themselves are checked when
 * the shares join (RowShares::JoinRows).
 */
std::string UnpackRowBlock(const char* bytes,
  std::size_t size,
  SphericalCover::Arrays& block,
  CullingStatistics& culling);
}

#endif
