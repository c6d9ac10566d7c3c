// SPDX-License-Identifier: BSD-3-Clause
#include "ErrorCollector.h"

#include "vtkMessageText.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>

ErrorCollector::ErrorCollector()
  : Callback(vtkSmartPointer<vtkCallbackCommand>::New())
{
  this->Callback->SetCallback(&ErrorCollector::OnError);
  this->Callback->SetClientData(this);
  this->WarningCallback = vtkSmartPointer<vtkCallbackCommand>::New();
  this->WarningCallback->SetCallback(&ErrorCollector::OnWarning);
}

void ErrorCollector::Watch(vtkAlgorithm* algorithm)
{
  algorithm->AddObserver(vtkCommand::ErrorEvent, this->Callback);
  algorithm->AddObserver(vtkCommand::WarningEvent, this->WarningCallback);
  // The executive's "returned failure for request" repeats what the algorithm said: observing
  // it keeps it off the terminal; it is never the first message of interest.
  algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->Callback);
}

void ErrorCollector::OnError(vtkObject* caller, unsigned long, void* clientData, void* callData)
{
  auto* self = static_cast<ErrorCollector*>(clientData);
  if (vtkExecutive::SafeDownCast(caller) || !callData)
  {
    return;
  }
  self->Messages.push_back(vtkMessageText::Strip(static_cast<const char*>(callData)));
}

void ErrorCollector::OnWarning(vtkObject*, unsigned long, void*, void* callData)
{
  if (callData)
  {
    Warnings().push_back(vtkMessageText::Strip(static_cast<const char*>(callData)));
  }
}

std::vector<std::string>& ErrorCollector::Warnings()
{
  static std::vector<std::string> warnings;
  return warnings;
}

std::string ErrorCollector::First() const
{
  return this->Messages.empty() ? std::string("the pipeline failed without a message")
                                : this->Messages.front();
}
