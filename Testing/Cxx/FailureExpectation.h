// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FailureExpectation.h
 * @brief Test helper: update an algorithm that must fail and check that it reported exactly
 * one error (with the expected words) and failed the request.
 *
 * Unlike vtkTest::ErrorObserver it counts the errors (one clear message is the contract), and
 * it also silences the executive's "returned failure" message.
 */
#ifndef SPHCOVER_FAILUREEXPECTATION_H
#define SPHCOVER_FAILUREEXPECTATION_H

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>

#include <iostream>
#include <string>
#include <vector>

namespace FailureExpectation
{
inline void Record(vtkObject*, unsigned long, void* clientData, void* callData)
{
  const std::string message = callData ? static_cast<const char*>(callData) : "";
  // Keep the message, not VTK's "ERROR: In file, line" header (CTest fails on "ERROR:").
  static_cast<std::vector<std::string>*>(clientData)
    ->push_back(message.substr(message.find('\n') + 1));
}

/// Updates `algorithm`; returns the number of failed checks (0 if it failed as expected with
/// one error containing every fragment). The message is printed for the test log.
inline int Check(vtkAlgorithm* algorithm,
  const std::vector<std::string>& fragments,
  const std::string& what,
  std::string* message = nullptr)
{
  std::vector<std::string> errors;
  std::vector<std::string> executiveErrors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(Record);
  onError->SetClientData(&errors);
  vtkNew<vtkCallbackCommand> onExecutiveError;
  onExecutiveError->SetCallback(Record);
  onExecutiveError->SetClientData(&executiveErrors);
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, onError);
  const unsigned long executiveTag =
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, onExecutiveError);
  const int status = algorithm->GetExecutive()->Update();
  algorithm->RemoveObserver(tag);
  algorithm->GetExecutive()->RemoveObserver(executiveTag);

  int failed = 0;
  if (status != 0)
  {
    std::cerr << "FAILED: " << what << ": the request succeeded\n";
    ++failed;
  }
  if (errors.size() != 1)
  {
    std::cerr << "FAILED: " << what << ": " << errors.size() << " errors instead of one\n";
    return failed + 1;
  }
  std::cout << what << ":\n  " << errors[0] << "\n";
  for (const std::string& fragment : fragments)
  {
    if (errors[0].find(fragment) == std::string::npos)
    {
      std::cerr << "FAILED: " << what << ": the message lacks '" << fragment << "'\n";
      ++failed;
    }
  }
  if (message)
  {
    *message = errors[0];
  }
  return failed;
}
}

#endif
