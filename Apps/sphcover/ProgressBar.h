// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ProgressBar.h
 * @brief A progress bar on stderr for one pipeline stage, fed by the algorithm's
 * ProgressEvent; silent with --quiet or when stderr is not a terminal (logs and pipes get
 * no carriage-return animation, and errors stay the only line on stderr).
 */
#ifndef SPHCOVER_PROGRESSBAR_H
#define SPHCOVER_PROGRESSBAR_H

#include <vtkSmartPointer.h>

#include <chrono>
#include <string>

class vtkAlgorithm;
class vtkCallbackCommand;
class vtkObject;

class ProgressBar
{
public:
  /// Observes `algorithm`'s progress under the name `stage`.
  ProgressBar(vtkAlgorithm* algorithm, const std::string& stage, bool quiet);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Seconds from the first progress report to the last.
  double Seconds() const;

private:
  static void OnProgress(vtkObject* caller, unsigned long, void* clientData, void* callData);
  void Show(double fraction);

  vtkAlgorithm* Algorithm;
  unsigned long Tag = 0;
  vtkSmartPointer<vtkCallbackCommand> Callback;
  std::string Stage;
  bool Quiet;
  bool Interactive;
  int LastPercent = -1;
  bool Started = false;
  bool Finished = false;
  std::chrono::steady_clock::time_point Start;
  std::chrono::steady_clock::time_point End;
};

#endif
