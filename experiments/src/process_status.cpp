#include "process_status.hpp"

#include <sys/wait.h>

#include <cerrno>
#include <cstring>

namespace dtlab::experiments {

int wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

std::string signal_name(int signal) {
  const char* abbreviation = sigabbrev_np(signal);
  return abbreviation == nullptr ? std::to_string(signal)
                                 : std::to_string(signal) + " (" + abbreviation + ")";
}

}  // namespace dtlab::experiments
