// SPDX-License-Identifier: BSD-3-Clause
#include "OutputFiles.h"

#include "ErrorCollector.h"
#include "vtkCoverDistribution.h"
#include "vtkSphericalCoverArrayNames.h"

#include <vtkImageData.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkOpenEXRWriter.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkXMLWriter.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <pthread.h>
#include <sys/types.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace sphcover_cli
{
namespace
{
/// The renames into place happen under this lock, and the signal thread takes it before it ends
/// the process, so a signal never cuts a commit in two.
std::mutex CommitLock;

/// The write end of the pipe to the janitor process (-1: none). The staging folders in use are
/// announced on it by the prefix of their names (folder and `.<name>.sphcover-<pid>.`): '+' and
/// the prefix to add, '-' to withdraw, each record ended by a NUL (a path may hold any other
/// byte).
int JanitorPipe = -1;

const std::string StagingTag = ".sphcover-";

sigset_t TerminationSignals()
{
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  return signals;
}

void Announce(char change, const fs::path& prefix)
{
  if (JanitorPipe < 0)
  {
    return;
  }
  const std::string record = change + prefix.string() + '\0';
  // Records are far below PIPE_BUF, so each write is atomic.
  [[maybe_unused]] const ssize_t written = write(JanitorPipe, record.data(), record.size());
}

/// The janitor: a child process that outlives sphcover by a moment. When the pipe closes
/// (sphcover ended, normally, by a signal, a crash or SIGKILL) it removes the staging folders
/// whose prefix is still announced. Removing them after the writer is gone is what makes it safe: a
/// writer still running could create them again.
[[noreturn]] void RunJanitor(int pipe)
{
  std::set<std::string> prefixes;
  std::string pending;
  char buffer[4096];
  for (;;)
  {
    const ssize_t count = read(pipe, buffer, sizeof(buffer));
    if (count < 0 && errno == EINTR)
    {
      continue;
    }
    if (count <= 0)
    {
      break;
    }
    pending.append(buffer, static_cast<std::size_t>(count));
    for (std::size_t end; (end = pending.find('\0')) != std::string::npos;)
    {
      const std::string path = pending.substr(1, end - 1);
      if (pending[0] == '+')
      {
        prefixes.insert(path);
      }
      else
      {
        prefixes.erase(path);
      }
      pending.erase(0, end + 1);
    }
  }
  std::error_code ignored;
  for (const fs::path prefix : prefixes)
  {
    const std::string start = prefix.filename().string();
    for (const fs::directory_entry& entry : fs::directory_iterator(prefix.parent_path(), ignored))
    {
      if (entry.path().filename().string().rfind(start, 0) == 0)
      {
        fs::remove_all(entry.path(), ignored);
      }
    }
  }
  _exit(0);
}

/// Starts the janitor; without one (fork failed) outputs are still whole, and a signal's
/// leftovers are removed by the next run.
void StartJanitor()
{
  int ends[2];
  if (pipe2(ends, O_CLOEXEC) != 0)
  {
    return;
  }
  const pid_t child = fork();
  if (child == 0)
  {
    // Ctrl-C reaches the whole process group: the janitor must outlive sphcover, not die with
    // it. It holds none of sphcover's output streams, so a caller reading them sees their end
    // when sphcover ends.
    std::signal(SIGINT, SIG_IGN);
    std::signal(SIGTERM, SIG_IGN);
    std::signal(SIGHUP, SIG_IGN);
    close(ends[1]);
    const int null = open("/dev/null", O_RDWR);
    for (int stream : { STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO })
    {
      dup2(null, stream);
    }
    RunJanitor(ends[0]);
  }
  close(ends[0]);
  if (child > 0)
  {
    JanitorPipe = ends[1];
  }
  else
  {
    close(ends[1]);
  }
}

/// The folder `path` is written into; throws "cannot write '<path>': no folder <folder>" when
/// it does not exist.
fs::path OutputFolder(const std::string& path)
{
  const fs::path folder = fs::absolute(path).parent_path();
  std::error_code error;
  if (!fs::is_directory(folder, error))
  {
    throw std::runtime_error("cannot write '" + path + "': no folder " + folder.string());
  }
  return folder;
}

/// The pid in a staging folder's name `.<name>.sphcover-<pid>.<random>`, or 0.
pid_t StagingOwner(const std::string& name)
{
  const std::size_t tag = name.rfind(StagingTag);
  if (name.empty() || name[0] != '.' || tag == std::string::npos)
  {
    return 0;
  }
  const char* digits = name.c_str() + tag + StagingTag.size();
  char* end = nullptr;
  const long pid = std::strtol(digits, &end, 10);
  return (end != digits && *end == '.' && pid > 0) ? static_cast<pid_t>(pid) : 0;
}

/// Removes the staging folders in `folder` left by runs that no longer exist (killed with
/// SIGKILL, or by a power cut): their pid does not run any more.
void RemoveAbandonedStaging(const fs::path& folder)
{
  std::error_code ignored;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ignored))
  {
    const pid_t owner = StagingOwner(entry.path().filename().string());
    if (owner != 0 && owner != getpid() && entry.is_directory(ignored) && kill(owner, 0) == -1 &&
      errno == ESRCH)
    {
      fs::remove_all(entry.path(), ignored);
    }
  }
}

