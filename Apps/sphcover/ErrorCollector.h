// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ErrorCollector.h
 * @brief Catches the errors VTK algorithms report (ErrorEvent) so the command line can print
 * one clear line instead of VTK's multi-line "ERROR: In file, line" blocks, and their warnings
 * (WarningEvent), which the command prints as one line each when it succeeds.
 */
#ifndef SPHCOVER_ERRORCOLLECTOR_H
#define SPHCOVER_ERRORCOLLECTOR_H

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkAlgorithm;
class vtkCallbackCommand;
class vtkObject;

class ErrorCollector
{
public:
  ErrorCollector();

  /// Collects the errors of the algorithm and of its executive ("returned failure").
  void Watch(vtkAlgorithm* algorithm);

  /// The first error an algorithm reported, without VTK's header and object address.
  std::string First() const;

  /// The warnings every watched algorithm of the process reported, in order, stripped as the
  /// errors (a light dropped behind too many panes: one per stage, not per ray).
  static std::vector<std::string>& Warnings();

private:
  static void OnError(vtkObject* caller, unsigned long, void* clientData, void* callData);
  static void OnWarning(vtkObject* caller, unsigned long, void* clientData, void* callData);

  vtkSmartPointer<vtkCallbackCommand> Callback;
  vtkSmartPointer<vtkCallbackCommand> WarningCallback;
  std::vector<std::string> Messages;
};

#endif
