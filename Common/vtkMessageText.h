// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkMessageText.h
 * @brief The message of a VTK error or warning event without VTK's header: what the command
 * line prints as its one line and what the ranks of a distributed filter agree on.
 */
#ifndef vtkMessageText_h
#define vtkMessageText_h

#include <string>

namespace vtkMessageText
{
/// "ERROR: In <file>, line <n>\n<class> (<address>): <message>\n\n" -> "<message>".
inline std::string Strip(const char* text)
{
  std::string message = text ? text : "";
  const size_t newline = message.find('\n');
  if (newline != std::string::npos)
  {
    message = message.substr(newline + 1);
  }
  const size_t address = message.find("): ");
  if (address != std::string::npos)
  {
    message = message.substr(address + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  return message;
}
}

#endif
