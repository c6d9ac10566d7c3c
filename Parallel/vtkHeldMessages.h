// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkHeldMessages.h
 * @brief Holds back the errors and warnings of an object while the ranks of a distributed step
 * have not agreed on them (vtkCoverDistribution::Agree): a failing rank would otherwise show
 * its own message and then the agreed one. Observes before any other observer and stops the
 * event. A null object holds nothing (one process: messages go out as they come).
 */
#ifndef vtkHeldMessages_h
#define vtkHeldMessages_h

#include "vtkMessageText.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkObject.h>

#include <string>
#include <vector>

class vtkHeldMessages
{
public:
  explicit vtkHeldMessages(vtkObject* object)
    : Object(object)
  {
    if (!object)
    {
      return;
    }
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(&vtkHeldMessages::Hold);
    this->Callback->SetAbortFlagOnExecute(1);
    this->ErrorTag = object->AddObserver(vtkCommand::ErrorEvent, this->Callback, 1.0f);
    this->WarningTag = object->AddObserver(vtkCommand::WarningEvent, this->Callback, 1.0f);
  }
  ~vtkHeldMessages()
  {
    if (this->Object)
    {
      this->Object->RemoveObserver(this->ErrorTag);
      this->Object->RemoveObserver(this->WarningTag);
    }
  }
  vtkHeldMessages(const vtkHeldMessages&) = delete;
  vtkHeldMessages& operator=(const vtkHeldMessages&) = delete;

  /// The first message held, or `otherwise` when there is none.
  std::string First(const std::string& otherwise) const
  {
    return this->Messages.empty() ? otherwise : this->Messages.front();
  }

private:
  static void Hold(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    static_cast<vtkHeldMessages*>(clientData)
      ->Messages.push_back(vtkMessageText::Strip(static_cast<const char*>(callData)));
  }

  vtkObject* Object;
  vtkNew<vtkCallbackCommand> Callback;
  unsigned long ErrorTag = 0;
  unsigned long WarningTag = 0;
  std::vector<std::string> Messages;
};

#endif
