// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRankRenderer.h"

#include "vtkCoverDistribution.h"

#include "math/ByteBuffer.h"

#include <vtkMultiProcessController.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace
{
/// Rank 0's pair count of the next view (-1: no more views) and its pairs, on every rank.
long long BroadcastPairs(vtkMultiProcessController* controller,
  long long count,
  std::vector<uint64_t>& pairs)
{
  controller->Broadcast(&count, 1, 0);
  if (count > 0)
  {
    pairs.resize(static_cast<std::size_t>(count));
    controller->Broadcast(reinterpret_cast<char*>(pairs.data()),
      static_cast<vtkIdType>(count * static_cast<long long>(sizeof(uint64_t))),
      0);
  }
  else
  {
    pairs.clear();
  }
  return count;
}

/// This rank's values (or its problem) as bytes for rank 0.
std::vector<char> Packed(const std::vector<glm::dvec3>& values, const std::string& problem)
{
  std::vector<char> bytes;
  sphcover::ByteWriter writer(bytes);
  writer.Value(static_cast<uint8_t>(problem.empty() ? 0 : 1));
  writer.Array(std::vector<char>(problem.begin(), problem.end()));
  writer.Array(values);
  return bytes;
}
}

vtkRankRenderer::vtkRankRenderer(vtkMultiProcessController* controller,
  const sphcover::RadianceRenderer& renderer)
  : Controller(controller)
  , Renderer(renderer)
{
}

vtkRankRenderer::~vtkRankRenderer()
{
  if (this->Controller->GetLocalProcessId() == 0 && !this->Finished)
  {
    this->Finish();
  }
}

std::vector<glm::dvec3> vtkRankRenderer::OwnValues(const std::vector<uint64_t>& pairs,
  const sphcover::ParallelFor& parallelFor,
  std::string& problem) const
{
  const uint64_t cells = this->Renderer.DirectionalCellCount();
  const uint64_t ranks = static_cast<uint64_t>(this->Controller->GetNumberOfProcesses());
  const uint64_t rank = static_cast<uint64_t>(this->Controller->GetLocalProcessId());
  std::vector<uint64_t> own;
  for (const uint64_t pair : pairs)
  {
    if ((pair / cells) % ranks == rank)
    {
      own.push_back(pair);
    }
  }
  try
  {
    return this->Renderer.DirectionalValues(own, parallelFor);
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  return {};
}

bool vtkRankRenderer::Render(const sphcover::Camera& camera,
  const sphcover::RenderSettings& settings,
  sphcover::RenderedImage& image,
  const sphcover::ParallelFor& parallelFor,
  const sphcover::ProgressCallback& progress)
{
  if (!this->Renderer.HasDirectionalIllumination())
  {
    return this->Renderer.Render(camera, settings, image, parallelFor, progress);
  }
  std::vector<uint64_t> pairs = this->Renderer.DirectionalPairs(camera, settings, parallelFor);
  BroadcastPairs(this->Controller, static_cast<long long>(pairs.size()), pairs);
  std::string problem;
  const std::vector<glm::dvec3> mine = this->OwnValues(pairs, parallelFor, problem);
  std::vector<std::vector<char>> all =
    vtkCoverDistribution::GatherBytes(this->Controller, Packed(mine, problem), false);

  // Every pair's value from the rank that holds its point's row, in the pairs' order.
  const uint64_t cells = this->Renderer.DirectionalCellCount();
  const std::size_t ranks = all.size();
  std::vector<std::vector<glm::dvec3>> values(ranks);
  for (std::size_t r = 0; r < ranks; ++r)
  {
    sphcover::ByteReader reader(all[r]);
    uint8_t failed = 1;
    std::vector<char> message;
    if (!reader.Value(failed) || !reader.Array(message) || !reader.Array(values[r]))
    {
      throw std::runtime_error("rank " + std::to_string(r) + "'s directional values are malformed");
    }
    if (failed != 0)
    {
      throw std::runtime_error("rank " + std::to_string(r) + " cannot evaluate its points' " +
        "directional part: " + std::string(message.begin(), message.end()));
    }
    all[r] = std::vector<char>();
  }
  sphcover::RadianceRenderer::DirectionalValueTable table;
  table.Keys = std::move(pairs);
  table.Values.reserve(table.Keys.size());
  std::vector<std::size_t> next(ranks, 0);
  for (const uint64_t pair : table.Keys)
  {
    const std::size_t r = static_cast<std::size_t>((pair / cells) % ranks);
    if (next[r] >= values[r].size())
    {
      throw std::runtime_error("rank " + std::to_string(r) + " sent too few directional values");
    }
    table.Values.push_back(values[r][next[r]++]);
  }
  return this->Renderer.Render(camera, settings, table, image, parallelFor, progress);
}

void vtkRankRenderer::Serve(const sphcover::ParallelFor& parallelFor)
{
  std::vector<uint64_t> pairs;
  while (BroadcastPairs(this->Controller, 0, pairs) >= 0)
  {
    std::string problem;
    const std::vector<glm::dvec3> mine = this->OwnValues(pairs, parallelFor, problem);
    vtkCoverDistribution::GatherBytes(this->Controller, Packed(mine, problem), false);
  }
}

void vtkRankRenderer::Finish()
{
  this->Finished = true;
  std::vector<uint64_t> none;
  BroadcastPairs(this->Controller, -1, none);
}
