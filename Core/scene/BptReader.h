// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BptReader.h
 * @brief Reads Bezier patch text files (.bpt): a patch count, then per patch "du dv" and
 * (du+1)(dv+1) control points "x y z", u fastest.
 *
 * Accepts any whitespace (spaces, tabs, CR LF line ends) and C number syntax including
 * exponent notation. Never trusts the declared counts for allocation: a file that claims
 * 10^9 patches but holds one fails with "unexpected end of file", not with an allocation.
 */
#ifndef SPHCOVER_BPTREADER_H
#define SPHCOVER_BPTREADER_H

#include "geometry/BezierPatch.h"

#include <istream>
#include <string>
#include <vector>

namespace sphcover
{

/// Throws InputError naming `displayName`, the line and the problem.
std::vector<BezierPatch> ParseBpt(std::istream& in, const std::string& displayName);

/// Throws InputError ("cannot open file") if the file cannot be read.
std::vector<BezierPatch> ReadBptFile(const std::string& path);

} // namespace sphcover

#endif
