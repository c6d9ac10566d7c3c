// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkRankRenderer.h
 * @brief A solution kept in pieces (`solve -o` under mpiexec) rendered by the ranks that hold
 * its pieces, no rank holding the whole cover: rank 0 traces each view and lists the (point,
 * out cell) pairs of the directional part it reads (RadianceRenderer::DirectionalPairs), each
 * rank evaluates the pairs of its own points r, r + K, ... from its share of the cover
 * (DirectionalValues, paper §5.3.1), and rank 0 renders with all of them. The image is the
 * serial one bit for bit: the same value of every pair, evaluated where its row is.
 *
 * Rank 0 drives (Render per view); the other ranks Serve until rank 0 is finished (Finish, or
 * its destructor, which also releases them when rank 0 fails between views). A diffuse solution
 * needs nothing from the other ranks. Per view: one broadcast of the pairs (8 bytes each) and
 * one gather of their values (24 bytes each) on rank 0.
 */
#ifndef vtkRankRenderer_h
#define vtkRankRenderer_h

#include "SphericalCoverParallelModule.h" // for export macro

#include "render/RadianceRenderer.h"

class vtkMultiProcessController;

class SPHERICALCOVERPARALLEL_EXPORT vtkRankRenderer
{
public:
  /// `renderer` is this rank's, built from its piece (vtkSolutionRenderer::New with `piece`).
  vtkRankRenderer(vtkMultiProcessController* controller,
    const sphcover::RadianceRenderer& renderer);
  /// Rank 0: Finish, if not yet.
  ~vtkRankRenderer();
  vtkRankRenderer(const vtkRankRenderer&) = delete;
  vtkRankRenderer& operator=(const vtkRankRenderer&) = delete;

  /// Rank 0: the view, with the directional values of every rank's points (the other ranks
  /// Serve). Throws what RadianceRenderer::Render throws, and std::runtime_error naming the rank
  /// whose values failed. False when `progress` stopped it.
  bool Render(const sphcover::Camera& camera,
    const sphcover::RenderSettings& settings,
    sphcover::RenderedImage& image,
    const sphcover::ParallelFor& parallelFor,
    const sphcover::ProgressCallback& progress);

  /// Ranks > 0: evaluates the pairs of this rank's points for every view rank 0 renders, until
  /// rank 0 is finished.
  void Serve(const sphcover::ParallelFor& parallelFor);

  /// Rank 0: tells the other ranks that there are no more views.
  void Finish();

private:
  /// This rank's pairs of `pairs` and their values ("" or the problem in `problem`).
  std::vector<glm::dvec3> OwnValues(const std::vector<uint64_t>& pairs,
    const sphcover::ParallelFor& parallelFor,
    std::string& problem) const;

  vtkMultiProcessController* Controller;
  const sphcover::RadianceRenderer& Renderer;
  bool Finished = false;
};

#endif
