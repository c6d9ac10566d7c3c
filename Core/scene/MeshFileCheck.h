// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MeshFileCheck.h
 * @brief Checks a mesh file (.obj, .ply, .vtp) for what VTK's readers trust without checking,
 * before one of them reads it.
 *
 * VTK 9.2's readers crash or abort on small hostile files: vtkOBJReader and vtkPLYReader read
 * beyond their point arrays for a face index past the last vertex (a segmentation fault),
 * vtkPLYReader allocates the element counts of its header (4e9 vertices: a length_error with
 * no file name) and frees an invalid pointer on a truncated binary file, and
 * vtkXMLPolyDataReader aborts when NumberOfPoints asks for more memory than there is. This
 * check reads the file once, without building the mesh, and reports such problems as one
 * InputError with the file's line (or none, for problems of the whole file).
 */
#ifndef SPHCOVER_MESHFILECHECK_H
#define SPHCOVER_MESHFILECHECK_H

#include <cstdint>
#include <string>

namespace sphcover
{

/// The most points or faces a mesh file may declare: far more than the method can solve (its
/// cost grows with the square of the patch count), small enough for any reader's arrays.
constexpr std::uint64_t MaxMeshElements = std::uint64_t(1) << 24;

/// Applies the input file policy (InputFile.h), then the checks of the format named by the
/// extension; other extensions are left to the caller. Throws InputError.
void CheckMeshFile(const std::string& path);

} // namespace sphcover

#endif
