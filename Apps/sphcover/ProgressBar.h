// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ProgressBar.h
 * @brief The progress of one pipeline stage on stderr, fed by the algorithm's ProgressEvent,
 * with the time elapsed and an estimate of the time left; nothing with --quiet.
 *
 * On a terminal: one line redrawn in place (carriage return),
 *   `cover [################                        ] 40%  12.3 s elapsed, about 18 s left`,
 * ending with the stage's total time. Elsewhere (a CI log, `2> log`, a pipe) no carriage-return
 * animation, which a log would keep as one garbled line, but plain lines,
 *   `cover: 40% (12.3 s elapsed, about 18 s left)`,
 * one when the stage has crossed a 10 % step and a second has passed since the last line, or
 * when LogInterval seconds have passed (a fast stage prints only its last line, a stage that
 * fails at once none, so that its error is the only line), and a last line
 * `cover: 100% (30.12 s elapsed)` when it completes.
 *
 * The time left assumes the rest of the stage runs at the rate so far (elapsed x (1 - f) / f):
 * a rough figure, as the stages' progress is not uniform in time; it is shown from 1 % on.
 */
#ifndef SPHCOVER_PROGRESSBAR_H
#define SPHCOVER_PROGRESSBAR_H

#include <vtkSmartPointer.h>

#include <chrono>
#include <cstddef>
#include <string>

class vtkAlgorithm;
class vtkCallbackCommand;
class vtkObject;

class ProgressBar
{
public:
  /// Observes `algorithm`'s progress under the name `stage`; shows it unless `quiet`, as a bar
  /// when stderr is a terminal (isatty), as plain lines otherwise.
  ProgressBar(vtkAlgorithm* algorithm, const std::string& stage, bool quiet);
  /// A stage that is no VTK algorithm (the frames of `sphcover walk`): fed by Update.
  ProgressBar(const std::string& stage, bool quiet);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Reports the stage's progress, a fraction in [0, 1] (what an algorithm's ProgressEvent does).
  void Update(double fraction) { this->Show(fraction); }

  /// Seconds from the first progress report to the last.
  double Seconds() const;

  /// Longest time between two plain lines of a stage still running, in seconds.
  static constexpr double LogInterval = 5.0;

private:
  static void OnProgress(vtkObject* caller, unsigned long, void* clientData, void* callData);
  void Show(double fraction);
  void ShowBar(int percent, bool done);
  void ShowLine(int percent, bool done);
  /// "12.3 s elapsed, about 18 s left" (no estimate below 1 % or when done).
  std::string Times(double fraction, bool done) const;

  /// The algorithm observed (null: fed by Update).
  vtkAlgorithm* Algorithm;
  unsigned long Tag = 0;
  vtkSmartPointer<vtkCallbackCommand> Callback;
  std::string Stage;
  bool Quiet;
  bool Interactive;
  int LastPercent = -1;
  /// Plain lines: the percentage and time of the last line printed (-1: none yet).
  int LastLinePercent = -1;
  double LastLineSeconds = 0.0;
  /// The bar: length of the last line drawn, to blank what a shorter one leaves behind.
  std::size_t LastBarLength = 0;
  bool Started = false;
  bool Finished = false;
  std::chrono::steady_clock::time_point Start;
  std::chrono::steady_clock::time_point End;
};

#endif