/// Moves the staged output into `folder`: subfolders (a multiblock file's pieces) first, so the
/// file that refers to them appears last.
void MoveIntoPlace(const fs::path& staging, const fs::path& folder, const fs::path& file)
{
  for (const fs::directory_entry& entry : fs::directory_iterator(staging))
  {
    if (entry.is_directory())
    {
      const fs::path destination = folder / entry.path().filename();
      fs::remove_all(destination);
      fs::rename(entry.path(), destination);
    }
  }
  fs::rename(staging / file, folder / file);
}
}

std::string ExtensionOf(const std::string& path)
{
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return extension;
}

void CheckOutputPath(const std::string& option,
  const std::string& path,
  const std::vector<std::string>& extensions,
  const std::string& kind)
{
  if (path.empty())
  {
    return;
  }
  if (std::find(extensions.begin(), extensions.end(), ExtensionOf(path)) == extensions.end())
  {
    std::string expected;
    for (const std::string& extension : extensions)
    {
      expected += (expected.empty() ? "" : " or ") + extension;
    }
    throw std::runtime_error(
      option + " '" + path + "': unknown " + kind + " format (expected " + expected + ")");
  }
  std::error_code error;
  if (fs::is_directory(path, error))
  {
    throw std::runtime_error("cannot write '" + path + "': it is a folder");
  }
  const fs::path folder = OutputFolder(path);
  if (access(folder.c_str(), W_OK) != 0)
  {
    throw std::runtime_error(
      "cannot write '" + path + "': folder " + folder.string() + ": " + std::strerror(errno));
  }
}

void WatchTerminationSignals()
{
  StartJanitor();
  const sigset_t signals = TerminationSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread(
    [signals]()
    {
      int signal = 0;
      while (sigwait(&signals, &signal) != 0)
      {
      }
      // Wait out a commit in progress, and keep the lock: nothing moves into place after this.
      CommitLock.lock();
      const char message[] = "\nsphcover: interrupted\n";
      // The leading newline ends a progress bar's line; without a terminal there is none.
      const int skip = isatty(STDERR_FILENO) ? 0 : 1;
      [[maybe_unused]] const ssize_t written =
        write(STDERR_FILENO, message + skip, sizeof(message) - 1 - skip);
      // End as the signal would have (the caller sees "terminated by SIGINT"); the janitor
      // removes the staging folders once the process is gone.
      std::signal(signal, SIG_DFL);
      sigset_t only;
      sigemptyset(&only);
      sigaddset(&only, signal);
      pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
      raise(signal);
      _exit(128 + signal);
    })
    .detach();
}

void WriteAtomically(const std::string& path, const std::function<void(const fs::path&)>& write)
{
  const fs::path target = fs::absolute(path);
  const fs::path folder = OutputFolder(path);
  const auto fail = [&path](const std::string& why)
  { return std::runtime_error("cannot write '" + path + "': " + why); };
  RemoveAbandonedStaging(folder);
  const fs::path prefix =
    folder / ("." + target.filename().string() + StagingTag + std::to_string(getpid()) + ".");
  // Announced before the folder exists, so no moment is left in which this process could end
  // with a folder the janitor does not know.
  Announce('+', prefix);
  std::string pattern = prefix.string() + "XXXXXX";
  if (!mkdtemp(pattern.data()))
  {
    Announce('-', prefix);
    throw fail(std::strerror(errno));
  }
  const fs::path staging = pattern;
  std::string failure;
  try
  {
    write(staging / target.filename());
    std::lock_guard<std::mutex> lock(CommitLock);
    MoveIntoPlace(staging, folder, target.filename());
  }
  catch (const fs::filesystem_error& e)
  {
    failure = e.code().message();
  }
  catch (const std::exception& e)
  {
    // A writer's message names the staged file: name the output the user asked for.
    failure = e.what();
    const std::string staged = (staging / target.filename()).string();
    for (std::size_t at; (at = failure.find(staged)) != std::string::npos;)
    {
      failure.replace(at, staged.size(), target.string());
    }
  }
  std::error_code ignored;
  fs::remove_all(staging, ignored);
  Announce('-', prefix);
  if (!failure.empty())
  {
    throw fail(failure);
  }
}

