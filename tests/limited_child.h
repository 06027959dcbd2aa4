// A program run as a child process under a wall-clock limit and an address-space limit (POSIX),
// for the fuzz test of scene input (tests/test_scene_fuzz.cpp): a child that allocates more than
// the limit gets a failed allocation instead of swapping the machine, and one that runs too long
// is asked to stop (SIGTERM), then killed (SIGKILL) if it does not.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace fibra::test {

struct ChildLimits {
  double seconds = 5;       // wall clock until SIGTERM
  double graceSeconds = 5;  // after SIGTERM, until SIGKILL
  std::uint64_t addressSpaceBytes = std::uint64_t(2) << 30;  // RLIMIT_AS
};

struct ChildResult {
  int status = -1;          // exit status; 256 + the signal when a signal ended it
  bool terminated = false;  // the wall-clock limit was reached and SIGTERM sent
  bool killed = false;      // it did not stop within the grace period either: SIGKILL
  double wallSeconds = 0;
};

namespace limited_child_detail {

// In the child: limits, stdout and stderr into `output`, then the program (never returns).
[[noreturn]] inline void execLimited(const std::string& program,
                                     const std::vector<std::string>& args,
                                     const std::string& output, std::uint64_t addressSpace) {
  const rlimit as{addressSpace, addressSpace};
  ::setrlimit(RLIMIT_AS, &as);
  const rlimit noCore{0, 0};
  ::setrlimit(RLIMIT_CORE, &noCore);
  const int fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::dup2(fd, 1);
  ::dup2(fd, 2);
  std::vector<char*> argv{const_cast<char*>(program.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv(program.c_str(), argv.data());
  ::_exit(127);
}

// Waits for `pid` until `deadline`; true with `status` set when it ended.
inline bool waitUntil(pid_t pid, std::chrono::steady_clock::time_point deadline, int& status) {
  for (;;) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace limited_child_detail

// Runs `program args...` with its stdout and stderr into the file `output`, under `limits`.
inline ChildResult runLimited(const std::string& program, const std::vector<std::string>& args,
                              const std::string& output, const ChildLimits& limits) {
  using namespace limited_child_detail;
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto after = [&](double s) {
    return start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  const pid_t pid = ::fork();
  if (pid == 0) execLimited(program, args, output, limits.addressSpaceBytes);
  ChildResult r;
  int status = 0;
  if (!waitUntil(pid, after(limits.seconds), status)) {
    r.terminated = true;
    ::kill(pid, SIGTERM);
    if (!waitUntil(pid, after(limits.seconds + limits.graceSeconds), status)) {
      r.killed = true;
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
    }
  }
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 256 + WTERMSIG(status);
  r.wallSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

}  // namespace fibra::test
