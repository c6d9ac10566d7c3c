// SPDX-License-Identifier: BSD-3-Clause
#include "ProgressBar.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>

#include <cstdio>
#include <iomanip>
#include <iostream>
#include <unistd.h>

ProgressBar::ProgressBar(vtkAlgorithm* algorithm, const std::string& stage, bool quiet)
  : Algorithm(algorithm)
  , Callback(vtkSmartPointer<vtkCallbackCommand>::New())
  , Stage(stage)
  , Quiet(quiet)
  , Interactive(isatty(fileno(stderr)) != 0)
{
  this->Callback->SetCallback(&ProgressBar::OnProgress);
  this->Callback->SetClientData(this);
  this->Tag = algorithm->AddObserver(vtkCommand::ProgressEvent, this->Callback);
}

ProgressBar::~ProgressBar()
{
  this->Algorithm->RemoveObserver(this->Tag);
  // A stage that stopped early (error, abort) leaves its bar unfinished: end the line so that
  // the error message starts on its own.
  if (!this->Quiet && this->Interactive && this->LastPercent >= 0 && !this->Finished)
  {
    std::cerr << std::endl;
  }
}

double ProgressBar::Seconds() const
{
  return this->Started ? std::chrono::duration<double>(this->End - this->Start).count() : 0.0;
}

void ProgressBar::OnProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  static_cast<ProgressBar*>(clientData)->Show(*static_cast<double*>(callData));
}

void ProgressBar::Show(double fraction)
{
  const auto now = std::chrono::steady_clock::now();
  if (!this->Started || fraction <= 0.0)
  {
    this->Started = true;
    this->Finished = false;
    this->Start = now;
    this->LastPercent = -1;
  }
  this->End = now;
  const int percent = static_cast<int>(100.0 * fraction + 0.5);
  if (this->Quiet || !this->Interactive || percent == this->LastPercent || this->Finished)
  {
    return;
  }
  this->LastPercent = percent;
  const bool done = fraction >= 1.0;
  constexpr int width = 40;
  const int filled = percent * width / 100;
  std::cerr << '\r' << this->Stage << " [" << std::string(static_cast<size_t>(filled), '#')
            << std::string(static_cast<size_t>(width - filled), ' ') << "] " << percent << '%';
  if (done)
  {
    std::cerr << "  " << std::fixed << std::setprecision(2) << this->Seconds() << " s\n"
              << std::defaultfloat;
  }
  std::cerr.flush();
  this->Finished = done;
}