namespace
{
/// `data` through the XML `writer` at `staged`; throws the writer's first error.
void WriteXml(vtkXMLWriter* writer, vtkDataObject* data, const fs::path& staged)
{
  // Inline base64 (zlib-compressed), not VTK's default appended data: from expat 2.6 on
  // (and Debian 12's libexpat1 2.5.0-1+deb12u5, which carries its "reparse deferral") the
  // XML reader of VTK 9.2 / ParaView 5.11 no longer stops at <AppendedData> and fails on
  // the bytes after it ("not well-formed"). Inline data is well-formed XML every reader
  // parses, and still bit-exact.
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  writer->SetInputData(data);
  writer->SetFileName(staged.string().c_str());
  ErrorCollector errors;
  errors.Watch(writer);
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
  {
    throw std::runtime_error(errors.First());
  }
}

/// Rank 0's `text` on every rank of `controller` (collective).
std::string BroadcastText(vtkMultiProcessController* controller, std::string text)
{
  vtkIdType length = static_cast<vtkIdType>(text.size());
  controller->Broadcast(&length, 1, 0);
  text.resize(static_cast<std::size_t>(length));
  if (length > 0)
  {
    controller->Broadcast(text.data(), length, 0);
  }
  return text;
}
}

void WriteXmlAtomically(vtkXMLWriter* writer, vtkDataObject* data, const std::string& path)
{
  WriteAtomically(path, [&](const fs::path& staged) { WriteXml(writer, data, staged); });
}

void WriteXmlAtomicallyOnRanks(vtkXMLWriter* writer,
  vtkDataObject* data,
  const std::string& path,
  vtkMultiProcessController* controller)
{
  // Rank 0 stages the file and tells the others where; each rank writes its part there; once
  // all agree that every part is written, rank 0 moves the whole into place.
  const auto writeHere = [&](const fs::path& staged)
  {
    std::string problem;
    try
    {
      WriteXml(writer, data, staged);
    }
    catch (const std::exception& e)
    {
      problem = e.what();
    }
    problem = vtkCoverDistribution::Agree(controller, problem);
    if (!problem.empty())
    {
      throw std::runtime_error(problem);
    }
  };
  if (controller->GetLocalProcessId() != 0)
  {
    const std::string staged = BroadcastText(controller, std::string());
    if (staged.empty())
    {
      throw std::runtime_error("cannot write '" + path + "'"); // rank 0 says why
    }
    writeHere(staged);
    return;
  }
  bool told = false;
  try
  {
    WriteAtomically(path,
      [&](const fs::path& staged)
      {
        BroadcastText(controller, staged.string());
        told = true;
        writeHere(staged);
      });
  }
  catch (const std::exception&)
  {
    if (!told)
    {
      BroadcastText(controller, std::string());
    }
    throw;
  }
}

void WriteTextAtomically(const std::string& text, const std::string& path)
{
  WriteAtomically(path,
    [&](const fs::path& staged)
    {
      std::ofstream out(staged, std::ios::binary);
      out << text;
      out.close();
      if (!out)
      {
        throw std::runtime_error(std::strerror(errno));
      }
    });
}

void WritePngAtomically(vtkImageData* image, const std::string& path)
{
  WriteAtomically(path,
    [&](const fs::path& staged)
    {
      vtkNew<vtkImageData> rgb;
      rgb->SetExtent(image->GetExtent());
      rgb->GetPointData()->SetScalars(
        image->GetPointData()->GetArray(vtkSphericalCoverArrayNames::RGB));
      vtkNew<vtkPNGWriter> writer;
      ErrorCollector errors;
      errors.Watch(writer);
      writer->SetInputData(rgb);
      writer->SetFileName(staged.string().c_str());
      writer->Write();
      if (writer->GetErrorCode() != 0 || !fs::is_regular_file(staged))
      {
        throw std::runtime_error(errors.First());
      }
    });
}

void WriteExrAtomically(vtkImageData* image, const std::string& path)
{
  WriteAtomically(path,
    [&](const fs::path& staged)
    {
      vtkNew<vtkOpenEXRWriter> writer;
      ErrorCollector errors;
      errors.Watch(writer);
      writer->SetInputData(image);
      writer->SetFileName(staged.string().c_str());
      writer->SetColorArrayName(vtkSphericalCoverArrayNames::Radiance);
      writer->AddChannelArray(vtkSphericalCoverArrayNames::Depth);
      if (!writer->Write())
      {
        throw std::runtime_error(errors.First());
      }
    });
}
}
