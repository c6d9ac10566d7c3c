// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCoverDistribution.h"

#include <vtkCommunicator.h>
#include <vtkDataSet.h>
#include <vtkMultiProcessController.h>
#include <vtkSmartPointer.h>

#include <exception>
#include <string>
#include <utility>

namespace vtkCoverDistribution
{
sphcover::RankShare ShareOf(vtkMultiProcessController* controller)
{
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  if (ranks <= 1)
  {
    return sphcover::RankShare();
  }
  return sphcover::RankShare(controller->GetLocalProcessId(),
    ranks,
    [controller, ranks](const std::vector<char>& mine,
      bool ok,
      bool sameSize,
      std::vector<std::vector<char>>& all,
      std::vector<char>& oks)
    {
      const std::size_t count = static_cast<std::size_t>(ranks);
      if (sameSize)
      {
        // One all-gather of the bytes and the flag.
        std::vector<char> sent(mine);
        sent.push_back(ok ? 1 : 0);
        std::vector<char> received(sent.size() * count);
        controller->AllGather(sent.data(), received.data(), static_cast<vtkIdType>(sent.size()));
        all.clear();
        oks.clear();
        for (std::size_t r = 0; r < count; ++r)
        {
          const auto first = received.begin() + static_cast<std::ptrdiff_t>(r * sent.size());
          all.emplace_back(first, first + static_cast<std::ptrdiff_t>(mine.size()));
          oks.push_back(*(first + static_cast<std::ptrdiff_t>(mine.size())));
        }
        return;
      }
      // Per rank its length and flag in one all-gather, then the bytes.
      const vtkIdType sent[2] = { static_cast<vtkIdType>(mine.size()), ok ? 1 : 0 };
      std::vector<vtkIdType> received(2 * static_cast<std::size_t>(ranks), 0);
      controller->AllGather(sent, received.data(), 2);
      std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks), 0);
      std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks), 0);
      vtkIdType total = 0;
      oks.assign(static_cast<std::size_t>(ranks), 0);
      for (std::size_t r = 0; r < lengths.size(); ++r)
      {
        lengths[r] = received[2 * r];
        oks[r] = received[2 * r + 1] != 0 ? 1 : 0;
        offsets[r] = total;
        total += lengths[r];
      }
      std::vector<char> bytes(static_cast<std::size_t>(total));
      controller->AllGatherV(mine.data(),
        bytes.data(),
        static_cast<vtkIdType>(mine.size()),
        lengths.data(),
        offsets.data());
      all.clear();
      for (std::size_t r = 0; r < lengths.size(); ++r)
      {
        all.emplace_back(bytes.begin() + offsets[r], bytes.begin() + offsets[r] + lengths[r]);
      }
    });
}

std::string Agree(vtkMultiProcessController* controller, const std::string& problem)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  // The lowest failing rank, or 2 K when none fails: the one whose message every rank gives.
  // A rank that failed only because another did (RankShare::PeerFailure) comes after every
  // rank that failed for a reason of its own.
  const bool peerFailed = problem.find(sphcover::RankShare::PeerFailure::Text) != std::string::npos;
  const int mine = problem.empty() ? 2 * ranks : (peerFailed ? ranks + rank : rank);
  int lowest = 2 * ranks;
  controller->AllReduce(&mine, &lowest, 1, vtkCommunicator::MIN_OP);
  if (lowest == 2 * ranks)
  {
    return std::string();
  }
  const int first = lowest % ranks;
  long long length = rank == first ? static_cast<long long>(problem.size()) : 0;
  controller->Broadcast(&length, 1, first);
  std::string message(static_cast<std::size_t>(length), ' ');
  if (rank == first)
  {
    message = problem;
  }
  controller->Broadcast(&message[0], static_cast<vtkIdType>(length), first);
  return message + " (rank " + std::to_string(first) + " of " + std::to_string(ranks) + ")";
}

