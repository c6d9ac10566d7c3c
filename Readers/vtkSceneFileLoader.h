// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSceneFileLoader
 * @brief Loads .scene and .bpt files into Core scenes, reading the meshes a scene refers to
 * (OBJ, PLY, VTP) with VTK's own readers: Core has none, it does not depend on VTK.
 *
 * Mesh faces keep the file's vertex order (their right-hand rule is the front side). Errors
 * the VTK readers report are turned into one sphcover::InputError naming the file.
 */
#ifndef vtkSceneFileLoader_h
#define vtkSceneFileLoader_h

#include "SphericalCoverReadersModule.h" // for export macro

#include "scene/SceneLoader.h" // for sphcover::MeshFace

#include <string>
#include <vector>

class SPHERICALCOVERREADERS_EXPORT vtkSceneFileLoader
{
public:
  /// A .scene file, or a .bpt file on its own (by extension). Throws sphcover::InputError.
  static sphcover::Scene Load(const std::string& path);

  /// The polygons of a mesh file. Throws sphcover::InputError.
  static std::vector<sphcover::MeshFace> ReadMeshFaces(const std::string& path);
};

#endif
