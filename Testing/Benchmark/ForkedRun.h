// Runs a benchmark case in a child process, so that its peak memory is its own; the result (a
// trivially copyable row) comes back through a pipe.
#ifndef OTPARAM_BENCHMARK_FORKEDRUN_H
#define OTPARAM_BENCHMARK_FORKEDRUN_H

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <type_traits>
#include <vector>

namespace otparam
{
namespace benchmark
{

template <typename Row, typename Run>
bool runInChild(Run&& run, Row& row)
{
  static_assert(std::is_trivially_copyable<Row>::value, "rows travel through a pipe");
  int fd[2];
  if (pipe(fd) != 0)
    return false;
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(fd[0]);
    const Row r = run();
    const ssize_t written = write(fd[1], &r, sizeof r);
    _exit(written == static_cast<ssize_t>(sizeof r) ? 0 : 1);
  }
  close(fd[1]);
  const ssize_t got = read(fd[0], &row, sizeof row);
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return got == static_cast<ssize_t>(sizeof row) && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// Peak resident memory of this process so far, MiB.
inline double peakMiB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

inline double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Median of one field over the rows of repeated runs.
template <typename Row>
double medianOf(const std::vector<Row>& rows, double Row::*field)
{
  std::vector<double> v;
  for (const Row& r : rows)
    v.push_back(r.*field);
  return median(v);
}

} // namespace benchmark
} // namespace otparam

#endif
