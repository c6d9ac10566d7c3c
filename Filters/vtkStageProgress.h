// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkStageProgress.h
 * @brief One stage of a filter's progress: its share of the filter's progress, its name and
 * the time it has left as the algorithm's progress text, and the abort flag, for the progress
 * callbacks the Core stages take.
 *
 * Why the text: ParaView's status bar labels an algorithm's progress with its progress text,
 * or else its class name (vtkPVProgressHandler), so "Spherical Cover: cover, about 12 s left"
 * says which stage runs and for how long where "vtkSphericalCoverFilter 40%" did not. The time
 * left is the stage's pace so far, (1 - f) / f times its elapsed time, shown once the stage has
 * run a second and done 1 % (before that the estimate is noise). Setting the text does not
 * modify the algorithm (vtkAlgorithm::SetProgressText), so it never re-executes a pipeline.
 *
 * The filters set their label as the text in their constructors, so the pipeline's own 0 % and
 * 100 % events (vtkStreamingDemandDrivenPipeline) are labelled too; a stage puts it back when
 * it ends.
 *
 * The callback returns false once the algorithm's AbortExecute is set (a VTK pipeline's
 * abort; ParaView 5.11's GUI never sets it, see README.md, "ParaView users").
 */
#ifndef vtkStageProgress_h
#define vtkStageProgress_h

#include <vtkAlgorithm.h>

#include <chrono>
#include <cmath>
#include <string>

class vtkStageProgress
{
public:
  /// A stage named `name` ("Filter: stage") whose progress runs from `begin` to `end` of the
  /// algorithm's; the clock starts now.
  vtkStageProgress(vtkAlgorithm* algorithm, std::string name, double begin, double end)
    : Algorithm(algorithm)
    , Name(std::move(name))
    , Begin(begin)
    , End(end)
    , Start(std::chrono::steady_clock::now())
  {
    const char* before = this->Algorithm->GetProgressText();
    this->Before = before ? before : "";
    this->Algorithm->SetProgressText(this->Name.c_str());
  }

  /// The text before the stage again (the filter's name, for the pipeline's 100 %).
  ~vtkStageProgress() { this->Algorithm->SetProgressText(this->Before.c_str()); }

  vtkStageProgress(const vtkStageProgress&) = delete;
  vtkStageProgress& operator=(const vtkStageProgress&) = delete;

  /// Reports the fraction `fraction` of the stage done; false when the algorithm was aborted.
  bool operator()(double fraction)
  {
    const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
    std::string text = this->Name;
    if (elapsed >= 1.0 && fraction >= 0.01 && fraction < 1.0)
    {
      const double left = elapsed * (1.0 - fraction) / fraction;
      text += ", about " + std::to_string(static_cast<long long>(std::ceil(left))) + " s left";
    }
    this->Algorithm->SetProgressText(text.c_str());
    this->Algorithm->UpdateProgress(this->Begin + (this->End - this->Begin) * fraction);
    return !this->Algorithm->GetAbortExecute();
  }

private:
  vtkAlgorithm* Algorithm;
  std::string Name;
  std::string Before;
  double Begin;
  double End;
  std::chrono::steady_clock::time_point Start;
};

#endif
