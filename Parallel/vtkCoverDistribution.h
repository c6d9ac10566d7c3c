// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkCoverDistribution.h
 * @brief The collective steps of a spherical cover built by the K processes of a
 * vtkMultiProcessController (MPI under pvbatch, pvserver and `mpiexec sphcover`): every rank
 * builds the rows H_i of a range of characteristic points (paper §3.3, §4.3: one R-buffer per
 * point, rows independent), balanced by Core's estimate of each row's work, and the row blocks
 * are gathered in receiver order, so the cover is the serial one bit for bit whatever K; rank 0
 * then deals the light propagation its rows (DealFromFirst).
 *
 * Contract of every function here: collective, so every rank of the controller calls it at the
 * same point, in the same order. A rank that fails does not return early: it reaches the next
 * Agree with its problem, and every rank then learns the same one message there. No function
 * blocks on a rank that has failed before an Agree, because each collective that moves data
 * comes after an Agree that said every rank is ready.
 */
#ifndef vtkCoverDistribution_h
#define vtkCoverDistribution_h

#include "math/RankShare.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

class vtkDataSet;
class vtkMultiProcessController;

namespace vtkCoverDistribution
{
/**
 * The controller as Core's RankShare (math/RankShare.h): Join is an all-gather of every
 * rank's flag and bytes (two collectives: the lengths and flags, then the bytes). One rank:
 * the plain RankShare.
 */
sphcover::RankShare ShareOf(vtkMultiProcessController* controller);

/**
 * Every rank's `problem` ("" when it has none) reduced to one: "" when no rank has a problem,
 * else the problem of the lowest rank that has one (a rank whose problem is only that another
 * failed, RankShare::PeerFailure, after the others), followed by " (rank r of K)", on every rank.
 */
std::string Agree(vtkMultiProcessController* controller, const std::string& problem);

/// The number of ranks for which `flag` holds.
int Count(vtkMultiProcessController* controller, bool flag);

/// Rank 0's dataset, copied into `data` on the other ranks (an instance of the same class).
void BroadcastFromFirst(vtkMultiProcessController* controller, vtkDataSet* data);

/**
 * Rank 0 deals every other rank its own bytes: it calls `blockOf(r)` for r = 1, ..., K - 1 in
 * turn and sends each block before making the next (so it holds one at a time), and returns an
 * empty block; every other rank returns the block rank 0 made for it. When `blockOf` throws on
 * rank 0, the ranks still waiting get a failure instead of a block and throw
 * sphcover::RankShare::PeerFailure, and rank 0 rethrows: no rank waits forever.
 */
std::vector<char> DealFromFirst(vtkMultiProcessController* controller,
  const std::function<std::vector<char>(int rank)>& blockOf);

/// What each rank did: its rows, the wall seconds it took to build them and their bytes.
struct RankFigures
{
  double Receivers = 0.0;
  double Seconds = 0.0;
  double Bytes = 0.0;
};

/// Every rank's figures, in rank order, on every rank.
std::vector<RankFigures> GatherFigures(vtkMultiProcessController* controller,
  const RankFigures& mine);

/**
 * Every rank's bytes, in rank order: on every rank when `everyRank`, else on rank 0 only (the
 * others get an empty list; rank 0 receives each rank's bytes into its own buffer, so that it
 * holds them once).
 */
std::vector<std::vector<char>> GatherBytes(vtkMultiProcessController* controller,
  std::vector<char> mine,
  bool everyRank);
}

#endif
