// SPDX-License-Identifier: BSD-3-Clause
#include "ProgressBar.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>

#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace
{
/// Seconds with one decimal below 100 s, whole seconds above (a log line stays short).
std::string FormatSeconds(double seconds)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(seconds < 100.0 ? 1 : 0) << seconds << " s";
  return text.str();
}
}

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

ProgressBar::ProgressBar(const std::string& stage, bool quiet)
  : Algorithm(nullptr)
  , Stage(stage)
  , Quiet(quiet)
  , Interactive(isatty(fileno(stderr)) != 0)
{
}

ProgressBar::~ProgressBar()
{
  if (this->Algorithm)
  {
    this->Algorithm->RemoveObserver(this->Tag);
  }
  // A stage that stopped early (error, abort) leaves its bar unfinished: end the line so that
  // the error message starts on its own. Plain lines always end with their newline.
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

std::string ProgressBar::Times(double fraction, bool done) const
{
  const double elapsed = this->Seconds();
  std::string text = FormatSeconds(elapsed) + " elapsed";
  if (!done && fraction >= 0.01)
  {
    text += ", about " + FormatSeconds(elapsed * (1.0 - fraction) / fraction) + " left";
  }
  return text;
}

void ProgressBar::Show(double fraction)
{
  const auto now = std::chrono::steady_clock::now();
  if (!this->Started || fraction <= 0.0)
  {
    // The first report, or the stage runs again (an algorithm updated twice): start over.
    this->Started = true;
    this->Finished = false;
    this->Start = now;
    this->LastPercent = -1;
    this->LastLinePercent = -1;
    this->LastLineSeconds = 0.0;
    this->LastBarLength = 0;
  }
  this->End = now;
  const int percent = static_cast<int>(100.0 * fraction + 0.5);
  if (this->Quiet || this->Finished)
  {
    return;
  }
  const bool done = fraction >= 1.0;
  if (this->Interactive)
  {
    if (percent != this->LastPercent)
    {
      this->ShowBar(percent, done);
    }
  }
  else
  {
    this->ShowLine(percent, done);
  }
  this->LastPercent = percent;
  this->Finished = done;
}

void ProgressBar::ShowBar(int percent, bool done)
{
  constexpr int width = 40;
  const int filled = percent * width / 100;
  std::ostringstream line;
  line << this->Stage << " [" << std::string(static_cast<size_t>(filled), '#')
       << std::string(static_cast<size_t>(width - filled), ' ') << "] " << percent << "%  ";
  if (done)
  {
    line << std::fixed << std::setprecision(2) << this->Seconds() << " s";
  }
  else
  {
    line << this->Times(percent / 100.0, false);
  }
  std::string text = line.str();
  // The time left shortens as the stage goes on: blank the end of the longer line before.
  const std::size_t length = text.size();
  if (length < this->LastBarLength)
  {
    text.append(this->LastBarLength - length, ' ');
  }
  this->LastBarLength = length;
  std::cerr << '\r' << text << (done ? "\n" : "");
  std::cerr.flush();
}

void ProgressBar::ShowLine(int percent, bool done)
{
  const double elapsed = this->Seconds();
  // A line when the stage has crossed a 10 % step since the last line (or its start) and
  // a second has passed, or LogInterval seconds have passed: a slow stage shows it is alive,
  // a fast one prints only its last line, and a stage that fails at once none.
  const int since = this->LastLinePercent < 0 ? 0 : this->LastLinePercent;
  const double quiet = elapsed - this->LastLineSeconds;
  const bool step = percent / 10 > since / 10 && quiet >= 1.0;
  const bool late = quiet >= LogInterval && percent != since;
  if (!done && !step && !late)
  {
    return;
  }
  this->LastLinePercent = percent;
  this->LastLineSeconds = elapsed;
  std::ostringstream line;
  if (done)
  {
    line << this->Stage << ": 100% (" << std::fixed << std::setprecision(2) << elapsed
         << " s elapsed)\n";
  }
  else
  {
    line << this->Stage << ": " << percent << "% (" << this->Times(percent / 100.0, false) << ")\n";
  }
  // One write per line: lines of a log stay whole.
  std::cerr << line.str() << std::flush;
}
