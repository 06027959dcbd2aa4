// Helpers for the scene, writer and command-line tests: temporary directories, files, CSV, the
// message of a SceneError, and running the fibra program (POSIX).
#pragma once

#include "engine/scene.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace fibra::test {

namespace fs = std::filesystem;

inline std::string sourcePath(const std::string& relative) {
  return std::string(FIBRA_SOURCE_DIR) + "/" + relative;
}

// A fresh, empty directory path (not created), removed with its contents at scope exit.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() /
              ("fibra_test_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void writeFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Rows of a CSV file without quoting, header included.
inline std::vector<std::vector<std::string>> readCsv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(readFile(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream l(line);
    for (std::string cell; std::getline(l, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// The message of the SceneError that f throws, or "(no error)".
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// Starts the fibra program with `args`, its stdout and stderr into `output`.
inline pid_t startFibra(const std::vector<std::string>& args, const std::string& output) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(FIBRA_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(FIBRA_BINARY, argv.data());
    ::_exit(127);
  }
  return pid;
}

// Exit status of a child; 256 + the signal when a signal ended it (so that an exit status of
// 130 and death by SIGINT differ).
inline int statusOf(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : 256 + WTERMSIG(status);
}

inline int waitStatus(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return statusOf(status);
}

// Exit status of a child within `seconds`; past that it is killed and -1 returned.
inline int waitStatusWithin(pid_t pid, double seconds) {
  for (int waited = 0; waited < seconds * 1000; waited += 5) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return statusOf(status);
    ::usleep(5000);
  }
  ::kill(pid, SIGKILL);
  waitStatus(pid);
  return -1;
}

struct RunResult {
  int status;
  std::string output;  // stdout and stderr
};

inline RunResult runFibra(const std::vector<std::string>& args, const TempDir& scratch) {
  fs::create_directories(scratch.path());
  const std::string log = scratch / "fibra.log";
  const int status = waitStatusWithin(startFibra(args, log), 120);
  return {status, readFile(log)};
}

}  // namespace fibra::test
