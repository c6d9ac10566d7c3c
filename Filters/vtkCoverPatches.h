// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkCoverPatches.h
 * @brief The patches a solution was built from, for the filters that take the illumination on
 * port 0 and the patches on an optional port 1 (vtkRadianceImageFilter, vtkIlluminationField).
 *
 * Why optional: in ParaView a filter with two required inputs opens a dialog in which the user
 * must pick the second input by hand (pqFiltersMenuReaction asks for every required input
 * port; an InputProperty with the hint `<Optional/>` is left out). The patches are already
 * upstream of the illumination: vtkLightPropagationFilter's input is vtkSphericalCoverFilter's
 * output, and the cover's input is the patches it was built from (the subdivision's Patches,
 * or a reader's surfaces). So an unconnected port 1 means "those patches", found by walking the
 * illumination's pipeline upstream (through ParaView's vtkPVPostFilter between stages), and a
 * connected port 1 wins (a saved solution, or other patches on purpose).
 */
#ifndef vtkCoverPatches_h
#define vtkCoverPatches_h

#include "SphericalCoverFiltersModule.h" // for export macro

class vtkAlgorithm;
class vtkDataSet;
class vtkInformationVector;

namespace vtkCoverPatches
{
/**
 * Port 1's dataset when port 1 is connected (nullptr when it is not a dataset); otherwise the
 * input of the nearest vtkSphericalCoverFilter upstream of port 0, or nullptr when there is
 * none. Call from RequestData: the upstream stages have executed by then.
 */
SPHERICALCOVERFILTERS_EXPORT vtkDataSet* Find(vtkAlgorithm* self,
  vtkInformationVector** inputVector);

/**
 * The same outside RequestData, for a filter that has executed (a render-time consumer such as
 * vtkViewDependentRadiance::SetSolutionFrom): port 1's current input data when connected, else
 * the input of the nearest vtkSphericalCoverFilter upstream of port 0.
 */
SPHERICALCOVERFILTERS_EXPORT vtkDataSet* Find(vtkAlgorithm* self);
}

#endif