int Count(vtkMultiProcessController* controller, bool flag)
{
  const int mine = flag ? 1 : 0;
  int count = 0;
  controller->AllReduce(&mine, &count, 1, vtkCommunicator::SUM_OP);
  return count;
}

void BroadcastFromFirst(vtkMultiProcessController* controller, vtkDataSet* data)
{
  controller->Broadcast(data, 0);
}

std::vector<char> DealFromFirst(vtkMultiProcessController* controller,
  const std::function<std::vector<char>(int rank)>& blockOf)
{
  // A length of -1 says rank 0 failed to make the block.
  constexpr int LengthTag = 19001;
  constexpr int BlockTag = 19002;
  const int ranks = controller->GetNumberOfProcesses();
  if (controller->GetLocalProcessId() != 0)
  {
    vtkIdType length = -1;
    controller->Receive(&length, 1, 0, LengthTag);
    if (length < 0)
    {
      throw sphcover::RankShare::PeerFailure();
    }
    std::vector<char> block(static_cast<std::size_t>(length));
    controller->Receive(block.data(), length, 0, BlockTag);
    return block;
  }
  std::exception_ptr failure;
  for (int r = 1; r < ranks; ++r)
  {
    std::vector<char> block;
    if (!failure)
    {
      try
      {
        block = blockOf(r);
      }
      catch (...)
      {
        failure = std::current_exception();
      }
    }
    const vtkIdType length = failure ? -1 : static_cast<vtkIdType>(block.size());
    controller->Send(&length, 1, r, LengthTag);
    if (!failure)
    {
      controller->Send(block.data(), length, r, BlockTag);
    }
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  return std::vector<char>();
}

std::vector<RankFigures> GatherFigures(vtkMultiProcessController* controller,
  const RankFigures& mine)
{
  const int ranks = controller->GetNumberOfProcesses();
  const double sent[3] = { mine.Receivers, mine.Seconds, mine.Bytes };
  std::vector<double> received(3 * static_cast<std::size_t>(ranks), 0.0);
  controller->AllGather(sent, received.data(), 3);
  std::vector<RankFigures> figures(static_cast<std::size_t>(ranks));
  for (std::size_t r = 0; r < figures.size(); ++r)
  {
    figures[r] = { received[3 * r], received[3 * r + 1], received[3 * r + 2] };
  }
  return figures;
}

std::vector<std::vector<char>> GatherBytes(vtkMultiProcessController* controller,
  std::vector<char> mine,
  bool everyRank)
{
  const int ranks = controller->GetNumberOfProcesses();
  const vtkIdType length = static_cast<vtkIdType>(mine.size());
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks), 0);
  controller->AllGather(&length, lengths.data(), 1);
  std::vector<std::vector<char>> blocks;
  if (!everyRank)
  {
    // Rank by rank into their own buffers: one buffer of all, split afterwards, would hold
    // every byte twice on rank 0.
    constexpr int BytesTag = 19003;
    if (controller->GetLocalProcessId() != 0)
    {
      controller->Send(mine.data(), length, 0, BytesTag);
      return blocks;
    }
    blocks.resize(lengths.size());
    blocks[0] = std::move(mine);
    for (std::size_t r = 1; r < lengths.size(); ++r)
    {
      blocks[r].resize(static_cast<std::size_t>(lengths[r]));
      controller->Receive(blocks[r].data(), lengths[r], static_cast<int>(r), BytesTag);
    }
    return blocks;
  }
  std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks), 0);
  vtkIdType total = 0;
  for (std::size_t r = 0; r < lengths.size(); ++r)
  {
    offsets[r] = total;
    total += lengths[r];
  }
  std::vector<char> all(static_cast<std::size_t>(total));
  controller->AllGatherV(mine.data(), all.data(), length, lengths.data(), offsets.data());
  for (std::size_t r = 0; r < lengths.size(); ++r)
  {
    blocks.emplace_back(all.begin() + offsets[r], all.begin() + offsets[r] + lengths[r]);
  }
  return blocks;
}
}
